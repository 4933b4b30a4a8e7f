"""Rules about Gazebo's plugins and sensors, each held to the robot it is written in, and
about what sdformat's URDF converter loses or moves before Gazebo sees the robot."""

from __future__ import annotations

from collections.abc import Iterator

from ...analysis import Analysis
from ...catalog import Rule, conversion, rules_in
from ...catalog import gazebo as catalog
from ...diagnostics import Diagnostic
from ._drive import drives
from ._losses import losses
from ._sensors import sensors
from ._settings import settings
from ._versions import ros_versions, simulators

__all__ = ["REPORTS", "gazebo"]


def gazebo(
    analysis: Analysis, select: frozenset[str] | None = None, *, for_gazebo: bool = True
) -> Iterator[Diagnostic]:
    """Every finding about the robot's Gazebo plugins and sensors, and about what Gazebo's
    URDF converter loses (of the rules in ``select``, by id; None: all of them; where Gazebo
    looks for meshes and what it makes of mimic joints only ``for_gazebo``, when the robot is
    checked for Gazebo: common to robots that never meet Gazebo, they would be noise)."""
    chosen = frozenset(r.id for r in REPORTS) if select is None else select
    if not for_gazebo:
        chosen -= {conversion.GAZEBO_MODEL_PATH.id, conversion.GAZEBO_MIMIC.id}
    if chosen & _LOSSES:
        yield from losses(analysis, select=chosen)
    found = analysis.gazebo_blocks
    if not found:
        return
    drive = {catalog.DIFF_DRIVE_SIZE.id, catalog.DIFF_DRIVE_WHEELS.id}
    for block in found:
        if chosen & drive:
            yield from drives(analysis, block)
        yield from sensors(analysis, block, select=chosen)
        if catalog.GAZEBO_SETTING.id in chosen:
            yield from settings(analysis, block)
    if catalog.PLUGIN_ROS_VERSION.id in chosen:
        yield from ros_versions(analysis, found)
    if catalog.PLUGIN_SIMULATOR.id in chosen:
        yield from simulators(analysis, found)


_LOSSES = frozenset(r.id for r in rules_in(conversion))
REPORTS: tuple[Rule, ...] = (*rules_in(catalog), *rules_in(conversion))
"""Every rule this module's check may report: the check runs only when one is selected."""
