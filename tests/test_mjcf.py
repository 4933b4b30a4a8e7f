"""`fishbot_urdf.export.mjcf`: the MJCF MuJoCo compiles, held body by body to the robot's own
masses, centres of mass and inertias, and to our kinematics at random configurations within
the limits (which tests/test_fk.py holds to pinocchio's on the same corpus), on the fishbot
and every robot of example-robot-data MuJoCo does not refuse as written."""

from __future__ import annotations

import math
import struct
from pathlib import Path

import mujoco
import numpy as np
import pinocchio as pin
import pytest
from conftest import FISHBOT, golden_inputs

import fishbot_urdf
from fishbot_urdf import Kinematics
from fishbot_urdf.analysis import Analysis, of
from fishbot_urdf.config import Config
from fishbot_urdf.diagnostics import Diagnostic
from fishbot_urdf.errors import ArgumentError, StructureError
from fishbot_urdf.export.mjcf import export_mjcf, to_mjcf
from fishbot_urdf.kinematics import joint_positions, link_poses
from fishbot_urdf.model import Inertial, JointType
from fishbot_urdf.spatial import Pose

CORPUS = [item for item in golden_inputs() if item.in_corpus]
XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"
TOLERANCE = 1e-9

# The corpus robots left out, each with why: what MuJoCo says when it refuses the robot as
# written (its inertials, a mesh), or, for ur3, that we refuse it (check_urdf does too).
EXCLUDED = {
    "human_description/robots/human.urdf": "moving bodies must be larger than mjMINVAL",
    "icub_description/robots/icub.urdf": "A + B >= C",
    "icub_description/robots/icub_reduced.urdf": "A + B >= C",
    "romeo_description/urdf/romeo.urdf": "moving bodies must be larger than mjMINVAL",
    "romeo_description/urdf/romeo_laas_small.urdf": "A + B >= C",
    "romeo_description/urdf/romeo_small.urdf": "A + B >= C",
    "ur_description/urdf/ur3.urdf": "has no name",
}


def _packages() -> dict[str, Path]:
    """example-robot-data's meshes are named package://example-robot-data/robots/..."""
    folder = CORPUS[0].path
    while folder.name != "example-robot-data":
        folder = folder.parent
    return {"example-robot-data": folder}


def _corpus_id(item: object) -> str:
    return item.id.partition("/")[2]  # type: ignore[attr-defined]


def test_the_exclusions_are_known() -> None:
    assert len(EXCLUDED) == 7
    assert set(EXCLUDED) <= {_corpus_id(item) for item in CORPUS}
    assert len(CORPUS) - len(EXCLUDED) == 62


def _analysis(path: Path, packages: dict[str, Path] | None = None) -> Analysis:
    return of(fishbot_urdf.load(path, packages=packages), packages=packages)


def _held_to_ours(analysis: Analysis, text: str, seed: int, urdf: Path | None = None) -> None:
    """The model of ``text`` compiles, and body by body has our masses, centres of mass,
    inertias and link poses (at the zero configuration and at random ones); and, for the
    ``urdf`` file pinocchio reads, pinocchio's link poses, mass and centre of mass."""
    model = mujoco.MjModel.from_xml_string(text)
    data = mujoco.MjData(model)
    data.qpos[:] = _qpos(model, joint_positions(analysis))  # a mimic's offset moves it
    mujoco.mj_forward(model, data)
    names = [model.body(b).name for b in range(1, model.nbody)]
    reached = [link for link in analysis.plan.links if link != "world"]
    assert sorted(names) == sorted(reached)
    poses = link_poses(analysis)
    bodies = _bodies(analysis, poses)
    for b, name in enumerate(names, start=1):
        pose = poses[name]
        np.testing.assert_allclose(data.xpos[b], pose.translation, rtol=0, atol=TOLERANCE)
        np.testing.assert_allclose(
            data.xmat[b].reshape(3, 3), pose.rotation, rtol=0, atol=TOLERANCE
        )
        mass, centre, ours = bodies.get(name, (0.0, None, None))
        assert model.body_mass[b] == pytest.approx(mass, rel=0, abs=TOLERANCE)
        if mass == 0.0:
            continue
        principal = data.ximat[b].reshape(3, 3)
        theirs = principal @ np.diag(model.body_inertia[b]) @ principal.T
        np.testing.assert_allclose(data.xipos[b], centre, rtol=0, atol=TOLERANCE)
        np.testing.assert_allclose(theirs, ours, rtol=0, atol=TOLERANCE)
    _configurations_held(analysis, model, data, names, seed, urdf)


