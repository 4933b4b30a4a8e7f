"""The rules on what sdformat's URDF converter loses or moves: each rule's failing example is
reported where it is written and its fixed one is clean, and the real converter (`ign sdf -p`,
sdformat 12), where it is installed, shows the loss in what it writes."""

from __future__ import annotations

import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import live_tool

from fishbot_urdf.catalog import Rule
from fishbot_urdf.catalog.conversion import (
    GAZEBO_DROPPED_LINK,
    GAZEBO_LUMPED_LINK,
    GAZEBO_LUMPING_FLAG,
    GAZEBO_MIMIC,
    GAZEBO_MODEL_PATH,
    GAZEBO_PLUGIN_LINK,
)
from fishbot_urdf.cli import cli


def _write(tmp_path: Path, text: str, name: str = "robot.urdf") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _check(path: Path, *args: str) -> tuple[int, str]:
    """`fishbot check` for Gazebo: its exit status and its findings (stderr)."""
    result = CliRunner().invoke(
        cli, ["check", "--isolated", "--target", "gazebo", *args, str(path)]
    )
    return result.exit_code, result.stderr


def _sdf(tmp_path: Path, text: str) -> ET.Element:
    """The model `ign sdf -p` writes for ``text`` (skipped where ign is not installed)."""
    ign = live_tool("ign", "ignition-tools libsdformat-dev")
    if ign is None:
        pytest.skip("ign is not installed")
    path = _write(tmp_path, text, "live.urdf")
    run = subprocess.run(
        [ign, "sdf", "-p", str(path)], capture_output=True, text=True, timeout=120, check=False
    )
    assert run.returncode == 0, run.stderr  # it exits 0 whatever it leaves out
    # (it writes a tag XML cannot read, <ignition::corrected_offsets>, beside moved offsets)
    model = ET.fromstring(run.stdout.replace("ignition::", "ignition_")).find("model")
    assert model is not None
    return model


def _links(model: ET.Element) -> list[str]:
    return [link.get("name", "") for link in model.findall("link")]


def _numbers(text: str | None) -> list[float]:
    return [float(v) for v in (text or "").split()]


# -- each rule's examples ------------------------------------------------------------------

REPORTED = {
    GAZEBO_MIMIC: "11:83: warning: joint 'right_joint' follows 'left_joint' by <mimic>, which "
    "sdformat 12's converter leaves out: in Gazebo Fortress and Classic it moves on its own "
    "(drive it with a controller or plugin of its own, or use Gazebo Harmonic (sdformat 14), "
    "whose converter keeps it) [gazebo-mimic]",
    GAZEBO_DROPPED_LINK: "4:3: error: link 'arm_mount' is fixed to 'base_link' (joint "
    "'mount_joint') and has no mass, nor has anything fixed below it: sdformat's converter goes "
    "no further down the tree, so Gazebo leaves out 'arm' below it (give 'arm_mount' a mass, or "
    "hang what moves below it on 'base_link') [gazebo-dropped-link]",
    GAZEBO_LUMPING_FLAG: "8:11: warning: <gazebo reference='camera_link'>: <preserveFixedJoint> "
    "does nothing on a link: the converter reads it on a fixed joint's name only (write it in "
    "<gazebo reference='camera_joint'>) [gazebo-lumping-flag]",
    GAZEBO_LUMPED_LINK: "8:11: warning: link 'camera_link' is lumped into 'base_link' (at xyz "
    "0.1 0 0.05 rpy 0 0 0): Gazebo puts sensor 'camera' (camera) in link 'base_link' at xyz 0.1 0 "
    "0.05 rpy 0 0 0, and its plugin 'camera' (libgazebo_ros_camera.so), which names no "
    "<frame_name>, stamps its messages with frame 'base_link' (write "
    "<frame_name>camera_link</frame_name> in the plugin, or keep link 'camera_link' with "
    "<preserveFixedJoint>true</preserveFixedJoint> in <gazebo reference='camera_joint'>) "
    "[gazebo-lumped-link]",
    GAZEBO_PLUGIN_LINK: "9:5: error: plugin 'ground_truth' (libgazebo_ros_p3d.so): <body_name> "
    "names link 'camera_link', which the converter lumps into 'base_link' (at xyz 0.1 0 0.05 rpy "
    "0 0 0) without renaming it here: Gazebo has no link 'camera_link' (name 'base_link', or "
    "keep link 'camera_link' with <preserveFixedJoint> in <gazebo reference='camera_joint'>) "
    "[gazebo-plugin-link]",
}


