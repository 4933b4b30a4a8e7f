"""`fishbot_urdf.Kinematics`: batched forward kinematics, frame queries and Jacobians, against
pinocchio (the PyPI `pin` wheel) on every corpus robot, and against the plain-Python poses."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from conftest import FISHBOT, golden_inputs

import fishbot_urdf
from fishbot_urdf import (
    ArgumentError,
    Joint,
    JointType,
    Kinematics,
    Link,
    Mimic,
    Origin,
    Robot,
    RobotError,
    UnknownNameError,
    forward_kinematics,
    link_poses,
    transform,
)
from fishbot_urdf.spatial import Pose, axis_angle, rpy_matrix

CORPUS = [item for item in golden_inputs() if item.in_corpus]
# Corpus robots we refuse to load (check_urdf refuses them too): nothing to compare.
REFUSED = {"ur3.urdf"}


def _pin_configuration(model: pin.Model, kin: Kinematics, q: np.ndarray) -> np.ndarray:
    """Our configuration as pinocchio's q: continuous joints as (cos, sin); a mimic joint
    (a joint of its own in pinocchio) at its leader's value times multiplier plus offset."""
    values = dict(zip(kin.variables, q, strict=True))
    out = np.zeros(model.nq)
    for j in range(1, model.njoints):
        joint = model.joints[j]
        value = _value(kin, model.names[j], values)
        if joint.nq == 2:
            out[joint.idx_q : joint.idx_q + 2] = (math.cos(value), math.sin(value))
        else:
            assert joint.nq == 1, joint.shortname()
            out[joint.idx_q] = value
    return out


def _value(kin: Kinematics, name: str, values: dict[str, float]) -> float:
    if name in values:
        return values[name]
    joint = kin.analysis.joints[name]
    assert joint.mimic is not None, name
    return joint.mimic.multiplier * _value(kin, joint.mimic.joint, values) + joint.mimic.offset


def _our_jacobian_from_pins(model: pin.Model, kin: Kinematics, pins: np.ndarray) -> np.ndarray:
    """Pinocchio's frame Jacobian in our columns: a mimic joint's column, times its
    multiplier, added to its leader's."""
    out = np.zeros((6, len(kin.variables)))
    where = {name: i for i, name in enumerate(kin.variables)}
    for j in range(1, model.njoints):
        name, factor = model.names[j], 1.0
        while name not in where:
            joint = kin.analysis.joints[name]
            assert joint.mimic is not None
            factor *= joint.mimic.multiplier
            name = joint.mimic.joint
        out[:, where[name]] += factor * pins[:, model.joints[j].idx_v]
    return out


