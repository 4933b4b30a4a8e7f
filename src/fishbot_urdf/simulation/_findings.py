"""The findings of a simulation, each placed where the robot's files can fix it, with the
cause where the description shows one."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from ..analysis import Analysis
from ..analysis.drive import Drive
from ..catalog import simulation as rules
from ..catalog.gazebo import DIFF_DRIVE_WHEELS
from ..catalog.physics import MJCF_REFUSED
from ..catalog.references import UNKNOWN_REFERENCE
from ..diagnostics import Diagnostic, Kind, Subject
from ..location import passed_through
from ..model import JointType, Location, Sphere
from ..spatial import mat_vec, rpy_matrix
from ..wording import did_you_mean

if TYPE_CHECKING:
    from ._driving import Wheel
    from ._world import World

__all__ = [
    "body_on_floor",
    "caster_drag",
    "exploded",
    "penetration",
    "refused",
    "sag",
    "sank",
    "self_contact",
    "slip",
    "speed",
    "tipped",
    "turn",
    "undrivable",
    "veered",
    "wheel_off",
]


def _link(analysis: Analysis, name: str) -> Subject:
    return Subject(Kind.LINK, name)


def _where_link(analysis: Analysis, name: str) -> Location | None:
    link = analysis.links.get(name)
    if link is None:
        return None
    for collision in link.collisions:
        if collision.source is not None:
            return collision.source
    return link.source


def _cm(metres: float) -> str:
    return f"{metres * 100:.1f} cm"


def sank(analysis: Analysis, wheel: Wheel, low: float) -> Diagnostic:
    """A wheel whose centre came ``low`` below its radius."""
    inertial = wheel.link.inertial
    mass = sum(link.inertial.mass for link in analysis.robot.links if link.inertial is not None)
    own = inertial.mass if inertial is not None else 0.0
    cause = f": it sinks into the floor under the robot's {mass:.3g} kg"
    hint = f"give the links their real masses (the wheel has {own:.3g} kg of them)"
    if not wheel.along and wheel.collision is not None:
        axis = " ".join(f"{v:g}" for v in wheel.joint.axis)
        along = mat_vec(rpy_matrix(wheel.collision.origin.rpy), (0.0, 0.0, 1.0))
        lies = " ".join(f"{round(v, 3):g}" for v in along)
        cause = (
            f": its collision cylinder lies along {lies} of the link, and joint "
            f"{wheel.joint.name!r} turns it about {axis}, so it rolls on its rims and flat sides"
        )
        hint = (
            "make the cylinder's axis and the joint's <axis> one, the axle (URDF's cylinders lie "
            'along z: rpy="1.5708 0 0" on the collision\'s origin lays one along y)'
        )
    where = wheel.collision.source if wheel.collision is not None else wheel.link.source
    return rules.SIM_SANK.report(
        f"{wheel.link.name} sank {_cm(low)}: its centre came down to "
        f"{_cm(wheel.radius - low)} above the floor as it rolled, for a wheel of radius "
        f"{_cm(wheel.radius)}{cause}",
        where,
        path=analysis.path,
        subject=_link(analysis, wheel.link.name),
        hint=hint,
    )


def wheel_off(
    analysis: Analysis, world: World, wheel: Wheel, share: float, wheels: tuple[Wheel, Wheel]
) -> Diagnostic:
    """A driven wheel that touched the floor at ``share`` of the looks."""
    below = _below_wheels(analysis, wheels)
    where = wheel.joint.source
    cause = ""
    hint = "place the wheels' lowest point at the floor the rest of the robot stands on"
    if below:
        links = " and ".join(link for link, _, _ in below)
        depth, at = below[0][1], below[0][2]
        reach = "reaches" if len(below) == 1 else "reach"
        cause = f": {links} {reach} {_cm(depth)} below the wheels' lowest point and hold them up"
        where = at or where
        hint = (
            f"raise {links} by {_cm(depth)}, so that their lowest point is the wheels'"
            + passed_through(where)
        )
    return rules.SIM_WHEEL_OFF_FLOOR.report(
        f"{wheel.link.name} touched the floor {share:.0%} of the time while driving{cause}",
        where,
        path=analysis.path,
        subject=_link(analysis, wheel.link.name),
        hint=hint,
    )


def _below_wheels(
    analysis: Analysis, wheels: tuple[Wheel, Wheel]
) -> list[tuple[str, float, Location | None]]:
    """The ball-shaped supports (casters) reaching below the wheels' lowest point in the
    robot's frame, every joint at zero, by more than a millimetre: the deepest, and those
    within a millimetre of it."""
    poses = analysis.zero_poses
    lows = [poses[w.link.name].translation[2] - w.radius for w in wheels if w.link.name in poses]
    if not lows:
        return []
    floor = min(lows)
    found: list[tuple[str, float, Location | None]] = []
    names = {w.link.name for w in wheels}
    for name, pose in poses.items():
        link = analysis.links.get(name)
        if link is None or name in names:
            continue
        for collision in link.collisions:
            if not isinstance(collision.geometry, Sphere):
                continue
            centre = pose.apply(collision.origin.xyz)
            depth = floor - (centre[2] - collision.geometry.radius)
            if depth > 0.001:
                found.append((name, depth, _joint_place(analysis, name) or collision.source))
    found.sort(key=lambda item: -item[1])
    return [item for item in found if item[1] > found[0][1] - 0.001]


def _joint_place(analysis: Analysis, link: str) -> Location | None:
    joint = analysis.parent_joint.get(link)
    if joint is None:
        return None
    return joint.origin.source or joint.source


def body_on_floor(
    analysis: Analysis, link: str, share: float, wheels: tuple[Wheel, Wheel]
) -> Diagnostic:
    """A link, neither wheel nor caster, that touched the floor at ``share`` of the looks."""
    radius = min(w.radius for w in wheels)
    return rules.SIM_BODY_ON_FLOOR.report(
        f"{link} rests on the floor {share:.0%} of the time while driving: the wheels "
        f"(radius {_cm(radius)}) do not hold it up",
        _where_link(analysis, link),
        path=analysis.path,
        subject=_link(analysis, link),
        hint="give the robot wheels large enough to hold the body above the floor, and the "
        "mass it has",
    )


def caster_drag(analysis: Analysis, link: str, pull: float, weight: float) -> Diagnostic:
    """A caster the floor holds back with ``pull`` newtons on average, sliding."""
    return rules.SIM_CASTER_DRAG.report(
        f"{link} drags on the floor: it holds the robot back with {pull:.3g} N, "
        f"{pull / weight:.0%} of the robot's weight, as it slides",
        _friction_place(analysis, link) or _where_link(analysis, link),
        path=analysis.path,
        subject=_link(analysis, link),
        hint=f'give it no friction: <gazebo reference="{link}"><mu1>0</mu1><mu2>0</mu2>'
        "</gazebo>, or a joint to roll on",
    )


_LEAST_GRIP = 0.05
"""The friction below which a wheel spins on the floor rather than rolling."""


def _weak(pair: Drive, rolled: float, asked: float) -> tuple[str, str, Location | None] | None:
    """The cause, fix and place when the wheels turned well short of the command with a
    torque the plugin limits them to."""
    if pair.torque is None or pair.dialect is None or abs(rolled) >= 0.9 * abs(asked):
        return None
    tag = pair.dialect.torque
    where = _plugin_place(pair, tag)
    written = pair.plugin is not None and pair.plugin.find(tag) is not None
    allows = f"<{tag}>" if written else f"<{tag}> not written: its default"
    cause = (
        f": its wheels turned for only {rolled:.3g} m/s, on the {pair.torque:.3g} N*m the "
        f"plugin allows them ({allows})"
    )
    return cause, f"give <{tag}> the torque of the wheels' motors" + passed_through(where), where


def _friction_place(analysis: Analysis, link: str) -> Location | None:
    for block in analysis.gazebo_blocks:
        if block.reference == link:
            found = block.element.find("mu1")
            at = block.place_of(found) if found is not None else None
            return at or block.where
    return None


def speed(
    analysis: Analysis,
    pair: Drive,
    wheels: tuple[Wheel, Wheel],
    moved: float,
    asked: float,
    rolled: float,
    told: float,
    seen: str,
    grip: float = 1.0,
) -> Diagnostic:
    """Driven straight at ``asked`` m/s, the robot moved at ``moved``; ``seen`` names the
    finding that explains it, if one does; ``grip`` is the wheels' friction (the least)."""
    cause, hint = "", "look at how the wheels touch the floor (fishbot view, Collision)"
    where = _plugin_place(pair, "") or wheels[0].joint.source
    if fault := _wheel_fault(analysis, pair, wheels):
        cause, hint, where = fault
    elif radius_cause := _radius_cause(pair, wheels[0].radius):
        cause, hint = radius_cause
        where = _plugin_place(pair, pair.dialect.size if pair.dialect else "") or where
        hint += passed_through(where)
    elif seen:
        cause = f": see {seen}"
        hint = f"fix what {seen} says"
    elif grip < _LEAST_GRIP:
        cause = (
            f": its wheels grip the floor with a friction of {grip:.3g} (their <gazebo "
            "reference> <mu1> and <mu2>): they spin in place"
        )
        hint = "give the wheels' <gazebo reference> <mu1> and <mu2> of about 1"
        where = _friction_place(analysis, wheels[0].link.name) or where
        hint += passed_through(where)
    elif torque := _weak(pair, rolled, asked):
        cause, hint, where = torque[0], torque[1], torque[2] or where
    elif abs(rolled - asked) > 0.1 * abs(asked):
        cause = (
            f": its wheels turned for {rolled:.3g} m/s, held back by a part on the floor or "
            "by their torque"
        )
    return rules.SIM_SPEED.report(
        f"driven straight at {asked:.3g} m/s, the robot moved at {moved:.3g} m/s{cause}",
        where,
        path=analysis.path,
        subject=Subject(Kind.ROBOT, analysis.robot.name),
        hint=hint,
    )


