"""`fishbot_urdf.targets` and `fishbot check --target`: an error that harms only programs
the robot is not for is a warning; a robot written for Gazebo is for Gazebo."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from fishbot_urdf import Config, ConfigError, check_file, load_config
from fishbot_urdf.catalog import Consumer
from fishbot_urdf.cli import cli
from fishbot_urdf.diagnostics import Severity
from fishbot_urdf.errors import UnknownNameError
from fishbot_urdf.targets import TARGETS, consumers_of, target_name, targets_of

# An arm for MoveIt: collision shapes for planning, no inertials.
KINEMATIC = """\
<robot name="arm">
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="upper">
    <collision><geometry><cylinder radius="0.03" length="0.3"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="upper"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>
"""
DIFF_DRIVE = """\
  <gazebo>
    <plugin name="drive" filename="libgazebo_ros_diff_drive.so"/>
  </gazebo>
</robot>
"""
SIMULATED = KINEMATIC.replace("</robot>\n", DIFF_DRIVE)


def run(*args: str) -> tuple[int, str]:
    result = CliRunner().invoke(cli, ["check", "-q", "--isolated", *args])
    return result.exit_code, result.stderr


def levels(stderr: str, rule: str) -> list[str]:
    return [line.split(": ")[1] for line in stderr.splitlines() if line.endswith(f"[{rule}]")]


@pytest.fixture
def robots(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "arm.urdf").write_text(KINEMATIC)
    (tmp_path / "sim.urdf").write_text(SIMULATED)
    return tmp_path


def test_a_kinematic_robot_for_moveit_has_no_errors(robots: Path) -> None:
    status, err = run("arm.urdf")
    assert status == 0
    assert levels(err, "missing-inertial") == ["warning", "warning"]


def test_a_robot_with_a_gazebo_plugin_is_for_gazebo(robots: Path) -> None:
    status, err = run("sim.urdf")
    assert status == 1
    assert levels(err, "missing-inertial") == ["error", "error"]
    assert "Gazebo drops it with everything below it" in err


def test_target_gazebo_given(robots: Path) -> None:
    assert run("--target", "gazebo", "arm.urdf")[0] == 1
    assert run("--target", "Gazebo,ros", "arm.urdf")[0] == 1
    assert run("--target", "ros", "--target", "mujoco", "arm.urdf")[0] == 1
    # Given targets replace the default: a Gazebo robot checked for RViz alone.
    status, err = run("--target", "rviz", "sim.urdf")
    assert (status, levels(err, "missing-inertial")) == (0, ["warning", "warning"])


def test_targets_in_the_configuration(robots: Path) -> None:
    Path("fishbot.toml").write_text('targets = ["ros", "drake"]\n')
    result = CliRunner().invoke(cli, ["check", "-q", "arm.urdf"])
    assert result.exit_code == 1
    assert levels(result.stderr, "missing-inertial") == ["error", "error"]
    # The command line's targets replace the file's.
    result = CliRunner().invoke(cli, ["check", "-q", "--target", "ros", "arm.urdf"])
    assert result.exit_code == 0


def test_a_severity_given_wins_over_the_targets(robots: Path) -> None:
    status, err = run("--severity", "missing-inertial=error", "arm.urdf")
    assert (status, levels(err, "missing-inertial")) == (1, ["error", "error"])
    status, err = run("--severity", "missing-inertial=note", "sim.urdf")
    assert (status, levels(err, "missing-inertial")) == (0, ["note", "note"])


def test_a_misspelt_target_is_a_usage_error(robots: Path) -> None:
    status, err = run("--target", "gazbo", "arm.urdf")
    assert status == 2
    assert "no target 'gazbo' (did you mean 'gazebo'?" in err


def test_a_misspelt_target_in_the_configuration(robots: Path) -> None:
    Path("fishbot.toml").write_text('targets = ["mujuco"]\n')
    with pytest.raises(ConfigError, match=r"targets: no target 'mujuco' \(did you mean 'mujoco'"):
        load_config("fishbot.toml")
    result = CliRunner().invoke(cli, ["check", "-q", "arm.urdf"])
    assert result.exit_code == 2
    assert result.stderr.startswith("fishbot.toml:1: error: targets: no target 'mujuco'")
    Path("fishbot.toml").write_text('targets = "gazebo"\n')
    with pytest.raises(ConfigError, match="targets must be a list of programs"):
        load_config("fishbot.toml")


def test_names_and_aliases() -> None:
    assert target_name("RViz") == "ros"
    assert target_name("robot-state-publisher") == "ros"
    assert target_name("check-urdf") == "check_urdf"
    assert target_name("gz") == "gazebo"
    with pytest.raises(UnknownNameError, match="did you mean 'pybullet'"):
        target_name("pybulet")
    assert consumers_of(["all"]) == frozenset(Consumer)
    assert target_name("ros_control") == "ros2_control"
    names = {"ros", "check_urdf", "gazebo", "mujoco", "drake", "pybullet", "ros2_control", "all"}
    assert set(TARGETS) == names


def test_the_default_targets_follow_the_robot(robots: Path) -> None:
    assert targets_of(check_file("arm.urdf").robot) == ("ros",)
    assert targets_of(check_file("sim.urdf").robot) == ("ros", "gazebo")
    assert targets_of(check_file("sim.urdf").robot, ["mujoco", "MuJoCo"]) == ("mujoco",)
    control = KINEMATIC.replace(
        "</robot>",
        '<ros2_control name="sim" type="system"><hardware>'
        "<plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware></ros2_control></robot>",
    )
    Path("control.urdf").write_text(control)
    assert targets_of(check_file("control.urdf").robot) == ("ros", "gazebo", "ros2_control")


def test_a_robot_with_ros2_control_is_for_ros2_control(tmp_path: Path) -> None:
    # A joint ros2_control is told of that the robot does not have: the controller manager
    # refuses it, on a real robot as in Gazebo.
    robot = tmp_path / "r.urdf"
    robot.write_text(
        KINEMATIC.replace(
            "</robot>",
            '<ros2_control name="arm" type="system"><hardware><plugin>arm/Hardware</plugin>'
            '</hardware><joint name="elbow"><command_interface name="position"/></joint>'
            "</ros2_control></robot>",
        )
    )
    status, err = run(str(robot))
    assert (status, levels(err, "unknown-reference")) == (1, ["error"])
    status, err = run("--target", "ros", str(robot))
    assert (status, levels(err, "unknown-reference")) == (0, ["warning"])


def test_the_library_takes_the_targets_from_the_configuration(robots: Path) -> None:
    default = check_file("arm.urdf").diagnostics
    assert {d.severity for d in default} == {Severity.WARNING}
    config = Config(targets=("pybullet",))
    assert {d.severity for d in check_file("arm.urdf", config=config).diagnostics} == {
        Severity.ERROR
    }


def test_what_urdfdom_refuses_stays_an_error_for_check_urdf(tmp_path: Path) -> None:
    robot = tmp_path / "r.urdf"
    robot.write_text(
        KINEMATIC.replace('<parent link="base_link"/>', '<parent link="base"/>')
    )  # urdfdom refuses a joint whose parent is not defined
    status, err = run("--target", "check_urdf", str(robot))
    assert status == 1
    assert levels(err, "undefined-link") == ["error"]
    assert levels(err, "missing-inertial") == ["warning", "warning"]
