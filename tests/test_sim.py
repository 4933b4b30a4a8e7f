"""`fishbot sim`: the fishbot driven in MuJoCo does what it is told, and each of the
learner's classic mistakes, made on a copy of the fishbot, shows up as the failure Gazebo
would show, with the line in the robot's files."""

from __future__ import annotations

import dataclasses
import json
import math
import shutil
import sys
import types
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import ARM, FISHBOT, REQUIRE_TOOLS

if not REQUIRE_TOOLS:  # on a user's machine without the [sim] extra: skipped, with a reason
    pytest.importorskip("mujoco", reason="fishbot sim needs the [sim] extra")

import fishbot_urdf
from fishbot_urdf.cli import cli
from fishbot_urdf.errors import ArgumentError
from fishbot_urdf.simulation import Outcome, simulate

MAIN = Path("urdf/fishbot/fishbot.urdf.xacro")
WHEEL = Path("urdf/fishbot/actuator/wheel.urdf.xacro")
CASTER = Path("urdf/fishbot/actuator/caster.urdf.xacro")
PLUGIN = Path("urdf/fishbot/plugins/gazebo_control_plugin.xacro")
# The fishbot's own numbers (robots/fishbot/urdf/fishbot/fishbot.urdf.xacro).
WHEEL_RADIUS = 0.032


def _sim(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["sim", *args])
    return result.exit_code, result.stdout, result.stderr


def _measure(outcome: Outcome, name: str, about: str = "") -> float:
    found = [m for m in outcome.measures if m.name == name and m.about == about]
    assert len(found) == 1, (name, about, outcome.measures)
    return found[0].value


@pytest.fixture(scope="module")
def fishbot() -> Outcome:
    return simulate(fishbot_urdf.load(FISHBOT / MAIN))


def test_the_fishbot_drives_as_it_is_told(fishbot: Outcome) -> None:
    assert fishbot.trial == "drive" and fishbot.ok, fishbot.findings
    assert [d.rule for d in fishbot.findings] == []
    # each wheel rolls on its 32 mm radius, sinking no more than MuJoCo's soft contact lets it
    for wheel in ("left_wheel_link", "right_wheel_link"):
        height = _measure(fishbot, "lowest wheel centre", wheel)
        assert WHEEL_RADIUS - 0.001 < height <= WHEEL_RADIUS + 0.001
    # the default command: 0.5 m/s and 1 rad/s, as linear.x and angular.z
    assert _measure(fishbot, "straight speed") == pytest.approx(0.5, rel=0.02)
    assert _measure(fishbot, "turn rate") == pytest.approx(1.0, rel=0.15)
    assert _measure(fishbot, "largest tilt") < 5.0
    # 1 s settling; 0.5 s ramping, 0.5 s settling to the speed, 2 s straight; 0.5 s stop;
    # the same turning: 7.5 s of 2 ms steps
    assert (fishbot.seconds, fishbot.steps) == (7.5, 3750)


def test_the_command_line_prints_the_table_and_exits_0() -> None:
    code, out, err = _sim(str(FISHBOT / MAIN), "--drive", "0.2,0.5", "--seconds", "1")
    assert (code, err) == (0, ""), err
    lines = out.splitlines()
    assert lines[0].startswith(
        "fishbot: dropped on the floor, driven straight at 0.2 m/s, turned at 0.5 rad/s "
        "(5.50 s simulated, 2750 steps)"
    )
    assert lines[-1] == "fishbot: did what it was told"
    speed = next(line for line in lines if line.lstrip().startswith("straight speed"))
    assert speed.split()[-1] == "ok" and "0.2 m/s" in speed


def test_json_gives_the_measures_and_findings() -> None:
    code, out, _ = _sim(str(FISHBOT / MAIN), "--format", "json", "--seconds", "1")
    assert code == 0
    report = json.loads(out)
    assert (report["robot"], report["trial"], report["ok"]) == ("fishbot", "drive", True)
    assert report["findings"] == []
    names = [m["name"] for m in report["measures"]]
    assert "straight speed" in names and "turn rate" in names
    straight = next(m for m in report["measures"] if m["name"] == "straight speed")
    assert straight["expected"] == 0.5 and straight["unit"] == "m/s" and straight["ok"]


