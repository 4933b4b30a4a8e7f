"""robots/fishbot is a ROS 2 package a learner can drop into a colcon workspace."""

from __future__ import annotations

import re

import yaml
from conftest import FISHBOT

import fishbot_urdf
from fishbot_urdf.config import Config
from fishbot_urdf.packages import package_name

FISHBOT_XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"


def test_package_manifest_and_build_file() -> None:
    assert package_name(FISHBOT / "package.xml") == "fishbot_description"
    manifest = (FISHBOT / "package.xml").read_text(encoding="utf-8")
    assert "<build_type>ament_cmake</build_type>" in manifest
    cmake = (FISHBOT / "CMakeLists.txt").read_text(encoding="utf-8")
    installed = re.search(r"install\(\s*DIRECTORY\s+([^)]*?)\s+DESTINATION", cmake)
    assert installed is not None
    assert set(installed.group(1).split()) == {"launch", "urdf", "config"}


def test_launch_file_compiles_and_uses_the_xacro_model() -> None:
    source = (FISHBOT / "launch" / "display_robot.launch.py").read_text(encoding="utf-8")
    compile(source, "display_robot.launch.py", "exec")
    for needed in ("'model'", "fishbot.urdf.xacro", "robot_state_publisher", "rviz2"):
        assert needed in source


def test_gazebo_launch_file_compiles_and_spawns_the_xacro_model() -> None:
    source = (FISHBOT / "launch" / "gazebo_sim.launch.py").read_text(encoding="utf-8")
    compile(source, "gazebo_sim.launch.py", "exec")
    for needed in ("fishbot.urdf.xacro", "gazebo.launch.py", "spawn_entity.py", "use_sim_time"):
        assert needed in source
    manifest = (FISHBOT / "package.xml").read_text(encoding="utf-8")
    for package in ("gazebo_ros", "gazebo_plugins"):
        assert f"<exec_depend>{package}</exec_depend>" in manifest


def test_the_fishbot_is_for_gazebo_and_clean_under_every_rule_and_target() -> None:
    for targets in (None, ("all",)):
        result = fishbot_urdf.check_file(
            FISHBOT_XACRO, config=Config(select=("ALL",), targets=targets)
        )
        assert result.ok and result.diagnostics == (), targets
        assert "gazebo" in result.targets or targets == ("all",)


def test_rviz_config() -> None:
    config = yaml.safe_load((FISHBOT / "config" / "display_robot_model.rviz").read_text())
    manager = config["Visualization Manager"]
    assert manager["Global Options"]["Fixed Frame"] == "base_footprint"
    classes = {display["Class"] for display in manager["Displays"]}
    assert {"rviz_default_plugins/RobotModel", "rviz_default_plugins/TF"} <= classes


def test_every_robot_in_the_package_checks_clean() -> None:
    robots = [
        *sorted((FISHBOT / "urdf").rglob("*.urdf")),
        FISHBOT / "urdf" / "first_robot.urdf.xacro",
        FISHBOT_XACRO,
    ]
    for path in robots:
        result = fishbot_urdf.check_file(path)
        assert result.ok and result.diagnostics == (), path