@pytest.mark.parametrize("rule", list(REPORTED), ids=[r.id for r in REPORTED])
def test_the_failing_example_is_reported_where_it_is_written(tmp_path: Path, rule: Rule) -> None:
    path = _write(tmp_path, rule.bad)
    status, found = _check(path)
    assert found == f"{path}:{REPORTED[rule]}\n"
    assert status == (1 if rule.severity.value == "error" else 0)


@pytest.mark.parametrize("rule", list(REPORTED), ids=[r.id for r in REPORTED])
def test_the_fixed_example_is_clean(tmp_path: Path, rule: Rule) -> None:
    assert _check(_write(tmp_path, rule.good)) == (0, "")


# -- what the real converter does to them --------------------------------------------------


def test_the_converter_leaves_out_a_moving_link_below_a_massless_mount(tmp_path: Path) -> None:
    assert _links(_sdf(tmp_path, GAZEBO_DROPPED_LINK.bad)) == ["base_link"]
    model = _sdf(tmp_path, GAZEBO_DROPPED_LINK.good)
    assert _links(model) == ["base_link", "arm"]
    assert [j.get("name") for j in model.findall("joint")] == ["arm_joint"]


def test_the_converter_lumps_a_link_whose_block_asks_to_keep_its_joint(tmp_path: Path) -> None:
    assert _links(_sdf(tmp_path, GAZEBO_LUMPING_FLAG.bad)) == ["base_link"]
    model = _sdf(tmp_path, GAZEBO_LUMPING_FLAG.good)
    assert _links(model) == ["base_link", "camera_link"]
    assert [(j.get("name"), j.get("type")) for j in model.findall("joint")] == [
        ("camera_joint", "fixed")
    ]


def test_the_converter_moves_a_lumped_links_sensor_to_the_link_above(tmp_path: Path) -> None:
    model = _sdf(tmp_path, GAZEBO_LUMPED_LINK.bad)
    assert _links(model) == ["base_link"]
    sensor = model.find("link[@name='base_link']/sensor[@name='camera']")
    assert sensor is not None
    # the reported pose: camera_joint's origin
    assert _numbers(sensor.findtext("pose")) == [0.1, 0, 0.05, 0, 0, 0]
    plugin = sensor.find("plugin")
    assert plugin is not None and plugin.find("frame_name") is None  # the frame: its link's
    fixed = _sdf(tmp_path, GAZEBO_LUMPED_LINK.good)
    assert fixed.findtext("link/sensor/plugin/frame_name") == "camera_link"


def test_the_converter_leaves_a_plugins_body_name_naming_a_lumped_link(tmp_path: Path) -> None:
    model = _sdf(tmp_path, GAZEBO_PLUGIN_LINK.bad)
    assert _links(model) == ["base_link"]
    assert model.findtext("plugin/body_name") == "camera_link"
    assert _links(_sdf(tmp_path, GAZEBO_PLUGIN_LINK.good)) == ["base_link"]


# -- the mass rules and this one, and the plugin names the converter renames -------------

_WHEEL = """\
<robot name="fishbot">
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="wheel">{wheel}</link>
  <joint name="wheel_joint" type="continuous"><axis xyz="0 1 0"/>
    <parent link="base_link"/><child link="wheel"/></joint>
  <link name="tyre">
    <inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/>
    </inertial></link>
  <joint name="tyre_joint" type="continuous"><axis xyz="0 1 0"/>
    <parent link="wheel"/><child link="tyre"/></joint>
</robot>
"""
_CYLINDER = '<collision><geometry><cylinder radius="0.03" length="0.02"/></geometry></collision>'


def test_a_moving_link_without_inertial_is_the_mass_rules_alone(tmp_path: Path) -> None:
    status, found = _check(_write(tmp_path, _WHEEL.format(wheel=_CYLINDER)))
    assert status == 1
    assert "[missing-inertial]" in found
    assert "[gazebo-dropped-link]" not in found


def test_a_moving_link_with_no_shape_nor_mass_is_this_rules(tmp_path: Path) -> None:
    # no mass rule speaks of a link with neither collision nor inertial; Gazebo drops it,
    # and the link with mass below it
    path = _write(tmp_path, _WHEEL.format(wheel=""))
    assert _check(path) == (
        1,
        f"{path}:5:3: error: link 'wheel' has no mass, and nothing is fixed to it: Gazebo leaves "
        "it out, and with it 'tyre' (give 'wheel', or a link fixed to it, a mass) "
        "[gazebo-dropped-link]\n",
    )
    assert _links(_sdf(tmp_path, _WHEEL.format(wheel=""))) == ["base_link"]


_BODY_NAME = """\
<robot name="fishbot">
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed"><origin xyz="0 0 0.2"/>
    <parent link="base_link"/><child link="imu_link"/></joint>
  <gazebo><plugin name="imu" filename="libgazebo_ros_imu.so">
    <bodyName>imu_link</bodyName></plugin></gazebo>
</robot>
"""


