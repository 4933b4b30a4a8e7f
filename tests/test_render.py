"""`fishbot render` and the scene: a PNG a person would see, checked by its pixels."""

from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import FISHBOT, binary_stl, box_stl
from PIL import Image

import fishbot_urdf
from fishbot_urdf.analysis import analyse
from fishbot_urdf.cli import cli
from fishbot_urdf.drawing.picture import render_png
from fishbot_urdf.drawing.scene import build_scene
from fishbot_urdf.inputs import TimeLimitError, time_limit

XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"


def _pixels(data: bytes) -> np.ndarray:
    image = Image.open(io.BytesIO(data))
    assert image.mode == "RGB"
    return np.asarray(image).astype(int)


def _share(pixels: np.ndarray, rgb: tuple[int, int, int], tolerance: int = 90) -> float:
    """The share of pixels whose colour is that of ``rgb``, shaded (same hue, any brightness
    down to a third)."""
    target = np.array(rgb, dtype=float)
    norm = pixels / np.maximum(pixels.max(axis=2, keepdims=True), 1)
    want = target / max(target.max(), 1)
    close = np.abs(norm - want).max(axis=2) * 255 < tolerance
    lit = pixels.max(axis=2) > 40
    return float((close & lit).mean())


@pytest.mark.parametrize("view", ["iso", "front", "side", "top"])
def test_the_fishbot_is_in_the_picture_in_its_colours(tmp_path: Path, view: str) -> None:
    out = tmp_path / "fishbot.png"
    result = CliRunner().invoke(
        cli, ["render", str(XACRO), "-o", str(out), "--view", view, "--size", "400x300"]
    )
    assert (result.exit_code, result.output) == (0, "")
    pixels = _pixels(out.read_bytes())
    assert pixels.shape == (300, 400, 3)
    background = (pixels == 255).all(axis=2).mean()
    assert 0.2 < background < 0.95  # the robot is there, framed with room around it
    # The body is blue, seen through (alpha 0.5) over white: blue well above red and
    # green; the wheels are yellow (fishbot.urdf.xacro's materials).
    r, g, b = (pixels[..., i] for i in range(3))
    assert ((b > r + 60) & (b > g + 60)).mean() > 0.05
    if view != "top":
        assert _share(pixels, (255, 255, 0)) > 0.002
    # Framed: the robot touches no edge.
    edges = np.concatenate([pixels[0], pixels[-1], pixels[:, 0], pixels[:, -1]])
    assert (edges == 255).all()


def test_a_joint_position_moves_the_picture_and_collision_shapes_are_drawn(
    tmp_path: Path,
) -> None:
    arm = tmp_path / "arm.urdf"
    arm.write_text(
        '<robot name="arm"><material name="red"><color rgba="1 0 0 1"/></material>'
        '<link name="a"><visual><geometry><box size="0.1 0.1 0.1"/></geometry>'
        '<material name="red"/></visual></link>'
        '<link name="b"><visual><origin xyz="0.5 0 0"/><geometry><box size="1 0.1 0.1"/>'
        '</geometry><material name="red"/></visual>'
        '<collision><geometry><sphere radius="0.2"/></geometry></collision></link>'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/>'
        '<limit lower="-2" upper="2" effort="1" velocity="1"/></joint></robot>'
    )
    flat = _pixels(render_png(build_scene(fishbot_urdf.load(arm)), "front", 200, 200))
    up = _pixels(render_png(build_scene(fishbot_urdf.load(arm), {"j": -1.5708}), "front", 200, 200))

    # Seen from the front the flat arm is end-on, a square; raised, it is a tall bar.
    def aspect(p: np.ndarray) -> float:
        drawn = (p != 255).any(axis=2)
        return np.nonzero(drawn.any(axis=1))[0].size / np.nonzero(drawn.any(axis=0))[0].size

    assert aspect(flat) == pytest.approx(1.0, abs=0.1)
    assert aspect(up) > 5
    assert _share(up, (255, 0, 0)) > 0.01
    runner = CliRunner()
    out = tmp_path / "collision.png"
    result = runner.invoke(cli, ["render", str(arm), "-o", str(out), "--collision"])
    assert result.exit_code == 0
    assert _share(_pixels(out.read_bytes()), (255, 0, 0)) == 0.0  # no visuals: no red


def test_a_mesh_is_read_and_one_that_cannot_be_is_its_bounding_box(tmp_path: Path) -> None:
    (tmp_path / "part.stl").write_bytes(box_stl(0.2, 0.1, 0.1))
    (tmp_path / "part.dae").write_text(
        '<COLLADA><library_geometries><geometry><mesh><source id="positions">'
        '<float_array id="positions-array" count="6">0 0 0 0.3 0.2 0.1</float_array>'
        "</source></mesh></geometry></library_geometries></COLLADA>"
    )
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a">'
        '<visual><geometry><mesh filename="part.stl"/></geometry></visual>'
        '<visual><geometry><mesh filename="part.dae"/></geometry></visual>'
        '<visual><geometry><mesh filename="missing.stl"/></geometry></visual></link></robot>'
    )
    scene = build_scene(fishbot_urdf.load(robot))
    assert len(scene.parts) == 2
    low, high = scene.bounds()
    # the STL's box, and the COLLADA file's positions' box
    np.testing.assert_allclose(low, [0, 0, 0], atol=1e-6)
    np.testing.assert_allclose(high, [0.3, 0.2, 0.1], atol=1e-6)
    dae, missing = scene.findings
    text = robot.read_text()
    column = text.index('<mesh filename="part.dae"') + 1
    assert (dae.rule, dae.severity.value, dae.where) == (
        "mesh-invalid",
        "warning",
        f"{robot}:1:{column}",
    )
    assert dae.message.startswith("link 'a': mesh 'part.dae' cannot be read (")
    assert dae.message.endswith("), drawn as its bounding box")
    column = text.index('<mesh filename="missing.stl"') + 1
    assert (missing.rule, missing.where) == ("mesh-not-found", f"{robot}:1:{column}")
    assert missing.message == (
        f"link 'a': mesh 'missing.stl' is not found (looked for {tmp_path / 'missing.stl'}; "
        "relative mesh names are read beside the robot file, as Gazebo, MuJoCo, PyBullet, "
        "pinocchio and yourdfpy read them), so it is not drawn"
    )
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(tmp_path / "r.png")])
    assert result.exit_code == 0
    # printed as check prints its findings: place, severity, message, hint, rule
    assert result.stderr == "".join(d.format() + "\n" for d in scene.findings)
    assert result.stderr.splitlines()[1].endswith(
        "(write package://PACKAGE/path for a file of a ROS package) [mesh-not-found]"
    )


