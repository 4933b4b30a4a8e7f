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


MIMIC = """\
<robot name="r">
  <link name="base_link"/><link name="left_wheel_link"/><link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
    <mimic joint="left_whel_joint"/>
  </joint>
</robot>
"""
"""A mimicked joint misspelt."""

FIXED_BY_EXAMPLE = [r for r in ROBOT_RULES if r.id == "control-interface"]


def test_a_misspelt_mimicked_joint(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(MIMIC)
    assert "undefined-mimic" in _rules(robot)
    _fix(robot)
    assert robot.read_text() == MIMIC.replace("left_whel_joint", "left_wheel_joint")
    assert _rules(robot) == []


NUMBERED = """\
<robot name="arm">
  <link name="link1"/><link name="link2"/><link name="link3"/>
  <joint name="joint1" type="fixed"><parent link="link1"/><child link="link2"/></joint>
  <joint name="joint2" type="fixed"><parent link="link2"/><child link="link4"/></joint>
</robot>
"""
"""A numbered link that does not exist: which number was meant is a guess."""


def test_a_guess_among_numbered_names_is_not_made(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(NUMBERED)
    _fix(robot)
    assert robot.read_text() == NUMBERED
    found = check_file(robot, workspace=Workspace(), fixes=True)
    offered = [f for d in found.diagnostics for f in d.fixes if not f.silences]
    assert offered and not any(f.safe for f in offered)


def test_a_typo_in_a_macro_called_twice_is_one_place_and_fixed(tmp_path: Path) -> None:
    """The left and right wheels of the fishbot are one macro: its misspelt parent link is
    two findings, one place to fix."""
    package = tmp_path / "fishbot_description"
    shutil.copytree(FISHBOT, package)
    wheel = package / "urdf/fishbot/actuator/wheel.urdf.xacro"
    good = wheel.read_text()
    wheel.write_text(good.replace('<parent link="base_link"/>', '<parent link="base_lnk"/>'))
    status, output = _fix(package / "urdf/fishbot/fishbot.urdf.xacro")
    assert status == 0, output
    assert wheel.read_text() == good
    assert "1 fix made in 1 file" in output


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


SHARED_MACRO = """\
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm">
    <link name="arm_link"/>
    <joint name="arm_joint" type="fixed"><parent link="base_link"/><child link="arm_link"/></joint>
  </xacro:macro>
</robot>
"""


def _robot_with_arm(base: str) -> str:
    return (
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="arm.xacro"/>\n'
        f'  <link name="{base}"/>\n'
        "  <xacro:arm/>\n"
        "</robot>\n"
    )


def test_a_file_two_robots_read_is_not_fixed_for_one_against_the_other(tmp_path: Path) -> None:
    (tmp_path / "arm.xacro").write_text(SHARED_MACRO)
    (tmp_path / "a.urdf.xacro").write_text(_robot_with_arm("base_link"))
    (tmp_path / "b.urdf.xacro").write_text(_robot_with_arm("base_lnk"))
    result = CliRunner().invoke(
        cli,
        [
            "check",
            "--isolated",
            "--fix",
            "-q",
            str(tmp_path / "a.urdf.xacro"),
            str(tmp_path / "b.urdf.xacro"),
        ],
    )
    assert (tmp_path / "arm.xacro").read_text() == SHARED_MACRO
    assert "a fix left out: another robot that reads the file had more findings" in result.output
    assert _rules(tmp_path / "a.urdf.xacro") == []


def test_a_file_that_cannot_be_written_leaves_the_others_fixed(tmp_path: Path) -> None:
    typo = ROBOT.replace('"bleu"', '"blue"').replace('"wheel_lnk"', '"wheel_link"')
    first, locked, last = (tmp_path / f"{n}.urdf" for n in ("a", "b", "c"))
    for file in (first, locked, last):
        file.write_text(typo)
    locked.chmod(0o444)  # read-only: refused, as a user would want, even for root
    result = CliRunner().invoke(
        cli, ["check", "--isolated", "--fix", "-q", str(first), str(locked), str(last)]
    )
    assert result.exit_code == 2
    assert "[io]" in result.output
    assert "undefined-link" in result.output  # the findings are still reported
    assert "base_lnk" not in first.read_text() and "base_lnk" not in last.read_text()
    assert "base_lnk" in locked.read_text()


def test_the_diff_of_a_file_without_a_last_line_break_applies(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT.rstrip("\n"))
    result = CliRunner().invoke(cli, ["check", "--isolated", "--diff", str(robot)])
    assert result.exit_code == 1
    assert "\\ No newline at end of file\n" in result.output


def test_fix_and_diff_need_files(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    stdin = CliRunner().invoke(cli, ["check", "--fix", "-"], input=ROBOT)
    assert stdin.exit_code == 2 and "not - (stdin)" in stdin.output
    sarif = CliRunner().invoke(cli, ["check", "--diff", "--format", "sarif", str(robot)])
    assert sarif.exit_code == 2 and "no --format or -o" in sarif.output


def test_an_inertial_added_to_a_crlf_file_keeps_its_line_breaks(tmp_path: Path) -> None:
    rule = next(r for r in ROBOT_RULES if r.id == "missing-inertial")
    robot = write_example(tmp_path, rule, rule.bad)
    robot.write_bytes(rule.bad.replace("\n", "\r\n").encode())
    _fix(robot, "--unsafe-fixes")
    data = robot.read_bytes()
    assert b"<inertial>" in data
    assert data.count(b"\n") == data.count(b"\r\n")


def test_a_robot_that_cannot_be_read_is_said_and_fails_the_diff(tmp_path: Path) -> None:
    result = CliRunner().invoke(cli, ["check", "--diff", str(tmp_path / "none.urdf")])
    assert result.exit_code == 2
    assert "no such file [io]" in result.output
