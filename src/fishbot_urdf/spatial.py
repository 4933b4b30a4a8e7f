"""Rotations, poses and symmetric 3x3 matrices in plain Python (no numpy: `check` stays light)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from .model import ZERO3, Origin, Vector3

__all__ = [
    "IDENTITY",
    "Matrix3",
    "Pose",
    "Quaternion",
    "eigenvalues",
    "eigh",
    "euler_ypr",
    "rpy_matrix",
    "urdfdom_angles",
    "urdfdom_quaternion",
    "urdfdom_rpy",
]

Matrix3 = tuple[Vector3, Vector3, Vector3]
Quaternion = tuple[float, float, float, float]  # x, y, z, w, as urdfdom stores a rotation

IDENTITY: Matrix3 = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def rpy_matrix(rpy: Vector3) -> Matrix3:
    """The rotation of URDF's ``rpy``: roll about x, then pitch about y, then yaw about z,
    all about the fixed axes (R = Rz(yaw) Ry(pitch) Rx(roll))."""
    roll, pitch, yaw = rpy
    if roll == pitch == yaw == 0.0:
        return IDENTITY
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )


def axis_angle(axis: Vector3, angle: float) -> Matrix3:
    """The rotation by ``angle`` (radians) about ``axis`` (normalised here; Rodrigues)."""
    norm = math.hypot(*axis)
    if norm == 0.0 or angle == 0.0:
        return IDENTITY
    x, y, z = (a / norm for a in axis)
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    return (
        (t * x * x + c, t * x * y - s * z, t * x * z + s * y),
        (t * x * y + s * z, t * y * y + c, t * y * z - s * x),
        (t * x * z - s * y, t * y * z + s * x, t * z * z + c),
    )


def dot(a: Vector3, b: Vector3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a: Vector3, b: Vector3) -> Vector3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def add(a: Vector3, b: Vector3) -> Vector3:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scale(a: Vector3, k: float) -> Vector3:
    return (a[0] * k, a[1] * k, a[2] * k)


def mat_vec(m: Matrix3, v: Vector3) -> Vector3:
    return (dot(m[0], v), dot(m[1], v), dot(m[2], v))


def transpose(m: Matrix3) -> Matrix3:
    return (
        (m[0][0], m[1][0], m[2][0]),
        (m[0][1], m[1][1], m[2][1]),
        (m[0][2], m[1][2], m[2][2]),
    )


def diagonal(v: Vector3) -> Matrix3:
    """The matrix with ``v`` on its diagonal."""
    return ((v[0], 0.0, 0.0), (0.0, v[1], 0.0), (0.0, 0.0, v[2]))


def mat_mul(a: Matrix3, b: Matrix3) -> Matrix3:
    bt = transpose(b)
    return (
        (dot(a[0], bt[0]), dot(a[0], bt[1]), dot(a[0], bt[2])),
        (dot(a[1], bt[0]), dot(a[1], bt[1]), dot(a[1], bt[2])),
        (dot(a[2], bt[0]), dot(a[2], bt[1]), dot(a[2], bt[2])),
    )


def mat_add(a: Matrix3, b: Matrix3) -> Matrix3:
    return (add(a[0], b[0]), add(a[1], b[1]), add(a[2], b[2]))


def rotate_tensor(r: Matrix3, tensor: Matrix3) -> Matrix3:
    """``R T R^T``: a tensor given in a frame rotated by ``R``, expressed in the outer frame."""
    if r is IDENTITY:  # the common case: an origin without rpy
        return tensor
    return mat_mul(mat_mul(r, tensor), transpose(r))


def point_mass_tensor(mass: float, offset: Vector3) -> Matrix3:
    """The parallel-axis term m (|d|^2 E - d d^T) of a point mass at ``offset``."""
    x, y, z = offset
    return (
        (mass * (y * y + z * z), -mass * x * y, -mass * x * z),
        (-mass * x * y, mass * (x * x + z * z), -mass * y * z),
        (-mass * x * z, -mass * y * z, mass * (x * x + y * y)),
    )


@dataclass(frozen=True, slots=True)
class Pose:
    """A rigid transform: a point p in this frame is ``rotation @ p + translation`` outside."""

    rotation: Matrix3 = IDENTITY
    translation: Vector3 = ZERO3

    @classmethod
    def of(cls, origin: Origin) -> Pose:
        """The transform of a URDF ``<origin>``."""
        return cls(rpy_matrix(origin.rpy), origin.xyz)

    def then(self, inner: Pose) -> Pose:
        """This pose followed by ``inner`` (a frame given relative to this one)."""
        return Pose(
            mat_mul(self.rotation, inner.rotation),
            add(mat_vec(self.rotation, inner.translation), self.translation),
        )

    def inverse(self) -> Pose:
        """The pose of the outer frame in this one (``p.then(p.inverse())`` is the identity)."""
        back = transpose(self.rotation)
        return Pose(back, scale(mat_vec(back, self.translation), -1.0))

    def apply(self, point: Vector3) -> Vector3:
        """Where ``point`` (in this frame) lies in the outer frame."""
        return add(mat_vec(self.rotation, point), self.translation)

    def matrix(self) -> list[list[float]]:
        """The 4x4 homogeneous matrix, rows (``numpy.array(pose.matrix())`` for numpy)."""
        r, t = self.rotation, self.translation
        return [[*r[0], t[0]], [*r[1], t[1]], [*r[2], t[2]], [0.0, 0.0, 0.0, 1.0]]


def quaternion(m: Any) -> tuple[float, float, float, float]:
    """x, y, z, w of a rotation matrix (nested sequences or a numpy array), from the largest
    of w, x, y, z as tf2's Matrix3x3::getRotation picks it."""
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0.0:
        s = math.sqrt(trace + 1.0)
        w, s = s * 0.5, 0.5 / s
        return ((m[2][1] - m[1][2]) * s, (m[0][2] - m[2][0]) * s, (m[1][0] - m[0][1]) * s, w)
    i = max(range(3), key=lambda d: m[d][d])  # the first of the largest, as tf2's order
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(m[i][i] - m[j][j] - m[k][k] + 1.0)
    out = [0.0, 0.0, 0.0, 0.0]
    out[i], s = s * 0.5, 0.5 / s
    out[3] = (m[k][j] - m[j][k]) * s
    out[j] = (m[j][i] + m[i][j]) * s
    out[k] = (m[k][i] + m[i][k]) * s
    return (float(out[0]), float(out[1]), float(out[2]), float(out[3]))