@pytest.mark.parametrize(
    ("args", "said", "code"),
    [
        (["--size", "10x10"], "is not WIDTHxHEIGHT", 2),
        (["-j", "nothing=1"], "no joint 'nothing'", 2),
        (["-j", "imu_joint=1"], "joint 'imu_joint' is fixed: it takes no position", 2),
        (
            ["--show", "mass,weight"],
            "Invalid value for --show: nothing to show called 'weight' (visual, collision, "
            "mass, inertia, frames, sensors, gazebo)",
            2,
        ),
    ],
)
def test_wrong_options(tmp_path: Path, args: list[str], said: str, code: int) -> None:
    result = CliRunner().invoke(cli, ["render", str(XACRO), "-o", str(tmp_path / "x.png"), *args])
    assert result.exit_code == code
    assert said in result.stderr
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize(
    ("wrong", "meant"),
    [
        ("inerta", "inertia"),
        ("frame", "frames"),
        ("visuals", "visual"),
        ("sensor", "sensors"),
        ("gazbo", "gazebo"),
    ],
)
def test_a_layer_mistyped_is_offered_the_one_it_looks_like(
    tmp_path: Path, wrong: str, meant: str
) -> None:
    out = tmp_path / "x.png"
    result = CliRunner().invoke(cli, ["render", str(XACRO), "-o", str(out), "--show", wrong])
    assert result.exit_code == 2
    assert result.stderr.splitlines()[-1] == (
        f"Error: Invalid value for --show: nothing to show called {wrong!r} (did you mean "
        f"{meant!r}? visual, collision, mass, inertia, frames, sensors, gazebo)"
    )
    assert not out.exists()


def test_a_package_not_found_is_one_warning_for_all_its_meshes(tmp_path: Path) -> None:
    mesh = '<visual><geometry><mesh filename="package://elsewhere/{}.stl"/></geometry></visual>'
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        f'<robot name="r"><link name="a">{mesh.format("a")}{mesh.format("b")}'
        '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link></robot>'
    )
    scene = build_scene(fishbot_urdf.load(robot))
    assert len(scene.parts) == 1  # the box
    [finding] = scene.findings
    assert (finding.rule, finding.severity.value) == ("mesh-not-found", "warning")
    assert finding.message == (
        "link 'a': mesh 'package://elsewhere/a.stl' is in package 'elsewhere', which is not "
        "found, so it is not drawn (nor 1 other mesh of it)"
    )
    assert finding.hint is not None and finding.hint.startswith("searched: the packages given")
    assert finding.data["package"] == "elsewhere"


def test_a_picture_too_big_is_one_limit_line_and_nothing_written(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><visual><geometry><box size="0.1 0.1 0.1"/>'
        "</geometry></visual></link></robot>"
    )
    out = tmp_path / "x.png"
    result = CliRunner().invoke(
        cli, ["render", str(robot), "-o", str(out), "--size", "30000x30000"]
    )
    assert result.exit_code == 2
    [line] = result.stderr.splitlines()
    assert line.startswith(f"{out}: error: a 30000 x 30000 picture is drawn on ")
    assert line.endswith("more than the bound of 67,108,864 (a 4096 x 4096 picture) [limit]")
    assert "Traceback" not in result.output
    assert not out.exists()


_GOOD_STL = box_stl(0.2, 0.1, 0.1)
_TRIANGLE = b"v 0 0 0\nv 0.2 0 0\nv 0 0.1 0.1\n"


@pytest.mark.parametrize(
    ("name", "data", "drawn"),
    [
        ("truncated.stl", _GOOD_STL[:-20], "drawn as its bounding box"),
        ("claims.stl", _GOOD_STL[:80] + (999).to_bytes(4, "little") + _GOOD_STL[84:], "box"),
        ("fewer.stl", _GOOD_STL[:80] + (2).to_bytes(4, "little") + _GOOD_STL[84:], "box"),
        ("empty.stl", b"", "nor its size: not drawn"),
        ("empty.obj", b"", "nor its size: not drawn"),
        ("garbage.stl", bytes(range(256)) * 40, "nor its size: not drawn"),
        ("garbage.obj", bytes(range(256)) * 40, "nor its size: not drawn"),
        ("number.obj", _TRIANGLE.replace(b"0.2", b"0.2x") + b"f 1 2 3\n", "box"),
        ("range.obj", _TRIANGLE + b"f 1 2 9\n", "drawn as its bounding box"),
        ("zero.obj", _TRIANGLE + b"f 0 1 2\n", "drawn as its bounding box"),
        ("negative.obj", _TRIANGLE + b"f -1 -2 -9\n", "drawn as its bounding box"),
        ("nan.obj", _TRIANGLE + b"v nan 0 0\nf 1 2 4\n", "drawn as its bounding box"),
        ("inf.stl", binary_stl([(0, 0, 0, 1, float("-inf"), 0, 0, 1, 0)]), "not drawn"),
    ],
)
def test_a_malformed_mesh_is_drawn_as_its_box_or_left_out_with_a_warning(
    tmp_path: Path, name: str, data: bytes, drawn: str
) -> None:
    (tmp_path / name).write_bytes(data)
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        f'<robot name="r"><link name="a"><visual><geometry><mesh filename="{name}"/>'
        '</geometry></visual><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
        "</link></robot>"
    )
    out = tmp_path / "r.png"
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(out), "--size", "64x48"])
    assert result.exit_code == 0, result.output
    [line] = result.stderr.splitlines()
    assert line.startswith(f"{robot}:1:50: warning: link 'a': mesh '{name}' cannot be read (")
    assert drawn in line
    assert line.endswith("(export the mesh again) [mesh-invalid]")
    assert _pixels(out.read_bytes()).shape == (48, 64, 3)
    scene = build_scene(fishbot_urdf.load(robot))
    assert len(scene.parts) == (2 if "box" in drawn else 1)
    assert [d.rule for d in scene.findings] == ["mesh-invalid"]


