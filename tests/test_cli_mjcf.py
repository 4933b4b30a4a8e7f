"""`fishbot mjcf`: the MJCF on standard output or in a file, the findings on stderr."""

from __future__ import annotations

from pathlib import Path

import mujoco
from click.testing import CliRunner
from conftest import FISHBOT

import fishbot_urdf
from fishbot_urdf.cli import cli
from fishbot_urdf.export.mjcf import to_mjcf

XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"
FIRST = FISHBOT / "urdf" / "first_robot.urdf"
WHEEL = """<robot name="r">
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="wheel">
    <collision><geometry><cylinder radius="0.03" length="0.02"/></geometry></collision>
  </link>
  <joint name="axle" type="continuous"><parent link="base"/><child link="wheel"/></joint>
</robot>
"""


def _mjcf(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["mjcf", *args])
    return result.exit_code, result.stdout, result.stderr


def test_standard_output_is_the_library_s_mjcf() -> None:
    code, out, err = _mjcf(str(XACRO))
    assert (code, err) == (0, "")
    assert out == to_mjcf(fishbot_urdf.load(XACRO))
    code, fixed, _ = _mjcf(str(XACRO), "--fixed-base")
    assert code == 0 and "freejoint" not in fixed
    mujoco.MjModel.from_xml_string(fixed)


def test_a_file_is_written_and_loads(tmp_path: Path) -> None:
    target = tmp_path / "build" / "fishbot.xml"
    code, out, err = _mjcf(str(XACRO), "-o", str(target))
    assert (code, out, err) == (0, "", "")
    model = mujoco.MjModel.from_xml_path(str(target))
    assert model.nbody == 12


def test_what_mujoco_refuses_and_what_is_left_out_are_findings(tmp_path: Path) -> None:
    # a moving link without <inertial>: MuJoCo refuses it, and no mass is made up for it
    wheel = tmp_path / "wheel.urdf"
    wheel.write_text(WHEEL)
    code, out, err = _mjcf(str(wheel), "-o", str(tmp_path / "wheel.xml"))
    assert (code, out) == (1, "")  # written, and MuJoCo refuses it
    assert (tmp_path / "wheel.xml").exists()
    assert err == (
        f"{wheel}:4:3: error: link 'wheel' has collision geometry and moves (joint 'axle' is "
        "continuous) but no <inertial> (Gazebo drops it with everything below it, as it drops "
        "one of mass 0; give it one computed from its collision shapes; `fishbot inertia ROBOT "
        "--fill --mass LINK=KG` says what to write and where, and with -o OUT writes a filled "
        "copy) [missing-inertial]\n"
        f"{wheel}:4:3: error: link 'wheel': it moves, and neither it nor a link fixed to it has "
        "mass: MuJoCo refuses the model (give it the mass and inertia of its shape) "
        "[mjcf-refused]\n"
    )
    robot = tmp_path / "robot.urdf"
    (tmp_path / "part.dae").write_bytes(b"")
    robot.write_text(
        '<robot name="r">\n  <link name="a">\n'
        '    <visual><geometry><mesh filename="part.dae"/></geometry></visual>\n'
        "  </link>\n</robot>\n"
    )
    code, out, err = _mjcf(str(robot), "--fixed-base")
    assert code == 0 and "<geom" not in out
    assert err == (
        f"{robot}:3:23: warning: link 'a': visual mesh 'part.dae' is a .dae file, which MuJoCo "
        "cannot read: left out of the MJCF (export it as binary STL or OBJ; or write the MJCF "
        "to a file (-o FILE), which converts it into a folder beside it) [mjcf-left-out]\n"
    )


def test_never_over_the_robot_and_a_broken_robot_writes_nothing(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(FIRST.read_text())
    code, _, err = _mjcf(str(robot), "-o", str(robot))
    assert code == 2 and err.count("\n") == 1
    assert robot.read_text() == FIRST.read_text()
    broken = tmp_path / "broken.urdf"
    broken.write_text(
        '<robot name="r"><link name="a"/><joint name="j" type="fixed">'
        '<parent link="a"/><child link="b"/></joint></robot>'
    )
    code, out, err = _mjcf(str(broken), "-o", str(tmp_path / "out.xml"))
    assert (code, out) == (1, "") and "[undefined-link]" in err
    assert not (tmp_path / "out.xml").exists()


ASCII_TETRAHEDRON = """solid part
facet normal 0 0 0
outer loop
vertex 0.0 0.0 0.0
vertex 0.5 0.0 0.0
vertex 0.0 0.5 0.0
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 0.0 0.0 0.0
vertex 0.0 0.5 0.0
vertex 0.0 0.0 0.25
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 0.0 0.0 0.0
vertex 0.0 0.0 0.25
vertex 0.5 0.0 0.0
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 0.5 0.0 0.0
vertex 0.0 0.5 0.0
vertex 0.0 0.0 0.25
endloop
endfacet
endsolid part
"""


def test_a_mesh_mujoco_cannot_read_is_converted_beside_the_file(tmp_path: Path) -> None:
    (tmp_path / "robot_meshes").mkdir()
    (tmp_path / "robot_meshes" / "part.stl").write_text(ASCII_TETRAHEDRON)
    robot = tmp_path / "robot_meshes" / "robot.urdf"
    robot.write_text(
        '<robot name="r">\n  <link name="a">\n'
        '    <visual><geometry><mesh filename="part.stl"/></geometry></visual>\n'
        "  </link>\n</robot>\n"
    )
    out = tmp_path / "build" / "robot.xml"
    code, out_text, err = _mjcf(str(robot), "--fixed-base", "-o", str(out))
    assert (code, out_text) == (0, "")
    assert err == (
        f"{robot}:3:23: note: link 'a': visual mesh 'part.stl' is an ASCII STL, which MuJoCo "
        "cannot read: converted to part.stl in the mesh folder (export it as binary STL or OBJ "
        "to have MuJoCo read it where it is) [mjcf-mesh-converted]\n"
    )
    assert sorted(p.name for p in (tmp_path / "build").iterdir()) == ["robot.xml", "robot_meshes"]
    model = mujoco.MjModel.from_xml_path(str(out))
    assert (model.nmesh, model.mesh_facenum.tolist()) == (1, [4])
    # robot.xml beside robot_meshes/, which holds the robot's files: refused, and nothing
    # written
    code, _, err = _mjcf(str(robot), "-o", str(tmp_path / "robot.xml"))
    assert (code, err) == (
        2,
        f"{tmp_path / 'robot_meshes'}: error: refusing to write converted meshes into the "
        f"folder of the input {robot} [io]\n",
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["build", "robot_meshes"]
    assert sorted(p.name for p in (tmp_path / "robot_meshes").iterdir()) == [
        "part.stl",
        "robot.urdf",
    ]
