"""Robot -> findings about mass and inertia, and about where the robot stands on the ground.

Simulators merge links joined by fixed joints into one rigid body (Gazebo lumps them,
MuJoCo fuses them), so whether a body can move is judged on the merged body; what no
piece of matter can have (a negative moment) is judged on every link, the root included.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import NamedTuple

from .diagnostics import Diagnostic, Severity
from .inertia import combine, geometry_inertia
from .kinematics import link_poses
from .model import (
    Box,
    Collision,
    Cylinder,
    Inertial,
    JointType,
    Link,
    Location,
    Origin,
    Robot,
    Sphere,
    Vector3,
)
from .spatial import Matrix3, Pose, eigh, rotate_tensor, rpy_matrix, transpose
from .xmlsource import diagnostic

__all__ = ["GROUND_TOLERANCE", "MISMATCH", "physics"]

GROUND_TOLERANCE = 0.002
"""How far (m) the lowest collision point may be from the ground before it is reported."""

MISMATCH = 0.10
"""How far (relative to the largest moment) an inertia may be from its collision shape's."""

# MuJoCo refuses a moving body whose mass or a principal moment is below this (mjMINVAL).
_TINY = 1e-15


def _tolerance(moments: tuple[float, float, float]) -> float:
    # Inertias are printed with a handful of digits: allow their rounding, and nothing near
    # a real violation.
    return max(1e-6 * max(abs(m) for m in moments), _TINY)


def _fmt(value: float) -> str:
    """A length or moment, short: 0.10, 0.12, 0.032, 3.9e-05."""
    if value == 0.0:
        return "0"
    return f"{value:.2f}" if abs(value) >= 0.1 else f"{value:.2g}"


def _moments(values: tuple[float, float, float]) -> str:
    """Principal moments for a message; rounding noise (-1e-22 next to 3e-06) shows as 0."""
    return ", ".join(_moment(v, values) for v in values)


def _moment(value: float, values: tuple[float, float, float]) -> str:
    return "0" if abs(value) <= _tolerance(values) else f"{value:.3g}"


class _Body(NamedTuple):
    """Links welded together by fixed joints, and how each sits in the first one's frame."""

    base: Link
    members: tuple[tuple[Link, Pose], ...]
    moved_by: str | None  # the joint that moves the body, None for a root body
    joint_type: JointType | None

    @property
    def inertials(self) -> list[tuple[Link, Inertial, Pose]]:
        """The members that have an inertial, with it."""
        return [(link, link.inertial, pose) for link, pose in self.members if link.inertial]


def _bodies(robot: Robot) -> list[_Body]:
    by_name = {link.name: link for link in robot.links}
    fixed_below: dict[str, list[tuple[str, Pose]]] = {}
    parent_joint: dict[str, tuple[str, JointType]] = {}
    for joint in robot.joints:
        if joint.child in parent_joint or joint.child not in by_name:
            continue
        parent_joint[joint.child] = (joint.name, joint.type)
        if joint.type is JointType.FIXED:
            fixed_below.setdefault(joint.parent, []).append((joint.child, Pose.of(joint.origin)))
    bodies: list[_Body] = []
    alone = Pose()
    for link in robot.links:
        moved_by, joint_type = parent_joint.get(link.name, (None, None))
        if joint_type is JointType.FIXED:
            continue  # part of its parent's body
        if link.name not in fixed_below:  # the common case: a body of one link
            bodies.append(_Body(link, ((link, alone),), moved_by, joint_type))
            continue
        members: list[tuple[Link, Pose]] = []
        stack = [(link.name, alone)]
        seen: set[str] = set()
        while stack:
            name, pose = stack.pop()
            if name in seen or name not in by_name:
                continue
            seen.add(name)
            members.append((by_name[name], pose))
            stack.extend((child, pose.then(o)) for child, o in fixed_below.get(name, ()))
        bodies.append(_Body(link, tuple(members), moved_by, joint_type))
    return bodies