def test_a_body_name_the_converter_renames_is_not_reported(tmp_path: Path) -> None:
    assert _check(_write(tmp_path, _BODY_NAME)) == (0, "")
    plugin = _sdf(tmp_path, _BODY_NAME).find("plugin")
    assert plugin is not None
    assert plugin.findtext("bodyName") == "base_link"
    assert _numbers(plugin.findtext("xyzOffset")) == [0, 0, 0.2]


_GRAVITY = """\
<robot name="fishbot">
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="arm">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="arm_joint" type="revolute"><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <parent link="base_link"/><child link="arm"/></joint>
  <link name="balloon">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="balloon_joint" type="fixed"><origin xyz="0 0 0.3"/>
    <parent link="arm"/><child link="balloon"/></joint>
  <gazebo reference="balloon"><gravity>false</gravity></gazebo>
  <gazebo reference="arm_joint"><disableFixedJointLumping>true</disableFixedJointLumping></gazebo>
</robot>
"""


def test_a_lumped_links_gravity_is_the_whole_links(tmp_path: Path) -> None:
    path = _write(tmp_path, _GRAVITY)
    assert _check(path) == (
        0,
        f"{path}:16:11: warning: link 'balloon' is lumped into 'arm' (at xyz 0 0 0.3 rpy 0 0 0): "
        "Gazebo applies the block's <gravity> to all of link 'arm' (write it in <gazebo "
        "reference='arm'> if meant for that link, or keep link 'balloon' with "
        "<preserveFixedJoint>true</preserveFixedJoint> in <gazebo reference='balloon_joint'>) "
        "[gazebo-lumped-link]\n"
        f"{path}:17:11: warning: <gazebo reference='arm_joint'>: <disableFixedJointLumping> does "
        "nothing on a revolute joint: the converter lumps only fixed joints (leave it out) "
        "[gazebo-lumping-flag]\n",
    )
    model = _sdf(tmp_path, _GRAVITY)
    assert _links(model) == ["base_link", "arm"]
    assert model.findtext("link[@name='arm']/gravity") == "false"  # the arm's, not the balloon's
    assert [j.get("type") for j in model.findall("joint")] == ["revolute"]


# -- package:// meshes Gazebo looks for as model:// ----------------------------------------


def _package(tmp_path: Path, folder: str, export: str = "") -> Path:
    """A package fishbot_description in ``tmp_path/folder`` with the mesh the example names,
    and the example robot in it."""
    package = tmp_path / folder
    (package / "meshes").mkdir(parents=True)
    (package / "meshes" / "base_link.stl").write_text("solid box\nendsolid box\n")
    (package / "package.xml").write_text(
        f"<package><name>fishbot_description</name><export>{export}</export></package>\n"
    )
    return _write(package, GAZEBO_MODEL_PATH.bad)


def test_a_package_mesh_is_a_model_uri_gazebo_looks_up(tmp_path: Path) -> None:
    robot = _package(tmp_path, "fishbot_description")
    env = {"GZ_SIM_RESOURCE_PATH": "", "IGN_GAZEBO_RESOURCE_PATH": "", "GAZEBO_MODEL_PATH": ""}
    result = CliRunner().invoke(
        cli, ["check", "--isolated", "--target", "gazebo", str(robot)], env=env
    )
    assert (result.exit_code, result.stderr) == (
        0,
        f"{robot}:4:23: warning: link 'base_link': mesh "
        "'package://fishbot_description/meshes/base_link.stl' is "
        "model://fishbot_description/meshes/base_link.stl to Gazebo, which looks for folder "
        "'fishbot_description' on GZ_SIM_RESOURCE_PATH (Gazebo Classic: GAZEBO_MODEL_PATH), and "
        f'{tmp_path} is on neither (add <gazebo_ros gazebo_model_path="${{prefix}}/.."/> to the '
        f"<export> of {robot.parent / 'package.xml'}, or put {tmp_path} on the path) "
        "[gazebo-model-path]\n",
    )
    # the folder above the package on Gazebo's path: found
    env["GZ_SIM_RESOURCE_PATH"] = str(tmp_path)
    result = CliRunner().invoke(
        cli, ["check", "--isolated", "--target", "gazebo", str(robot)], env=env
    )
    assert (result.exit_code, result.stderr) == (0, "")
    model = _sdf(tmp_path, GAZEBO_MODEL_PATH.bad)
    assert model.findtext("link/visual/geometry/mesh/uri") == (
        "model://fishbot_description/meshes/base_link.stl"
    )
    fixed = _sdf(tmp_path, GAZEBO_MODEL_PATH.good)
    assert fixed.findtext("link/visual/geometry/mesh/uri") == "meshes/base_link.stl"


