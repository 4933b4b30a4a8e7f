"""The kinematic plan (`fishbot_urdf.analysis.plan`) and its two evaluators: the plain
Python one `check` uses and the numpy `Kinematics` agree to 1e-12, with each other and with
a reference written here from URDF's definitions, on random trees with every joint type and
mimics of every kind, and on every robot the test dependencies ship."""

from __future__ import annotations

import math
import sysconfig
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import fishbot_urdf
from fishbot_urdf import Joint, JointType, Kinematics, Link, Mimic, Origin, Robot, link_poses
from fishbot_urdf.analysis import analyse
from fishbot_urdf.analysis.poses import place
from fishbot_urdf.errors import FishbotUrdfError, StructureError

ONE = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)
TYPES = (*ONE, JointType.FIXED, JointType.FLOATING, JointType.PLANAR)
PARTS = {
    JointType.PLANAR: ("x", "y", "yaw"),
    JointType.FLOATING: ("x", "y", "z", "roll", "pitch", "yaw"),
}


# -- a reference, from the definitions: 4x4 matrices, rotations as products ---------------
def _rx(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _ry(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rz(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """URDF's rpy: about the fixed x, then y, then z."""
    return _rz(yaw) @ _ry(pitch) @ _rx(roll)


def _about(axis: np.ndarray, angle: float) -> np.ndarray:
    """The rotation by ``angle`` about the unit ``axis``: a turn about z, seen in an
    orthonormal basis whose third vector is ``axis`` (no Rodrigues)."""
    helper = np.eye(3)[int(np.argmin(np.abs(axis)))]
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    basis = np.column_stack([u, np.cross(axis, u), axis])
    return basis @ _rz(angle) @ basis.T


def _matrix(rotation: np.ndarray, translation: np.ndarray) -> np.ndarray:
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = rotation, translation
    return out


def _unit(axis: tuple[float, float, float]) -> np.ndarray | None:
    vector = np.array(axis, dtype=float)
    norm = math.hypot(*vector)  # (a sum of squares underflows for an axis like 1e-160)
    return vector / norm if norm > 0 else None


def _plane(axis: np.ndarray | None) -> np.ndarray:
    """x and y turned by the shortest rotation from z to ``axis``, as columns (3, 2); for
    -z, and for no axis at all, half a turn about x."""
    z = np.array([0.0, 0.0, 1.0])
    if axis is None or np.linalg.norm(np.cross(z, axis)) < 1e-12:
        turn = np.eye(3) if axis is not None and axis[2] > 0 else _rx(math.pi).round()
    else:
        about = np.cross(z, axis)
        sine = float(np.linalg.norm(about))  # atan2, not acos: near z acos loses half the digits
        turn = _about(about / sine, math.atan2(sine, float(axis[2])))
    return turn[:, :2]


def _reference(robot: Robot, q: dict[str, float]) -> tuple[dict[str, np.ndarray], list[str]]:
    """Every link's pose on a tree whose first joint to each link is its parent joint, and
    the variables in file order (``q`` names them; what it leaves out is 0).

    A mimic joint (revolute, continuous, prismatic) is at multiplier * leader + offset, its
    chain followed to a joint that mimics nothing; a chain reaching a fixed, planar or
    floating joint, or a joint that is no link's parent joint, holds it at the chain's
    offset; a chain that names no joint, or loops, leaves it to move on its own."""
    by_name: dict[str, Joint] = {}
    for joint in robot.joints:
        by_name.setdefault(joint.name, joint)
    parent_of: dict[str, Joint] = {}
    for joint in robot.joints:
        parent_of.setdefault(joint.child, joint)
    placing = {id(j) for j in parent_of.values()}

    def chain(joint: Joint) -> tuple[str | None, float, float] | None:
        multiplier, offset, seen, current = 1.0, 0.0, {joint.name}, joint
        while current.mimic is not None:
            leader = by_name.get(current.mimic.joint)
            if leader is None or leader.name in seen:
                return None  # on its own
            offset += multiplier * current.mimic.offset
            multiplier *= current.mimic.multiplier
            if leader.type not in ONE:
                return (None, 0.0, offset)
            seen.add(leader.name)
            current = leader
        return (current.name, multiplier, offset)

    variables: list[str] = []
    for joint in robot.joints:
        if id(joint) not in placing:
            continue
        if joint.type in PARTS:
            variables.extend(f"{joint.name}.{p}" for p in PARTS[joint.type])
        elif joint.type in ONE and (joint.mimic is None or chain(joint) is None):
            variables.append(joint.name)
    poses = {robot.links[0].name: np.eye(4)}
    for link in robot.links[1:]:
        joint = parent_of[link.name]
        pose = poses[joint.parent] @ _matrix(_rpy(*joint.origin.rpy), np.array(joint.origin.xyz))
        axis = _unit(joint.axis)
        if joint.type is JointType.FLOATING:
            v = [q.get(f"{joint.name}.{p}", 0.0) for p in PARTS[joint.type]]
            pose = pose @ _matrix(_rpy(*v[3:]), np.array(v[:3]))
        elif joint.type is JointType.PLANAR:
            x, y, yaw = (q.get(f"{joint.name}.{p}", 0.0) for p in PARTS[joint.type])
            turn = np.eye(3) if axis is None else _about(axis, yaw)
            pose = pose @ _matrix(turn, _plane(axis) @ np.array([x, y]))
        elif joint.type in ONE and axis is not None:
            found = chain(joint) if joint.mimic is not None else (joint.name, 1.0, 0.0)
            if found is None:
                found = (joint.name, 1.0, 0.0)
            leader, multiplier, offset = found
            value = offset
            if leader is not None and leader in variables:
                value += multiplier * q.get(leader, 0.0)
            if joint.type is JointType.PRISMATIC:
                pose = pose @ _matrix(np.eye(3), value * axis)
            else:
                pose = pose @ _matrix(_about(axis, value), np.zeros(3))
        poses[link.name] = pose
    return poses, variables


# -- random trees -------------------------------------------------------------------------
_small = st.floats(-2.0, 2.0, allow_nan=False)
_angle = st.floats(-math.pi, math.pi, allow_nan=False)
_vector = st.tuples(_small, _small, _small)
# Origins turned about x or z alone meet axes along x or z: the numpy side folds those turns
# into the joint's angle.
_rpys = st.one_of(
    st.tuples(_angle, _angle, _angle),
    st.tuples(st.just(0.0), st.just(0.0), _angle),
    st.tuples(_angle, st.just(0.0), st.just(0.0)),
)
_axes = st.one_of(
    st.sampled_from([(1.0, 0.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, -1.0)]),
    st.just((0.0, 0.0, 0.0)),
    _vector,
)


@st.composite
def _robots(draw: st.DrawFn) -> Robot:
    """A tree of up to 10 links in link order (each joint's parent comes before its child),
    with every joint type, random origins and axes, a few second joints to a link that
    already has its parent (no link's parent joint: a mimic of one is held), and mimics of
    every joint, of joints that do not exist, of themselves and round loops."""
    count = draw(st.integers(1, 10))
    shapes = []
    for child in range(1, count):
        parent = draw(st.integers(0, child - 1))
        shapes.append((f"j{child}", draw(st.sampled_from(TYPES)), parent, child))
    for k, (a, b) in enumerate(
        draw(st.lists(st.tuples(st.integers(0, 9), st.integers(0, 9)), max_size=2))
    ):
        if a < b < count:
            shapes.append((f"extra{k}", draw(st.sampled_from(TYPES)), a, b))
    names = [name for name, *_ in shapes]
    leaders = st.sampled_from([*names, "nowhere"]) if names else st.just("nowhere")
    mimics = st.one_of(
        st.none(),
        st.builds(Mimic, leaders, st.floats(-3.0, 3.0), st.floats(-2.0, 2.0)),
    )
    joints = tuple(
        Joint(
            name,
            joint_type,
            f"l{parent}",
            f"l{child}",
            Origin(draw(_vector), draw(_rpys)),
            draw(_axes),
            mimic=draw(mimics),
        )
        for name, joint_type, parent, child in shapes
    )
    return Robot("r", links=tuple(Link(f"l{i}") for i in range(count)), joints=joints)


@settings(max_examples=400, deadline=None)
@given(_robots(), st.integers(0, 2**32 - 1))
def test_both_evaluators_and_the_reference_agree_on_random_trees(robot: Robot, seed: int) -> None:
    kin = Kinematics(robot)
    plan = kin.analysis.plan
    rng = np.random.default_rng(seed)
    q = rng.uniform(-math.pi, math.pi, len(plan.variables))
    expected, variables = _reference(robot, dict(zip(plan.variables, q, strict=True)))
    assert list(plan.variables) == variables
    numpy_poses = kin.forward(q)
    plain_poses = place(plan, list(q))
    assert sorted(plan.links) == sorted(expected)  # a tree: every link placed
    for i, name in enumerate(plan.links):
        plain = np.array(plain_poses[i].matrix())
        np.testing.assert_allclose(numpy_poses[i], plain, rtol=0, atol=1e-12, err_msg=name)
        np.testing.assert_allclose(plain, expected[name], rtol=0, atol=1e-12, err_msg=name)
    # link_poses takes the revolute, continuous and prismatic joints' positions by name
    named = {
        joint: float(q[column])
        for joint, column in plan.columns.items()
        if kin.analysis.joints[joint].type in ONE
    }
    at_zero = kin.configuration(named)
    public = link_poses(kin.analysis, named)
    for i, pose in enumerate(kin.forward(at_zero)):
        np.testing.assert_allclose(
            np.array(public[plan.links[i]].matrix()), pose, rtol=0, atol=1e-12
        )


def test_the_plan_resolves_every_mimic_to_its_driver() -> None:
    # fixed <- planar-mimic; chain c3 -> c2 -> c1; a loop; a mimic of a fixed joint; a fixed
    # joint that mimics: each one's driver, multiplier and offset, whatever its type.
    robot = Robot(
        "r",
        links=tuple(Link(n) for n in "abcdefgh"),
        joints=(
            Joint("c1", JointType.CONTINUOUS, "a", "b"),
            Joint("c2", JointType.REVOLUTE, "b", "c", mimic=Mimic("c1", 2.0, 0.5)),
            Joint("c3", JointType.PRISMATIC, "c", "d", mimic=Mimic("c2", -1.0, 0.25)),
            Joint("weld", JointType.FIXED, "a", "e", mimic=Mimic("c1", 3.0, 1.0)),
            Joint("held", JointType.REVOLUTE, "e", "f", mimic=Mimic("weld", 2.0, 0.5)),
            Joint("loop1", JointType.CONTINUOUS, "a", "g", mimic=Mimic("loop2")),
            Joint("loop2", JointType.CONTINUOUS, "g", "h", mimic=Mimic("loop1")),
        ),
    )
    plan = analyse(robot).plan
    assert plan.variables == ("c1", "loop1", "loop2")
    follows = {
        name: (f.leader, f.multiplier, f.offset) if f else None for name, f in plan.mimics.items()
    }
    # c3 = -(2 c1 + 0.5) + 0.25 = -2 c1 - 0.25
    assert follows == {
        "c2": ("c1", 2.0, 0.5),
        "c3": ("c1", -2.0, -0.25),
        "weld": ("c1", 3.0, 1.0),
        "held": (None, 0.0, 0.5),
        "loop1": None,
        "loop2": None,
    }
    steps = {plan.links[s.link]: s for s in plan.steps}
    assert (steps["d"].column, steps["d"].multiplier, steps["d"].offset) == (0, -2.0, -0.25)
    assert steps["e"].kind is JointType.FIXED  # a fixed joint does not move, mimic or not
    assert (steps["f"].column, steps["f"].offset) == (-1, 0.5)
    assert all(plan.index[plan.links[s.parent]] < s.link for s in plan.steps)


def _corpus() -> list[Path]:
    """Every URDF the test dependencies ship (example-robot-data, hpp-environments,
    cookie-description)."""
    found: list[Path] = []
    for key in ("purelib", "platlib"):
        share = Path(sysconfig.get_paths()[key])
        found += sorted((share / "cmeel.prefix" / "share").rglob("*.urdf"))
        found += sorted((share / "cookie_description").rglob("*.urdf"))
    return sorted(set(found))


CORPUS = _corpus()
# The corpus robots refused before any kinematics, as check_urdf refuses them too
# (tests/test_parity.py compares the two): example-robot-data's ur3.urdf has no robot name.
REFUSED = {"ur3.urdf"}


def test_the_corpus_is_installed() -> None:
    assert len(CORPUS) >= 150, "pip install -e '.[test]' installs the corpus"


@pytest.mark.parametrize("path", CORPUS, ids=[p.name for p in CORPUS])
def test_both_evaluators_agree_on_every_corpus_robot(path: Path) -> None:
    try:
        analysis = analyse(fishbot_urdf.load(path))
    except FishbotUrdfError:
        assert path.name in REFUSED
        return
    assert path.name not in REFUSED
    plan = analysis.plan
    try:
        kin = Kinematics(analysis)
    except StructureError:  # several roots: the plain evaluator poses each tree alone
        assert len(plan.roots) != 1 or analysis.topology.loop_from_root
        return
    rng = np.random.default_rng(len(plan.links))
    batch = rng.uniform(-math.pi, math.pi, (3, len(plan.variables)))
    numpy_poses = kin.forward(batch)
    for b, q in enumerate(batch):
        for i, pose in enumerate(place(plan, list(q))):
            np.testing.assert_allclose(
                numpy_poses[b, i], np.array(pose.matrix()), rtol=0, atol=1e-12
            )


def test_the_variables_outwards_follow_the_tree_not_the_file() -> None:
    # Joints written from the tip back to the root, a floating joint among them.
    def joint(name: str, parent: str, child: str, kind: JointType) -> Joint:
        return Joint(name, kind, parent, child, axis=(0.0, 0.0, 1.0))

    robot = Robot(
        "arm",
        links=tuple(Link(n) for n in ("base", "upper", "fore", "hand", "free")),
        joints=(
            joint("wrist", "fore", "hand", JointType.REVOLUTE),
            joint("loose", "base", "free", JointType.FLOATING),
            joint("elbow", "upper", "fore", JointType.CONTINUOUS),
            joint("shoulder", "base", "upper", JointType.CONTINUOUS),
        ),
    )
    plan = analyse(robot).plan
    assert plan.variables[0] == "wrist"
    outwards = plan.outwards()
    assert sorted(outwards) == sorted(plan.variables)
    assert outwards.index("shoulder") < outwards.index("elbow") < outwards.index("wrist")
    loose = [name for name in outwards if name.startswith("loose.")]
    assert loose == [name for name in plan.variables if name.startswith("loose.")]
    assert outwards.index(loose[-1]) - outwards.index(loose[0]) == len(loose) - 1  # together