def _world_inertial(pose: Pose, inertial: Inertial) -> tuple[float, np.ndarray, np.ndarray]:
    """A link's mass, centre of mass and inertia about it, in the world (numpy, apart from
    the converter's arithmetic)."""
    frame = pose.then(Pose.of(inertial.origin))
    i = inertial.inertia
    tensor = np.array([[i.ixx, i.ixy, i.ixz], [i.ixy, i.iyy, i.iyz], [i.ixz, i.iyz, i.izz]])
    rotation = np.array(frame.rotation)
    return inertial.mass, np.array(frame.translation), rotation @ tensor @ rotation.T


def _refused(tensor: np.ndarray) -> bool:
    """Whether MuJoCo refuses an inertia on a body: not positive semi-definite, or its
    principal moments break the triangle inequality (by more than the rounding of turning
    it into the world's frame: Stretch's base_imu has A + B = C exactly, in its own)."""
    a, b, c = np.linalg.eigvalsh(tensor)
    return bool(a < -1e-12 * c or a + b < c * (1.0 - 1e-12))


def _combined(
    pieces: list[tuple[float, np.ndarray, np.ndarray]],
) -> tuple[float, np.ndarray, np.ndarray]:
    mass = sum(m for m, _, _ in pieces)
    centre = sum(m * c for m, c, _ in pieces) / mass
    tensor = sum(
        t + m * (np.dot(c - centre, c - centre) * np.eye(3) - np.outer(c - centre, c - centre))
        for m, c, t in pieces
    )
    return mass, centre, tensor


def _bodies(
    analysis: Analysis, poses: dict[str, Pose]
) -> dict[str, tuple[float, np.ndarray, np.ndarray]]:
    """Each MuJoCo body's mass, centre and inertia in the world: its link's, with those of
    links fixed to it whose inertia (with what joined theirs) MuJoCo refuses on a body of
    their own: a link's below it, or its parent's when that one can join no parent."""
    plan = analysis.plan
    steps = {plan.links[step.link]: step for step in plan.steps}
    joining: dict[str, list[tuple[float, np.ndarray, np.ndarray]]] = {}
    kept: dict[str, list[tuple[float, np.ndarray, np.ndarray]]] = {}
    joined_up: set[str] = set()
    for link in reversed(plan.links):  # children first
        inertial = analysis.links[link].inertial
        pieces = joining.pop(link, [])
        if inertial is not None and inertial.mass != 0.0:
            pieces.append(_world_inertial(poses[link], inertial))
        if not pieces or link == "world":
            continue
        if _refused(_combined(pieces)[2]):
            step = steps.get(link)
            if step is not None and step.kind is JointType.FIXED:
                parent = plan.links[step.parent]
                if parent != "world":
                    joining.setdefault(parent, []).extend(pieces)
                    joined_up.add(link)
                    continue
            children = [
                s
                for s in plan.steps
                if plan.links[s.parent] == link
                and s.joint.type is JointType.FIXED
                and plan.links[s.link] not in joined_up
            ]
            # the first, in the order of the robot's joints, that takes them
            children.sort(key=lambda s: analysis.robot.joints.index(s.joint))
            for s in children:
                child = plan.links[s.link]
                together = kept.get(child, []) + pieces
                if not _refused(_combined(together)[2]):
                    kept[child] = together
                    break
            else:
                kept[link] = pieces
            continue
        kept[link] = pieces
    return {link: _combined(pieces) for link, pieces in kept.items()}