def _wheel_fault(
    analysis: Analysis, pair: Drive, wheels: tuple[Wheel, Wheel]
) -> tuple[str, str, Location | None] | None:
    """The cause, fix and place of what is wrong with the wheels themselves: a revolute
    joint that stops at its limits; axes a plugin turns opposite ways (a mirrored motor,
    which the plugin does not know of); wheels of two radii."""
    stopping = _stopping(wheels)
    if stopping is not None:
        return stopping
    poses = analysis.zero_poses
    left, right = wheels
    if pair.plugin is not None and left.link.name in poses and right.link.name in poses:
        ys = [mat_vec(poses[w.link.name].rotation, w.joint.axis)[1] for w in wheels]
        if ys[0] * ys[1] < 0:
            back = right if ys[1] < 0 else left
            cause = (
                f": joint {back.joint.name!r} turns about -y and the other about +y, and the "
                "drive plugin turns both joints the same way: that wheel rolls backwards"
            )
            return cause, "give both wheel joints the axis 0 1 0", back.joint.source
    if (
        left.radius > 0
        and right.radius > 0
        and abs(left.radius - right.radius) > 0.01 * max(left.radius, right.radius)
    ):
        cause = (
            f": {left.link.name} rolls on {_cm(left.radius)} and {right.link.name} on "
            f"{_cm(right.radius)}, so at one speed they drive it round in a circle"
        )
        where = right.collision.source if right.collision is not None else right.link.source
        return cause, "give both wheels one radius", where
    return None


