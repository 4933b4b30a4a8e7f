"""The joint rules: wheel axes, axis length, limits in degrees, zero limits, rpy in degrees,
mimic chains."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import pytest
from conftest import FISHBOT

import fishbot_urdf
from fishbot_urdf import (
    Collision,
    Cylinder,
    Inertial,
    Joint,
    JointType,
    Limit,
    Link,
    Mimic,
    Origin,
    Robot,
    Visual,
)
from fishbot_urdf.catalog import Family, get


def _rules(*joints: Joint, links: tuple[Link, ...] = ()) -> list[tuple[str, str]]:
    names = {"base"} | {j.child for j in joints}
    given = {link.name for link in links}
    every = links + tuple(Link(n) for n in sorted(names - given))
    found = fishbot_urdf.check(Robot("r", links=every, joints=joints))
    # The physics rules have their own say about links without an <inertial>.
    return [(d.rule, d.message) for d in found if get(d.rule).family is Family.JOINTS]


def _wheel(rpy: tuple[float, float, float], radius: float = 0.03, length: float = 0.02) -> Link:
    return Link("wheel", collisions=(Collision(Cylinder(radius, length), Origin(rpy=rpy)),))


SIDEWAYS = (math.pi / 2, 0.0, 0.0)  # the cylinder's z axis turned onto -y


@pytest.mark.parametrize(
    ("axis", "rpy", "fires"),
    [
        ((0.0, 0.0, 1.0), SIDEWAYS, True),  # the turntable
        ((0.0, 1.0, 0.0), SIDEWAYS, False),
        ((0.0, -1.0, 0.0), SIDEWAYS, False),  # either sense of the axis
        ((0.0, 0.0, 1.0), (0.0, 0.0, 0.0), False),  # a flat disc turning about z
        ((1.0, 0.0, 0.0), (0.0, math.pi / 2, 0.0), False),  # pitch turns z onto x
    ],
)
def test_a_wheel_turns_about_its_cylinders_axis(
    axis: tuple[float, float, float], rpy: tuple[float, float, float], fires: bool
) -> None:
    joint = Joint("j", JointType.CONTINUOUS, "base", "wheel", axis=axis)
    rules = [rule for rule, _ in _rules(joint, links=(_wheel(rpy),))]
    assert ("wheel-axis" in rules) is fires


def test_the_wheel_message_names_the_axis_to_write() -> None:
    joint = Joint("j", JointType.CONTINUOUS, "base", "wheel", axis=(0.0, 0.0, 1.0))
    [(rule, message)] = _rules(joint, links=(_wheel(SIDEWAYS),))
    assert rule == "wheel-axis"
    # R(pi/2, 0, 0) takes z to (0, -sin(pi/2), cos(pi/2)) = (0, -1, 0).
    assert (
        message == "joint 'j' turns about 0 0 1, but its wheel 'wheel' is a cylinder along 0 -1 0"
    )


def test_a_long_cylinder_on_a_continuous_joint_is_no_wheel() -> None:
    joint = Joint("j", JointType.CONTINUOUS, "base", "wheel", axis=(0.0, 0.0, 1.0))
    assert _rules(joint, links=(_wheel(SIDEWAYS, radius=0.01, length=0.5),)) == []


def _revolute(**limit: float) -> Joint:
    values = {"effort": 10.0, "velocity": 2.0, "lower": -1.0, "upper": 1.0, **limit}
    return Joint("j", JointType.REVOLUTE, "base", "arm", limit=Limit(**values))


@pytest.mark.parametrize(
    ("limit", "rule"),
    [
        ({"lower": -90.0, "upper": 90.0}, "wide-limit"),
        ({"lower": -2 * math.pi, "upper": 2 * math.pi}, None),
        ({"lower": -6.2832, "upper": 6.2832}, None),  # 2 pi, rounded as people write it
        ({"lower": -6.98132, "upper": 6.98132}, None),  # a wrist's +-400 degrees, in radians
        ({"upper": 1e16}, "wide-limit"),  # "no limit": a continuous joint
        ({"velocity": 180.0}, "velocity-degrees"),
        ({"velocity": 100.0}, None),  # a placeholder, not degrees
        ({"velocity": 15.0}, None),
        ({"velocity": 30.0}, None),  # a fast legged-robot motor
        ({"effort": 0.0}, "zero-limit"),
        ({"velocity": 0.0}, "zero-limit"),
    ],
)
def test_limits_that_read_as_degrees_or_zero(limit: dict[str, float], rule: str | None) -> None:
    assert [r for r, _ in _rules(_revolute(**limit))] == ([rule] if rule else [])


def test_the_zero_limit_message_says_what_each_zero_means() -> None:
    assert _rules(_revolute(effort=0.0, velocity=0.0)) == [
        (
            "zero-limit",
            "joint 'j': effort and velocity limits are 0: no motor may drive it and "
            "it may not move",
        )
    ]


def test_a_mimic_joints_zero_limits_are_its_leaders_business() -> None:
    leader = _revolute()
    follower = Joint(
        "f",
        JointType.REVOLUTE,
        "base",
        "finger",
        limit=Limit(effort=0.0, velocity=0.0, lower=-1.0, upper=1.0),
        mimic=Mimic("j"),
    )
    assert _rules(leader, follower) == []


def test_an_axis_must_be_of_unit_length() -> None:
    joint = Joint("j", JointType.CONTINUOUS, "base", "arm", axis=(0.0, 0.0, 2.0))
    assert _rules(joint) == [("axis-length", "joint 'j': axis 0 0 2 has length 2")]
    rounded = Joint("j", JointType.CONTINUOUS, "base", "arm", axis=(0.0, 0.7071, 0.7071))
    assert _rules(rounded) == []


@pytest.mark.parametrize("part", ["inertial", "visual", "collision"])
def test_rpy_in_degrees_on_any_origin(part: str) -> None:
    turned = Origin(rpy=(0.0, 0.0, 90.0))
    shape = Cylinder(0.01, 0.5)
    parts = {
        "inertial": {"inertial": Inertial(1.0, origin=turned)},
        "visual": {"visuals": (Visual(shape, turned),)},
        "collision": {"collisions": (Collision(shape, turned),)},
    }
    link = Link("arm", **parts[part])  # type: ignore[arg-type]
    joint = Joint("j", JointType.FIXED, "base", "arm", origin=Origin(rpy=(180.0, 0.0, 0.0)))
    found = _rules(joint, links=(link,))
    assert [r for r, _ in found] == ["rpy-degrees", "rpy-degrees"]
    assert f"link 'arm': <{part}>: rpy 0 0 90" in found[1][1]


def test_mimic_chains_and_a_zero_multiplier() -> None:
    a = Joint("a", JointType.CONTINUOUS, "base", "l1")
    b = Joint("b", JointType.CONTINUOUS, "base", "l2", mimic=Mimic("a"))
    c = Joint("c", JointType.CONTINUOUS, "base", "l3", mimic=Mimic("b", multiplier=0.0))
    assert _rules(a, b, c) == [
        ("mimic-chain", "joint 'c' mimics 'b' with multiplier 0: it never moves"),
        ("mimic-chain", "joint 'c' mimics 'b', which mimics 'a' in turn"),
    ]


def test_a_mimic_on_or_of_a_fixed_joint() -> None:
    lead = Joint("lead", JointType.REVOLUTE, "base", "l1", limit=Limit(1.0, 1.0, -1.0, 1.0))
    weld = Joint("weld", JointType.FIXED, "base", "l2", mimic=Mimic("lead", 2.0))
    follower = Joint("follower", JointType.CONTINUOUS, "l2", "l3", mimic=Mimic("weld", 1.0, 0.5))
    assert _rules(lead, weld, follower) == [
        ("mimic-fixed", "joint 'weld' is fixed, but mimics 'lead': it never moves"),
        (
            "mimic-fixed",
            "joint 'follower' mimics 'weld', a fixed joint, which has no position: it stays at "
            "its offset 0.5",
        ),
    ]
    # What the kinematics do with them: the fixed joint stays put, the follower at 0.5 rad.
    poses = fishbot_urdf.link_poses(
        Robot(
            "r",
            links=tuple(Link(n) for n in ("base", "l1", "l2", "l3")),
            joints=(lead, weld, follower),
        ),
        {"lead": 0.7},
    )
    assert poses["l2"].rotation == ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    # about x (the default axis) by 0.5: y turns onto (0, cos 0.5, sin 0.5)
    assert [row[1] for row in poses["l3"].rotation] == pytest.approx(
        [0.0, math.cos(0.5), math.sin(0.5)], abs=1e-15
    )
    # A mimic of a moving joint, and a fixed joint without one, are no finding.
    plain = Joint("plain", JointType.FIXED, "base", "l4")
    moving = Joint("moving", JointType.CONTINUOUS, "base", "l5", mimic=Mimic("lead"))
    assert _rules(lead, plain, moving) == []


def _hints(*joints: Joint, links: tuple[Link, ...] = ()) -> dict[str, str | None]:
    names = {"base"} | {j.child for j in joints}
    every = links + tuple(Link(n) for n in sorted(names - {link.name for link in links}))
    found = fishbot_urdf.check(Robot("r", links=every, joints=joints))
    return {d.rule: d.hint for d in found if get(d.rule).family is Family.JOINTS}


def test_the_fishbot_s_wheel_turned_by_1_57079_suggests_a_clean_axis(tmp_path: Path) -> None:
    # The fishbot's wheel cylinder is turned by rpy="1.57079 0 0": R takes its z axis to
    # (0, -sin 1.57079, cos 1.57079) = (0, -1, 6.327e-06), which is y within 1e-4.
    copy = tmp_path / "fishbot"
    shutil.copytree(FISHBOT, copy)
    wheel = copy / "urdf" / "fishbot" / "actuator" / "wheel.urdf.xacro"
    text = wheel.read_text(encoding="utf-8")
    assert '<axis xyz="0.0 1.0 0.0"/>' in text
    wheel.write_text(text.replace('<axis xyz="0.0 1.0 0.0"/>', '<axis xyz="0.0 0.0 1.0"/>'))
    found = fishbot_urdf.check_file(copy / "urdf" / "fishbot" / "fishbot.urdf.xacro").diagnostics
    hints = {d.hint for d in found if d.rule == "wheel-axis"}
    messages = {d.message.split(", but ")[1] for d in found if d.rule == "wheel-axis"}
    assert messages == {
        "its wheel 'left_wheel_link' is a cylinder along 0 -1 0",
        "its wheel 'right_wheel_link' is a cylinder along 0 -1 0",
    }
    assert hints == {
        'a wheel turns about its cylinder\'s axis: <axis xyz="0 1 0"/> '
        "(0 -1 0 turns it the other way)"
    }


@pytest.mark.parametrize(
    ("axis", "rpy", "suggested"),
    [
        ((0.0, 0.0, 1.0), (math.pi / 2, 0.0, 0.0), "0 1 0"),  # no sense given: the positive one
        ((0.0, 0.0, 1.0), (-1.57079, 0.0, 0.0), "0 1 0"),
        ((0.0, -0.5, 0.8), (1.57079, 0.0, 0.0), "0 -1 0"),  # the joint's axis leans to -y
        ((0.0, 0.0, 1.0), (0.0, 1.57079, 0.0), "1 0 0"),
        ((0.0, 0.0, 1.0), (math.pi / 4, 0.0, 0.0), "0 -0.7071 0.7071"),  # nothing to round
    ],
)
def test_a_suggested_wheel_axis_is_rounded_to_a_clean_one(
    axis: tuple[float, float, float], rpy: tuple[float, float, float], suggested: str
) -> None:
    joint = Joint("j", JointType.CONTINUOUS, "base", "wheel", axis=axis)
    hint = _hints(joint, links=(_wheel(rpy),))["wheel-axis"]
    assert hint is not None
    assert hint.startswith(f'a wheel turns about its cylinder\'s axis: <axis xyz="{suggested}"/>')


def test_the_unit_axis_suggested_for_a_long_one_is_rounded() -> None:
    joint = Joint("j", JointType.CONTINUOUS, "base", "arm", axis=(0.0, 2.0, 0.0001))
    assert _hints(joint)["axis-length"] == 'write the unit vector: <axis xyz="0 1 0"/>'


LIMITED = """\
<robot name="r">
  <link name="base"/><link name="arm"/>
  <joint name="arm_joint" type="{type}">
    <parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit {bounds} effort="1" velocity="1"/>
  </joint>