def _configurations_held(
    analysis: Analysis,
    model: mujoco.MjModel,
    data: mujoco.MjData,
    names: list[str],
    seed: int,
    urdf: Path | None,
) -> None:
    kin = Kinematics(analysis)
    rng = np.random.default_rng(seed)
    for _ in range(3):
        q = np.array([_sample(analysis, name, rng) for name in kin.variables])
        values = dict(zip(kin.variables, q.tolist(), strict=True))
        given = {n: v for n, v in values.items() if n in analysis.joints}
        moved = {**values, **joint_positions(analysis, given)}  # mimic joints follow
        data.qpos[:] = _qpos(model, moved)
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        placed = kin.forward(q)
        for b, name in enumerate(names, start=1):
            ours = placed[kin.link_index(name)]
            np.testing.assert_allclose(data.xpos[b], ours[:3, 3], rtol=0, atol=TOLERANCE)
            np.testing.assert_allclose(
                data.xmat[b].reshape(3, 3), ours[:3, :3], rtol=0, atol=TOLERANCE
            )
        if urdf is not None:
            _pinocchio_held(urdf, model, data, moved)


def _pinocchio_held(
    urdf: Path, model: mujoco.MjModel, data: mujoco.MjData, moved: dict[str, float]
) -> None:
    """Pinocchio, given the same joint positions, places every link where MuJoCo does and
    finds the same mass and centre of mass (its robot's base fixed where MuJoCo's is)."""
    pin_model = pin.buildModelFromUrdf(str(urdf))
    pin_data = pin_model.createData()
    q = np.zeros(pin_model.nq)
    for j in range(1, pin_model.njoints):
        joint, value = pin_model.joints[j], moved[pin_model.names[j]]
        if joint.nq == 2:  # continuous: cos, sin
            q[joint.idx_q : joint.idx_q + 2] = (math.cos(value), math.sin(value))
        else:
            q[joint.idx_q] = value
    pin.framesForwardKinematics(pin_model, pin_data, q)
    for f, frame in enumerate(pin_model.frames):
        if frame.type == pin.FrameType.BODY and frame.name != "world":
            b = model.body(frame.name).id
            placed = pin_data.oMf[f]
            np.testing.assert_allclose(data.xpos[b], placed.translation, rtol=0, atol=TOLERANCE)
            np.testing.assert_allclose(
                data.xmat[b].reshape(3, 3), placed.rotation, rtol=0, atol=TOLERANCE
            )
    # pinocchio's bodies, the root link's among them (on its universe joint, which its
    # totals leave out)
    masses = [pin_model.inertias[j].mass for j in range(pin_model.njoints)]
    total = sum(masses)
    assert model.body_subtreemass[0] == pytest.approx(total, rel=1e-12, abs=TOLERANCE)
    if total > 0:
        levers = [
            pin_data.oMi[j].act(pin_model.inertias[j].lever) for j in range(pin_model.njoints)
        ]
        com = sum(m * lever for m, lever in zip(masses, levers, strict=True)) / total
        np.testing.assert_allclose(data.subtree_com[0], com, rtol=0, atol=TOLERANCE)


def _qpos(model: mujoco.MjModel, positions: dict[str, float]) -> np.ndarray:
    """MuJoCo's configuration of our joint positions (a free joint at its start)."""
    qpos = model.qpos0.copy()
    for j in range(model.njnt):
        name = model.joint(j).name
        if model.jnt_type[j] != mujoco.mjtJoint.mjJNT_FREE:
            qpos[model.jnt_qposadr[j]] = positions.get(name, 0.0)
    return qpos


def _sample(analysis: Analysis, variable: str, rng: np.random.Generator) -> float:
    """A position within the joint's limits (any angle or distance for one without)."""
    joint = analysis.joints.get(variable)
    limited = (JointType.REVOLUTE, JointType.PRISMATIC)
    if joint is not None and joint.type in limited and joint.limit is not None:
        lower, upper = joint.limit.lower, joint.limit.upper
        if lower < upper:
            return float(rng.uniform(lower, upper))
        return lower
    return float(rng.uniform(-math.pi, math.pi))