def _stopping(wheels: tuple[Wheel, Wheel]) -> tuple[str, str, Location | None] | None:
    """The cause, fix and place when a wheel's joint is revolute, and stops at its limits."""
    for wheel in wheels:
        joint, limit = wheel.joint, wheel.joint.limit
        if joint.type is JointType.REVOLUTE and limit is not None:
            cause = (
                f": wheel joint {joint.name!r} is revolute, and stops at its limits "
                f"({limit.lower:.3g} to {limit.upper:.3g} rad)"
            )
            return cause, "make the wheel's joint continuous", joint.source
    return None


def _radius_cause(pair: Drive, rolls: float) -> tuple[str, str] | None:
    """The cause and the fix when ``pair``'s plugin is told a wheel radius other than the
    ``rolls`` its wheels roll on."""
    told = pair.radius
    if pair.dialect is None or told is None or rolls <= 0 or abs(told - rolls) <= 0.01 * rolls:
        return None
    size = pair.dialect.size
    value = rolls if pair.dialect.radius else 2 * rolls
    cause = (
        f": the drive turns the wheels for a radius of {_cm(told)} (its <{size}>), and they "
        f"roll on {_cm(rolls)}"
    )
    return cause, f"write <{size}>{value:.4g}</{size}>"


def veered(
    analysis: Analysis, pair: Drive, wheels: tuple[Wheel, Wheel], asked: float, rate: float
) -> Diagnostic:
    """Driven straight at ``asked`` m/s, the robot turned at ``rate`` rad/s."""
    cause, hint = "", "look at the wheels and casters as they touch the floor"
    where = _plugin_place(pair, "") or wheels[0].joint.source
    if fault := _wheel_fault(analysis, pair, wheels):
        cause, hint, where = fault
    return rules.SIM_TURN.report(
        f"driven straight at {asked:.3g} m/s, the robot turned at {rate:.3g} rad/s{cause}",
        where,
        path=analysis.path,
        subject=Subject(Kind.ROBOT, analysis.robot.name),
        hint=hint,
    )


