"""Forward kinematics in numpy, for many configurations at once.

A `Kinematics` evaluates the robot's kinematic plan (`fishbot_urdf.analysis.plan`: the
links, parents before children, and per joint its origin, axis and configuration column),
with per joint the constant matrices its motion needs. Evaluating it for a batch of
configurations is then one small numpy step per link, over the whole batch. Configuration
vectors are the plan's: one number per variable, in `Kinematics.variables` order (see
`fishbot_urdf.analysis.plan` for planar and floating joints, and for mimic joints, which
follow their driver's variable).

numpy is imported when a `Kinematics` is built, not with this module.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..analysis import Analysis, of
from ..analysis.plan import PARTS, Step
from ..errors import ArgumentError, StructureError, UnknownNameError
from ..graph import root
from ..model import JointType, Robot
from .positions import check_value, not_a_variable

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["Kinematics", "forward_kinematics", "jacobian", "transform"]

Configuration = Any  # an array of shape (n,) or (B, n), or a mapping of names to values


class Kinematics:
    """The forward kinematics of one robot (a tree with one root), in numpy.

    Attributes:
        links: Every link reached from the root, parents before children; ``forward``
            gives their poses in this order.
        variables: The configuration's entries, by name: a joint's name, or
            ``joint.x``-style names for planar and floating joints.
        joints: The joints that own variables, in file order.
        root: The root link, whose frame poses are given in.
    """

    def __init__(self, robot: Robot | Analysis) -> None:
        """Raises:
        StructureError: The robot has no root or several, or a joint loop below its root.
        """
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        analysis = of(robot)
        self.analysis = analysis
        self.root = root(analysis)
        if analysis.topology.loop_from_root:
            raise StructureError(f"robot {analysis.robot.name!r} has a joint loop below its root")
        plan = analysis.plan
        self.joints: tuple[str, ...] = plan.joints
        self.variables: tuple[str, ...] = plan.variables
        self.links: tuple[str, ...] = plan.links
        self._index = plan.index
        self._steps = steps = plan.steps
        variables = plan.variables
        self._constants = [_constants(np, s) for s in steps]
        # Origins turned about their joint's axis add to the joint's angle.
        self._phases = np.zeros((len(variables), 1))
        for step, constants in zip(steps, self._constants, strict=True):
            if constants.phase and _plain(step):
                self._phases[step.column] = constants.phase
        self._phased = bool(np.any(self._phases))

    # -- configurations ------------------------------------------------------------------
    def configuration(self, positions: Mapping[str, float] | None = None) -> NDArray[Any]:
        """The configuration vector of ``positions`` (by variable name; the rest are 0).

        Raises:
            UnknownNameError: A name is no joint (the error names the closest variables).
            ArgumentError: A name is a joint that has no variable of its own (fixed, a
                mimic, planar or floating: see `positions.not_a_variable`), or a value is not
                a finite number, or is outside a joint's limits.
        """
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        q = np.zeros(len(self.variables))
        where = {name: i for i, name in enumerate(self.variables)}
        joints = self.analysis.joints
        for name, value in (positions or {}).items():
            if name not in where:
                raise not_a_variable(self.analysis, name, self.variables)
            value = check_value(joints.get(name), name, value)
            q[where[name]] = value
        return q

    def _batch(self, q: Configuration) -> tuple[NDArray[Any], bool]:
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        if isinstance(q, Mapping):
            q = self.configuration(q)
        array = np.asarray(q, dtype=float)
        single = array.ndim == 1
        if array.ndim not in (1, 2) or array.shape[-1] != len(self.variables):
            raise ArgumentError(
                f"a configuration has shape (n,) or (B, n) with n = {len(self.variables)} "
                f"(the variables), not {array.shape}",
                name="q",
            )
        return array.reshape(1, -1) if single else array, single

    # -- poses ---------------------------------------------------------------------------
    def _poses(self, q: NDArray[Any]) -> NDArray[Any]:
        """Every link's pose, transposed, as an array (L, 4, 4, B): ``[l, j, i, b]`` is
        entry (i, j) of link l's pose in configuration b. With the batch last each step
        works on contiguous rows of B numbers, and with the poses transposed a constant
        rotation applies from the left, as one matrix product over the whole batch."""
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        batch = q.shape[0]
        poses = np.empty((len(self.links), 4, 4, batch))  # every step writes its link
        poses[:, :3, 3] = 0.0
        poses[:, 3, 3] = 1.0
        poses[0, :, :3] = np.eye(4)[:, :3, None]
        columns = np.ascontiguousarray(q.T)
        angles = columns + self._phases if self._phased else columns
        sines, cosines = np.sin(angles), np.cos(angles)
        for step, constants in zip(self._steps, self._constants, strict=True):
            _place(np, step, constants, poses, columns, sines, cosines)
        return poses

    def _frames(self, q: NDArray[Any]) -> tuple[NDArray[Any], NDArray[Any]]:
        """Rotations (B, L, 3, 3) and positions (B, L, 3) of every link in the root frame."""
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        poses = self._poses(q)
        rotations = np.moveaxis(poses[:, :3, :3], -1, 0).swapaxes(-1, -2)
        return rotations, np.moveaxis(poses[:, 3, :3], -1, 0)

    def forward(self, q: Configuration) -> NDArray[Any]:
        """Every link's 4x4 pose in the root frame: shape (L, 4, 4) for one configuration
        (an array of shape (n,), or a mapping of variable names to values), (B, L, 4, 4)
        for a batch (B, n). Links are in ``links`` order."""
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        array, single = self._batch(q)
        # A view of the transposed, batch-last array, as (B, L, 4, 4) poses: no copy.
        poses = np.moveaxis(self._poses(array), -1, 0).swapaxes(-1, -2)
        return poses[0] if single else poses

    def link_index(self, name: str) -> int:
        """Where link ``name`` is in ``links``.

        Raises:
            UnknownNameError: No link reached from the root has that name.
        """
        try:
            return self._index[name]
        except KeyError:
            raise UnknownNameError("link", name, self.links) from None

    def transform(self, q: Configuration, frame_from: str, frame_to: str) -> NDArray[Any]:
        """The pose of ``frame_to`` in ``frame_from`` (it maps points given in
        ``frame_to`` to ``frame_from``), as ``tf2_echo frame_from frame_to`` prints it:
        (4, 4), or (B, 4, 4) for a batch.

        Raises:
            UnknownNameError: A frame is no link reached from the root.
        """
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        a, b = self.link_index(frame_from), self.link_index(frame_to)
        array, single = self._batch(q)
        rotations, positions = self._frames(array)
        ra, pa, rb, pb = rotations[:, a], positions[:, a], rotations[:, b], positions[:, b]
        inverse = np.swapaxes(ra, -1, -2)
        result = np.zeros((array.shape[0], 4, 4))
        result[:, :3, :3] = inverse @ rb
        result[:, :3, 3] = (inverse @ (pb - pa)[..., None])[..., 0]
        result[:, 3, 3] = 1.0
        return result[0] if single else result

    def jacobian(self, q: Configuration, frame: str) -> NDArray[Any]:
        """The geometric Jacobian of link ``frame``: (6, n), or (B, 6, n) for a batch.

        Rows: the velocity of the frame's origin (x, y, z), then its angular velocity, both
        in the root frame's axes (pinocchio's LOCAL_WORLD_ALIGNED). Columns: the variables.
        For planar and floating joints the columns are the joint's velocities along and
        about its child frame's axes (as pinocchio's), not derivatives of the parameters.

        Raises:
            UnknownNameError: ``frame`` is no link reached from the root.
        """
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        target = self.link_index(frame)
        array, single = self._batch(q)
        rotations, positions = self._frames(array)
        batch = array.shape[0]
        result = np.zeros((batch, 6, len(self.variables)))
        by_link = {s.link: (s, c) for s, c in zip(self._steps, self._constants, strict=True)}
        end = positions[:, target]
        link = target
        while link != 0:  # up the tree to the root
            step, constants = by_link[link]
            parent_r = rotations[:, step.parent]
            joint_r = parent_r @ constants.rotation
            child_p = positions[:, link]
            if step.column >= 0 and step.kind is not JointType.FIXED:
                _columns(np, step, constants, result, joint_r, rotations[:, link], child_p, end)
            link = step.parent
        return result[0] if single else result


@dataclass(frozen=True, slots=True)
class _Constants:
    """What one joint's motion needs, computed once: its origin's rotation and translation,
    its unit axis, and for rotations about an axis that is not x, y or z, K and k k^T
    (Rodrigues)."""

    rotation: Any
    xyz: Any
    axis: Any
    cross: Any
    outer: Any
    plane: Any  # planar joints: the two directions of the plane (3, 2)
    turned: bool  # the origin has a rotation (not folded into ``phase``)
    offsets: tuple[tuple[int, float], ...]  # the origin's non-zero coordinates
    aligned: tuple[int, float] | None  # the axis is +-x, +-y or +-z: (which, sign)
    phase: float  # an origin turned about the joint's own axis: the angle added to its own


def _constants(np: Any, step: Step) -> _Constants:
    rotation = np.array(step.origin.rotation, dtype=float)
    xyz = np.array(step.origin.translation, dtype=float)
    axis = np.array(step.axis, dtype=float)  # of length 1, or 0 0 0
    skew = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    plane = None if step.plane is None else np.array(step.plane, dtype=float).T
    aligned = None
    for i in range(3):
        # 1e-9 1 0 has a y of 1.0 once made of length 1: the other two must be 0 as well
        if abs(axis[i]) == 1.0 and not axis[(i + 1) % 3] and not axis[(i + 2) % 3]:
            aligned = (i, float(axis[i]))
    offsets = tuple((i, float(v)) for i, v in enumerate(xyz) if v != 0.0)
    turned = bool(np.any(rotation != np.eye(3)))
    phase = 0.0
    revolving = step.kind in (JointType.REVOLUTE, JointType.CONTINUOUS)
    if turned and revolving and aligned is not None:
        # R_o = Rot(axis, phase) when R_o keeps the axis: then R_o Rot(axis, q) is
        # Rot(axis, q + phase), and the origin's rotation costs nothing.
        i, sign = aligned
        a, b = (i + 1) % 3, (i + 2) % 3
        keeps = abs(rotation[i, i] - 1.0) < 1e-15 and not rotation[i, a] and not rotation[a, i]
        keeps = keeps and not rotation[i, b] and not rotation[b, i]
        if keeps:
            phase = sign * math.atan2(rotation[b, a], rotation[a, a])
            turned = False
    return _Constants(
        rotation, xyz, axis, skew, np.outer(axis, axis), plane, turned, offsets, aligned, phase
    )


def _place(
    np: Any,
    step: Step,
    constants: _Constants,
    poses: Any,
    columns: Any,
    sines: Any,
    cosines: Any,
) -> None:
    """Fill in the pose of ``step``'s link from its parent's, both transposed in ``poses``:
    row k of a rotation block is the rotation's column k, row 3 the position."""
    parent_r, parent_p = poses[step.parent, :3, :3], poses[step.parent, 3, :3]
    rotation, position = poses[step.link, :3, :3], poses[step.link, 3, :3]
    position[...] = parent_p
    for i, value in constants.offsets:  # the joint frame's origin
        position += value * parent_r[i]
    width = 3 * parent_r.shape[-1]
    if constants.turned:  # the joint frame's axes: (R_p R_o)^T = R_o^T R_p^T
        np.matmul(constants.rotation.T, parent_r.reshape(3, width), out=rotation.reshape(3, width))
    else:
        rotation[...] = parent_r
    kind = step.kind
    if kind is JointType.FIXED:
        return
    if kind in PARTS:
        _place_many(np, step, constants, rotation, position, columns)
        return
    plain = _plain(step)
    if plain:
        value = columns[step.column]
    elif step.column >= 0:
        value = step.multiplier * columns[step.column] + step.offset
    else:  # a mimic of a joint that is not placed: held at its offset
        value = np.full(columns.shape[1], step.offset)
    if kind is JointType.PRISMATIC:
        if constants.aligned is not None:
            i, sign = constants.aligned
            position += (sign * value) * rotation[i]
        else:
            position += value * np.einsum("kib,k->ib", rotation, constants.axis)
        return
    s = sines[step.column] if plain else np.sin(value + constants.phase)
    c = cosines[step.column] if plain else np.cos(value + constants.phase)
    if constants.aligned is not None:  # two columns turn, as in Rz = [[c, -s], [s, c]]
        i, sign = constants.aligned
        a, b = (i + 1) % 3, (i + 2) % 3
        first, second = rotation[a], rotation[b]
        kept = first.copy()
        signed = s if sign > 0 else -s
        first *= c
        first += second * signed
        second *= c
        second -= kept * signed
        return
    # Rodrigues: (J (I c + K s + k k^T (1 - c)))^T = J^T c + K^T J^T s + k k^T J^T (1 - c)
    joint_r = rotation.copy().reshape(3, width)
    crossed = (constants.cross.T @ joint_r).reshape(rotation.shape)
    along = (constants.outer @ joint_r).reshape(rotation.shape)
    rotation[...] = joint_r.reshape(rotation.shape) * c + crossed * s + along * (1.0 - c)