def physics(
    robot: Robot, path: str, *, ground_tolerance: float = GROUND_TOLERANCE
) -> Iterator[Diagnostic]:
    """Every finding about the robot's masses, inertias and stance on the ground.

    Args:
        robot: The robot.
        path: The file findings without a location are reported against.
        ground_tolerance: How far (m) below or above z = 0 of a footprint root the lowest
            collision point may be.
    """
    # Principal moments, once per link (they do not change when the inertia is turned).
    moments = {
        link.name: eigh(link.inertial.inertia.matrix())[0]
        for link in robot.links
        if link.inertial is not None and _finite(link.inertial)
    }
    for body in _bodies(robot):
        yield from _body(body, path, moments, bool(robot.joints))
    for link in robot.links:
        if link.name in moments:
            yield from _mismatch(link, path, moments[link.name])
    yield from _ground(robot, path, ground_tolerance)


def _at(
    rule: str, message: str, where: Location | None, path: str, hint: str, error: bool = True
) -> Diagnostic:
    severity = Severity.ERROR if error else Severity.WARNING
    return diagnostic(rule, message, where, hint=hint, severity=severity, path=path)


def _finite(inertial: Inertial) -> bool:
    return all(
        math.isfinite(v) for v in (inertial.mass, *(getattr(inertial.inertia, f) for f in _FIELDS))
    )


def _body(
    body: _Body, path: str, moments: dict[str, Vector3], jointed: bool
) -> Iterator[Diagnostic]:
    having = body.inertials
    parts = [(inertial, pose) for _, inertial, pose in having]
    finite = all(link.name in moments for link, _, _ in having)
    # Fused with its fixed neighbours a body may be physical although one link's own numbers
    # are not: simulators that merge fixed links load it, so that is only a warning.
    merged = finite and len(parts) > 1 and _physical(combine(parts).principal_moments)
    for link, _ in body.members:
        inertial = link.inertial
        if inertial is not None:
            yield from _inertial(link, inertial, path, merged, moments.get(link.name))
    if finite:
        yield from _moving(body, having, path, moments, jointed)


def _place(link: Link, where: Location | None) -> Location | None:
    """Where to report about a part of ``link``: the part itself, unless a xacro macro from
    another file wrote it (common_inertia.xacro's inertia, say); then the link, which is
    near the macro's call."""
    if where is None or link.source is None or where.path == link.source.path:
        return where or link.source
    return link.source


def _inertial(
    link: Link, inertial: Inertial, path: str, merged: bool, moments: Vector3 | None
) -> Iterator[Diagnostic]:
    owner = f"link {link.name!r}"
    if moments is None:  # not finite
        yield _at(
            "bad-number",
            f"{owner}: the mass or inertia is not finite",
            inertial.source,
            path,
            "write finite numbers",
        )
        return
    if inertial.mass < 0:
        yield _at(
            "negative-mass",
            f"{owner}: mass {inertial.mass:g} kg is negative",
            inertial.source,
            path,
            "mass is >= 0 kg",
        )
    where = _place(link, inertial.inertia.source or inertial.source)
    also = (
        "; merged with the links fixed to it the body is physical, so simulators that merge "
        "fixed links load it, but the numbers are still wrong"
        if merged
        else ""
    )
    if moments[0] < -_tolerance(moments):
        # A negative moment written in the file is a sign slip, merged or not.
        slip = any(getattr(inertial.inertia, f) < 0 for f in ("ixx", "iyy", "izz"))
        yield _at(
            "inertia-not-positive",
            f"{owner}: the inertia is not positive definite: principal moments "
            f"{_moments(moments)} kg*m^2",
            where,
            path,
            _negative_hint(inertial) + ("" if slip else also),
            error=slip or not merged,
        )
    elif not _physical(moments):
        yield _at(
            "inertia-triangle",
            f"{owner}: principal moments {_moments(moments)} kg*m^2 break the triangle "
            f"inequality ({_moment(moments[0], moments)} + {_moment(moments[1], moments)} "
            f"< {_moment(moments[2], moments)})",
            where,
            path,
            "no rigid body has one moment larger than the other two together; "
            "MuJoCo refuses it" + also,
            error=not merged,
        )


_FIELDS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def _physical(moments: tuple[float, float, float]) -> bool:
    """Moments no lower than zero that obey the triangle inequality (within rounding)."""
    tol = _tolerance(moments)
    return moments[0] >= -tol and moments[0] + moments[1] >= moments[2] - tol


