"""Fixes as text edits: `fishbot check --fix` and `--diff`, and the suppression comment any
finding can take.

Every rule whose findings offer a fix is fixed here through the command line: the fixed
file then checks clean of that rule, and only the lines the fix names changed.
"""

from __future__ import annotations

import difflib
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import FISHBOT, box_stl
from test_rules import ROBOT_RULES, write_example

from fishbot_urdf.catalog import Rule
from fishbot_urdf.cli import cli
from fishbot_urdf.config import Config
from fishbot_urdf.fixes import apply
from fishbot_urdf.lint import check_file
from fishbot_urdf.workspace import Workspace

ROBOT = """\
<robot name="r">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="base_link">
    <visual><geometry><box size="0.2 0.2 0.1"/></geometry><material name="bleu"/></visual>
  </link>
  <link name="wheel_link"/>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_lnk"/><child link="wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <gazebo reference="wheel_lnk"><mu1>1.0</mu1></gazebo>
</robot>
"""
"""Three misspelt names, each used once: a parent link, a material and a Gazebo reference."""

MESHES = """\
<robot name="r">
  <link name="base_link">
    <visual><geometry><mesh filename="meshes/Base.stl"/></geometry></visual>
    <visual><geometry><mesh filename="meshes/part_mm.stl"/></geometry></visual>
  </link>
</robot>
"""
"""A mesh named in the wrong case, and one in millimetres."""

XACRO = """\
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="wheel_radius" value="0.03"/>
  <link name="a">
    <visual><geometry><sphere radius="${wheel_radus}"/></geometry></visual>
  </link>
</robot>
"""
"""A property misspelt: the expansion stops, and the fix lets it go on."""


def _fix(file: Path, *options: str) -> tuple[int, str]:
    result = CliRunner().invoke(cli, ["check", "--isolated", "--fix", *options, str(file)])
    return result.exit_code, result.output


def _rules(file: Path) -> list[str]:
    return [d.rule for d in check_file(file, workspace=Workspace()).diagnostics]


def _changed_lines(before: str, after: str) -> set[int]:
    """The lines of ``before`` that ``after`` changes (1-based)."""
    changed: set[int] = set()
    matcher = difflib.SequenceMatcher(None, before.splitlines(), after.splitlines())
    for tag, start, end, _, _ in matcher.get_opcodes():
        if tag != "equal":
            changed.update(range(start + 1, max(end, start + 1) + 1))
    return changed


def test_misspelt_names_are_replaced_by_the_names_meant(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    assert {"undefined-link", "undefined-material", "unknown-reference"} <= set(_rules(robot))
    status, _ = _fix(robot)
    assert status == 0
    fixed = robot.read_text()
    assert fixed == ROBOT.replace('"base_lnk"', '"base_link"').replace('"bleu"', '"blue"').replace(
        '"wheel_lnk"', '"wheel_link"'
    )
    assert _rules(robot) == []


def test_a_mesh_in_the_wrong_case_and_one_in_millimetres(tmp_path: Path) -> None:
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "base.stl").write_bytes(box_stl(0.2, 0.2, 0.1))
    (tmp_path / "meshes" / "part_mm.stl").write_bytes(box_stl(200, 200, 100))
    robot = tmp_path / "robot.urdf"
    robot.write_text(MESHES)
    assert {"mesh-case", "mesh-units"} <= set(_rules(robot))
    status, _ = _fix(robot)
    assert status == 0
    assert robot.read_text() == MESHES.replace("Base.stl", "base.stl").replace(
        'part_mm.stl"/>', 'part_mm.stl" scale="0.001 0.001 0.001"/>'
    )
    assert _rules(robot) == []