def _plain(step: Step) -> bool:
    """The step's joint owns its variable (no mimic's multiplier or offset)."""
    return step.column >= 0 and step.multiplier == 1.0 and step.offset == 0.0


def _place_many(
    np: Any, step: Step, constants: _Constants, rotation: Any, position: Any, columns: Any
) -> None:
    """Planar and floating joints: several variables each (rotation and position are the
    link's transposed rotation and its position, as `_place` keeps them)."""
    c = step.column
    joint_r = rotation.copy()
    if step.kind is JointType.PLANAR:
        shift = constants.plane @ columns[c : c + 2]  # (3, B) in the joint frame
        angle = columns[c + 2]
        s, co = np.sin(angle), np.cos(angle)
        if not constants.axis.any():  # an axis 0 0 0 turns nothing (Rodrigues would scale)
            s, co = np.zeros_like(angle), np.ones_like(angle)
        local = (
            np.eye(3)[:, :, None] * co
            + constants.cross[:, :, None] * s
            + constants.outer[:, :, None] * (1.0 - co)
        )
    else:
        shift = columns[c : c + 3]
        local = np.moveaxis(_rpy(np, columns[c + 3 : c + 6].T), 0, -1)
    position += np.einsum("kib,kb->ib", joint_r, shift)
    np.einsum("kib,kjb->ijb", local, joint_r, out=rotation)