@pytest.mark.parametrize(
    ("mesh", "data"),
    [
        ('scale="1e300 1 1"', b"v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n"),  # overflows
        ("", b"v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n"),  # finite, but too far
    ],
)
def test_a_mesh_too_big_to_draw_is_a_warning_not_a_numpy_warning(
    tmp_path: Path, mesh: str, data: bytes
) -> None:
    # The test configuration turns every warning into an error: a RuntimeWarning from an
    # overflow in numpy would fail this test.
    (tmp_path / "big.obj").write_bytes(data)
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        f'<robot name="r"><link name="a"><visual><geometry><mesh filename="big.obj" {mesh}/>'
        '</geometry></visual><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
        "</link></robot>"
    )
    scene = build_scene(fishbot_urdf.load(robot))
    assert len(scene.parts) == 1
    [finding] = scene.findings
    assert (finding.rule, finding.where) == ("shape-not-drawn", f"{robot}:1:50")
    assert finding.message == (
        "link 'a': mesh 'big.obj' is not drawn: its corners are not finite numbers, or lie "
        "farther than 1e+09 m from the root"
    )
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(tmp_path / "r.png")])
    assert result.exit_code == 0
    assert result.stderr == finding.format() + "\n"
    with pytest.deprecated_call():  # the strings of old, for a while
        assert scene.warnings == (finding.message,)


def test_building_a_scene_stops_at_the_deadline(tmp_path: Path) -> None:
    analysis = analyse(fishbot_urdf.load(XACRO))
    with time_limit(1e-6), pytest.raises(TimeLimitError) as info:
        render_png(build_scene(analysis))
    assert info.value.what == "building the scene"


def test_a_robot_whose_only_fault_is_an_inertial_is_drawn(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="base_link">'
        '<visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>'
        '<inertial><mass value="1"/></inertial></link></robot>'
    )
    out = tmp_path / "r.png"
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(out)])
    assert result.exit_code == 0, result.stderr
    assert _pixels(out.read_bytes()).std() > 0  # something is drawn
    (line,) = result.stderr.splitlines()
    assert line == (
        f"{robot}:1:103: error: link 'base_link': <inertial> has no <inertia> "
        '(write <inertia ixx=".." ixy="0" ixz="0" iyy=".." iyz="0" izz=".."/>) [missing-element]'
    )


def test_a_xacro_argument_named_as_a_joint_is_a_warning(tmp_path: Path) -> None:
    out = tmp_path / "r.png"
    result = CliRunner().invoke(
        cli, ["render", str(XACRO), "right_wheel_joint:=90deg", "-o", str(out)]
    )
    assert result.exit_code == 0
    assert out.exists()
    assert result.stderr == (
        f"{XACRO}: warning: argument 'right_wheel_joint' is given, but no <xacro:arg> declares "
        "it and nothing reads it ('right_wheel_joint' is a joint: did you mean "
        "`-j right_wheel_joint=90deg`?) [xacro-unknown-arg]\n"
    )


def test_the_first_robots_imu_is_seen_through_its_body(tmp_path: Path) -> None:
    # first_robot.urdf: a cylinder (radius 0.1 m, 0.12 m long) white at alpha 0.5 around a
    # 2 cm black box at alpha 0.5, 3 cm above the body's centre.
    first = FISHBOT / "urdf" / "first_robot.urdf"
    out = tmp_path / "first.png"
    result = CliRunner().invoke(
        cli, ["render", str(first), "-o", str(out), "--view", "front", "--size", "400x300"]
    )
    assert (result.exit_code, result.output) == (0, "")
    pixels = _pixels(out.read_bytes())
    # Seen from the front the body is 0.2 m wide and 0.12 m tall, framed with a 12% margin:
    # 0.2 m * 1.12 over the 400 pixels, 0.56 mm a pixel, the body's centre in the middle.
    metre = 1 / (0.2 * 1.12 / 400)
    imu_row = round(150 - 0.03 * metre)  # 3 cm up
    half = int(0.01 * metre) - 4  # within the IMU's 2 cm
    imu = pixels[imu_row - half : imu_row + half, 200 - half : 200 + half]
    body = pixels[150 - half : 150 + half, 200 - half : 200 + half]  # below the IMU
    assert imu.mean() < body.mean() - 50  # the black IMU darkens the white body
    assert np.ptp(imu, axis=2).max() < 10  # and stays grey: black seen through white
    # Where the IMU is not, the body lets the white background through: brighter than
    # its face drawn opaque, lit at 0.88.
    assert body.mean() > 0.88 * 255 + 3