def slip(
    analysis: Analysis, pair: Drive, wheels: tuple[Wheel, Wheel], moved: float, rolled: float
) -> Diagnostic:
    """The robot moved at ``moved`` m/s while its wheels turned for ``rolled``."""
    return rules.SIM_SPEED.report(
        f"the robot moved at {moved:.3g} m/s while its wheels turned for {rolled:.3g} m/s: "
        "they slip",
        _where_link(analysis, wheels[0].link.name),
        path=analysis.path,
        subject=Subject(Kind.ROBOT, analysis.robot.name),
        hint="give the wheels grip: <mu1> and <mu2> in their <gazebo reference>",
    )


def turn(
    analysis: Analysis,
    pair: Drive,
    wheels: tuple[Wheel, Wheel],
    rate: float,
    asked: float,
    told: float,
    apart: float,
    seen: str,
) -> Diagnostic:
    """Turned on the spot at ``asked`` rad/s, the robot turned at ``rate``; ``seen`` names
    the finding that explains it, if one does."""
    left = wheels[0]
    hint = "look at the wheels and casters as they touch the floor"
    where = _plugin_place(pair, "")
    cause = ""
    if fault := _wheel_fault(analysis, pair, wheels):
        cause, hint, where = fault
    elif asked * rate < 0 and abs(rate) > 0.1 * abs(asked):
        poses = analysis.zero_poses
        ys = [poses[w.link.name].translation[1] if w.link.name in poses else 0.0 for w in wheels]
        side = "right" if ys[0] < ys[1] else "left"
        cause = (
            f": it turns the other way, as the drive's left wheel {left.joint.name!r} is on "
            f"the robot's {side}"
        )
        if side == "right":
            cause += " and its right wheel on the left: left and right are swapped"
            hint = "swap the joints the drive is given for its left and right wheels"
        else:
            hint = "turn the wheel joints' axes the same way, along +y"
        where = _plugin_place(pair, pair.dialect.left if pair.dialect else "") or where
        hint += passed_through(where)
    elif radius_cause := _radius_cause(pair, wheels[0].radius):
        cause, hint = radius_cause
        where = _plugin_place(pair, pair.dialect.size if pair.dialect else "") or where
        hint += passed_through(where)
    elif told > 0 and abs(told - apart) > 0.02 * apart:
        tag = pair.dialect.separation if pair.dialect is not None else "wheel separation"
        cause = (
            f": the drive is told the wheels are {told:.4g} m apart (<{tag}>), they are "
            f"{apart:.4g} m"
        )
        where = _plugin_place(pair, tag) or where
        hint = f"write <{tag}>{apart:.4g}</{tag}>" + passed_through(where)
    elif seen:
        cause, hint = f": see {seen}", f"fix what {seen} says"
    return rules.SIM_TURN.report(
        f"turned on the spot at {asked:.3g} rad/s, the robot turned at {rate:.3g} rad/s{cause}",
        where or left.joint.source,
        path=analysis.path,
        subject=Subject(Kind.ROBOT, analysis.robot.name),
        hint=hint,
    )