def test_a_misspelt_property_that_stops_the_expansion_is_fixed(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(XACRO)
    diff = CliRunner().invoke(cli, ["check", "--isolated", "--diff", str(robot)])
    assert diff.exit_code == 1
    assert '-    <visual><geometry><sphere radius="${wheel_radus}"/>' in diff.output
    assert robot.read_text() == XACRO  # --diff writes nothing
    status, _ = _fix(robot)
    assert status == 0
    assert robot.read_text() == XACRO.replace("wheel_radus}", "wheel_radius}")


def test_a_name_many_places_miss_is_not_replaced_by_fix(tmp_path: Path) -> None:
    """The link's own name misspelt: every joint naming it fails, and replacing each would
    spread the misspelling. Offered (unsafe), not applied."""
    package = tmp_path / "fishbot_description"
    shutil.copytree(FISHBOT, package)
    base = package / "urdf/fishbot/base.urdf.xacro"
    base.write_text(base.read_text().replace('name="base_link"', 'name="base_lnk"', 1))
    before = {p: p.read_text() for p in package.rglob("*.xacro")}
    top = package / "urdf/fishbot/fishbot.urdf.xacro"
    status, _ = _fix(top)
    assert status == 1
    assert {p: p.read_text() for p in package.rglob("*.xacro")} == before
    result = check_file(top, workspace=Workspace(), fixes=True)
    offered = [f for d in result.diagnostics if d.rule == "undefined-link" for f in d.fixes]
    assert offered and not any(f.safe for f in offered)


def test_a_file_outside_the_robots_package_is_never_edited(tmp_path: Path) -> None:
    shared = tmp_path / "shared"
    shared.mkdir()
    (shared / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="part">'
        '<joint name="j" type="fixed"><parent link="base_lnk"/><child link="b"/></joint>'
        '<link name="b"/></xacro:macro></robot>\n'
    )
    package = tmp_path / "pkg"
    package.mkdir()
    (package / "package.xml").write_text("<package><name>pkg</name></package>\n")
    top = package / "robot.urdf.xacro"
    top.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="../shared/parts.xacro"/><link name="base_link"/>'
        "<xacro:part/></robot>\n"
    )
    (package / "fishbot.toml").write_text(f"allow-read = [{str(shared)!r}]\n")
    result = CliRunner().invoke(cli, ["check", "--fix", str(top)])
    assert "undefined-link" in result.output
    assert "base_lnk" in (shared / "parts.xacro").read_text()
    config = Config(allow_read=(str(shared),))
    found = check_file(top, workspace=Workspace(), fixes=True, config=config)
    assert all(not d.fixes for d in found.diagnostics if d.rule == "undefined-link")


FIXED_BY_EXAMPLE = [r for r in ROBOT_RULES if r.id in ("undefined-mimic", "control-interface")]


@pytest.mark.parametrize("rule", FIXED_BY_EXAMPLE, ids=[r.id for r in FIXED_BY_EXAMPLE])
def test_a_rules_failing_example_is_fixed_and_nothing_else_changes(
    tmp_path: Path, rule: Rule
) -> None:
    robot = write_example(tmp_path, rule, rule.bad)
    found = check_file(robot, workspace=Workspace(), fixes=True)
    fixes = [f for d in found.diagnostics if d.rule == rule.id for f in d.fixes if f.safe]
    assert fixes
    _, output = _fix(robot, "--target", "all")
    assert rule.id not in _rules(robot), output
    lines = {line for fix in fixes for edit in fix.edits for line in (edit.line, edit.end_line)}
    assert _changed_lines(rule.bad, robot.read_text()) <= lines


def test_an_inertial_at_waters_density_is_offered_and_applied_only_as_unsafe(
    tmp_path: Path,
) -> None:
    rule = next(r for r in ROBOT_RULES if r.id == "missing-inertial")
    robot = write_example(tmp_path, rule, rule.bad)
    _fix(robot)
    assert robot.read_text() == rule.bad  # a guess at the mass: not a safe fix
    _fix(robot, "--unsafe-fixes")
    assert "missing-inertial" not in _rules(robot)
    text = robot.read_text()
    # A cylinder r = 0.032, l = 0.04 of water: m = 1000 pi r^2 l.
    mass = 1000 * 3.141592653589793 * 0.032**2 * 0.04
    assert f'<mass value="{mass:.6g}' in text or f'<mass value="{mass:.12g}' in text
    assert _changed_lines(rule.bad, text) <= {4, 5, 6, 7}


SILENCEABLE = [r for r in ROBOT_RULES if not r.fatal]


@pytest.mark.parametrize("rule", SILENCEABLE, ids=[r.id for r in SILENCEABLE])
def test_a_finding_is_silenced_by_the_comment_it_offers(tmp_path: Path, rule: Rule) -> None:
    robot = write_example(tmp_path, rule, rule.bad)
    every = Config(targets=("all",))  # each finding, whatever program it harms
    found = check_file(robot, workspace=Workspace(), fixes=True, config=every)
    mine = [d for d in found.diagnostics if d.rule == rule.id]
    (silencing,) = [f for f in mine[0].fixes if f.silences]
    assert not silencing.safe
    edits = [e for e in silencing.edits if Path(e.path).resolve() == robot.resolve()]
    robot.write_text(apply(robot.read_text(), edits))
    after = check_file(robot, workspace=Workspace(), config=every)
    assert "unused-suppression" not in [d.rule for d in after.diagnostics]
    assert sum(d.rule == rule.id for d in after.diagnostics) < len(mine)
    assert rule.id in [d.rule for d in after.suppressed]