@pytest.mark.parametrize("item", CORPUS, ids=[_corpus_id(item) for item in CORPUS])
def test_mujoco_compiles_every_corpus_robot_to_our_numbers(item: object) -> None:
    path: Path = item.path  # type: ignore[attr-defined]
    name = _corpus_id(item)
    packages = _packages()
    if name in EXCLUDED:
        if name.endswith("ur3.urdf"):
            with pytest.raises(fishbot_urdf.RobotError, match=EXCLUDED[name]):
                _analysis(path, packages)
            return
        text, found = export_mjcf(_analysis(path, packages))
        with pytest.raises(ValueError, match=EXCLUDED[name].replace("+", r"\+")):
            mujoco.MjModel.from_xml_string(text)
        # said before MuJoCo says it
        assert "mjcf-refused" in {d.rule for d in found}
        return
    analysis = _analysis(path, packages)
    text, found = export_mjcf(analysis)
    assert "mjcf-refused" not in {d.rule for d in found}
    _held_to_ours(analysis, text, len(name), urdf=path)


def _issue_robot(name: str) -> tuple[Path, dict[str, Path] | None]:
    """A robot the issue names, and the packages its meshes are in."""
    if name == "fishbot":
        return XACRO, None
    if name == "upkie":
        import upkie_description

        folder = Path(upkie_description.URDF_PATH).parent.parent
        return Path(upkie_description.URDF_PATH), {"upkie_description": folder}
    if name == "stretch":
        import stretch_urdf

        return Path(stretch_urdf.__file__).parent / "SE3" / _STRETCH, None
    robots = _packages()["example-robot-data"] / "robots"
    return robots / _IN_EXAMPLE_ROBOT_DATA[name], _packages()


_STRETCH = "stretch_description_SE3_eoa_wrist_dw3_tool_sg3.urdf"
_IN_EXAMPLE_ROBOT_DATA = {
    "panda": "panda_description/urdf/panda.urdf",
    "ur5": "ur_description/urdf/ur5_robot.urdf",
    "go1": "go1_description/urdf/go1.urdf",
}


@pytest.mark.parametrize("name", ["fishbot", "panda", "ur5", "go1", "upkie", "stretch"])
def test_the_robots_of_the_issue_load_with_every_mass(tmp_path: Path, name: str) -> None:
    """The six robots the issue names load in MuJoCo, every body with our mass, centre of
    mass and inertia, every link where we place it, and the whole robot weighs what its
    URDF's links do (other converters drop Stretch's root inertial: 17.4 of its 24.8 kg)."""
    path, packages = _issue_robot(name)
    analysis = _analysis(path, packages)
    urdf = tmp_path / "robot.urdf"  # expanded, for pinocchio
    urdf.write_text(fishbot_urdf.to_urdf(analysis.robot))
    made = export_mjcf(analysis)
    assert "mjcf-refused" not in {d.rule for d in made.findings}
    _held_to_ours(analysis, made.text, len(name), urdf)
    model = mujoco.MjModel.from_xml_string(made.text)
    total = math.fsum(link.inertial.mass for link in analysis.robot.links if link.inertial)
    assert model.body_subtreemass[0] == pytest.approx(total, rel=1e-12, abs=TOLERANCE)
    if name == "stretch":
        assert total == pytest.approx(24.8, abs=0.05)
        root = analysis.links[analysis.plan.roots[0]].inertial
        assert root is not None and model.body(analysis.plan.roots[0]).mass[0] == root.mass


def test_the_fishbot_floats_or_is_fixed_as_asked(tmp_path: Path) -> None:
    analysis = _analysis(XACRO)
    urdf = tmp_path / "fishbot.urdf"  # expanded, for pinocchio
    urdf.write_text(fishbot_urdf.to_urdf(analysis.robot))
    floating = to_mjcf(analysis)
    assert "<freejoint />" in floating
    _held_to_ours(analysis, floating, 1, urdf)
    fixed = to_mjcf(analysis, base="fixed")
    assert "freejoint" not in fixed
    _held_to_ours(analysis, fixed, 2, urdf)
    model = mujoco.MjModel.from_xml_string(fixed)
    assert model.nq == 2  # the two wheels
    assert model.jnt_range.tolist() == [[0.0, 0.0], [0.0, 0.0]]  # continuous: no limit
    visual, collision = model.geom_group[:2].tolist()
    assert (visual, collision) == (2, 3)
    assert model.geom_contype[0] == model.geom_conaffinity[0] == 0