@pytest.mark.parametrize("item", CORPUS, ids=[item.id for item in CORPUS])
def test_poses_and_jacobians_are_pinocchios(item: object) -> None:
    path = str(item.path)  # type: ignore[attr-defined]
    if Path(path).name in REFUSED:
        with pytest.raises(RobotError):
            fishbot_urdf.load(path)
        return
    kin = Kinematics(fishbot_urdf.load(path))
    model = pin.buildModelFromUrdf(path)
    data = model.createData()
    rng = np.random.default_rng(len(path))
    batch = rng.uniform(-math.pi, math.pi, (3, len(kin.variables)))
    ours = kin.forward(batch)
    bodies = [f for f in range(model.nframes) if model.frames[f].type == pin.FrameType.BODY]
    assert {model.frames[f].name for f in bodies} == set(kin.links)
    if model.nv == 0:  # pinocchio's Jacobians crash (SIGSEGV) on a robot with no joints
        pin.framesForwardKinematics(model, data, np.zeros(0))
        for f in bodies:
            theirs = data.oMf[f].homogeneous
            np.testing.assert_allclose(ours[:, kin.link_index(model.frames[f].name)][0], theirs)
        assert kin.jacobian(batch[0], kin.links[-1]).shape == (6, 0)
        return
    for b, q in enumerate(batch):
        pin.computeJointJacobians(model, data, _pin_configuration(model, kin, q))
        pin.updateFramePlacements(model, data)
        for f in bodies:
            name = model.frames[f].name
            theirs = data.oMf[f].homogeneous
            np.testing.assert_allclose(ours[b, kin.link_index(name)], theirs, rtol=0, atol=1e-12)
            j_pin = pin.getFrameJacobian(model, data, f, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
            expected = _our_jacobian_from_pins(model, kin, j_pin)
            np.testing.assert_allclose(kin.jacobian(q, name), expected, rtol=0, atol=1e-12)


def test_the_zero_configuration_is_the_plain_poses() -> None:
    robot = fishbot_urdf.load(FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro")
    kin = Kinematics(robot)
    plain = link_poses(robot)
    poses = kin.forward(np.zeros(len(kin.variables)))
    for i, name in enumerate(kin.links):
        np.testing.assert_allclose(poses[i], np.array(plain[name].matrix()), atol=1e-15)


def test_a_batch_is_its_configurations_one_by_one_and_a_mapping_is_a_vector() -> None:
    robot = fishbot_urdf.load(FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro")
    kin = Kinematics(robot)
    assert kin.variables == ("left_wheel_joint", "right_wheel_joint")
    batch = np.random.default_rng(3).uniform(-3, 3, (5, 2))
    together = kin.forward(batch)
    assert together.shape == (5, len(kin.links), 4, 4)
    for b in range(5):
        np.testing.assert_array_equal(together[b], kin.forward(batch[b]))
    named = forward_kinematics(robot, {"right_wheel_joint": 0.5})
    np.testing.assert_array_equal(named, kin.forward(np.array([0.0, 0.5])))
    plain = link_poses(robot, {"right_wheel_joint": 0.5})["right_wheel_link"]
    np.testing.assert_allclose(
        named[kin.link_index("right_wheel_link")], np.array(plain.matrix()), atol=1e-15
    )


def test_bad_configurations_are_named() -> None:
    kin = Kinematics(fishbot_urdf.load(FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"))
    with pytest.raises(UnknownNameError, match="did you mean 'left_wheel_joint'"):
        kin.forward({"left_whel_joint": 1.0})
    with pytest.raises(UnknownNameError, match="no link 'base_lnk'"):
        kin.transform({}, "base_lnk", "laser_link")
    with pytest.raises(ArgumentError, match=r"shape \(n,\) or \(B, n\) with n = 2"):
        kin.forward(np.zeros(3))
    with pytest.raises(ArgumentError, match="not a finite number"):
        kin.forward({"left_wheel_joint": math.inf})


def test_a_transform_is_the_inverse_of_the_other_way_and_pose_inverse_agrees() -> None:
    robot = fishbot_urdf.load(FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro")
    q = {"left_wheel_joint": 1.2}
    there = transform(robot, q, "left_wheel_link", "laser_link")
    back = transform(robot, q, "laser_link", "left_wheel_link")
    np.testing.assert_allclose(there @ back, np.eye(4), atol=1e-15)
    poses = link_poses(robot, q)
    plain = poses["left_wheel_link"].inverse().then(poses["laser_link"])
    np.testing.assert_allclose(there, np.array(plain.matrix()), atol=1e-15)


def test_pose_inverse_undoes_the_pose() -> None:
    pose = Pose(rpy_matrix((0.3, -1.1, 2.0)), (1.0, -2.0, 0.5))
    both = pose.then(pose.inverse())
    np.testing.assert_allclose(np.array(both.matrix()), np.eye(4), atol=1e-15)


def _one(joint_type: JointType, axis: tuple[float, float, float] = (0.0, 0.0, 1.0)) -> Robot:
    origin = Origin((0.1, -0.2, 0.3), (0.4, 0.5, -0.6))
    return Robot(
        "r",
        links=(Link("a"), Link("b")),
        joints=(Joint("j", joint_type, "a", "b", origin, axis),),
    )


def test_floating_joints_take_xyz_then_rpy_as_pinocchios_free_flyer() -> None:
    kin = Kinematics(_one(JointType.FLOATING))
    assert kin.variables == ("j.x", "j.y", "j.z", "j.roll", "j.pitch", "j.yaw")
    q = np.array([0.5, -1.0, 2.0, 0.3, -0.2, 1.4])
    origin = Pose(rpy_matrix((0.4, 0.5, -0.6)), (0.1, -0.2, 0.3))
    expected = origin.then(Pose(rpy_matrix((0.3, -0.2, 1.4)), (0.5, -1.0, 2.0)))
    np.testing.assert_allclose(kin.forward(q)[1], np.array(expected.matrix()), atol=1e-15)
    # pinocchio's free flyer: q = (x, y, z, qx, qy, qz, qw), v in the child frame
    model = pin.Model()
    placement = pin.SE3(np.array(origin.rotation), np.array(origin.translation))
    joint = model.addJoint(0, pin.JointModelFreeFlyer(), placement, "j")
    model.addBodyFrame("b", joint, pin.SE3.Identity(), 0)
    data = model.createData()
    quat = pin.Quaternion(np.array(rpy_matrix((0.3, -0.2, 1.4))))
    q_pin = np.concatenate([q[:3], quat.coeffs()])
    pin.computeJointJacobians(model, data, q_pin)
    pin.updateFramePlacements(model, data)
    frame = model.getFrameId("b")
    np.testing.assert_allclose(kin.forward(q)[1], data.oMf[frame].homogeneous, atol=1e-12)
    theirs = pin.getFrameJacobian(model, data, frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    np.testing.assert_allclose(kin.jacobian(q, "b"), theirs, atol=1e-12)


def test_planar_joints_take_x_y_yaw_in_the_plane_normal_to_the_axis() -> None:
    kin = Kinematics(_one(JointType.PLANAR))
    assert kin.variables == ("j.x", "j.y", "j.yaw")
    q = np.array([0.5, -1.0, 0.7])
    origin = Pose(rpy_matrix((0.4, 0.5, -0.6)), (0.1, -0.2, 0.3))
    expected = origin.then(Pose(rpy_matrix((0.0, 0.0, 0.7)), (0.5, -1.0, 0.0)))
    np.testing.assert_allclose(kin.forward(q)[1], np.array(expected.matrix()), atol=1e-15)
    model = pin.Model()
    placement = pin.SE3(np.array(origin.rotation), np.array(origin.translation))
    joint = model.addJoint(0, pin.JointModelPlanar(), placement, "j")
    model.addBodyFrame("b", joint, pin.SE3.Identity(), 0)
    data = model.createData()
    pin.computeJointJacobians(model, data, np.array([0.5, -1.0, math.cos(0.7), math.sin(0.7)]))
    pin.updateFramePlacements(model, data)
    frame = model.getFrameId("b")
    theirs = pin.getFrameJacobian(model, data, frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    np.testing.assert_allclose(kin.jacobian(q, "b"), theirs, atol=1e-12)
    # about x: the plane is y-z (z turned onto x by the shortest rotation takes x to -z)
    sideways = Kinematics(_one(JointType.PLANAR, (1.0, 0.0, 0.0)))
    moved = sideways.forward(np.array([1.0, 0.0, 0.0]))[1]
    np.testing.assert_allclose(moved[:3, 3], origin.apply((0.0, 0.0, -1.0)), atol=1e-15)


def test_mimic_chains_follow_their_first_leader() -> None:
    robot = Robot(
        "r",
        links=(Link("a"), Link("b"), Link("c"), Link("d")),
        joints=(
            Joint("j1", JointType.CONTINUOUS, "a", "b"),
            Joint("j2", JointType.CONTINUOUS, "b", "c", mimic=Mimic("j1", 2.0, 0.1)),
            Joint("j3", JointType.PRISMATIC, "c", "d", mimic=Mimic("j2", -1.0, 0.5)),
        ),
    )
    kin = Kinematics(robot)
    assert kin.variables == ("j1",)
    poses = kin.forward(np.array([0.3]))
    # j2 = 2 * 0.3 + 0.1 = 0.7 about x (the default axis); j3 = -0.7 + 0.5 = -0.2 along x
    plain = link_poses(robot, {"j1": 0.3})
    np.testing.assert_allclose(
        poses[kin.link_index("d")], np.array(plain["d"].matrix()), atol=1e-15
    )
    assert poses[kin.link_index("d")][0, 3] == pytest.approx(-0.2)  # along x, the default axis


def test_a_10000_link_chain_works_without_recursion() -> None:
    count = 10_000
    links = tuple(Link(f"l{i}") for i in range(count))
    joints = tuple(
        Joint(
            f"j{i}",
            JointType.REVOLUTE,
            f"l{i}",
            f"l{i + 1}",
            Origin((0.0, 0.0, 0.01)),
            limit=fishbot_urdf.Limit(1.0, 1.0, -1.0, 1.0),
        )
        for i in range(count - 1)
    )
    kin = Kinematics(Robot("chain", links, joints))
    poses = kin.forward(np.zeros((2, count - 1)))
    assert poses.shape == (2, count, 4, 4)
    # straight up: the last link 9 999 steps of 0.01 m above the first
    assert poses[1, -1, 2, 3] == pytest.approx(99.99)


def test_both_evaluators_follow_one_mimic_rule() -> None:
    # A revolute joint mimicking a fixed joint is held at its offset (the fixed joint is at
    # 0); one mimicking a planar joint too; mimics that loop move on their own.
    robot = Robot(
        "r",
        links=tuple(Link(n) for n in "abcdefgh"),
        joints=(
            Joint("fixed", JointType.FIXED, "a", "b"),
            Joint("held", JointType.REVOLUTE, "b", "c", mimic=Mimic("fixed", 2.0, 0.5)),
            Joint("plane", JointType.PLANAR, "a", "d"),
            Joint("held2", JointType.CONTINUOUS, "d", "e", mimic=Mimic("plane", 1.0, -0.25)),
            Joint("loop1", JointType.CONTINUOUS, "a", "f", mimic=Mimic("loop2", 1.0, 0.3)),
            Joint("loop2", JointType.CONTINUOUS, "f", "g", mimic=Mimic("loop1", 1.0, 0.2)),
            Joint("lead", JointType.PRISMATIC, "a", "h"),
        ),
    )
    kin = Kinematics(robot)
    assert kin.variables == ("plane.x", "plane.y", "plane.yaw", "loop1", "loop2", "lead")
    rng = np.random.default_rng(7)
    for _ in range(20):
        loop1, loop2, lead = rng.uniform(-3, 3, 3)
        q = kin.configuration({"loop1": loop1, "loop2": loop2, "lead": lead})
        plain = link_poses(robot, {"loop1": loop1, "loop2": loop2, "lead": lead})
        poses = kin.forward(q)
        for link in "abcdefgh":
            np.testing.assert_allclose(
                poses[kin.link_index(link)], np.array(plain[link].matrix()), atol=1e-12
            )
    turned = Pose(rotation=axis_angle((1.0, 0.0, 0.0), 0.5))  # the default axis, at 0.5
    np.testing.assert_allclose(
        kin.forward(kin.configuration())[kin.link_index("c")],
        np.array(turned.matrix()),
        atol=1e-15,
    )