def _plugin_place(pair: Drive, tag: str) -> Location | None:
    """Where ``tag`` of ``pair``'s plugin is written (its first), else the plugin."""
    if pair.plugin is None or pair.block is None:
        return None
    found = pair.plugin.find(tag) if tag else None
    at = pair.block.place_of(found) if found is not None else None
    return at or pair.block.place_of(pair.plugin) or pair.block.where


def undrivable(analysis: Analysis, pair: Drive) -> list[Diagnostic]:
    """Why ``pair``'s wheels cannot be driven: a joint it names that the robot does not have,
    or one that does not turn (empty when both can be)."""
    found = []
    names = pair.dialect
    for name, tag in (
        (pair.left, names.left if names else ""),
        (pair.right, names.right if names else ""),
    ):
        joint = analysis.joints.get(name)
        where = _plugin_place(pair, tag)
        if joint is None:
            found.append(
                UNKNOWN_REFERENCE.report(
                    f"the drive's wheel joint {name!r} is not a joint of the robot: fishbot sim "
                    "cannot drive it",
                    where,
                    path=analysis.path,
                    subject=Subject(Kind.JOINT, name),
                    hint=f"{did_you_mean(name, analysis.joints)}name the wheel's continuous joint",
                )
            )
        elif joint.type not in (JointType.CONTINUOUS, JointType.REVOLUTE):
            found.append(
                DIFF_DRIVE_WHEELS.report(
                    f"the drive's wheel joint {name!r} is a {joint.type.value} joint, which does "
                    "not turn: fishbot sim cannot drive it",
                    where or joint.source,
                    path=analysis.path,
                    subject=Subject(Kind.JOINT, name),
                    hint="make the wheel's joint continuous, about the axle",
                )
            )
    return found


def refused(analysis: Analysis, why: str) -> Diagnostic:
    """MuJoCo refuses the model for ``why`` (its message), which the conversion did not
    foresee: at the link the message names, if it names one."""
    first, _, rest = why.strip().removeprefix("Error: ").partition("\n")
    named = re.search(r"Element name '([^']*)'", rest)
    link = named.group(1) if named else ""
    where = _where_link(analysis, link) if link in analysis.links else None
    subject = Subject(Kind.LINK, link) if where else Subject(Kind.ROBOT, analysis.robot.name)
    return MJCF_REFUSED.report(
        f"MuJoCo refuses the model: {first}" + (f" (link {link!r})" if where else ""),
        where,
        path=analysis.path,
        subject=subject,
        hint="fishbot mjcf -o robot.xml writes the model, to load in MuJoCo and see",
    )


def exploded(analysis: Analysis, time: float, fastest: str) -> Diagnostic:
    """The state blew up at ``time`` seconds; ``fastest`` spun fastest just before."""
    link = analysis.links.get(fastest)
    where = None
    if link is not None:
        where = link.inertial.source if link.inertial is not None else link.source
    spun = f", {fastest} spinning fastest just before" if link is not None else ""
    return rules.SIM_EXPLODED.report(
        f"the simulation blew up {time:.3f} s after it started: a position or speed became "
        f"infinite{spun}",
        where,
        path=analysis.path,
        subject=Subject(Kind.ROBOT, analysis.robot.name),
        hint="give each link the mass and inertia of its part (fishbot inertia --fill)",
    )


