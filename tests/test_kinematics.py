"""`fishbot_urdf.kinematics`: link poses at a joint configuration."""

from __future__ import annotations

import math

import pytest
from conftest import FISHBOT

import fishbot_urdf
from fishbot_urdf.errors import ArgumentError, UnknownNameError
from fishbot_urdf.kinematics import Kinematics, joint_positions, link_poses
from fishbot_urdf.model import Joint, JointType, Limit, Link, Mimic, Origin, Robot

LIMIT = Limit(effort=1.0, velocity=1.0, lower=-3.0, upper=3.0)


def _arm() -> Robot:
    # base -(shoulder: revolute about z, 1 m along x)-> upper -(elbow, same)-> fore
    # -(slide: prismatic along 0 0 2, i.e. z)-> tip; 'copy' mimics the shoulder x2 + 0.5.
    return Robot(
        "arm",
        links=tuple(Link(n) for n in ("base", "upper", "fore", "tip", "copy")),
        joints=(
            Joint(
                "shoulder",
                JointType.REVOLUTE,
                "base",
                "upper",
                Origin((1.0, 0, 0)),
                (0, 0, 1),
                LIMIT,
            ),
            Joint(
                "elbow", JointType.REVOLUTE, "upper", "fore", Origin((1.0, 0, 0)), (0, 0, 1), LIMIT
            ),
            Joint("slide", JointType.PRISMATIC, "fore", "tip", Origin(), (0, 0, 2), LIMIT),
            Joint(
                "copy_joint",
                JointType.REVOLUTE,
                "base",
                "copy",
                axis=(0, 0, 1),
                limit=LIMIT,
                mimic=Mimic("shoulder", multiplier=2.0, offset=0.5),
            ),
        ),
    )


def test_zero_configuration_reproduces_the_origins() -> None:
    robot = fishbot_urdf.load(FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro")
    poses = link_poses(robot)
    # base_joint 0 0 0.091, then left_wheel_joint 0 0.1 -0.06; laser 0.10 + 0.05 up.
    assert poses["left_wheel_link"].translation == pytest.approx((0.0, 0.1, 0.031))
    assert poses["laser_link"].translation == pytest.approx((0.0, 0.0, 0.241))
    assert poses["base_footprint"].translation == (0.0, 0.0, 0.0)
    assert set(poses) == {link.name for link in robot.links}


def test_revolute_and_prismatic_joints_move_their_children() -> None:
    poses = link_poses(_arm(), {"shoulder": math.pi / 2, "slide": 0.25})
    # The shoulder turns 90 degrees: the elbow, 1 m along the upper arm's x, is at (1, 1, 0).
    assert poses["fore"].translation == pytest.approx((1.0, 1.0, 0.0))
    # The slide moves 0.25 m along its (normalised) axis z.
    assert poses["tip"].translation == pytest.approx((1.0, 1.0, 0.25))
    # fore's x axis now points along the world's y.
    assert [row[0] for row in poses["fore"].rotation] == pytest.approx([0.0, 1.0, 0.0], abs=1e-12)


def test_mimic_joints_follow_their_leader() -> None:
    values = joint_positions(_arm(), {"shoulder": 0.25})
    assert values["copy_joint"] == 2.0 * 0.25 + 0.5
    assert joint_positions(_arm())["copy_joint"] == 0.5
    assert joint_positions(_arm(), {"copy_joint": 1.0})["copy_joint"] == 1.0


def test_positions_must_name_moving_joints() -> None:
    with pytest.raises(UnknownNameError, match="no joint 'wrist'") as info:
        link_poses(_arm(), {"wrist": 1.0})
    assert isinstance(info.value, KeyError)  # as a mapping lookup would raise
    assert info.value.known == ("copy_joint", "elbow", "shoulder", "slide")
    robot = Robot("r", (Link("a"), Link("b")), (Joint("j", JointType.FIXED, "a", "b"),))
    with pytest.raises(ArgumentError, match="joint 'j' is fixed") as wrong:
        link_poses(robot, {"j": 1.0})
    assert isinstance(wrong.value, ValueError)


def test_a_long_chain_needs_no_recursion() -> None:
    n = 20_000
    links = tuple(Link(f"l{i}") for i in range(n))
    joints = tuple(
        Joint(f"j{i}", JointType.FIXED, f"l{i}", f"l{i + 1}", Origin((0.001, 0, 0)))
        for i in range(n - 1)
    )
    poses = link_poses(Robot("chain", links, joints))
    assert poses[f"l{n - 1}"].translation[0] == pytest.approx(0.001 * (n - 1))


def test_positions_must_be_finite() -> None:
    with pytest.raises(ValueError, match="not a finite number"):
        link_poses(_arm(), {"shoulder": float("nan")})


def test_both_evaluators_word_a_refused_position_alike() -> None:
    arm = _arm()
    numpy = Kinematics(arm)
    # the same value refused by the plain-Python evaluator and by the numpy one, in words
    # the command line's -j gives too
    for positions in ({"shoulder": math.nan}, {"slide": 3.5}, {"elbow": -3.5}):
        with pytest.raises(ArgumentError) as plain:
            link_poses(arm, positions)
        with pytest.raises(ArgumentError) as batched:
            numpy.configuration(positions)
        assert plain.value.message == batched.value.message
        assert plain.value.name == batched.value.name == next(iter(positions))
    with pytest.raises(ArgumentError) as outside:
        link_poses(arm, {"slide": 3.5})
    assert outside.value.message == "joint 'slide': position 3.5 is outside its limits -3 .. 3"
    # a mimic joint is no variable of the configuration: it is said to follow its leader
    with pytest.raises(ArgumentError, match="'copy_joint' mimics 'shoulder' and follows it"):
        numpy.configuration({"copy_joint": 0.1})