def _negative_hint(inertial: Inertial) -> str:
    negative = [f for f in ("ixx", "iyy", "izz") if getattr(inertial.inertia, f) < 0]
    if negative:
        listed = ", ".join(f"{f}={getattr(inertial.inertia, f):g}" for f in negative)
        return f"moments of inertia are >= 0, but {listed}"
    return "the products ixy, ixz, iyz are too large for the moments ixx, iyy, izz"


def _moving(
    body: _Body,
    having: list[tuple[Link, Inertial, Pose]],
    path: str,
    moments: dict[str, Vector3],
    jointed: bool,
) -> Iterator[Diagnostic]:
    with_shape = [link for link, _ in body.members if link.collisions]
    fill = "`fishbot inertia ROBOT --fill -o OUT` adds one from its geometry"
    if body.moved_by is None or body.joint_type is None:
        # The root's body: a mobile robot's base, unless the robot is bolted to the world.
        if not having and with_shape and body.base.name != "world" and jointed:
            link = with_shape[0]
            yield _at(
                "missing-inertial",
                f"link {link.name!r} has collision geometry but no <inertial>, and nothing "
                "it is fixed to has one: the robot's base weighs nothing",
                link.source,
                path,
                f"Gazebo drops a link without an inertial; {fill}",
                error=False,
            )
        return
    moves = f"moves (joint {body.moved_by!r} is {body.joint_type.value})"
    owner = f"link {body.base.name!r}"
    if not having:
        if with_shape:
            link = with_shape[0]
            yield _at(
                "missing-inertial",
                f"link {link.name!r} has collision geometry and {moves} but no <inertial>",
                link.source,
                path,
                f"simulators drop a link without mass or cannot move it; {fill}",
                error=False,
            )
        return
    if any(inertial.mass < 0 for _, inertial, _ in having):
        return  # reported as a negative mass
    first = having[0][1]
    if len(having) == 1:  # the link alone: its own mass and moments
        mass, principal = first.mass, moments[having[0][0].name]
    else:
        together = combine((inertial, pose) for _, inertial, pose in having)
        mass, principal = together.mass, together.principal_moments
    if mass <= _TINY:
        yield _at(
            "massless-link",
            f"{owner} {moves} but its mass is {mass:g} kg",
            _place(having[0][0], first.source),
            path,
            "a moving body needs a mass (MuJoCo: above 1e-15); give its real mass",
        )
    elif -_tolerance(principal) <= principal[0] <= _TINY:
        # (below that the link's own inertia is reported as not positive definite)
        yield _at(
            "massless-link",
            f"{owner} {moves} but has no inertia about some axis: principal moments "
            f"{_moments(principal)} kg*m^2",
            _place(having[0][0], first.source),
            path,
            "a moving body needs every moment above 1e-15 kg*m^2 (MuJoCo refuses it otherwise); "
            "compute them with `fishbot inertia box|cylinder|sphere`",
        )


# -- inertia against the collision shape --------------------------------------------------


def _mismatch(link: Link, path: str, moments: Vector3) -> Iterator[Diagnostic]:
    inertial = link.inertial
    if inertial is None or len(link.collisions) != 1 or not inertial.mass > 0:
        return
    collision = link.collisions[0]
    shape = collision.geometry
    if not isinstance(shape, Box | Cylinder | Sphere):
        return
    if moments[0] < -_tolerance(moments) or moments[2] <= _TINY:
        return  # reported as not positive definite, or a point mass
    declared = rotate_tensor(rpy_matrix(inertial.origin.rpy), inertial.inertia.matrix())
    turn = rpy_matrix(collision.origin.rpy)
    closed = geometry_inertia(shape, inertial.mass).inertia
    wanted = rotate_tensor(turn, closed.matrix())
    largest = max(closed.ixx, closed.iyy, closed.izz)  # diagonal: these are its moments
    if largest <= 0.0:
        return
    gap = max(abs(declared[i][j] - wanted[i][j]) for i in range(3) for j in range(3))
    if gap <= MISMATCH * largest:
        return
    # What the numbers are, seen in the collision's own frame. Numbers that fit no such
    # shape were measured (CAD), not computed: a collision shape only approximates those.
    seen = rotate_tensor(transpose(turn), declared)
    found = _describe(shape, seen, inertial.mass, turn)
    if found is None:
        return
    yield _at(
        "inertia-mismatch",
        f"link {link.name!r}: {found}",
        _place(link, inertial.source),
        path,
        _command(shape, inertial.mass, collision.origin),
        error=False,
    )