def test_two_runs_measure_the_same() -> None:
    robot = fishbot_urdf.load(FISHBOT / MAIN)
    one, two = simulate(robot, seconds=0.5), simulate(robot, seconds=0.5)
    assert one.measures == two.measures


# -- the learner's mistakes, each on a copy of the fishbot --------------------------------

_MISTAKES = {
    # the wheels' collision cylinders left along z: URDF's cylinders lie along the link's z
    "wheels along z": (
        WHEEL,
        '<collision>\n        <origin xyz="0.0 0.0 0.0" rpy="1.57079 0.0 0.0"/>',
        '<collision>\n        <origin xyz="0.0 0.0 0.0" rpy="0.0 0.0 0.0"/>',
    ),
    # a body of 100 kg on wheels of 5 mm
    "heavy body, tiny wheels": (
        MAIN,
        '<xacro:property name="base_mass" value="1.0"/>\n  <xacro:property name="imu_mass"',
        '<xacro:property name="base_mass" value="100.0"/>\n  <xacro:property name="imu_mass"',
    ),
    # left and right swapped in the drive plugin
    "wheels swapped": (
        MAIN,
        'left_joint="left_wheel_joint" right_joint="right_wheel_joint"',
        'left_joint="right_wheel_joint" right_joint="left_wheel_joint"',
    ),
    # the casters 1 cm below the wheels' contact plane
    "casters too low": (
        MAIN,
        '<xacro:property name="caster_z" value="-0.076"/>',
        '<xacro:property name="caster_z" value="-0.086"/>',
    ),
    # a wheel without its <inertial>
    "wheel without inertial": (
        WHEEL,
        '      <xacro:cylinder_inertia m="${mass}" r="${radius}" h="${length}"\n'
        '                              xyz="0.0 0.0 0.0" rpy="1.57079 0.0 0.0"/>\n',
        "",
    ),
}


def _copy(tmp_path: Path, mistake: str) -> Path:
    """The fishbot package with one mistake made in one of its files."""
    root = tmp_path / "fishbot_description"
    shutil.copytree(FISHBOT, root)
    file, old, new = _MISTAKES[mistake]
    text = (root / file).read_text(encoding="utf-8")
    assert text.count(old) >= 1, (mistake, old)
    (root / file).write_text(text.replace(old, new), encoding="utf-8")
    if mistake == "heavy body, tiny wheels":
        text = (root / MAIN).read_text(encoding="utf-8")
        old = '<xacro:property name="wheel_radius" value="0.032"/>'
        assert old in text
        new = '<xacro:property name="wheel_radius" value="0.005"/>'
        (root / MAIN).write_text(text.replace(old, new), encoding="utf-8")
    return root


def _line(path: Path, text: str, nth: int = 1) -> int:
    """The line of the ``nth`` occurrence of ``text`` in ``path``."""
    content = path.read_text(encoding="utf-8")
    at = -1
    for _ in range(nth):
        at = content.index(text, at + 1)
    return content.count("\n", 0, at) + 1


def _findings(err: str) -> list[tuple[str, int, str]]:
    """(file, line, rule) of each finding printed."""
    found = []
    for line in err.splitlines():
        place, _, rest = line.partition(": ")
        parts = place.rsplit(":", 2)
        rule = rest.rsplit("[", 1)[-1].rstrip("]")
        found.append((parts[0], int(parts[1]) if len(parts) == 3 else 0, rule))
    return found


def test_wheels_along_z_sink_and_roll_wrong(tmp_path: Path) -> None:
    root = _copy(tmp_path, "wheels along z")
    code, out, err = _sim(str(root / MAIN))
    assert code == 1, out + err
    found = _findings(err)
    # at the wheel's <collision> (the macro's second element that says so): each wheel
    collision = _line(root / WHEEL, "<collision>")
    assert (str(root / WHEEL), collision, "sim-sank") in found
    assert [r for _, _, r in found].count("sim-sank") == 2
    assert "its collision cylinder lies along 0 0 1 of the link, and joint" in err
    # rolling on its rims, sqrt(0.032^2 + 0.02^2) m from the axle at most, it runs fast
    speed = next(line for line in out.splitlines() if line.split()[:2] == ["straight", "speed"])
    assert float(speed.split()[2]) > 0.5


