"""Rules about names and the link tree: what urdfdom refuses, and what it lets through."""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from ..analysis import Analysis
from ..diagnostics import (
    FOLLOWS,
    Diagnostic,
    Kind,
    Severity,
    Subject,
    did_you_mean,
    listing,
)
from ..model import Joint, Location, Robot
from . import Consumer, Family, Rule

__all__ = ["structure"]

_SIMULATORS = (Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET)
_ALL = (Consumer.URDFDOM, *_SIMULATORS)
E = Severity.ERROR

NO_LINKS = Rule(
    "no-links",
    E,
    Family.STRUCTURE,
    summary="The robot has no links.",
    explanation="A robot is made of links, and needs at least one. check_urdf fails on a "
    "`<robot>` with none (`No link elements found in urdf file`), and so do Gazebo and PyBullet. "
    "In a xacro file it usually means the links are in a macro that is never called, or in a file "
    "that is never included.",
    bad="""\
<robot name="fishbot">
  <material name="blue">
    <color rgba="0 0 1 1"/>
  </material>
</robot>
""",
    good="""\
<robot name="fishbot">
  <material name="blue">
    <color rgba="0 0 1 1"/>
  </material>
  <link name="base_link"/>
</robot>
""",
    # MuJoCo and Drake load an empty model.
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.PYBULLET),
)
DUPLICATE_LINK = Rule(
    "duplicate-link",
    E,
    Family.STRUCTURE,
    summary="Two links have the same name.",
    explanation="Links are found by name, by joints, TF and every tool, so each name may be used "
    "once. check_urdf fails with `link 'wheel_link' is not unique`, and Gazebo, MuJoCo, Drake and "
    "PyBullet refuse the file too. It often comes from a xacro macro called twice without a "
    "prefix that makes its names differ; give each link its own name.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="wheel_link"/>
  <link name="wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
DUPLICATE_JOINT = Rule(
    "duplicate-joint",
    E,
    Family.STRUCTURE,
    summary="Two joints have the same name.",
    explanation="Joint names must be unique too: joint states and controllers name the joint they "
    "mean. check_urdf fails with `joint 'wheel_joint' is not unique`, Gazebo and Drake refuse the "
    "file, and PyBullet crashes on it. Name each joint after what it moves.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    # MuJoCo 4.0 loads two joints of one name.
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.DRAKE, Consumer.PYBULLET),
)
DUPLICATE_MATERIAL = Rule(
    "duplicate-material",
    E,
    Family.STRUCTURE,
    summary="Two materials at the robot's top level have the same name.",
    explanation="A material defined directly in `<robot>` is shared, by name, with every "
    "`<visual>` that names it, so two of them with one name leave the colour in doubt. check_urdf "
    "fails with `material 'blue' is not unique`, Gazebo refuses the file, and Drake refuses two "
    "definitions that differ. Keep one, or give the other its own name.",
    bad="""\
<robot name="fishbot">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <material name="blue"><color rgba="0 0 0.8 1"/></material>
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="blue"/>
    </visual>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <material name="dark_blue"><color rgba="0 0 0.8 1"/></material>
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="blue"/>
    </visual>
  </link>
</robot>
""",
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.DRAKE),
)
UNDEFINED_LINK = Rule(
    "undefined-link",
    E,
    Family.STRUCTURE,
    summary="A joint's parent or child names a link that is not defined.",
    explanation="A joint connects two links by name, and both must be defined in the robot. "
    "check_urdf fails (`parent link [base] of joint [laser_joint] not found`), and Gazebo, "
    "MuJoCo, Drake and PyBullet refuse the file too. The cause is usually a typo, or a prefix "
    "that a xacro macro puts on one name and not on the other; fishbot suggests the closest link "
    "name.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base"/>
    <child link="laser_link"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/>
    <child link="laser_link"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
JOINT_SELF_LOOP = Rule(
    "joint-self-loop",
    E,
    Family.STRUCTURE,
    summary="A joint's parent and child are the same link.",
    explanation="A joint connects a parent link to another link, its child. With one link at both "
    "ends, check_urdf still reports success but leaves that link out of the tree it prints, and "
    "Gazebo and PyBullet load the robot without it; MuJoCo and Drake refuse the file. Name as "
    "parent the link the child is attached to.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="laser_link"/>
    <child link="laser_link"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/>
    <child link="laser_link"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
MISSING_LIMIT = Rule(
    "missing-limit",
    E,
    Family.STRUCTURE,
    summary="A revolute or prismatic joint has no <limit>.",
    explanation="A revolute or prismatic joint moves between end stops, so it needs `<limit lower "
    "upper effort velocity>`. check_urdf fails with `is of type REVOLUTE but it does not specify "
    "limits`, and Gazebo and PyBullet refuse the joint; MuJoCo and Drake let it move without end. "
    "A joint that turns without end, such as a wheel's axle, is continuous and needs no limit.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="-1.57" upper="1.57" effort="1.0" velocity="2.0"/>
  </joint>
</robot>
""",
    # MuJoCo and Drake read a revolute joint without <limit> as one that turns freely.
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.PYBULLET),
)
LIMIT_RANGE = Rule(
    "limit-range",
    E,
    Family.STRUCTURE,
    summary="A joint's lower limit is above its upper limit.",
    explanation="`lower` must not be above `upper`. check_urdf accepts such a joint, but the "
    "simulators each read it their own way: Gazebo swaps the two with a warning, MuJoCo and "
    "PyBullet drop the limit and let the joint turn past it, and Drake refuses the joint. Swap "
    "the two values, or check the sign of each.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="1.57" upper="-1.57" effort="1.0" velocity="2.0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="-1.57" upper="1.57" effort="1.0" velocity="2.0"/>
  </joint>
</robot>
""",
    consumers=_SIMULATORS,
)
NEGATIVE_LIMIT = Rule(
    "negative-limit",
    E,
    Family.STRUCTURE,
    summary="A joint's effort or velocity limit is negative.",
    explanation="`effort` (N or N*m) and `velocity` (m/s or rad/s) are the most a joint may push "
    "and move, in either direction, so they are zero or more. check_urdf accepts a negative one, "
    "but Gazebo reads it as no limit at all, and Drake refuses a negative velocity. Write the "
    "magnitude.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="-1.57" upper="1.57" effort="1.0" velocity="-2.0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="-1.57" upper="1.57" effort="1.0" velocity="2.0"/>
  </joint>
</robot>
""",
    # MuJoCo ignores the two values; PyBullet keeps them but does not apply them.
    consumers=(Consumer.GAZEBO, Consumer.DRAKE),
)
ZERO_AXIS = Rule(
    "zero-axis",
    E,
    Family.STRUCTURE,
    summary="A moving joint's axis is 0 0 0.",
    explanation="A joint turns about, or slides along, its `<axis>`, which therefore cannot be 0 "
    "0 0. check_urdf accepts it, but the KDL tree robot_state_publisher builds gives every link "
    "below the joint a NaN pose, and so does PyBullet; Gazebo reports an error and turns about 0 "
    "0 1 instead, and MuJoCo and Drake refuse the file. Give the direction, such as `0 1 0` for a "
    "wheel whose axle lies along y.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/>
    <child link="left_wheel_link"/>
    <axis xyz="0 0 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/>
    <child link="left_wheel_link"/>
    <axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
UNDEFINED_MIMIC = Rule(
    "undefined-mimic",
    E,
    Family.STRUCTURE,
    summary="A <mimic> names a joint that does not exist, its own joint, or a loop of mimics.",
    explanation='`<mimic joint="...">` makes a joint follow another one, named exactly. '
    "check_urdf accepts a name that matches no joint, but MoveIt logs an error and moves the "
    "joint on its own, MuJoCo ignores the mimic, and Drake refuses the file. Name the joint to "
    "follow. Joints that mimic each other round a loop (`a` follows `b`, `b` follows `a`) have "
    "no joint that moves of its own: let one of them lead.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
    <mimic joint="left_wheel"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
    <mimic joint="left_wheel_joint"/>
  </joint>
</robot>
""",
    # Gazebo and PyBullet read no <mimic> at all, right or wrong.
    consumers=(Consumer.URDFDOM, Consumer.MUJOCO, Consumer.DRAKE),
)
MULTIPLE_PARENTS = Rule(
    "multiple-parents",
    E,
    Family.STRUCTURE,
    summary="A link is the child of more than one joint.",
    explanation="In URDF every link but the root hangs from exactly one joint; a link that is the "
    "child of two joints closes a loop, which a tree cannot hold. check_urdf accepts it and "
    "prints the link twice, Gazebo counts the link's mass twice (with fixed joints), MuJoCo and "
    "Drake refuse the file, and PyBullet crashes. Keep one of the joints.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser_link"/>
  </joint>
  <joint name="laser_mount_joint" type="fixed">
    <parent link="base_link"/><child link="laser_link"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser_link"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
MULTIPLE_ROOTS = Rule(
    "multiple-roots",
    E,
    Family.STRUCTURE,
    summary="More than one link is no joint's child.",
    explanation="Every link but one must be some joint's child; the one that is not is the root "
    "the whole robot hangs from. A link that no joint reaches, usually because its joint was "
    "forgotten, is a second root: check_urdf fails with `Two root links found`, Gazebo refuses "
    "the file, PyBullet crashes, and Drake lets the extra part fall away as a body of its own. "
    "Add the joint that attaches it.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="imu_link"/>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed">
    <parent link="base_link"/><child link="imu_link"/>
  </joint>
</robot>
""",
    # MuJoCo welds every root link to the world, as it does the first.
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.DRAKE, Consumer.PYBULLET),
)
NO_ROOT = Rule(
    "no-root",
    E,
    Family.STRUCTURE,
    summary="Every link is some joint's child.",
    explanation="When every link is some joint's child, the joints form a loop and the robot has "
    "no root to hang from. check_urdf fails with `No root link found`, and Gazebo, MuJoCo, Drake "
    "and PyBullet refuse the file too. Look for a joint whose parent and child are swapped; the "
    "`cycle` finding names the loop.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser_link"/>
  </joint>
  <joint name="base_joint" type="fixed">
    <parent link="laser_link"/><child link="base_link"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser_link"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
CYCLE = Rule(
    "cycle",
    E,
    Family.STRUCTURE,
    summary="Joints form a loop.",
    explanation="URDF describes a tree: following joints from parent to child never leads back to "
    "a link already passed. When a loop leaves out the root, check_urdf reports success but "
    "silently leaves the loop's links out of the robot, and Gazebo and PyBullet do the same; "
    "MuJoCo and Drake refuse the file. Break the loop by giving each link its one parent on the "
    "way out from the root.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="right_wheel_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="left_wheel_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
UNREACHABLE_LINK = Rule(
    "unreachable-link",
    E,
    Family.STRUCTURE,
    summary="A link is not connected to the root (it hangs below a joint loop).",
    explanation="A link that hangs below a joint loop cannot be reached from the root, so it has "
    "no place in the robot. check_urdf reports success without it, Gazebo and PyBullet load the "
    "robot without it, and MuJoCo and Drake refuse the file. Break the loop (see `cycle`) and the "
    "link is attached again.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="arm_link"/>
  <link name="hand_link"/>
  <link name="tool_link"/>
  <joint name="arm_joint" type="fixed"><parent link="hand_link"/><child link="arm_link"/></joint>
  <joint name="hand_joint" type="fixed"><parent link="arm_link"/><child link="hand_link"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="hand_link"/><child link="tool_link"/></joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="arm_link"/>
  <link name="hand_link"/>
  <link name="tool_link"/>
  <joint name="arm_joint" type="fixed"><parent link="base_link"/><child link="arm_link"/></joint>
  <joint name="hand_joint" type="fixed"><parent link="arm_link"/><child link="hand_link"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="hand_link"/><child link="tool_link"/></joint>
</robot>
""",
    consumers=_ALL,
)


def structure(analysis: Analysis) -> Iterator[Diagnostic]:
    """Every finding about the robot's names, joints and link tree."""
    yield from _names(analysis)
    yield from _joints(analysis)
    yield from _tree(analysis)


def _robot(robot: Robot) -> str:
    """How findings name the robot (a nameless one is reported separately)."""
    return f"robot {robot.name!r}" if robot.name else "the robot"


def _the_robot(robot: Robot) -> Subject:
    return Subject(Kind.ROBOT, robot.name)


_DUPLICATES = {
    Kind.LINK: DUPLICATE_LINK,
    Kind.JOINT: DUPLICATE_JOINT,
    Kind.MATERIAL: DUPLICATE_MATERIAL,
}


def _names(analysis: Analysis) -> Iterator[Diagnostic]:
    robot, path = analysis.robot, analysis.path
    if not robot.links:
        yield NO_LINKS.report(
            f"{_robot(robot)} has no links",
            robot.source,
            path=path,
            subject=_the_robot(robot),
            hint='a robot needs at least one <link name="...">',
        )
    for kind, items in (
        (Kind.LINK, robot.links),
        (Kind.JOINT, robot.joints),
        (Kind.MATERIAL, robot.materials),
    ):
        first: dict[str, Location | None] = {}
        for item in items:
            if not item.name:
                continue
            if item.name in first:
                where = first[item.name]
                seen = f" (first defined at line {where.line})" if where else ""
                subject = Subject(kind, item.name)
                yield _DUPLICATES[kind].report(
                    f"{subject} is defined twice{seen}",
                    item.source,
                    path=path,
                    subject=subject,
                    hint=f"every {kind.value} needs a unique name",
                )
            else:
                first[item.name] = item.source


def _suggest(name: str, candidates: Iterable[str]) -> str:
    names = set(candidates)
    guess = did_you_mean(name, names)
    return f"{guess}links: {listing(names)}" if names else "the robot defines no links"


def _joints(analysis: Analysis) -> Iterator[Diagnostic]:
    robot, path = analysis.robot, analysis.path
    link_names = analysis.links.keys()
    joint_names = analysis.joints.keys()
    for joint in robot.joints:
        owner = Subject(Kind.JOINT, joint.name)
        parent, child = joint.parent, joint.child
        ends: tuple[tuple[str, str, Location | None], ...] = ()  # none undefined, nearly always
        if (parent and parent not in link_names) or (child and child not in link_names):
            ends = (("parent", parent, joint.parent_source), ("child", child, joint.child_source))
        for end, name, where in ends:
            if name and name not in link_names:
                yield UNDEFINED_LINK.report(
                    f"{owner}: {end} link {name!r} is not defined",
                    where or joint.source,
                    path=path,
                    subject=owner,
                    hint=_suggest(name, link_names),
                    data={"end": end, "link": name},
                )
        if joint.parent and joint.parent == joint.child:
            yield JOINT_SELF_LOOP.report(
                f"{owner}: parent and child are the same link {joint.parent!r}",
                joint.child_source or joint.source,
                path=path,
                subject=owner,
                hint="a joint connects two different links",
            )
        yield from _limits(joint, owner, path)
        if joint.type.uses_axis and joint.axis == (0.0, 0.0, 0.0):
            yield ZERO_AXIS.report(
                f"{owner}: the axis is 0 0 0, so the joint cannot move",
                joint.source,
                path=path,
                subject=owner,
                hint='give a unit vector, e.g. <axis xyz="0 0 1"/>',
            )
        mimic = joint.mimic
        if mimic is not None and mimic.joint:
            if mimic.joint not in joint_names:
                guess = did_you_mean(mimic.joint, joint_names).strip()
                yield UNDEFINED_MIMIC.report(
                    f"{owner}: mimics joint {mimic.joint!r}, which is not defined",
                    mimic.source,
                    path=path,
                    subject=owner,
                    hint=guess or "name an existing joint",
                )
            elif mimic.joint == joint.name:
                yield UNDEFINED_MIMIC.report(
                    f"{owner}: mimics itself",
                    mimic.source,
                    path=path,
                    subject=owner,
                    hint="name another joint",
                )
    yield from _mimic_loops(analysis)


def _mimic_loops(analysis: Analysis) -> Iterator[Diagnostic]:
    """Joints that mimic each other round a loop (a -> b -> a): none of them leads."""
    follows = {
        joint.name: joint.mimic.joint
        for joint in analysis.robot.joints
        if joint.mimic is not None and joint.mimic.joint and joint.mimic.joint != joint.name
    }
    done: set[str] = set()
    for start in follows:
        if start in done:
            continue
        trail: list[str] = []
        at: str | None = start
        while at is not None and at not in done and at not in trail:
            trail.append(at)
            at = follows.get(at)
        done.update(trail)
        if at is None or at not in trail:
            continue  # the chain ends at a joint that leads, or joins one seen before
        loop = trail[trail.index(at) :]
        shown = " -> ".join([*loop, loop[0]])
        for name in loop:
            joint = analysis.joints[name]
            owner = Subject(Kind.JOINT, name)
            assert joint.mimic is not None
            yield UNDEFINED_MIMIC.report(
                f"{owner}: mimics in a loop ({shown}), so no joint of it leads",
                joint.mimic.source,
                path=analysis.path,
                subject=owner,
                hint="let one joint of the loop mimic none",
            )


def _limits(joint: Joint, owner: Subject, path: str) -> Iterator[Diagnostic]:
    limit = joint.limit
    if limit is None:
        if joint.type.needs_limit:
            yield MISSING_LIMIT.report(
                f"{owner}: a {joint.type.value} joint needs <limit>",
                joint.source,
                path=path,
                subject=owner,
                hint='write <limit lower=".." upper=".." effort=".." velocity=".."/>',
            )
        return
    if joint.type.needs_limit and limit.lower > limit.upper:
        yield LIMIT_RANGE.report(
            f"{owner}: lower limit {limit.lower:g} is above upper limit {limit.upper:g}",
            limit.source,
            path=path,
            subject=owner,
            hint="swap them, lower <= upper",
        )
    for name in ("effort", "velocity"):
        value = getattr(limit, name)
        if value < 0:
            yield NEGATIVE_LIMIT.report(
                f"{owner}: {name} limit {value:g} is negative",
                limit.source,
                path=path,
                subject=owner,
                hint=f"{name} is a magnitude, >= 0",
            )


def _broken_ends(analysis: Analysis) -> list[str]:
    """The rules that report a joint whose parent or child is missing or misspelt: such a
    joint leaves its child as an extra root, which is their consequence, not news."""
    causes: set[str] = set()
    for joint in analysis.robot.joints:
        for name in (joint.parent, joint.child):
            if not name:
                causes.update(("missing-element", "missing-attribute"))
            elif name not in analysis.links:
                causes.add(UNDEFINED_LINK.id)
    return sorted(causes)


def _tree(analysis: Analysis) -> Iterator[Diagnostic]:
    robot, topo, path = analysis.robot, analysis.topology, analysis.path
    if not robot.links:
        return
    by_name = analysis.links
    for name, joints in topo.parents.items():
        if len(joints) > 1:
            listed = ", ".join(repr(j.name) for j in joints)
            yield MULTIPLE_PARENTS.report(
                f"link {name!r} is the child of {len(joints)} joints: {listed}",
                joints[1].child_source or joints[1].source,
                path=path,
                subject=Subject(Kind.LINK, name),
                hint="a link has one parent joint; in a URDF tree loops are not allowed",
            )
    if len(topo.roots) > 1:
        listed = ", ".join(repr(r) for r in topo.roots)
        yield MULTIPLE_ROOTS.report(
            f"{_robot(robot)} has {len(topo.roots)} root links: {listed}",
            by_name[topo.roots[1]].source,
            path=path,
            subject=_the_robot(robot),
            hint="connect every link but one to a parent with a joint",
            data={"roots": list(topo.roots), FOLLOWS: _broken_ends(analysis)},
        )
    if not topo.roots:
        yield NO_ROOT.report(
            f"{_robot(robot)} has no root link: every link is some joint's child",
            robot.source,
            path=path,
            subject=_the_robot(robot),
            hint="one link must be no joint's child; look for a joint loop",
        )
    in_loop: set[str] = set()
    for loop in analysis.loops:
        links = [j.parent for j in loop]
        in_loop.update(links)
        first = min(loop, key=lambda j: j.source.line if j.source else 0)
        yield CYCLE.report(
            f"joints {', '.join(repr(j.name) for j in loop)} form a loop: "
            + " -> ".join([*links, links[0]]),
            first.source,
            path=path,
            subject=Subject(Kind.JOINT, first.name),
            hint="URDF is a tree; break the loop or model it with a mimic joint",
            data={"joints": [j.name for j in loop]},
        )
    if len(topo.roots) <= 1:
        for link in robot.links:
            if link.name not in topo.reachable and link.name not in in_loop:
                yield UNREACHABLE_LINK.report(
                    f"link {link.name!r} is not connected to the root",
                    link.source,
                    path=path,
                    subject=Subject(Kind.LINK, link.name),
                    hint="it hangs below a joint loop",
                )
