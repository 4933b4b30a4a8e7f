"""The checks: one module per family of rules, each registered here against the rules of the
catalogue (`fishbot_urdf.catalog`) it reports, so that a check runs only when one of its
rules is selected (``--select structure`` opens no mesh file).

The rules' data (``Rule``, ``all_rules``, ``get``, ``ids``) is the catalogue's, and kept here
under its former names.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

from ..analysis import Analysis, of
from ..catalog import Consumer, Family, Rule, all_rules, get, ids
from ..diagnostics import Diagnostic
from ..packages import PackageFinder
from . import gazebo, joints, meshes, mujoco, physics, references, shapes, structure

__all__ = [
    "CHECKS",
    "Check",
    "Consumer",
    "Family",
    "Rule",
    "Settings",
    "all_rules",
    "get",
    "ids",
]


@dataclass(frozen=True, slots=True)
class Settings:
    """What a check may need besides the robot.

    Attributes:
        packages: Where ``package://`` names are looked up (folders by package name, or a
            `PackageFinder` that keeps its answers); None: the analysis's own.
        ground_tolerance: How far (m) the lowest collision point may be from z = 0.
        for_gazebo: Whether the robot is checked for Gazebo: what only Gazebo's set-up
            decides (where it looks for meshes) is judged only then.
        select: The ids of the rules selected (None: all), for a check that runs its parts
            only for their rules (Gazebo's).
        for_mujoco: Whether the robot is checked for MuJoCo: what MuJoCo refuses of the MJCF
            `fishbot mjcf` writes is foretold only then.
    """

    packages: Mapping[str, str | Path] | PackageFinder | None = None
    ground_tolerance: float = physics.GROUND_TOLERANCE
    for_gazebo: bool = True
    select: frozenset[str] | None = None
    for_mujoco: bool = False


@dataclass(frozen=True, slots=True)
class Check:
    """One check over an analysed robot, and every rule it may report.

    Attributes:
        name: The check's name (its module's).
        reports: Every rule it may report: it runs only when one of them is selected.
        run: The check.
        uses_values: Whether it judges the numbers of links and joints: its findings about
            one whose values could not be read follow from that fault (names and the tree's
            shape are read even then).
        by_line: Whether each of its findings judges one element's own numbers (a shape's
            size): it follows only from a value that could not be read on that element's
            line, so that one shape's fault hides none of its link's other shapes (a finding
            with no line, about a shape made up where none could be read, follows from any).
    """

    name: str
    reports: tuple[Rule, ...]
    run: Callable[[Analysis, Settings], Iterable[Diagnostic]]
    uses_values: bool = True
    by_line: bool = False


CHECKS: tuple[Check, ...] = (
    Check(
        "structure",
        structure.REPORTS,
        lambda analysis, _: structure.structure(analysis),
        uses_values=False,
    ),
    Check("joints", joints.REPORTS, lambda analysis, _: joints.joints(analysis)),
    Check("references", references.REPORTS, lambda analysis, _: references.references(analysis)),
    Check("shapes", shapes.REPORTS, lambda analysis, _: shapes.shapes(analysis), by_line=True),
    # A mesh's name and file first, then what the files hold: read only when a rule about
    # that is selected (--select mesh-not-found opens no mesh file).
    Check(
        "meshes",
        meshes.NAMES_REPORTS,
        lambda analysis, s: meshes.mesh_names(of(analysis, s.packages)),
    ),
    Check(
        "mesh contents",
        meshes.CONTENTS_REPORTS,
        lambda analysis, s: meshes.mesh_contents(of(analysis, s.packages)),
    ),
    Check(
        "physics",
        physics.REPORTS,
        lambda analysis, s: physics.physics(analysis, ground_tolerance=s.ground_tolerance),
    ),
    Check(
        "gazebo",
        gazebo.REPORTS,
        lambda analysis, s: gazebo.gazebo(analysis, s.select, for_gazebo=s.for_gazebo),
    ),
    # The MJCF's bodies, foretold from the masses alone (it opens no mesh file).
    Check(
        "mujoco",
        mujoco.REPORTS,
        lambda analysis, s: mujoco.predict(analysis) if s.for_mujoco else (),
    ),
)
"""Every check, in the order its findings come."""