def test_swapped_wheels_turn_the_other_way(tmp_path: Path) -> None:
    root = _copy(tmp_path, "wheels swapped")
    code, out, err = _sim(str(root / MAIN))
    assert code == 1, out + err
    found = _findings(err)
    # the check's finding on the drive says why, then the simulation's what came of it
    left = _line(root / PLUGIN, "<left_joint>")
    assert found == [
        (str(root / PLUGIN), left, "diff-drive-wheels"),
        (str(root / PLUGIN), left, "sim-turn"),
    ]
    assert "it turns the other way" in err and "left and right are swapped" in err
    # straight on, the swap does nothing: both wheels are told the same speed
    assert any(
        line.split()[:2] == ["straight", "speed"] and line.endswith("ok")
        for line in out.splitlines()
    )


def test_casters_below_the_wheels_lift_them(tmp_path: Path) -> None:
    root = _copy(tmp_path, "casters too low")
    code, out, err = _sim(str(root / MAIN))
    assert code == 1, out + err
    found = _findings(err)
    where = (
        str(root / CASTER),
        _line(root / CASTER, '<origin xyz="${xyz}"'),
        "sim-wheel-off-floor",
    )
    assert where in found
    # both casters, made by one macro from one caster_z, and the call that passes it
    assert "back_caster_link and front_caster_link reach 1.0 cm below the wheels' lowest" in err
    assert "or what macro caster_xacro called at" in err


def test_a_heavy_body_on_tiny_wheels_does_not_drive(tmp_path: Path) -> None:
    root = _copy(tmp_path, "heavy body, tiny wheels")
    code, out, err = _sim(str(root / MAIN))
    assert code == 1, out + err
    # the casters, 2.7 cm below the 5 mm wheels, take the 100 kg: the robot rocks over on
    # them (what it did lying over is not said again) and hardly moves
    rules = [r for _, _, r in _findings(err)]
    assert rules == ["sim-tipped"]
    assert "base_link's 100 kg are" in err
    speed = next(line for line in out.splitlines() if line.split()[:2] == ["straight", "speed"])
    assert abs(float(speed.split()[2])) < 0.1


def test_a_wheel_without_inertial_is_refused_at_its_link(tmp_path: Path) -> None:
    root = _copy(tmp_path, "wheel without inertial")
    code, out, err = _sim(str(root / MAIN))
    assert code == 1
    assert out == "fishbot: not simulated: MuJoCo refuses the model\n"
    link = _line(root / WHEEL, '<link name="${name}_wheel_link">')
    assert _findings(err) == [(str(root / WHEEL), link, "mjcf-refused")] * 2


# -- robots without wheels, and the command line ------------------------------------------


def test_an_arm_strong_enough_holds_and_a_weak_one_sags() -> None:
    strong = simulate(fishbot_urdf.parse(ARM.format(effort=100)))
    assert strong.trial == "hold" and strong.ok
    assert _measure(strong, "largest drift") < 1e-3
    weak = simulate(fishbot_urdf.parse(ARM.format(effort=1)))
    assert not weak.ok
    (sag,) = weak.findings
    assert sag.rule == "sim-sag" and sag.line == 10
    # gravity on a 5 kg arm whose mass is 0.5 m out, held level: 5 * 9.81 * 0.5 N*m
    assert f"gravity puts {5 * 9.81 * 0.5:.3g} N*m on it there" in sag.message
    assert "its effort limit is 1 N*m" in sag.message
    assert _measure(weak, "drift", "shoulder") > 1.0  # it fell to its limit


def test_two_wheel_joints_without_a_plugin_are_driven() -> None:
    # the fishbot before its Gazebo step: no drive plugin, its casters still frictionless
    robot = fishbot_urdf.load(FISHBOT / MAIN)
    extras = tuple(e for e in robot.extras if "gazebo_ros_diff_drive" not in e)
    assert len(extras) == len(robot.extras) - 1
    plain = dataclasses.replace(robot, extras=extras, extra_places=())
    outcome = simulate(plain, seconds=1.0)
    assert outcome.trial == "drive" and outcome.ok, outcome.findings
    assert _measure(outcome, "straight speed") == pytest.approx(0.5, rel=0.02)