def test_a_package_that_exports_its_model_path_is_found(tmp_path: Path) -> None:
    robot = _package(tmp_path, "src", '<gazebo_ros gazebo_model_path="${prefix}/.."/>')
    assert _check(robot) == (0, "")


def test_a_package_in_a_folder_of_another_name_is_found_only_installed(tmp_path: Path) -> None:
    robot = _package(tmp_path, "fishbot-description")
    status, found = _check(robot)
    assert status == 0
    assert (
        "; its folder is named 'fishbot-description', so Gazebo finds it only where it is "
        "installed, as share/fishbot_description (add" in found
    )
    assert found.endswith(", and install the package) [gazebo-model-path]\n")


def test_where_gazebo_looks_for_meshes_is_judged_only_for_gazebo(tmp_path: Path) -> None:
    # a robot with no <gazebo> block is checked for ROS alone; `fishbot sdf` writes for Gazebo
    robot = _package(tmp_path, "fishbot_description")
    env = {"GZ_SIM_RESOURCE_PATH": "", "IGN_GAZEBO_RESOURCE_PATH": "", "GAZEBO_MODEL_PATH": ""}
    checked = CliRunner().invoke(cli, ["check", "--isolated", "-q", str(robot)], env=env)
    assert (checked.exit_code, checked.stderr) == (0, "")
    converted = CliRunner().invoke(cli, ["sdf", str(robot)], env=env)
    assert converted.exit_code == 0
    assert converted.stderr.endswith("[gazebo-model-path]\n")
    assert converted.stderr.count("\n") == 1


_KG = (
    '<inertial><mass value="1"/>'
    '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'
)


def test_a_finding_about_the_second_block_on_a_link_is_at_that_block(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        f"""<robot name="r">
  <link name="base">{_KG}</link>
  <link name="cam">{_KG}</link>
  <joint name="j" type="fixed"><parent link="base"/><child link="cam"/></joint>
  <gazebo reference="cam"><material>Gazebo/Red</material></gazebo>
  <gazebo reference="cam"><preserveFixedJoint>true</preserveFixedJoint></gazebo>
</robot>
""",
    )
    status, err = _check(path)
    assert (status, err.split(": warning:")[0]) == (0, f"{path}:6:11")
    assert err.rstrip().endswith("[gazebo-lumping-flag]")


def test_a_dropped_links_hint_names_its_parent_in_the_urdf(tmp_path: Path) -> None:
    # mount hangs on base, which is lumped into footprint: moving arm up means base
    path = _write(
        tmp_path,
        f"""<robot name="r">
  <link name="footprint"/>
  <link name="base">{_KG}</link>
  <link name="mount"/>
  <link name="arm">{_KG}</link>
  <joint name="b" type="fixed"><parent link="footprint"/><child link="base"/></joint>
  <joint name="m" type="fixed"><parent link="base"/><child link="mount"/></joint>
  <joint name="a" type="continuous"><parent link="mount"/><child link="arm"/></joint>
</robot>
""",
    )
    status, err = _check(path)
    assert status == 1
    assert (
        "(give 'mount' a mass, or hang what moves below it on 'base') [gazebo-dropped-link]" in err
    )


def test_sdf_says_a_block_on_nothing_is_dropped_with_its_sensor(tmp_path: Path) -> None:
    text = f"""<robot name="r">
  <link name="base">{_KG}</link>
  <gazebo reference="bse"><sensor name="imu_sensor" type="imu">
    <plugin name="imu" filename="libgazebo_ros_imu_sensor.so"/></sensor></gazebo>
</robot>
"""
    path = _write(tmp_path, text)
    result = CliRunner().invoke(cli, ["sdf", str(path)])
    assert (result.exit_code, result.stderr) == (
        0,
        f"{path}:3:11: error: <gazebo reference> names link or joint 'bse', which the robot does "
        "not have: Gazebo's converter drops the block without a word, and with it sensor "
        "'imu_sensor', plugin 'imu' (did you mean 'base'?) [unknown-reference]\n",
    )
    model = _sdf(tmp_path, text)  # the real converter's output
    assert model.find(".//sensor") is None and model.find(".//plugin") is None


def test_the_converter_writes_a_mimic_joint_as_a_joint_of_its_own(tmp_path: Path) -> None:
    model = _sdf(tmp_path, GAZEBO_MIMIC.bad)
    (joint,) = model.findall("joint[@name='right_joint']")
    assert joint.get("type") == "prismatic"
    assert not [e for e in joint.iter() if "mimic" in e.tag]