FRAMES = """\
<robot name="frames">
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed"><parent link="base_link"/><child link="imu_link"/></joint>
</robot>
"""


def test_a_robot_with_nothing_to_draw_is_an_error_and_no_picture(tmp_path: Path) -> None:
    robot = tmp_path / "frames.urdf"
    robot.write_text(FRAMES)
    out = tmp_path / "frames.png"
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(out)])
    assert result.exit_code == 1
    assert result.stdout == ""
    assert result.stderr == (
        f"{robot}:1:1: error: robot 'frames': no link has a visual shape: there is nothing to "
        "draw (give a link a <visual>; `fishbot render --collision` draws its 1 collision "
        "shape) [nothing-drawn]\n"
        "nothing written: fix the errors above first\n"
    )
    assert not out.exists()
    # Its collision shape is drawn.
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(out), "--collision"])
    assert (result.exit_code, result.output) == (0, "")
    assert (_pixels(out.read_bytes()) != 255).any()


def test_a_robot_whose_shapes_cannot_be_drawn_has_nothing_to_draw(tmp_path: Path) -> None:
    robot = tmp_path / "lost.urdf"
    robot.write_text(
        '<robot name="lost"><link name="a"><visual><geometry><mesh filename="gone.stl"/>'
        "</geometry></visual></link></robot>"
    )
    scene = build_scene(fishbot_urdf.load(robot))
    assert scene.parts == ()
    gone, nothing = scene.findings  # nothing-drawn after the warning it speaks of
    assert gone.rule == "mesh-not-found"
    assert (nothing.rule, nothing.severity.value, nothing.where) == (
        "nothing-drawn",
        "error",
        f"{robot}:1:1",
    )
    assert nothing.message == (
        "robot 'lost': its only visual shape cannot be drawn: there is nothing to draw"
    )
    assert (nothing.hint, dict(nothing.data)) == (
        "its mesh file is not found: the mesh-not-found warning says where",
        {
            "kind": "visual",
            "visuals": 1,
            "collisions": 0,
            "other_drawable": 0,
            "meshes_not_found": 1,
            "packages": (),
        },
    )
    collision = build_scene(fishbot_urdf.load(robot), collision=True)
    [finding] = collision.findings
    assert (
        finding.message == "robot 'lost': no link has a collision shape: there is nothing to draw"
    )
    out = tmp_path / "lost.png"
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(out), "--collision"])
    assert result.exit_code == 1
    # Its one visual shape cannot be drawn either: it is not offered.
    assert result.stderr.splitlines()[-2].endswith("(give a link a <collision>) [nothing-drawn]")
    assert not out.exists()


MESHES_NOT_FOUND = """<robot name="lost">
  <link name="base_link">
    <visual><geometry><mesh filename="package://lost_description/meshes/base.stl"/></geometry></visual>
    <collision><geometry><mesh filename="package://lost_description/meshes/base.stl"/></geometry></collision>
  </link>
  <link name="wheel_link">
    <visual><geometry><mesh filename="meshes/wheel.stl"/></geometry></visual>
    <collision><geometry>{wheel}</geometry></collision>
  </link>
  <joint name="j" type="fixed"><parent link="base_link"/><child link="wheel_link"/></joint>
</robot>
"""


@pytest.mark.parametrize("collision", [False, True])
def test_meshes_not_found_are_said_and_the_other_kind_offered_only_when_it_draws(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, collision: bool
) -> None:
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    robot = tmp_path / "lost.urdf"
    robot.write_text(MESHES_NOT_FOUND.format(wheel='<mesh filename="meshes/wheel.stl"/>'))
    out = tmp_path / "lost.png"
    given = ["render", str(robot), "-o", str(out), *(["--collision"] if collision else [])]
    result = CliRunner().invoke(cli, given)
    kind = "collision" if collision else "visual"
    assert result.exit_code == 1
    assert result.stderr.splitlines()[-2] == (
        f"{robot}:1:1: error: robot 'lost': none of its 2 {kind} shapes can be drawn: there "
        "is nothing to draw (none of its mesh files is found: each mesh-not-found warning "
        "says where; give the folder of its package with --package lost_description=PATH) "
        "[nothing-drawn]"
    )
    assert not out.exists()
    # A collision box that can be drawn is offered, but only to a picture of the visuals.
    robot.write_text(MESHES_NOT_FOUND.format(wheel='<box size="0.1 0.1 0.1"/>'))
    result = CliRunner().invoke(cli, given)
    if collision:
        assert (result.exit_code, out.exists()) == (0, True)
        assert "[nothing-drawn]" not in result.stderr
        return
    assert result.exit_code == 1
    assert result.stderr.splitlines()[-2] == (
        f"{robot}:1:1: error: robot 'lost': none of its 2 visual shapes can be drawn: there "
        "is nothing to draw (none of its mesh files is found: each mesh-not-found warning "
        "says where; give the folder of its package with --package lost_description=PATH; "
        "`fishbot render --collision` draws 1 of its 2 collision shapes) [nothing-drawn]"
    )