def test_wrong_arguments_are_usage_errors() -> None:
    code, _, err = _sim(str(FISHBOT / MAIN), "--drive", "fast")
    assert code == 2 and "is not V,OMEGA" in err
    code, _, err = _sim(str(FISHBOT / MAIN), "--seconds", "0")
    assert code == 2
    with pytest.raises(ArgumentError):
        simulate(fishbot_urdf.load(FISHBOT / MAIN), seconds=math.inf)


def test_without_mujoco_one_line_says_how_to_install_it(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "mujoco", None)
    code, out, err = _sim(str(FISHBOT / MAIN))
    assert (code, out) == (2, "")
    assert err == (
        "fishbot sim: error: setup: the mujoco package, an optional part of fishbot-urdf that "
        "the simulation needs, is not installed (install it: pip install 'fishbot-urdf[sim]') "
        "[tool-missing]\n"
    )


def _edited(tmp_path: Path, file: Path, old: str, new: str) -> Path:
    """The fishbot package with ``old`` replaced by ``new`` in ``file``."""
    root = tmp_path / "fishbot_description"
    shutil.copytree(FISHBOT, root)
    text = (root / file).read_text(encoding="utf-8")
    assert old in text
    (root / file).write_text(text.replace(old, new), encoding="utf-8")
    return root


def test_a_wheel_joint_that_does_not_turn_is_not_driven(tmp_path: Path) -> None:
    old = '<joint name="${name}_wheel_joint" type="continuous">'
    root = _edited(tmp_path, WHEEL, old, old.replace("continuous", "fixed"))
    code, out, err = _sim(str(root / MAIN))
    assert code == 1
    assert out == "fishbot: not simulated: the drive's wheels cannot be driven\n"
    rules = [r for _, _, r in _findings(err)]
    assert rules == ["diff-drive-wheels", "diff-drive-wheels"]
    assert "is a fixed joint, which does not turn" in err


def test_a_drive_naming_no_joint_is_not_driven(tmp_path: Path) -> None:
    old = 'left_joint="left_wheel_joint"'
    root = _edited(tmp_path, MAIN, old, 'left_joint="left_wheel_jiont"')
    code, out, _ = _sim(str(root / MAIN), "--format", "json")
    assert code == 1
    report = json.loads(out)
    assert (report["ok"], report["steps"]) == (False, 0)
    # at the drive's <left_joint>, with the name meant
    (first,) = report["findings"]
    assert first["rule"] == "unknown-reference"
    assert first["line"] == _line(root / PLUGIN, "<left_joint>")
    assert "did you mean 'left_wheel_joint'?" in first["hint"]


@pytest.mark.parametrize("command", ["0,0", "0,1", "-0.3,-0.5"])
def test_standing_still_turning_and_reversing_pass(command: str) -> None:
    code, out, err = _sim(str(FISHBOT / MAIN), "--drive", command, "--seconds", "1")
    assert (code, err) == (0, ""), out


def test_one_base_at_a_time(tmp_path: Path) -> None:
    for command in ("sim", "mjcf"):
        result = CliRunner().invoke(
            cli, [command, str(FISHBOT / MAIN), "--fixed-base", "--floating-base"]
        )
        assert result.exit_code == 2
        assert "--fixed-base and --floating-base cannot both be given" in result.output


def test_the_time_limit_stops_a_long_run() -> None:
    code, _, err = _sim(str(FISHBOT / MAIN), "--seconds", "600", "--timeout", "1")
    assert code == 2
    assert "the simulation takes longer than the time limit of 1 s" in err


