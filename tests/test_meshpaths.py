"""One rule for mesh names, asked by every command and library function: a relative name is
read beside the robot file (never beside the included xacro file that wrote it),
``package://`` in the package's folder; check, render, view, tf, inertia and the library
agree on which meshes are found, and where."""

from __future__ import annotations

from pathlib import Path
from typing import NoReturn

import pytest
from click.testing import CliRunner
from conftest import box_stl

import fishbot_urdf
from fishbot_urdf.analysis import analyse
from fishbot_urdf.analysis.meshpaths import RULE, MeshNotFoundError, MeshPaths, State
from fishbot_urdf.cli import cli
from fishbot_urdf.drawing.scene import build_scene
from fishbot_urdf.inertia import fill_inertials
from fishbot_urdf.lint import check_file
from fishbot_urdf.packages import PackageFinder

_LINK = """\
  <link name="{link}">
    <visual><geometry><mesh filename="{name}"/></geometry></visual>
    <collision><geometry><mesh filename="{name}"/></geometry></collision>
  </link>
  <joint name="{link}_joint" type="fixed"><parent link="base"/><child link="{link}"/></joint>
"""

# link -> the mesh name it is written with
NAMES = {
    "plain": "meshes/plain.stl",  # beside the robot file: found
    "packaged": "package://demo/meshes/packaged.stl",  # in the package: found
    "missing": "meshes/none.stl",  # nowhere
}
INCLUDED = "meshes/arm.stl"  # written in urdf/parts/arm.xacro, the file is beside it only


@pytest.fixture
def robot(tmp_path: Path) -> Path:
    """The package "demo": urdf/robot.urdf.xacro includes urdf/parts/arm.xacro, whose mesh
    meshes/arm.stl lies beside it (urdf/parts/meshes/arm.stl), not beside the robot file."""
    root = tmp_path / "demo"
    (root / "urdf" / "parts" / "meshes").mkdir(parents=True)
    (root / "urdf" / "meshes").mkdir()
    (root / "meshes").mkdir()
    (root / "package.xml").write_text('<package format="3"><name>demo</name></package>')
    box = box_stl(0.2, 0.1, 0.1)
    (root / "urdf" / "meshes" / "plain.stl").write_bytes(box)
    (root / "meshes" / "packaged.stl").write_bytes(box)
    (root / "urdf" / "parts" / "meshes" / "arm.stl").write_bytes(box)
    (root / "urdf" / "parts" / "arm.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        + _LINK.format(link="arm", name=INCLUDED)
        + "</robot>\n"
    )
    links = "".join(_LINK.format(link=link, name=name) for link, name in NAMES.items())
    path = root / "urdf" / "robot.urdf.xacro"
    path.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="base"/>\n'
        '  <xacro:include filename="parts/arm.xacro"/>\n'
        f"{links}</robot>\n"
    )
    return path


def _expected(robot: Path) -> dict[str, Path | None]:
    """Each link's mesh file, as the rule finds it (None: not found)."""
    root = robot.parent.parent
    return {
        "arm": None,
        "plain": robot.parent / "meshes" / "plain.stl",
        "packaged": root / "meshes" / "packaged.stl",
        "missing": None,
    }


def _not_found(lines: str) -> set[str]:
    """The links of the mesh-not-found lines printed."""
    return {
        line.split("link '", 1)[1].split("'", 1)[0]
        for line in lines.splitlines()
        if line.endswith("[mesh-not-found]")
    }


def test_the_library_resolves_by_one_rule(robot: Path) -> None:
    analysis = analyse(fishbot_urdf.load(robot))
    paths = analysis.mesh_paths
    assert analysis.mesh_paths is paths  # built once
    found = {
        link: paths.get(name).file if paths.get(name).found else None
        for link, name in {**NAMES, "arm": INCLUDED}.items()
    }
    assert found == _expected(robot)
    arm = paths.get(INCLUDED)
    assert (arm.state, arm.file) == (State.MISSING, robot.parent / INCLUDED)
    assert paths.get(NAMES["missing"]).state is State.MISSING
    [mesh] = {c.geometry for c in analysis.links["arm"].collisions}
    assert paths.beside_writer(mesh) == robot.parent / "parts" / INCLUDED
    assert paths.in_package(robot.parent / "parts" / INCLUDED) == ("demo", f"urdf/parts/{INCLUDED}")
    with pytest.raises(MeshNotFoundError) as info:
        paths.file(mesh)
    assert info.value.rule == "mesh-not-found"
    assert info.value.message == (
        f"mesh '{INCLUDED}' is not found (looked for {robot.parent / INCLUDED}; {RULE})"
    )
    assert (info.value.path, info.value.line) == (str(robot.parent / "parts" / "arm.xacro"), 4)


def test_check_says_where_it_looked_by_which_rule_and_the_classic_mistake(robot: Path) -> None:
    result = check_file(robot)
    missing = [d for d in result.diagnostics if d.rule == "mesh-not-found"]
    assert {d.subject.name for d in missing if d.subject} == {"arm", "missing"}
    visual = next(d for d in missing if d.subject and d.subject.name == "arm")
    arm = robot.parent / "parts" / "arm.xacro"
    assert visual.format() == (
        f"{arm}:3:23: error: link 'arm': mesh '{INCLUDED}' is not found (looked for "
        f"{robot.parent / INCLUDED}; relative mesh names are read beside the robot file, as "
        "Gazebo, MuJoCo, PyBullet, pinocchio and yourdfpy read them) (it is beside "
        f"{arm}, which wrote it, but the expanded robot keeps no trace of that file: write "
        "package://demo/urdf/parts/meshes/arm.stl (or $(find demo)/urdf/parts/meshes/arm.stl))"
        " [mesh-not-found]"
    )
    assert visual.data["beside_writer"] == str(robot.parent / "parts" / INCLUDED)
    assert visual.data["looked_for"] == str(robot.parent / INCLUDED)
    other = next(d for d in missing if d.subject and d.subject.name == "missing")
    assert "beside_writer" not in other.data