def tipped(analysis: Analysis, root: str, degrees: float, *, wheeled: bool) -> Diagnostic:
    """The root leaned ``degrees`` from upright: placed at the inertial that weighs most,
    height times mass, above the root (what raises the centre of mass), if one does."""
    hint = "check where each link's mass is (fishbot view, Mass)"
    if wheeled:
        hint += ", and place the casters where they hold the body up"
    where, high = _where_link(analysis, root), ""
    top = _heaviest_high(analysis)
    if top is not None:
        link, height, mass = top
        inertial = analysis.links[link].inertial
        where = inertial.source if inertial is not None and inertial.source else where
        high = f"; {link}'s {mass:.3g} kg are {height:.3g} m up"
        hint += passed_through(where)
    return rules.SIM_TIPPED.report(
        f"{root} tipped over: it leaned {degrees:.0f} degrees from upright{high}",
        where,
        path=analysis.path,
        subject=_link(analysis, root),
        hint=hint,
    )


def _heaviest_high(analysis: Analysis) -> tuple[str, float, float] | None:
    """Of the links holding a tenth of the robot's mass or more, the one whose mass times
    its height above the root, every joint at zero, is the greatest (its name, height,
    mass), if one is above the root at all."""
    best: tuple[float, str, float, float] | None = None
    total = sum(link.inertial.mass for link in analysis.robot.links if link.inertial is not None)
    for name, pose in analysis.zero_poses.items():
        link = analysis.links.get(name)
        # (a link of a tenth of the robot's mass or more: a gram high up raises nothing)
        if link is None or link.inertial is None or link.inertial.mass < 0.1 * total:
            continue
        height = pose.apply(link.inertial.origin.xyz)[2]
        weight = height * link.inertial.mass
        if height > 0 and (best is None or weight > best[0]):
            best = (weight, name, height, link.inertial.mass)
    return None if best is None else (best[1], best[2], best[3])


def penetration(analysis: Analysis, link: str, depth: float) -> Diagnostic:
    """A shape of ``link`` sank ``depth`` into the floor."""
    return rules.SIM_PENETRATION.report(
        f"{link} sank {_cm(depth)} into the floor",
        _where_link(analysis, link),
        path=analysis.path,
        subject=_link(analysis, link),
        hint="spread the weight on larger collision shapes, or give the robot its real mass",
    )


def sag(
    analysis: Analysis, joint: str, moved: float, gravity: float, effort: float | None
) -> Diagnostic:
    """A held joint that moved ``moved`` from where it was held."""
    known = analysis.joints.get(joint)
    sliding = known is not None and known.type is JointType.PRISMATIC
    length, force = ("m", "N") if sliding else ("rad", "N*m")
    limit = "it has no effort limit"
    if effort is not None and abs(gravity) > effort:
        limit = f"its effort limit is {effort:.3g} {force}"
    elif effort is not None:
        limit = f"its effort limit of {effort:.3g} {force} holds that: the links it carries move it"
    where = None
    if known is not None:
        where = known.limit.source if known.limit is not None else known.source
    return rules.SIM_SAG.report(
        f"joint {joint!r} sagged {moved:.3g} {length} from where it was held: gravity puts "
        f"{abs(gravity):.3g} {force} on it there, and {limit}",
        where,
        path=analysis.path,
        subject=Subject(Kind.JOINT, joint),
        hint="give the joint its motor's effort limit, or the links their real masses",
    )


def self_contact(analysis: Analysis, one: str, other: str, depth: float, at: str) -> Diagnostic:
    """The collision shapes of ``one`` and ``other`` overlap by ``depth`` at ``at``."""
    return rules.SIM_SELF_CONTACT.report(
        f"the collision shapes of {one} and {other} overlap by {_cm(depth)} {at}, as MuJoCo "
        "collides them (a mesh by its convex hull)",
        _where_link(analysis, one),
        path=analysis.path,
        subject=_link(analysis, one),
        hint="shrink the collision shapes to the parts they stand for",
    )