def test_a_blow_up_leaves_no_mujoco_log(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # MuJoCo writes MUJOCO_LOG.TXT in the current folder, and prints, when it warns of a
    # blow-up; fishbot sim says it once, as a finding, and writes nothing. The wheels here
    # are given the inertia of a cylinder 1e5 times smaller than theirs.
    old = '<xacro:cylinder_inertia m="${mass}" r="${radius}" h="${length}"'
    new = '<xacro:cylinder_inertia m="${mass}" r="${radius * 1e-5}" h="${length * 1e-5}"'
    root = _edited(tmp_path, WHEEL, old, new)
    monkeypatch.chdir(tmp_path)
    code, out, err = _sim(str(root / MAIN))
    assert code == 1
    assert [r for _, _, r in _findings(err)] == ["sim-exploded"]
    assert "WARNING" not in out + err
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()


def test_a_mujoco_folder_left_by_an_uninstall_is_no_mujoco(monkeypatch: pytest.MonkeyPatch) -> None:
    # pip uninstall mujoco can leave its folder behind: Python then imports it as an empty
    # namespace package
    monkeypatch.setitem(sys.modules, "mujoco", types.ModuleType("mujoco"))
    code, out, err = _sim(str(FISHBOT / MAIN))
    assert (code, out) == (2, "")
    assert "the mujoco package, an optional part of fishbot-urdf" in err
    assert err.count("\n") == 1


def test_json_reports_a_robot_whose_tree_is_in_doubt(tmp_path: Path) -> None:
    robot = tmp_path / "two.urdf"
    robot.write_text('<robot name="two"><link name="a"/><link name="b"/></robot>\n')
    code, out, err = _sim(str(robot), "--format", "json")
    assert (code, err) == (1, "")
    report = json.loads(out)
    assert (report["ok"], report["trial"], report["steps"]) == (False, None, 0)
    assert [f["rule"] for f in report["findings"]] == ["multiple-roots"]


def test_wheels_of_two_radii_drive_in_a_circle(tmp_path: Path) -> None:
    old = '<xacro:wheel_xacro name="left" side="1" radius="${wheel_radius}"'
    root = _edited(tmp_path, MAIN, old, old.replace("${wheel_radius}", "0.04"))
    code, out, err = _sim(str(root / MAIN))
    assert code == 1, out
    assert "driven straight at 0.5 m/s, the robot turned at" in err
    assert "left_wheel_link rolls on 4.0 cm and right_wheel_link on 3.2 cm" in err


def test_a_mirrored_wheel_axis_is_named(tmp_path: Path) -> None:
    root = _edited(tmp_path, WHEEL, '<axis xyz="0.0 1.0 0.0"/>', '<axis xyz="0.0 ${side} 0.0"/>')
    code, _, err = _sim(str(root / MAIN))
    assert code == 1
    axis = _line(root / WHEEL, '<joint name="${name}_wheel_joint"')
    assert (str(root / WHEEL), axis, "sim-speed") in _findings(err)
    assert "joint 'right_wheel_joint' turns about -y and the other about +y" in err


def test_an_absurd_command_is_a_usage_error() -> None:
    code, _, err = _sim(str(FISHBOT / MAIN), "--drive", "1e9,0")
    assert code == 2 and "a speed of at most 20 m/s" in err


def test_wheels_without_grip_are_named(tmp_path: Path) -> None:
    old = "      <mu1>20.0</mu1>\n      <mu2>20.0</mu2>"
    root = _edited(tmp_path, WHEEL, old, "      <mu1>0</mu1>\n      <mu2>0</mu2>")
    code, _, err = _sim(str(root / MAIN))
    assert code == 1
    assert "its wheels grip the floor with a friction of 0" in err
    assert (str(root / WHEEL), _line(root / WHEEL, "<mu1>0</mu1>"), "sim-speed") in _findings(err)


def test_a_torque_too_small_is_named(tmp_path: Path) -> None:
    old = "<max_wheel_torque>30</max_wheel_torque>"
    root = _edited(tmp_path, PLUGIN, old, "<max_wheel_torque>0.005</max_wheel_torque>")
    code, _, err = _sim(str(root / MAIN))
    assert code == 1
    assert "on the 0.005 N*m the plugin allows them (<max_wheel_torque>)" in err
    torque = _line(root / PLUGIN, "<max_wheel_torque>")
    assert (str(root / PLUGIN), torque, "sim-speed") in _findings(err)