def eigenvalues(m: Matrix3) -> Vector3:
    """The eigenvalues of a symmetric 3x3 matrix, smallest first (`eigh` without its
    vectors)."""
    if m[0][1] == 0.0 and m[0][2] == 0.0 and m[1][2] == 0.0:  # most URDF inertias
        a, b, c = sorted((m[0][0], m[1][1], m[2][2]))
        return a, b, c
    return eigh(m)[0]


def eigh(m: Matrix3) -> tuple[Vector3, Matrix3]:
    """Eigenvalues (ascending) and unit eigenvectors (the columns) of a symmetric 3x3 matrix.

    Cyclic Jacobi rotations: exact to rounding for the small matrices of inertia work, and
    free of the cancellation of the closed-form cubic when two moments are equal.
    """
    if m[0][1] == 0.0 and m[0][2] == 0.0 and m[1][2] == 0.0:  # most URDF inertias
        order = sorted(range(3), key=lambda i: m[i][i])
        unit = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)
        columns = [unit[i] for i in order]
        return (
            (m[order[0]][order[0]], m[order[1]][order[1]], m[order[2]][order[2]]),
            transpose((columns[0], columns[1], columns[2])),
        )
    # Worked on scaled to its largest entry, so that no square overflows (an inertia of
    # 1e200 is finite, its square is not), and scaled back at the end.
    scale = max(abs(x) for row in m for x in row)
    a = [[x / scale for x in row] for row in m]
    v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    for _ in range(50):
        off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2]
        size = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2]
        if off <= 1e-30 * size or off == 0.0:
            break
        for p, q in ((0, 1), (0, 2), (1, 2)):
            if a[p][q] == 0.0:
                continue
            theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q])
            t = math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1.0))
            c = 1.0 / math.sqrt(t * t + 1.0)
            s = t * c
            for k in range(3):  # columns p and q
                akp, akq = a[k][p], a[k][q]
                a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
            for k in range(3):  # rows p and q
                apk, aqk = a[p][k], a[q][k]
                a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
            for k in range(3):
                vkp, vkq = v[k][p], v[k][q]
                v[k][p], v[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    order = sorted(range(3), key=lambda i: a[i][i])
    values = (
        a[order[0]][order[0]] * scale,
        a[order[1]][order[1]] * scale,
        a[order[2]][order[2]] * scale,
    )
    vectors = (
        (v[0][order[0]], v[0][order[1]], v[0][order[2]]),
        (v[1][order[0]], v[1][order[1]], v[1][order[2]]),
        (v[2][order[0]], v[2][order[1]], v[2][order[2]]),
    )
    return values, vectors


def urdfdom_rpy(rpy: Vector3) -> Vector3:
    """Roll, pitch, yaw as urdfdom gives them back after storing them as a quaternion.

    The same operations in the same order as urdfdom's Rotation::setFromRPY, normalize and
    getRPY, so the printed numbers match urdf_to_graphviz's, down to the sign of a zero
    pitch (``0 0 0`` comes back as ``0 -0 0``) and the gimbal-lock cases.
    """
    return urdfdom_angles(urdfdom_quaternion(rpy))


def urdfdom_quaternion(rpy: Vector3) -> Quaternion:
    """The unit quaternion ``(x, y, z, w)`` urdfdom stores for roll, pitch, yaw (radians):
    its Rotation::setFromRPY and normalize, operation for operation."""
    phi, the, psi = rpy[0] / 2.0, rpy[1] / 2.0, rpy[2] / 2.0
    sin, cos = math.sin, math.cos
    x = sin(phi) * cos(the) * cos(psi) - cos(phi) * sin(the) * sin(psi)
    y = cos(phi) * sin(the) * cos(psi) + sin(phi) * cos(the) * sin(psi)
    z = cos(phi) * cos(the) * sin(psi) - sin(phi) * sin(the) * cos(psi)
    w = cos(phi) * cos(the) * cos(psi) + sin(phi) * sin(the) * sin(psi)
    s = math.sqrt(x * x + y * y + z * z + w * w)
    if s == 0.0:
        return 0.0, 0.0, 0.0, 1.0
    return x / s, y / s, z / s, w / s


def urdfdom_angles(q: Quaternion) -> Vector3:
    """Roll, pitch, yaw (radians) of the quaternion ``(x, y, z, w)`` as urdfdom's
    Rotation::getRPY gives them, its gimbal-lock cases included."""
    x, y, z, w = q
    sqx, sqy, sqz, sqw = x * x, y * y, z * z, w * w
    sarg = -2 * (x * z - w * y)
    if sarg <= -0.99999:
        return 0.0, -math.pi / 2, 2 * math.atan2(x, -y)
    if sarg >= 0.99999:
        return 0.0, math.pi / 2, 2 * math.atan2(-x, y)
    return (
        math.atan2(2 * (y * z + w * x), sqw - sqx - sqy + sqz),
        math.asin(sarg),
        math.atan2(2 * (x * y + w * z), sqw + sqx - sqy - sqz),
    )


def euler_ypr(m: list[list[float]]) -> tuple[float, float, float]:
    """Roll, pitch, yaw (R = Rz(yaw) Ry(pitch) Rx(roll)), pitch in [-pi/2, pi/2], as tf2's
    Matrix3x3::getEulerYPR gives them (its -0.0 pitch included)."""
    if abs(m[2][0]) >= 1.0:
        yaw = 0.0
        if m[2][0] < 0:
            delta = math.atan2(m[0][1], m[0][2])
            return delta, math.pi / 2, yaw
        delta = math.atan2(-m[0][1], -m[0][2])
        return delta, -math.pi / 2, yaw
    pitch = -math.asin(m[2][0])
    c = math.cos(pitch)
    roll = math.atan2(m[2][1] / c, m[2][2] / c)
    yaw = math.atan2(m[1][0] / c, m[0][0] / c)
    return roll, pitch, yaw