ARM = """\
<robot name="arm">
  <link name="world"/>
  <link name="base"><inertial><mass value="2"/><origin xyz="0 0 0.1" rpy="0.1 0.2 0.3"/>
    <inertia ixx="0.03" ixy="0.001" ixz="0.002" iyy="0.04" iyz="0.003" izz="0.05"/></inertial>
  </link>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/>
    <origin xyz="0 0 0.5"/></joint>
  <link name="upper">{upper}</link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.2" rpy="0 0.5 0"/><axis xyz="0 1 1"/>
    <limit lower="-1" upper="2" effort="1" velocity="1"/>
    <dynamics damping="0.5" friction="0.25"/></joint>
  <link name="finger"><inertial><mass value="0.1"/>
    <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
  <joint name="slide" type="prismatic"><parent link="upper"/><child link="finger"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
  <link name="twin"><inertial><mass value="0.1"/>
    <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
  <joint name="twin_slide" type="prismatic"><parent link="upper"/><child link="twin"/>
    <axis xyz="-1 0 0"/><limit lower="0" upper="0.08" effort="1" velocity="1"/>
    <mimic joint="slide" multiplier="2" offset="0.001"/></joint>
  <link name="puck"><inertial><mass value="0.3"/>
    <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <joint name="glide" type="planar"><parent link="base"/><child link="puck"/>
    <axis xyz="0 1 1"/><origin xyz="0.3 0 0"/></joint>
  <link name="drone"><inertial><mass value="0.3"/>
    <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <joint name="loose" type="floating"><parent link="puck"/><child link="drone"/>
    <origin xyz="0.1 0 0" rpy="0.3 0 0"/></joint>
</robot>
"""
UPPER = """<inertial><mass value="0.5"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>"""


def _arm(upper: str = UPPER) -> Analysis:
    return of(fishbot_urdf.parse(ARM.format(upper=upper)))


def test_every_joint_type_mimics_limits_and_dynamics_are_mujocos() -> None:
    analysis = _arm()
    text = to_mjcf(analysis)
    _held_to_ours(analysis, text, 3)
    model = mujoco.MjModel.from_xml_string(text)
    shoulder = model.joint("shoulder")
    assert shoulder.range.tolist() == [-1.0, 2.0] and model.jnt_limited[shoulder.id]
    assert model.dof_damping[model.jnt_dofadr[shoulder.id]] == 0.5
    assert model.dof_frictionloss[model.jnt_dofadr[shoulder.id]] == 0.25
    # the mimic joint is held to its leader
    assert model.neq == 1
    assert model.eq_type[0] == mujoco.mjtEq.mjEQ_JOINT
    assert (model.eq_obj1id[0], model.eq_obj2id[0]) == (
        model.joint("twin_slide").id,
        model.joint("slide").id,
    )
    assert model.eq_data[0][:5].tolist() == [0.001, 2.0, 0.0, 0.0, 0.0]
    # planar: two slides and a hinge; floating below the top: three slides, three hinges
    kinds = {model.joint(j).name: int(model.jnt_type[j]) for j in range(model.njnt)}
    assert [n for n in kinds if n.startswith(("glide", "loose"))] == [
        "glide.x",
        "glide.y",
        "glide.yaw",
        "loose.x",
        "loose.y",
        "loose.z",
        "loose.yaw",
        "loose.pitch",
        "loose.roll",
    ]
    # world fixed to the base: nothing free
    assert mujoco.mjtJoint.mjJNT_FREE not in kinds.values()
    floating = mujoco.MjModel.from_xml_string(to_mjcf(analysis, base="floating"))
    assert floating.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE


def test_a_massless_moving_link_stays_massless() -> None:
    # no mass made up from the shapes: MuJoCo refuses the body, as the rules say it does
    shape = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
    text = to_mjcf(_arm(upper=shape))
    assert 'inertiafromgeom="false"' in text
    with pytest.raises(ValueError, match="mass and inertia of moving bodies"):
        mujoco.MjModel.from_xml_string(text)
    (refused,) = [d for d in export_mjcf(_arm(upper=shape)).findings]
    assert refused.rule == "mjcf-refused" and refused.subject.name == "upper"  # type: ignore[union-attr]
    found = fishbot_urdf.check(_arm(upper=shape), config=Config(targets=("mujoco",)))
    errors = {(d.rule, d.subject and d.subject.name) for d in found if d.is_error}
    assert ("missing-inertial", "upper") in errors


def _stl(triangles: list[tuple[tuple[float, float, float], ...]]) -> bytes:
    """A binary STL file of ``triangles``."""
    data = bytearray(80) + struct.pack("<I", len(triangles))
    for corners in triangles:
        data += struct.pack("<12fH", 0.0, 0.0, 0.0, *(v for c in corners for v in c), 0)
    return bytes(data)


_O, _X, _Y, _Z = (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)
TETRAHEDRON = _stl([(_O, _Y, _X), (_O, _X, _Z), (_O, _Z, _Y), (_X, _Y, _Z)])
SQUARE = _stl([(_O, _X, _Y), (_X, (1.0, 1.0, 0.0), _Y)])


def test_meshes_mujoco_cannot_read_are_left_out(tmp_path: Path) -> None:
    (tmp_path / "part.stl").write_bytes(TETRAHEDRON)
    (tmp_path / "square.stl").write_bytes(SQUARE)
    (tmp_path / "empty.stl").write_bytes(b"")
    (tmp_path / "part.dae").write_bytes(b"")
    # normals, and a face that names none (pybullet's table_square)
    corners = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\n"
    faces = "f 1//1 3//1 2//1\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
    (tmp_path / "mixed.obj").write_text(corners + faces)
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a">'
        '<visual><geometry><mesh filename="part.dae"/></geometry></visual>'
        '<visual><geometry><mesh filename="gone.stl"/></geometry></visual>'
        '<visual><geometry><mesh filename="part.stl" scale="0.001 0.001 0.001"/></geometry>'
        "</visual>\n"
        '<visual><geometry><mesh filename="empty.stl"/></geometry></visual>\n'
        '<visual><geometry><mesh filename="square.stl"/></geometry></visual>\n'
        '<collision><geometry><mesh filename="square.stl"/></geometry></collision>\n'
        '<visual><geometry><mesh filename="mixed.obj"/></geometry></visual>\n'
        "</link></robot>"
    )
    text, findings = export_mjcf(_analysis(robot), base="fixed")  # (no mass: held still)
    assert text.count("<geom") == 2  # the tetrahedron, and the square that is only seen
    # (visuals first, then collisions)
    assert [d.format() for d in findings] == [
        f"{robot}:1:50: warning: link 'a': visual mesh 'part.dae' is a .dae file, which MuJoCo "
        "cannot read: left out of the MJCF (export it as binary STL or OBJ) [mjcf-left-out]",
        f"{robot}:1:115: warning: link 'a': visual mesh 'gone.stl' is not found: left out of "
        "the MJCF (name the file that is there) [mjcf-left-out]",
        f"{robot}:2:19: warning: link 'a': visual mesh 'empty.stl' holds no triangles MuJoCo "
        "reads: left out of the MJCF (export it as binary STL or OBJ) [mjcf-left-out]",
        f"{robot}:5:19: warning: link 'a': visual mesh 'mixed.obj' has normals, and faces that "
        "name none, which MuJoCo refuses: left out of the MJCF (export it as binary STL or OBJ) "
        "[mjcf-left-out]",
        f"{robot}:4:22: warning: link 'a': collision mesh 'square.stl' has every vertex in one "
        "plane, no volume for a convex hull: left out of the MJCF (collide with a thin box, or "
        "give the mesh its thickness) [mjcf-left-out]",
    ]
    assert f'<mesh name="part" file="{tmp_path.resolve() / "part.stl"}"' in text
    assert 'scale="0.001 0.001 0.001"' in text
    mujoco.MjModel.from_xml_string(text)


