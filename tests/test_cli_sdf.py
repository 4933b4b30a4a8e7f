"""`fishbot sdf` says what the conversion loses: the SDF on standard output (or -o), the
findings of the conversion rules on stderr, as `fishbot check` prints them."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

import fishbot_urdf
from fishbot_urdf.catalog.conversion import GAZEBO_DROPPED_LINK, GAZEBO_LUMPED_LINK
from fishbot_urdf.cli import cli

_DROPPED = (
    "4:3: error: link 'arm_mount' is fixed to 'base_link' (joint 'mount_joint') and has no "
    "mass, nor has anything fixed below it: sdformat's converter goes no further down the "
    "tree, so Gazebo leaves out 'arm' below it (give 'arm_mount' a mass, or hang what moves "
    "below it on 'base_link') [gazebo-dropped-link]"
)


def _robot(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "robot.urdf"
    path.write_text(text, encoding="utf-8")
    return path


def test_sdf_prints_what_the_conversion_loses_on_stderr(tmp_path: Path) -> None:
    robot = _robot(tmp_path, GAZEBO_DROPPED_LINK.bad)
    result = CliRunner().invoke(cli, ["sdf", str(robot)])
    assert (result.exit_code, result.stderr) == (0, f"{robot}:{_DROPPED}\n")
    assert result.stdout == fishbot_urdf.to_sdf(fishbot_urdf.load(robot))
    assert "arm" not in result.stdout.replace("arm_", "")  # the link it says is lost


def test_sdf_writes_the_file_and_still_says_what_is_lost(tmp_path: Path) -> None:
    robot = _robot(tmp_path, GAZEBO_DROPPED_LINK.bad)
    out = tmp_path / "robot.sdf"
    result = CliRunner().invoke(cli, ["sdf", str(robot), "-o", str(out)])
    assert (result.exit_code, result.stdout, result.stderr) == (0, "", f"{robot}:{_DROPPED}\n")
    assert out.read_text(encoding="utf-8") == fishbot_urdf.to_sdf(fishbot_urdf.load(robot))


def test_a_robot_that_loses_nothing_is_written_in_silence(tmp_path: Path) -> None:
    robot = _robot(tmp_path, GAZEBO_DROPPED_LINK.good)
    result = CliRunner().invoke(cli, ["sdf", str(robot)])
    assert (result.exit_code, result.stderr) == (0, "")


def test_the_losses_are_silenced_as_check_silences_them(tmp_path: Path) -> None:
    text = GAZEBO_DROPPED_LINK.bad.replace(
        '  <link name="arm_mount"/>',
        '  <!-- fishbot: ignore[gazebo-dropped-link] -->\n  <link name="arm_mount"/>',
    )
    robot = _robot(tmp_path, text)
    assert CliRunner().invoke(cli, ["sdf", str(robot)]).stderr == ""
    robot.write_text(GAZEBO_DROPPED_LINK.bad, encoding="utf-8")
    (tmp_path / "fishbot.toml").write_text('ignore = ["gazebo"]\n', encoding="utf-8")
    assert CliRunner().invoke(cli, ["sdf", str(robot)]).stderr == ""


def test_sdf_judges_the_losses_for_gazebo(tmp_path: Path) -> None:
    # a robot with no <gazebo> block is checked for ROS alone, but its SDF is for Gazebo
    robot = _robot(tmp_path, GAZEBO_DROPPED_LINK.bad)
    checked = CliRunner().invoke(cli, ["check", "--isolated", "-q", str(robot)])
    assert checked.stderr == f"{robot}:{_DROPPED}\n".replace(": error: ", ": warning: ", 1)
    assert ": error: " in CliRunner().invoke(cli, ["sdf", str(robot)]).stderr


def test_a_sensor_on_a_lumped_link_is_said_with_its_new_place(tmp_path: Path) -> None:
    robot = _robot(tmp_path, GAZEBO_LUMPED_LINK.bad)
    result = CliRunner().invoke(cli, ["sdf", str(robot)])
    assert result.exit_code == 0
    assert result.stdout == fishbot_urdf.to_sdf(fishbot_urdf.load(robot))
    (finding,) = result.stderr.splitlines()
    assert finding.startswith(f"{robot}:") and finding.endswith("[gazebo-lumped-link]")
    assert ": warning: " in finding