def test_nothing_drawn_comes_after_the_warnings_it_speaks_of(tmp_path: Path) -> None:
    robot = tmp_path / "allmiss.urdf"
    robot.write_text(
        '<robot name="allmiss">\n'
        '  <link name="base"><visual><geometry><mesh filename="meshes/base.stl"/></geometry>'
        "</visual></link>\n"
        '  <link name="arm"><visual><geometry><mesh filename="meshes/arm.stl"/></geometry>'
        "</visual></link>\n"
        '  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>\n'
        "</robot>\n",
        encoding="utf-8",
    )
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(tmp_path / "t.png")])
    assert result.exit_code == 1
    beside = (
        "relative mesh names are read beside the robot file, as Gazebo, MuJoCo, PyBullet, "
        "pinocchio and yourdfpy read them), so it is not drawn (write package://PACKAGE/path "
        "for a file of a ROS package) [mesh-not-found]"
    )
    # By place, as check lists them; the error at the robot's first line, which says that
    # each mesh-not-found warning says where, after them.
    assert result.stderr.splitlines() == [
        f"{robot}:2:39: warning: link 'base': mesh 'meshes/base.stl' is not found (looked "
        f"for {tmp_path / 'meshes' / 'base.stl'}; {beside}",
        f"{robot}:3:38: warning: link 'arm': mesh 'meshes/arm.stl' is not found (looked "
        f"for {tmp_path / 'meshes' / 'arm.stl'}; {beside}",
        f"{robot}:1:1: error: robot 'allmiss': none of its 2 visual shapes can be drawn: there "
        "is nothing to draw (none of its mesh files is found: each mesh-not-found warning says "
        "where) [nothing-drawn]",
        "nothing written: fix the errors above first",
    ]


def test_a_configuration_that_ignores_nothing_drawn_gets_the_blank_picture(
    tmp_path: Path,
) -> None:
    (tmp_path / "frames.urdf").write_text(FRAMES)
    (tmp_path / "fishbot.toml").write_text('ignore = ["nothing-drawn"]\n')
    out = tmp_path / "frames.png"
    result = CliRunner().invoke(cli, ["render", str(tmp_path / "frames.urdf"), "-o", str(out)])
    assert (result.exit_code, result.output) == (0, "")
    assert (_pixels(out.read_bytes()) == 255).all()


def test_render_help_says_what_nothing_to_draw_does() -> None:
    result = CliRunner().invoke(cli, ["render", "--help"])
    text = " ".join(result.stdout.split())
    assert (
        "A robot with no shape to draw (no visuals, or none that can be drawn) is an error" in text
    )
    assert (
        "1 the robot has errors that leave its shape or tree in doubt, or nothing to draw "
        "(nothing is written)" in text
    )


def test_the_library_draws_the_picture_fishbot_render_draws(tmp_path: Path) -> None:
    first = FISHBOT / "urdf" / "first_robot.urdf"
    out = tmp_path / "cli.png"
    args = ["render", str(first), "-o", str(out), "--view", "front", "--size", "400x300"]
    assert CliRunner().invoke(cli, args).exit_code == 0
    robot = fishbot_urdf.load(first)
    data = fishbot_urdf.picture(robot, view="front", width=400, height=300)
    assert data == out.read_bytes()
    written = tmp_path / "deep" / "first.png"
    assert fishbot_urdf.picture(robot, written, view="front", width=400, height=300) == data
    assert written.read_bytes() == data
    with pytest.raises(fishbot_urdf.InputError, match="refusing to write over the input"):
        fishbot_urdf.picture(robot, first)  # the robot's own file


def test_the_library_picture_poses_the_joints_and_refuses_nothing_to_draw(
    tmp_path: Path,
) -> None:
    arm = tmp_path / "arm.urdf"
    arm.write_text(
        '<robot name="arm"><link name="a"><visual><geometry><box size="0.1 0.1 0.1"/>'
        '</geometry></visual></link><link name="b"><visual><origin xyz="0.5 0 0"/>'
        '<geometry><box size="1 0.1 0.1"/></geometry></visual></link>'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/>'
        '<limit lower="-2" upper="2" effort="1" velocity="1"/></joint></robot>'
    )
    robot = fishbot_urdf.load(arm)
    flat = _pixels(fishbot_urdf.picture(robot, view="front", width=200, height=200))
    up = _pixels(
        fishbot_urdf.picture(robot, view="front", width=200, height=200, positions={"j": -1.5708})
    )

    def aspect(p: np.ndarray) -> float:
        drawn = (p != 255).any(axis=2)
        return np.nonzero(drawn.any(axis=1))[0].size / np.nonzero(drawn.any(axis=0))[0].size

    assert aspect(flat) == pytest.approx(1.0, abs=0.1)  # end on, a square
    assert aspect(up) > 5  # raised, a tall bar
    with pytest.raises(fishbot_urdf.UnknownNameError):
        fishbot_urdf.picture(robot, positions={"elbow": 1.0})
    out = tmp_path / "nothing.png"
    with pytest.raises(fishbot_urdf.RobotError) as info:
        fishbot_urdf.picture(robot, out, collision=True)  # it has no collision shape
    [finding] = info.value.diagnostics
    assert (finding.rule, finding.severity.value) == ("nothing-drawn", "error")
    assert not out.exists()


# -- what RViz's "Mass Properties" show: a ball of lead and the box of the same inertia ---


def _red(pixels: np.ndarray) -> np.ndarray:
    """Where the picture is RViz's mass and inertia red (shaded, not blended with white)."""
    r, g, b = (pixels[..., i] for i in range(3))
    return (r > 70) & (g < 40) & (b < 40)


def _runs(row: np.ndarray) -> list[tuple[int, int]]:
    """The first and last column of each run of True in a row."""
    padded = np.concatenate([[False], row, [False]]).astype(int)
    starts = np.nonzero(np.diff(padded) == 1)[0]
    ends = np.nonzero(np.diff(padded) == -1)[0] - 1
    return list(zip(starts.tolist(), ends.tolist(), strict=True))


def _render(tmp_path: Path, robot: Path, *options: str) -> np.ndarray:
    out = tmp_path / "out.png"
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(out), *options])
    assert (result.exit_code, result.output) == (0, ""), result.stderr
    return _pixels(out.read_bytes())