def test_refusals() -> None:
    with pytest.raises(ArgumentError, match="base 'welded' is none of auto, fixed, floating"):
        to_mjcf(_arm(), base="welded")  # type: ignore[arg-type]
    twice = ARM.format(upper=UPPER).replace('"finger"', '"upper"')
    with pytest.raises(StructureError, match="a link or joint name used twice"):
        to_mjcf(fishbot_urdf.parse(twice))


def test_a_fixed_link_whose_inertia_mujoco_refuses_joins_its_parent() -> None:
    antenna = """
  <link name="antenna"><inertial><mass value="0.01"/><origin xyz="0 0.1 0" rpy="0 0 0.5"/>
    <inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-5"/></inertial></link>
  <joint name="antenna_joint" type="fixed"><parent link="upper"/><child link="antenna"/>
    <origin xyz="0 0 0.3" rpy="0.2 0 0"/></joint>
</robot>"""
    robot = fishbot_urdf.parse(ARM.format(upper=UPPER).replace("</robot>", antenna))
    analysis = of(robot)
    text, found = export_mjcf(analysis)
    _held_to_ours(analysis, text, 4)  # the upper arm's body holds both inertials
    (finding,) = found
    assert finding.format().endswith(
        "warning: link 'antenna': its principal moments break the triangle inequality "
        "(A + B >= C), which MuJoCo refuses on a body of its own: its inertial joins that of "
        "'upper', to which it is fixed (give it the inertia of its shape) [mjcf-joined-inertial]"
    )
    model = mujoco.MjModel.from_xml_string(text)
    assert model.body("antenna").mass[0] == 0.0
    assert model.body("upper").mass[0] == pytest.approx(0.51, abs=1e-15)


def test_a_root_whose_inertia_mujoco_refuses_joins_the_link_fixed_below_it() -> None:
    # as go1 and anymal write their base: a placeholder inertia, the mass on a trunk
    robot = fishbot_urdf.parse("""<robot name="dog">
  <link name="base"><inertial><mass value="1e-6"/>
    <inertia ixx="1e-6" ixy="1e-6" ixz="1e-6" iyy="1e-6" iyz="1e-6" izz="1e-6"/></inertial>
  </link>
  <link name="trunk"><inertial><mass value="5"/><origin xyz="0.01 0 0"/>
    <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.06"/></inertial></link>
  <joint name="floating_base" type="fixed"><parent link="base"/><child link="trunk"/>
    <origin xyz="0 0 0.1" rpy="0 0 0.3"/></joint>
</robot>""")
    analysis = of(robot)
    text, (finding,) = export_mjcf(analysis)
    _held_to_ours(analysis, text, 5)
    assert "link 'base': its inertia is not positive definite, which MuJoCo refuses" in (
        finding.format()
    )
    assert "its inertial joins that of 'trunk', to which it is fixed" in finding.format()
    model = mujoco.MjModel.from_xml_string(text)
    assert (model.body("base").mass[0], model.body("trunk").mass[0]) == (0.0, 5.000001)


def _mujoco_findings(robot: fishbot_urdf.Robot, *targets: str) -> list[Diagnostic]:
    config = Config(targets=targets) if targets else Config()
    found = fishbot_urdf.check(robot, config=config)
    return [d for d in found if d.rule in ("mjcf-refused", "mjcf-joined-inertial")]


def test_check_for_mujoco_foretells_what_the_conversion_finds() -> None:
    """`check --target mujoco` (and `all`) reports the conversion's own mjcf-refused and
    mjcf-joined-inertial findings, at their severity, without writing the MJCF; for any
    other target it does not look."""
    antenna = """
  <link name="antenna"><inertial><mass value="0.01"/>
    <inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-5"/></inertial></link>
  <joint name="antenna_joint" type="fixed"><parent link="base"/><child link="antenna"/></joint>
</robot>"""
    robot = fishbot_urdf.parse(ARM.format(upper="").replace("</robot>", antenna))
    converted = export_mjcf(robot).findings
    assert [(d.rule, d.severity.value) for d in converted] == [
        ("mjcf-joined-inertial", "warning"),
        ("mjcf-refused", "error"),
    ]
    for targets in (("mujoco",), ("all",), ("ros", "mjcf")):
        assert _mujoco_findings(robot, *targets) == sorted(converted, key=lambda d: d.line or 0)
    assert _mujoco_findings(robot) == []
    assert _mujoco_findings(robot, "gazebo", "ros") == []
    # selected alone, it alone runs
    only = fishbot_urdf.check(robot, config=Config(targets=("mujoco",), select=("mjcf-refused",)))
    assert [d.rule for d in only] == ["mjcf-refused"]