def _command(shape: Box | Cylinder | Sphere, mass: float, origin: Origin) -> str:
    """The `fishbot inertia` command that prints the inertial matching the collision."""
    if isinstance(shape, Box):
        words = f"box --mass {mass:g} --size {' '.join(f'{s:g}' for s in shape.size)}"
    elif isinstance(shape, Cylinder):
        words = f"cylinder --mass {mass:g} --radius {shape.radius:g} --length {shape.length:g}"
    else:
        words = f"sphere --mass {mass:g} --radius {shape.radius:g}"
    for name, values in (("xyz", origin.xyz), ("rpy", origin.rpy)):
        if any(values):
            words += f" --{name} {' '.join(f'{v:g}' for v in values)}"
    return (
        f"fix the one that is wrong; `fishbot inertia {words}` prints the inertial of the collision"
    )


def _off_diagonal(m: Matrix3) -> bool:
    scale = max(abs(m[0][0]), abs(m[1][1]), abs(m[2][2]))
    return max(abs(m[0][1]), abs(m[0][2]), abs(m[1][2])) > 1e-3 * scale


def _axis(turn: Matrix3, index: int) -> str:
    """The link axis closest to the collision frame's axis ``index``."""
    column = [turn[k][index] for k in range(3)]
    best = max(range(3), key=lambda k: abs(column[k]))
    if abs(column[best]) > math.cos(math.radians(5)):
        return "xyz"[best]
    return "(" + " ".join(f"{c:.2f}" for c in column) + ")"


def _differs(a: float, b: float) -> bool:
    return abs(a - b) > 0.05 * max(abs(a), abs(b)) and _fmt(a) != _fmt(b)


def _describe(
    shape: Box | Cylinder | Sphere, seen: Matrix3, mass: float, turn: Matrix3
) -> str | None:
    """Which shape of the collision's kind the declared inertia (in the collision's frame)
    matches, against the collision itself; None when it matches none."""
    if isinstance(shape, Sphere):
        moments = eigh(seen)[0]
        radius = math.sqrt(max(0.0, 5.0 * sum(moments) / 3.0 / (2.0 * mass)))
        if moments[2] - moments[0] <= MISMATCH * moments[2] and _differs(radius, shape.radius):
            return (
                f"inertial matches a sphere r={_fmt(radius)}, "
                f"but the collision sphere has r={_fmt(shape.radius)}"
            )
        return None
    if _off_diagonal(seen):
        return None
    diagonal = (seen[0][0], seen[1][1], seen[2][2])
    if isinstance(shape, Box):
        squares = [6.0 * (sum(diagonal) - 2.0 * diagonal[k]) / mass for k in range(3)]
        if min(squares) < 0:
            return None
        sides = [math.sqrt(s) for s in squares]
        return (
            "inertial matches a box "
            + " x ".join(_fmt(s) for s in sides)
            + ", but the collision box is "
            + " x ".join(_fmt(s) for s in shape.size)
        )
    # A cylinder: its axis is where the odd moment out is.
    k = min(range(3), key=lambda i: abs(diagonal[(i + 1) % 3] - diagonal[(i + 2) % 3]))
    across = (diagonal[(k + 1) % 3] + diagonal[(k + 2) % 3]) / 2.0
    if abs(diagonal[(k + 1) % 3] - diagonal[(k + 2) % 3]) > MISMATCH * across:
        return None
    radius = math.sqrt(2.0 * diagonal[k] / mass)
    square = 12.0 * across / mass - 3.0 * radius * radius
    if square < 0:
        return None
    length = math.sqrt(square)
    found = f"inertial matches a cylinder r={_fmt(radius)} h={_fmt(length)}"
    if k != 2:
        return (
            f"{found} along the link's {_axis(turn, k)} axis, "
            f"but the collision cylinder lies along its {_axis(turn, 2)} axis"
        )
    wrong = [
        f"{name}={_fmt(real)}"
        for name, fit, real in (("r", radius, shape.radius), ("h", length, shape.length))
        if _differs(fit, real)
    ]
    if not wrong:
        return None
    return f"{found}, but the collision cylinder has {' '.join(wrong)}"


# -- the ground ----------------------------------------------------------------------------