def test_the_fishbots_inertia_boxes_are_sized_as_rviz_sizes_them(tmp_path: Path) -> None:
    pixels = _render(tmp_path, XACRO, "--show", "mass,inertia", "--view", "front")
    red = _red(pixels)
    assert red.mean() > 0.1
    assert not (_red(_render(tmp_path, XACRO, "--view", "front"))).any()  # not by default
    # Seen from the front (+x, orthographic), y to the right and z up. base_link is a
    # cylinder of 1 kg, r = 0.1 m, h = 0.12 m: ixx = iyy = m (3 r^2 + h^2) / 12 = 0.0037,
    # izz = m r^2 / 2 = 0.005. Its box: sqrt(6 (iyy + izz - ixx) / m) = sqrt(0.03) = 0.1732 m
    # wide (y), sqrt(6 (ixx + iyy - izz) / m) = 0.12 m high (z). Each wheel (0.1 kg,
    # r = 0.032, h = 0.04, its axis along y) has a box 0.04 m wide in y, at y = +-0.1:
    # the rows where the wheels' boxes meet the body's are 0.24 m wide (all red, from
    # y = -0.12 to 0.12); the body's rows above the wheels, 0.1732 m.
    widths = [end - start + 1 for row in red for start, end in _runs(row)]
    widest = max(widths)
    body = max(set(widths), key=widths.count)  # the most common width: the body's box
    assert body / widest == pytest.approx(math.sqrt(0.03) / 0.24, rel=0.02)
    # The body's box is 0.12 m high: its rows of that width, from the box's top down to
    # where the wheels' boxes begin (their axes at z = -0.06, 0.0554 m high: z = -0.0323).
    rows = [i for i, row in enumerate(red) if body in [e - s + 1 for s, e in _runs(row)]]
    metres = 0.24 / widest
    assert (max(rows) - min(rows) + 1) * metres == pytest.approx(0.06 + 0.0323, abs=0.004)
    # Centred on the robot, which is symmetric about y = 0.
    columns = np.nonzero(red.any(axis=0))[0]
    wide_row = next(row for row in red if red.shape[1] > 0 and row.sum() == widest)
    body_row = red[rows[len(rows) // 2]]
    middle = (columns.min() + columns.max()) / 2
    assert np.nonzero(body_row)[0].mean() == pytest.approx(middle, abs=1.5)
    assert np.nonzero(wide_row)[0].mean() == pytest.approx(middle, abs=1.5)


def test_the_fishbots_mass_is_a_ball_of_lead(tmp_path: Path) -> None:
    red = _red(_render(tmp_path, XACRO, "--show", "mass", "--view", "front"))

    # A ball of lead (11340 kg/m^3) of mass m has the diameter 2 (3 m / (4 pi 11340))^(1/3):
    # base_link's 1 kg, 0.0552 m; each wheel's 0.1 kg, 0.0256 m, at y = +-0.1, so the
    # picture is 0.2 + 0.0256 m wide.
    def diameter(mass: float) -> float:
        return float(2 * (3 * mass / (4 * math.pi * 11340)) ** (1 / 3))

    columns = np.nonzero(red.any(axis=0))[0]
    across = columns.max() - columns.min() + 1
    metres = (0.2 + diameter(0.1)) / across
    middle = round((columns.min() + columns.max()) / 2)
    # The body's ball: the widest run of red through the middle column.
    body = max(e - s + 1 for row in red if row[middle] for s, e in _runs(row) if s <= middle <= e)
    assert body * metres == pytest.approx(diameter(1.0), abs=2.5 * metres)


WRONG_INERTIAL = """\
<robot name="wrong">
  <material name="green"><color rgba="0 1 0 1"/></material>
  <link name="body">
    <visual>
      <geometry><cylinder radius="0.05" length="0.2"/></geometry>
      <material name="green"/>
    </visual>
    <inertial>
      <!-- the cylinder's own inertia, but its centre of mass written 0.3 m off the shape -->
      <origin xyz="0.3 0 0"/>
      <mass value="1"/>
      <inertia ixx="0.00395833" ixy="0" ixz="0" iyy="0.00395833" iyz="0" izz="0.00125"/>
    </inertial>
  </link>
</robot>
"""


def test_an_inertial_off_its_shape_is_seen_off_it(tmp_path: Path) -> None:
    robot = tmp_path / "wrong.urdf"
    robot.write_text(WRONG_INERTIAL, encoding="utf-8")
    pixels = _render(tmp_path, robot, "--show", "visual,inertia", "--view", "top")
    r, g, b = (pixels[..., i].astype(int) for i in range(3))
    green = (g > 70) & (r < 40) & (b < 40)
    red = (r > g + 60) & (r > b + 60)  # seen through, over the white background
    assert green.any() and red.any()
    # From the top: x is up the picture. The shape is a disc 0.1 m across at x = 0; the
    # box of its inertia (ixx = iyy = m (3 r^2 + h^2) / 12, izz = m r^2 / 2) is
    # sqrt(6 (iyy + izz - ixx) / m) = sqrt(0.0075) = 0.0866 m square, centred 0.3 m up.
    green_rows, red_rows = np.nonzero(green.any(axis=1))[0], np.nonzero(red.any(axis=1))[0]
    metres = 0.1 / (green_rows.max() - green_rows.min() + 1)
    apart = (green_rows.min() + green_rows.max()) / 2 - (red_rows.min() + red_rows.max()) / 2
    assert apart * metres == pytest.approx(0.3, abs=0.01)
    assert (red_rows.max() - red_rows.min() + 1) * metres == pytest.approx(0.0866, abs=0.006)
    assert red_rows.max() < green_rows.min()  # wholly off the shape
    red_columns, green_columns = np.nonzero(red.any(axis=0))[0], np.nonzero(green.any(axis=0))[0]
    assert (red_columns.min() + red_columns.max()) / 2 == pytest.approx(
        (green_columns.min() + green_columns.max()) / 2, abs=1.5
    )


TOO_BIG = """\
<robot name="big">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="base_link">
    <visual>
      <geometry><box size="0.1 0.1 0.1"/></geometry>
      <material name="blue"/>
    </visual>
    <inertial>
      <mass value="1"/>
      <inertia ixx="1.0" ixy="0" ixz="0" iyy="1.0" iyz="0" izz="1.0"/>
    </inertial>
  </link>
</robot>
"""


def test_an_inertia_far_too_big_lets_its_shape_be_seen_inside_it(tmp_path: Path) -> None:
    robot = tmp_path / "big.urdf"
    robot.write_text(TOO_BIG, encoding="utf-8")
    # 1 kg with ixx = iyy = izz = 1 kg*m^2 (the 0.1 m box's own is 0.00167): a cube
    # sqrt(6 (1 + 1 - 1) / 1) = 2.45 m across, around a shape 0.1 m across. Drawn with the
    # shape, it is seen through (alpha 0.4): the blue box shows in the middle of the red.
    pixels = _render(tmp_path, robot, "--show", "visual,inertia", "--view", "front")
    r, g, b = (pixels[..., i].astype(int) for i in range(3))
    height, width = r.shape
    blue = b > r + 20
    rows, columns = np.nonzero(blue)
    assert (rows.min() + rows.max()) / 2 == pytest.approx(height / 2, abs=2)
    assert (columns.min() + columns.max()) / 2 == pytest.approx(width / 2, abs=2)
    red = (r > g + 60) & (r > b + 60)
    across = np.nonzero(red[height // 2])[0]
    box_width = across.max() - across.min() + 1
    assert (columns.max() - columns.min() + 1) / box_width == pytest.approx(0.1 / 2.449, rel=0.1)
    assert g[blue].max() < 20  # the box's red over the shape's blue: no white in it
    # Alone, as RViz draws it: opaque red, the middle as red as the rest.
    alone = _render(tmp_path, robot, "--show", "inertia", "--view", "front")
    assert not (alone[..., 2].astype(int) > alone[..., 0].astype(int) + 20).any()
    assert _red(alone)[height // 2, width // 2]


def test_an_inertia_box_in_its_shapes_plane_tints_it_without_specks(tmp_path: Path) -> None:
    robot = tmp_path / "body.urdf"
    # The fishbot's body: a cylinder of r = 0.1 m, h = 0.12 m and its own inertia, whose box
    # (0.1732 x 0.1732 x 0.12 m) has its top and bottom in the planes of the cylinder's.
    robot.write_text(
        TOO_BIG.replace('<box size="0.1 0.1 0.1"/>', '<cylinder radius="0.1" length="0.12"/>')
        .replace('ixx="1.0"', 'ixx="0.0037"')
        .replace('iyy="1.0"', 'iyy="0.0037"')
        .replace('izz="1.0"', 'izz="0.005"'),
        encoding="utf-8",
    )
    pixels = _render(tmp_path, robot, "--show", "visual,inertia", "--size", "400x300")
    r, g, b = (pixels[..., i].astype(int) for i in range(3))
    shape = b > g + 40
    bare = shape & (r < 10)  # blue the box's red does not tint
    rows = np.nonzero(shape.any(axis=1))[0]
    cap = range(rows.min(), rows.min() + (rows.max() - rows.min()) * 3 // 10)
    # Across the top, the bare blue is the cylinder's rim past the box's sides, on the left
    # and the right: no specks of it where the box's top lies on the cap.
    assert max(len(_runs(bare[row])) for row in cap) <= 2
    assert bare[cap.start : cap.stop].any()


def test_an_inertia_no_solid_has_is_a_warning_and_no_box(tmp_path: Path) -> None:
    robot = tmp_path / "wrong.urdf"
    robot.write_text(WRONG_INERTIAL.replace('izz="0.00125"', 'izz="0.01"'), encoding="utf-8")
    out = tmp_path / "out.png"
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(out), "--show", "inertia"])
    # izz = 0.01 > ixx + iyy: no box has these moments; RViz draws none, and says so.
    assert result.exit_code == 1  # nothing else to draw
    assert (
        f"{robot}:8:5: warning: link 'body': inertial has no inertia box drawn (RViz draws "
        "none either): a principal moment of its inertia is larger than the other two "
        "together (no solid has such moments: compute the inertia again, from the part's "
        "shape and mass) [shape-not-drawn]"
    ) in result.stderr.splitlines()
    assert not out.exists()
    result = CliRunner().invoke(
        cli, ["render", str(robot), "-o", str(out), "--show", "visual,inertia"]
    )
    assert result.exit_code == 0 and "[shape-not-drawn]" in result.stderr
    assert not _red(_pixels(out.read_bytes())).any()


NO_BOXES = """\
<robot name="bad">
  <link name="base"/>
  <link name="negative">
    <inertial>
      <mass value="1"/>
      <inertia ixx="-1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
  </link>
  <link name="triangle">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.01"/>
    </inertial>
  </link>
  <link name="massless">
    <inertial>
      <mass value="0"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
    </inertial>
  </link>
  <joint name="a" type="fixed"><parent link="base"/><child link="negative"/></joint>
  <joint name="b" type="fixed"><parent link="base"/><child link="triangle"/></joint>
  <joint name="c" type="fixed"><parent link="base"/><child link="massless"/></joint>
</robot>
"""


def test_each_inertial_without_a_box_is_told_why(tmp_path: Path) -> None:
    robot = tmp_path / "bad.urdf"
    robot.write_text(NO_BOXES, encoding="utf-8")
    out = tmp_path / "out.png"
    result = CliRunner().invoke(
        cli, ["render", str(robot), "-o", str(out), "--show", "mass,inertia,frames"]
    )
    assert result.exit_code == 0
    no_box = "inertial has no inertia box drawn (RViz draws none either)"
    assert result.stderr.splitlines() == [
        f"{robot}:4:5: warning: link 'negative': {no_box}: its inertia is not positive "
        "definite: ixx, ixx*iyy - ixy^2 and the determinant are not all above 0 (a moment is "
        "negative or 0, or a product too large: compute the inertia again, from the part's "
        "shape and mass) [shape-not-drawn]",
        f"{robot}:10:5: warning: link 'triangle': {no_box}: a principal moment of its inertia "
        "is larger than the other two together (no solid has such moments: compute the "
        "inertia again, from the part's shape and mass) [shape-not-drawn]",
        # RViz draws no box for a mass of 0, whatever the inertia
        f"{robot}:16:5: warning: link 'massless': {no_box}: its mass, 0 kg, is not positive "
        "(give the link its mass in kg; a link that carries no mass needs no <inertial>) "
        "[shape-not-drawn]",
    ]
    assert out.exists()


def test_show_frames_draws_each_links_axes_small_beside_a_small_arm(tmp_path: Path) -> None:
    arm = tmp_path / "arm.urdf"
    link = (
        '<link name="{0}"><visual><origin xyz="0 0 0.01"/>'
        '<geometry><box size="0.01 0.01 0.02"/></geometry><material name="grey"/></visual></link>'
    )
    arm.write_text(
        '<robot name="small"><material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>'
        + "".join(link.format(name) for name in ("a", "b", "c"))
        + '<joint name="j1" type="revolute"><parent link="a"/><child link="b"/>'
        '<origin xyz="0 0 0.02"/><axis xyz="0 1 0"/>'
        '<limit lower="-2" upper="2" effort="1" velocity="1"/></joint>'
        '<joint name="j2" type="revolute"><parent link="b"/><child link="c"/>'
        '<origin xyz="0 0 0.02"/><axis xyz="0 1 0"/>'
        '<limit lower="-2" upper="2" effort="1" velocity="1"/></joint></robot>',
        encoding="utf-8",
    )
    plain = _render(tmp_path, arm, "--view", "side")
    framed = _render(tmp_path, arm, "--show", "visual,frames", "--view", "side")
    r, g, b = (framed[..., i] for i in range(3))
    assert ((r > 70) & (g < 40) & (b < 40)).any()  # the x axes: drawn
    assert not ((plain[..., 0] > 70) & (plain[..., 1] < 40)).any()

    def aspect(pixels: np.ndarray) -> float:
        rows, columns = np.nonzero((pixels < 250).any(axis=2))
        return float((columns.max() - columns.min() + 1) / (rows.max() - rows.min() + 1))

    # From the side (+y), x to the left: the arm is 1 cm wide and 6 cm high. Its axes are
    # a tenth of its size (the diagonal of its box, sqrt(0.01^2 + 0.01^2 + 0.06^2) m),
    # 6.2 mm long: each x axis reaches 1.2 mm past the arm's side, where RViz's 10 cm axes
    # would make the picture ten times as wide.
    axes = 0.1 * math.sqrt(0.01**2 + 0.01**2 + 0.06**2)
    assert aspect(framed) / aspect(plain) == pytest.approx((0.005 + axes) / 0.01, rel=0.05)


def test_the_library_names_the_layers_it_can_show() -> None:
    with pytest.raises(fishbot_urdf.ArgumentError) as caught:
        build_scene(fishbot_urdf.load(FISHBOT / "urdf" / "first_robot.urdf"), show=("weight",))
    assert caught.value.message == (
        "nothing to show called 'weight' (visual, collision, mass, inertia, frames, sensors, "
        "gazebo)"
    )
    with pytest.raises(fishbot_urdf.ArgumentError) as caught:
        build_scene(fishbot_urdf.load(XACRO), show=("inerta",))
    assert caught.value.message == (
        "nothing to show called 'inerta' (did you mean 'inertia'? visual, collision, mass, "
        "inertia, frames, sensors, gazebo)"
    )
    with pytest.raises(fishbot_urdf.ArgumentError, match="nothing to show: name one of"):
        build_scene(fishbot_urdf.load(XACRO), show=())
    scene = build_scene(fishbot_urdf.load(XACRO), show=("mass",), collision=True)
    assert {part.layer for part in scene.parts} == {"mass", "collision"}


def test_an_inertial_of_wild_numbers_is_warned_of_not_a_numpy_warning(tmp_path: Path) -> None:
    robot = tmp_path / "wild.urdf"
    robot.write_text(
        '<robot name="wild"><link name="a"><visual><geometry><box size="0.1 0.1 0.1"/>'
        '</geometry></visual><inertial><mass value="1e300"/><inertia ixx="1e300" ixy="1e200" '
        'ixz="0" iyy="1e300" iyz="0" izz="1e300"/></inertial></link></robot>',
        encoding="utf-8",
    )
    out = tmp_path / "wild.png"
    result = CliRunner().invoke(
        cli, ["render", str(robot), "-o", str(out), "--show", "visual,mass,inertia"]
    )
    # ixx iyy - ixy^2 overflows (inf - inf): no box, as RViz's doubles find none either; the
    # ball of 1e300 kg of lead is 1e98 m across, farther than anything is drawn.
    assert result.exit_code == 0
    lines = result.stderr.splitlines()
    assert len(lines) == 2 and all(line.endswith("[shape-not-drawn]") for line in lines)
    assert "has no inertia box drawn" in lines[0] and "is not drawn" in lines[1]
    assert out.exists()