def test_a_free_base_without_inertia_about_an_axis_is_refused() -> None:
    # as pybullet's random_urdfs write a body: izz of 0, and nothing fixed to it
    robot = fishbot_urdf.parse("""<robot name="block">
  <link name="block"><inertial><mass value="0.1"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="0"/></inertial></link>
</robot>""")
    text, (finding,) = export_mjcf(robot)
    with pytest.raises(ValueError, match="mass and inertia of moving bodies"):
        mujoco.MjModel.from_xml_string(text)
    assert finding.rule == "mjcf-refused"
    assert "it moves, and with the links fixed to it it has no inertia about some axis" in (
        finding.message
    )
    assert _mujoco_findings(robot, "mujoco") == [finding]
    # held still, MuJoCo takes it
    text, found = export_mjcf(robot, base="fixed")
    assert found == ()
    mujoco.MjModel.from_xml_string(text)


def test_a_moving_body_massless_alone_is_taken_with_what_is_fixed_to_it() -> None:
    # two point masses, fixed apart: together they have inertia about two axes only
    rod = """<robot name="rod">
  <link name="a"><inertial><mass value="1"/>{a}</inertial></link>
  <link name="b"><inertial><mass value="1"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/><origin xyz="0 0 1"/></joint>
</robot>"""
    point = '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>'
    ball = '<inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/>'
    for inertia, refused in ((point, True), (ball, False)):
        text, found = export_mjcf(fishbot_urdf.parse(rod.format(a=inertia)))
        assert [d.rule for d in found] == (["mjcf-refused"] if refused else [])
        if refused:
            with pytest.raises(ValueError, match="mass and inertia of moving bodies"):
                mujoco.MjModel.from_xml_string(text)
        else:
            mujoco.MjModel.from_xml_string(text)


def test_shapes_of_no_size_are_left_out() -> None:
    # upkie and laikago draw frames as boxes of size 0; MuJoCo refuses any geom of size 0
    robot = fishbot_urdf.parse("""<robot name="frames">
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial>
    <visual><geometry><box size="0 0 0"/></geometry></visual>
    <collision><geometry><cylinder radius="0" length="0.1"/></geometry></collision>
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
</robot>""")
    text, found = export_mjcf(robot)
    assert text.count("<geom") == 1
    mujoco.MjModel.from_xml_string(text)
    assert [(d.rule, d.line, d.message) for d in found] == [
        (
            "mjcf-empty-shape",
            4,
            "link 'base': <visual> box of size \"0 0 0\", which MuJoCo refuses: left out of "
            "the MJCF",
        ),
        (
            "mjcf-empty-shape",
            5,
            "link 'base': <collision> cylinder of radius 0, which MuJoCo refuses: left out of "
            "the MJCF",
        ),
    ]


def test_a_planar_joints_parts_never_take_a_joints_name() -> None:
    inertial = (
        '<inertial><mass value="1"/>'
        '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'
    )
    robot = fishbot_urdf.parse(
        f'<robot name="odd"><link name="world"/><link name="a">{inertial}</link>'
        f'<link name="b">{inertial}</link>'
        '<joint name="pl" type="planar"><parent link="world"/><child link="a"/>'
        '<axis xyz="0 0 1"/></joint>'
        '<joint name="pl.x" type="continuous"><parent link="a"/><child link="b"/></joint>'
        "</robot>"
    )
    model = mujoco.MjModel.from_xml_string(to_mjcf(robot))
    names = [model.joint(i).name for i in range(model.njnt)]
    assert names == ["pl.x_", "pl.y", "pl.yaw", "pl.x"]