</robot>
"""


def _limited(tmp_path: Path, kind: str, bounds: str) -> list[tuple[str, str, str]]:
    path = tmp_path / "r.urdf"
    path.write_text(LIMITED.format(type=kind, bounds=bounds), encoding="utf-8")
    found = fishbot_urdf.check_file(path).diagnostics
    return [(d.rule, d.severity.value, d.message) for d in found]


def test_a_limit_without_bounds_holds_the_joint_at_0_for_urdfdom(tmp_path: Path) -> None:
    # upkie's wheels (upkie-description 2.2.0): revolute, <limit effort velocity> alone
    assert _limited(tmp_path, "revolute", "") == [
        (
            "limit-unset",
            "warning",
            "joint 'arm_joint': <limit> has no lower and no upper, so urdfdom reads both as 0 "
            "and holds the joint at 0 (robot_state_publisher, MoveIt, Gazebo, pinocchio), while "
            "MuJoCo and PyBullet leave it free",
        )
    ]
    [(_, _, message)] = _limited(tmp_path, "prismatic", 'upper="0.2"')
    assert message == (
        "joint 'arm_joint': <limit> has no lower, so urdfdom reads it as 0 and limits the joint "
        "to 0 .. 0.2, while MuJoCo leaves it free"
    )


def test_a_bound_left_out_that_leaves_lower_above_upper_is_one_error(tmp_path: Path) -> None:
    # not limit-range as well: the bound left out is the fault
    assert _limited(tmp_path, "revolute", 'lower="0.5"') == [
        (
            "limit-unset",
            "error",
            "joint 'arm_joint': <limit> has no upper, read as 0, which leaves lower 0.5 above "
            "upper 0: Drake refuses the joint, MuJoCo and PyBullet leave it free",
        )
    ]
    assert [r for r, _, _ in _limited(tmp_path, "revolute", 'lower="0.5" upper="0"')] == [
        "limit-range"
    ]


@pytest.mark.parametrize(
    ("kind", "bounds"),
    [("continuous", ""), ("revolute", 'lower="0" upper="0"'), ("revolute", 'lower="-1" upper="1"')],
)
def test_bounds_written_or_not_needed_are_not_unset(tmp_path: Path, kind: str, bounds: str) -> None:
    assert _limited(tmp_path, kind, bounds) == []


def test_the_model_keeps_which_bounds_were_left_out(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(LIMITED.format(type="revolute", bounds='upper="1"'), encoding="utf-8")
    limit = fishbot_urdf.load(path).joints[0].limit
    assert limit is not None and limit.unset == ("lower",)
    assert limit == Limit(1.0, 1.0, 0.0, 1.0)  # as urdfdom reads it
    # written back, the bound stays out (MuJoCo and PyBullet read a 0 written otherwise)
    written = fishbot_urdf.to_urdf(fishbot_urdf.load(path))
    assert '<limit upper="1" effort="1" velocity="1"/>' in written
