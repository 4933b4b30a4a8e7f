"""The arithmetic sdformat's URDF converter lumps links with: Gazebo's quaternions for poses
and ODE's mass operations for inertials, operation for operation, so that the numbers come
out as it prints them (sdformat 12, src/parser_urdf.cc)."""

from __future__ import annotations

import math
from typing import NamedTuple

from ..model import Vector3
from ..spatial import Quaternion, urdfdom_angles

__all__ = [
    "IDENTITY",
    "NO_MASS",
    "Mass",
    "Placement",
    "compose",
    "euler",
    "lump",
    "product",
    "quaternion",
    "reach",
    "then",
]

IDENTITY: Quaternion = (0.0, 0.0, 0.0, 1.0)

_Rows = list[list[float]]


class Placement(NamedTuple):
    """A position (metres) and a rotation as a quaternion ``(x, y, z, w)``."""

    xyz: Vector3
    rotation: Quaternion


class Mass(NamedTuple):
    """A link's inertial as the converter holds it.

    Attributes:
        mass: kg.
        frame: The inertial frame in the link's frame (its origin the centre of mass).
        inertia: ixx, ixy, ixz, iyy, iyz, izz in kg*m^2, in ``frame``.
    """

    mass: float
    frame: Placement
    inertia: tuple[float, float, float, float, float, float]


NO_MASS = Mass(0.0, Placement((0.0, 0.0, 0.0), IDENTITY), (0.0,) * 6)


def _rotate(q: Quaternion, v: Vector3) -> Vector3:
    """``v`` rotated by ``q`` as gz::math::Quaternion's ``q * v`` computes it."""
    qx, qy, qz, qw = q
    uv = (qy * v[2] - qz * v[1], qz * v[0] - qx * v[2], qx * v[1] - qy * v[0])
    uuv = (qy * uv[2] - qz * uv[1], qz * uv[0] - qx * uv[2], qx * uv[1] - qy * uv[0])
    k = 2.0 * qw
    return (
        v[0] + uv[0] * k + uuv[0] * 2.0,
        v[1] + uv[1] * k + uuv[1] * 2.0,
        v[2] + uv[2] * k + uuv[2] * 2.0,
    )