def _rpy(np: Any, angles: Any) -> Any:
    """R = Rz(yaw) Ry(pitch) Rx(roll) for a batch (B, 3) of angles."""
    cr, cp, cy = (np.cos(angles[:, i]) for i in range(3))
    sr, sp, sy = (np.sin(angles[:, i]) for i in range(3))
    out = np.empty((angles.shape[0], 3, 3))
    out[:, 0, 0] = cy * cp
    out[:, 0, 1] = cy * sp * sr - sy * cr
    out[:, 0, 2] = cy * sp * cr + sy * sr
    out[:, 1, 0] = sy * cp
    out[:, 1, 1] = sy * sp * sr + cy * cr
    out[:, 1, 2] = sy * sp * cr - cy * sr
    out[:, 2, 0] = -sp
    out[:, 2, 1] = cp * sr
    out[:, 2, 2] = cp * cr
    return out


def _columns(
    np: Any,
    step: Step,
    constants: _Constants,
    result: Any,
    joint_r: Any,
    child_r: Any,
    child_p: Any,
    end: Any,
) -> None:
    """Add the Jacobian columns of ``step``'s joint (a mimic's, times its multiplier, to its
    leader's)."""
    kind, c = step.kind, step.column

    def turn(axis: Any, about: Any) -> Any:
        return np.concatenate([np.cross(axis, end - about), axis], axis=1)

    def slide(axis: Any) -> Any:
        return np.concatenate([axis, np.zeros_like(axis)], axis=1)

    if kind in (JointType.REVOLUTE, JointType.CONTINUOUS):
        result[:, :, c] += step.multiplier * turn(joint_r @ constants.axis, child_p)
    elif kind is JointType.PRISMATIC:
        result[:, :, c] += step.multiplier * slide(joint_r @ constants.axis)
    elif kind is JointType.PLANAR:
        for i in range(2):
            result[:, :, c + i] += slide(child_r @ constants.plane[:, i])
        result[:, :, c + 2] += turn(joint_r @ constants.axis, child_p)
    else:
        for i in range(3):
            result[:, :, c + i] += slide(child_r[:, :, i])
            result[:, :, c + 3 + i] += turn(child_r[:, :, i], child_p)


def forward_kinematics(robot: Robot | Analysis | Kinematics, q: Configuration) -> NDArray[Any]:
    """Every link's 4x4 pose in the root frame (see `Kinematics.forward`)."""
    return _of(robot).forward(q)


def transform(
    robot: Robot | Analysis | Kinematics, q: Configuration, frame_from: str, frame_to: str
) -> NDArray[Any]:
    """The pose of ``frame_to`` in ``frame_from`` (see `Kinematics.transform`)."""
    return _of(robot).transform(q, frame_from, frame_to)


def jacobian(robot: Robot | Analysis | Kinematics, q: Configuration, frame: str) -> NDArray[Any]:
    """The geometric Jacobian of link ``frame`` (see `Kinematics.jacobian`)."""
    return _of(robot).jacobian(q, frame)


def _of(robot: Robot | Analysis | Kinematics) -> Kinematics:
    return robot if isinstance(robot, Kinematics) else Kinematics(robot)