def test_every_command_and_function_agrees(
    robot: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    expected = _expected(robot)
    lost = {link for link, file in expected.items() if file is None}
    runner = CliRunner()

    # check
    checked = runner.invoke(cli, ["check", "--isolated", "-q", str(robot)])
    assert checked.exit_code == 1
    assert _not_found(checked.stderr) == lost

    # render, and the scene it draws
    analysis = analyse(fishbot_urdf.load(robot))
    scene = build_scene(analysis)
    assert {p.link for p in scene.parts} == set(expected) - lost
    assert {d.subject.name for d in scene.findings if d.subject} == lost
    assert {d.rule for d in scene.findings} == {"mesh-not-found"}
    picture = tmp_path / "robot.png"
    rendered = runner.invoke(cli, ["render", str(robot), "-o", str(picture)])
    assert rendered.exit_code == 0
    assert _not_found(rendered.stderr) == lost
    assert rendered.stderr == "".join(d.format() + "\n" for d in scene.findings)

    # view (stopped as soon as it has said what it serves)
    pytest.importorskip("viser", reason="fishbot view needs the [view] extra")

    def stop(seconds: float) -> NoReturn:
        raise SystemExit(0)

    monkeypatch.setattr("fishbot_urdf.cli.view.time.sleep", stop)
    viewed = runner.invoke(cli, ["view", str(robot), "--port", "0"])
    assert viewed.exit_code == 0, viewed.output
    assert _not_found(viewed.stderr) == lost

    # tf poses the robot without opening a mesh
    posed = runner.invoke(cli, ["tf", str(robot), "base", "plain"])
    assert (posed.exit_code, posed.stderr) == (0, "")

    # inertia: the library's filling, and the command's
    filling = fill_inertials(analysis, density=1000.0)
    assert set(filling.inertials) == set(expected) - lost
    assert {d.subject.name for d in filling.skipped if d.subject} == lost
    assert {d.data["reason"] for d in filling.skipped} == {"mesh-not-found"}
    filled = tmp_path / "filled.urdf"
    made = runner.invoke(cli, ["inertia", str(robot), "--fill", "--density", "1", "-o", filled])
    assert made.exit_code == 1  # the robot's own errors come first: its missing meshes
    assert _not_found(made.stderr) == lost
    assert not filled.exists()
    tabled = runner.invoke(cli, ["inertia", str(robot)])
    assert _not_found(tabled.stderr) == lost

    # the files never written over: those found, and only those
    result = check_file(robot)
    assert result.analysis is not None
    inputs = result.analysis.mesh_paths.found(result.analysis.robot)
    assert inputs == [file for file in expected.values() if file is not None]
    out = expected["plain"]
    assert out is not None
    written = runner.invoke(cli, ["check", "--isolated", "-q", str(robot), "-o", str(out)])
    assert written.exit_code == 2
    assert f"{out}: error:" in written.stderr


def test_inertia_fills_what_check_finds(tmp_path: Path) -> None:
    # A robot whose meshes are all found: check is clean and --fill writes every link.
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "plain.stl").write_bytes(box_stl(0.2, 0.1, 0.1))
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="base"/>'
        + _LINK.format(link="plain", name="meshes/plain.stl")
        + "</robot>"
    )
    assert [d.rule for d in check_file(robot).diagnostics] == ["missing-inertial"]
    filled = tmp_path / "filled.urdf"
    runner = CliRunner()
    made = runner.invoke(
        cli, ["inertia", str(robot), "--fill", "--mass", "plain=0.5", "-o", str(filled)]
    )
    assert made.exit_code == 0, made.output
    assert made.stderr == f"Wrote {filled}: <inertial> added to 1 link: plain (0.5 kg)\n"
    inertial = fishbot_urdf.load(filled).links[1].inertial
    assert inertial is not None and inertial.inertia.ixx == pytest.approx(0.5 / 12 * 0.02)


def test_a_robot_read_from_text_has_no_folder_for_relative_names(tmp_path: Path) -> None:
    paths = MeshPaths("<string>", PackageFinder())
    assert paths.get("meshes/a.stl").state is State.NO_FOLDER
    text = '<robot name="r">' + _LINK.format(link="a", name="meshes/a.stl").split("<joint")[0]
    robot = fishbot_urdf.parse(text + "</robot>")
    scene = build_scene(robot)
    finding, nothing = scene.findings  # its only shape is not drawn: nothing is
    assert nothing.rule == "nothing-drawn"
    assert (finding.rule, finding.severity.value) == ("mesh-not-found", "warning")
    assert finding.message == (
        "link 'a': mesh 'meshes/a.stl' is a relative name, and the robot was read from text, "
        "so it is not drawn"
    )
    assert fishbot_urdf.check(robot) == ()  # nothing to judge it against


@pytest.mark.parametrize(
    ("name", "state"),
    [
        ("package:/x.stl", State.MALFORMED),
        ("package:///nowhere_here.stl", State.MISSING),
        ("https://example.com/x.stl", State.REMOTE),
        ("package://nowhere_here/x.stl", State.NO_PACKAGE),
        ("MESHES/plain.stl", State.OTHER_CASE),
    ],
)
def test_states(robot: Path, name: str, state: State, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    path = MeshPaths(str(robot), PackageFinder()).get(name)
    assert path.state is state
    assert not path.found