def product(a: Quaternion, b: Quaternion) -> Quaternion:
    """The quaternion product ``a * b``, as gz::math::Quaternion computes it."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def then(outer: Placement, inner: Placement) -> Placement:
    """``inner`` (given in a child's frame) in the frame ``outer`` places the child in: the
    converter's TransformToParentFrame."""
    turned = _rotate(outer.rotation, inner.xyz)
    xyz = (outer.xyz[0] + turned[0], outer.xyz[1] + turned[1], outer.xyz[2] + turned[2])
    return Placement(xyz, product(outer.rotation, inner.rotation))


def quaternion(rpy: Vector3) -> Quaternion:
    """Roll, pitch, yaw (radians) as gz::math's Quaternion::Euler makes them ``(x, y, z, w)``."""
    phi, the, psi = rpy[0] / 2.0, rpy[1] / 2.0, rpy[2] / 2.0
    sin, cos = math.sin, math.cos
    w = cos(phi) * cos(the) * cos(psi) + sin(phi) * sin(the) * sin(psi)
    x = sin(phi) * cos(the) * cos(psi) - cos(phi) * sin(the) * sin(psi)
    y = cos(phi) * sin(the) * cos(psi) + sin(phi) * cos(the) * sin(psi)
    z = cos(phi) * cos(the) * sin(psi) - sin(phi) * sin(the) * cos(psi)
    s = math.sqrt(w * w + x * x + y * y + z * z)
    if abs(s) <= 1e-6:
        return IDENTITY
    return x / s, y / s, z / s, w / s


def compose(outer: Placement, inner: Placement) -> Placement:
    """``inner`` placed by ``outer`` as gz::math's Pose3 product computes it (the position
    turned as q * v * q^-1, in quaternions)."""
    qx, qy, qz, qw = outer.rotation
    s = qw * qw + qx * qx + qy * qy + qz * qz
    inverse = IDENTITY if abs(s) <= 1e-6 else (-qx / s, -qy / s, -qz / s, qw / s)
    turned = product(outer.rotation, product((*inner.xyz, 0.0), inverse))
    xyz = (outer.xyz[0] + turned[0], outer.xyz[1] + turned[1], outer.xyz[2] + turned[2])
    return Placement(xyz, product(outer.rotation, inner.rotation))


def euler(q: Quaternion) -> Vector3:
    """Roll, pitch, yaw (radians) as gz::math::Quaternion::Euler gives them (it normalises a
    copy first; at a pitch of +-pi/2 the yaw is 0)."""
    x, y, z, w = q
    s = math.sqrt(w * w + x * x + y * y + z * z)
    if abs(s) <= 1e-6:
        x, y, z, w = 0.0, 0.0, 0.0, 1.0
    else:
        x, y, z, w = x / s, y / s, z / s, w / s
    squ, sqx, sqy, sqz = w * w, x * x, y * y, z * z
    sarg = -2 * (x * z - w * y)
    pitch = -0.5 * math.pi if sarg <= -1.0 else 0.5 * math.pi if sarg >= 1.0 else math.asin(sarg)
    if abs(sarg - 1) < 1e-15:
        return math.atan2(2 * (x * y - z * w), squ - sqx + sqy - sqz), pitch, 0.0
    if abs(sarg + 1) < 1e-15:
        return math.atan2(-2 * (x * y - z * w), squ - sqx + sqy - sqz), pitch, 0.0
    roll = math.atan2(2 * (y * z + w * x), squ - sqx - sqy + sqz)
    return roll, pitch, math.atan2(2 * (x * y + w * z), squ + sqx - sqy - sqz)


def reach(chain: list[Placement], placement: Placement) -> Placement:
    """``placement`` carried out through ``chain`` (innermost fixed joint first)."""
    for outer in chain:
        placement = then(outer, placement)
    return placement


class _Ode:
    """ODE's dMass: a mass, its centre and its inertia tensor (3x3, about the centre)."""

    __slots__ = ("c", "i", "mass")

    def __init__(self, mass: float, inertia: tuple[float, ...]) -> None:
        ixx, ixy, ixz, iyy, iyz, izz = inertia
        self.mass = mass
        self.c = [0.0, 0.0, 0.0]
        self.i: _Rows = [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]

    def rotate(self, r: _Rows) -> None:
        """dMassRotate: I = R I R^T and c = R c, the lower triangle copied from the upper."""
        i = self.i
        t = [[_sum3(r[k][0] * i[a][0], r[k][1] * i[a][1], r[k][2] * i[a][2]) for k in range(3)]
             for a in range(3)]  # fmt: skip
        new = [[_sum3(t[0][k] * r[a][0], t[1][k] * r[a][1], t[2][k] * r[a][2]) for k in range(3)]
               for a in range(3)]  # fmt: skip
        _symmetric(new)
        self.i = new
        c = self.c
        self.c = [_sum3(r[a][0] * c[0], r[a][1] * c[1], r[a][2] * c[2]) for a in range(3)]

    def translate(self, x: float, y: float, z: float) -> None:
        """dMassTranslate: the same mass moved by (x, y, z), its tensor taken about the new
        centre by the parallel-axis rule as ODE writes it."""
        chat = _cross(self.c)
        ahat = _cross([x + self.c[0], y + self.c[1], z + self.c[2]])
        t1, t2 = _times(ahat, ahat), _times(chat, chat)
        for a in range(3):
            for b in range(3):
                self.i[a][b] += self.mass * (t2[a][b] - t1[a][b])
        _symmetric(self.i)
        self.c = [self.c[0] + x, self.c[1] + y, self.c[2] + z]

    def add(self, other: _Ode) -> None:
        """dMassAdd: both masses as one."""
        total = self.mass + other.mass
        denom = 1.0 / total if total else math.inf
        self.c = [(self.c[k] * self.mass + other.c[k] * other.mass) * denom for k in range(3)]
        self.mass = total
        self.i = [[self.i[a][b] + other.i[a][b] for b in range(3)] for a in range(3)]

    def unturn(self, rotation: Quaternion) -> None:
        """Rotated out of a frame turned by ``rotation``, one Euler angle at a time."""
        roll, pitch, yaw = urdfdom_angles(rotation)
        self.rotate(_euler_matrix(-roll, 0.0, 0.0))
        self.rotate(_euler_matrix(0.0, -pitch, 0.0))
        self.rotate(_euler_matrix(0.0, 0.0, -yaw))


def _sum3(a: float, b: float, c: float) -> float:
    return a + b + c


def _symmetric(m: _Rows) -> None:
    m[1][0], m[2][0], m[2][1] = m[0][1], m[0][2], m[1][2]


def _cross(a: list[float]) -> _Rows:
    return [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]]


def _times(a: _Rows, b: _Rows) -> _Rows:
    return [[_sum3(b[0][k] * a[r][0], b[1][k] * a[r][1], b[2][k] * a[r][2]) for k in range(3)]
            for r in range(3)]  # fmt: skip


def _euler_matrix(phi: float, theta: float, psi: float) -> _Rows:
    """ODE's dRFromEulerAngles."""
    sphi, cphi = math.sin(phi), math.cos(phi)
    stheta, ctheta = math.sin(theta), math.cos(theta)
    spsi, cpsi = math.sin(psi), math.cos(psi)
    return [
        [cpsi * ctheta, spsi * ctheta, -stheta],
        [cpsi * stheta * sphi - spsi * cphi, spsi * stheta * sphi + cpsi * cphi, ctheta * sphi],
        [cpsi * stheta * cphi + spsi * sphi, spsi * stheta * cphi - cpsi * sphi, ctheta * cphi],
    ]


def lump(parent: Mass | None, child: Mass, joint: Placement) -> Mass:
    """The parent's inertial with a child's, welded at ``joint`` (the child's frame in the
    parent's), added in: sdformat's ReduceInertialToParent. The result keeps the parent's
    inertial rotation, centred at the joint centre of mass."""
    base = parent or NO_MASS
    whole = _Ode(base.mass, base.inertia)
    whole.unturn(base.frame.rotation)
    whole.translate(*base.frame.xyz)
    part = _Ode(child.mass, child.inertia)
    part.unturn(child.frame.rotation)
    part.translate(*child.frame.xyz)
    part.unturn(joint.rotation)
    part.translate(*joint.xyz)
    whole.add(part)
    centre = (whole.c[0], whole.c[1], whole.c[2])
    whole.translate(-centre[0], -centre[1], -centre[2])
    whole.rotate(_euler_matrix(*urdfdom_angles(base.frame.rotation)))
    i = whole.i
    inertia = (i[0][0], i[0][1], i[0][2], i[1][1], i[1][2], i[2][2])
    return Mass(whole.mass, Placement(centre, base.frame.rotation), inertia)