def _extent(collision: Collision, pose: Pose) -> tuple[float, float] | None:
    """The lowest and highest z of a collision shape placed by its link's ``pose`` (None for
    a mesh, whose points are not read)."""
    frame = pose.then(Pose.of(collision.origin))
    z = frame.translation[2]
    row = frame.rotation[2]  # how each of the shape's axes leans on the vertical
    shape = collision.geometry
    if isinstance(shape, Sphere):
        reach = shape.radius
    elif isinstance(shape, Box):
        reach = sum(abs(row[k]) * shape.size[k] / 2.0 for k in range(3))
    elif isinstance(shape, Cylinder):
        upright = min(1.0, abs(row[2]))
        reach = upright * shape.length / 2.0 + math.sqrt(1.0 - upright * upright) * shape.radius
    else:
        return None
    return z - reach, z + reach


# Joints whose motion leaves a round part's lowest point where it is: a wheel on its axle.
_STANDING = (JointType.FIXED, JointType.CONTINUOUS)


def _ground(robot: Robot, path: str, tolerance: float) -> Iterator[Diagnostic]:
    children = {joint.child for joint in robot.joints}
    roots = [link for link in robot.links if link.name not in children]
    if len(roots) != 1 or roots[0].visuals or roots[0].collisions or roots[0].inertial:
        return  # the ground is z = 0 of a footprint root, a bare frame
    root = roots[0]
    if root.name == "world":
        return  # Gazebo's name for the world itself: the robot is mounted, not standing
    # Only links the root holds through fixed joints and wheel axles: an arm's height at
    # the zero configuration says nothing about the ground.
    held = {root.name}
    joints = [j for j in robot.joints if j.type in _STANDING]
    below: dict[str, list[str]] = {}
    for joint in joints:
        below.setdefault(joint.parent, []).append(joint.child)
    stack = [root.name]
    while stack:
        for child in below.get(stack.pop(), ()):
            if child not in held:
                held.add(child)
                stack.append(child)
    poses = link_poses(Robot(robot.name, robot.links, tuple(joints)))
    spans: list[tuple[float, float, Link, Collision]] = []
    # Whether the robot may stand on something we cannot place: a mesh, or a leg or an
    # arm (a link on a joint that is neither fixed nor a wheel's axle).
    unknown = False
    for link in robot.links:
        if link.name not in held or link is root:
            unknown = unknown or (link.name not in held and bool(link.collisions))
            continue
        for collision in link.collisions:
            span = _extent(collision, poses[link.name])
            if span is None:
                unknown = True
            else:
                spans.append((*span, link, collision))
    if not spans:
        return
    bottom = min(spans, key=lambda item: item[0])
    top = max(item[1] for item in spans)
    if top <= -bottom[0]:
        return  # the root sits inside the robot (a pelvis, a waist): not on the ground
    where = f"the ground (z = 0 of {root.name!r}) at the zero configuration"
    passes = f"up to {tolerance * 1000:g} mm passes (--ground-tolerance)"
    # Compared to the micrometre: a wheel turned by rpy 1.57079 rather than pi/2 sinks
    # 0.0001 mm more than its radius says, which is no finding.
    reported: set[str] = set()
    for z, _, link, collision in sorted(spans, key=lambda item: item[0]):
        if z < -tolerance - _MICROMETRE and link.name not in reported:
            reported.add(link.name)
            depth = _mm(-z, tolerance)
            yield _at(
                "below-ground",
                f"link {link.name!r} reaches {depth} mm below {where}",
                collision.source or link.source,
                path,
                f"raise the joints above it or shorten the shape by {depth} mm; {passes}",
                error=False,
            )
    z, _, link, collision = bottom
    if z > tolerance + _MICROMETRE and not unknown:
        height = _mm(z, tolerance)
        yield _at(
            "above-ground",
            f"link {link.name!r}, the robot's lowest point, is {height} mm above {where}",
            collision.source or link.source,
            path,
            f"the robot floats: lower the joint below {root.name!r} by {height} mm; {passes}",
            error=False,
        )


_MICROMETRE = 1e-6


def _mm(metres: float, tolerance: float) -> str:
    """A distance in mm, with the digits that show it is beyond ``tolerance``."""
    for digits in (1, 2, 3, 4):
        text = f"{metres * 1000:.{digits}f}"
        if float(text) != round(tolerance * 1000, digits):
            return text
    return f"{metres * 1000:.4f}"
