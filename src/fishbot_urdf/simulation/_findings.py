"""The findings of a simulation, each placed where the robot's files can fix it, with the
cause where the description shows one."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from ..analysis import Analysis
from ..analysis.drive import Drive
from ..catalog import simulation as rules
from ..catalog.physics import MJCF_REFUSED
from ..diagnostics import Diagnostic, Kind, Subject
from ..model import JointType, Location, Sphere
from ..spatial import mat_vec, rpy_matrix

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
            f": its collision cylinder lies along {lies} of the link, not along joint "
            f"{wheel.joint.name!r}'s axis ({axis}), so it rolls on its rims and flat sides"
        )
        hint = 'turn the cylinder onto the axle: rpy="1.5708 0 0" on its origin for an axle along y'
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
    if below is not None:
        link, depth, at = below
        cause = f": {link} reaches {_cm(depth)} below the wheels' lowest point and holds them up"
        hint = f"raise {link} by {_cm(depth)}, so that its lowest point is the wheels'"
        where = at or where
    return rules.SIM_WHEEL_OFF_FLOOR.report(
        f"{wheel.link.name} touched the floor {share:.0%} of the time while driving{cause}",
        where,
        path=analysis.path,
        subject=_link(analysis, wheel.link.name),
        hint=hint,
    )


def _below_wheels(
    analysis: Analysis, wheels: tuple[Wheel, Wheel]
) -> tuple[str, float, Location | None] | None:
    """The ball-shaped support (a caster) reaching lowest below the wheels' lowest point in
    the robot's frame, every joint at zero, if one does by more than a millimetre."""
    poses = analysis.zero_poses
    lows = [poses[w.link.name].translation[2] - w.radius for w in wheels if w.link.name in poses]
    if not lows:
        return None
    floor = min(lows)
    deepest: tuple[str, float, Location | None] | None = None
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
            if depth > 0.001 and (deepest is None or depth > deepest[1]):
                deepest = (name, depth, _joint_place(analysis, name) or collision.source)
    return deepest


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
) -> Diagnostic:
    """Driven straight at ``asked`` m/s, the robot moved at ``moved``; ``seen`` names the
    finding that explains it, if one does."""
    cause, hint = "", "look at how the wheels touch the floor (fishbot view, Collision)"
    where = _plugin_place(pair, pair.dialect.size if pair.dialect else "") or wheels[0].joint.source
    if radius_cause := _radius_cause(pair, wheels[0].radius):
        cause, hint = radius_cause
    elif seen:
        cause = f": see {seen}"
        hint = f"fix what {seen} says"
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
    left, right = wheels
    hint = "look at the wheels and casters as they touch the floor"
    where = _plugin_place(pair, pair.dialect.separation if pair.dialect else "")
    cause = ""
    if asked * rate < 0 and abs(rate) > 0.1 * abs(asked):
        side = "right" if left.joint.origin.xyz[1] < right.joint.origin.xyz[1] else "left"
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
    elif radius_cause := _radius_cause(pair, wheels[0].radius):
        cause, hint = radius_cause
    elif told > 0 and abs(told - apart) > 0.02 * apart:
        tag = pair.dialect.separation if pair.dialect is not None else "wheel separation"
        cause = (
            f": the drive is told the wheels are {told:.4g} m apart (<{tag}>), they are "
            f"{apart:.4g} m"
        )
        hint = f"write <{tag}>{apart:.4g}</{tag}>"
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


def tipped(analysis: Analysis, root: str, degrees: float) -> Diagnostic:
    """The root leaned ``degrees`` from upright."""
    return rules.SIM_TIPPED.report(
        f"{root} tipped over: it leaned {degrees:.0f} degrees from upright",
        _where_link(analysis, root),
        path=analysis.path,
        subject=_link(analysis, root),
        hint="check where each link's mass is (fishbot view, Mass), and place the casters "
        "where they hold the body up",
    )


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
    if effort is not None:
        limit = f"its effort limit is {effort:.3g} {force}"
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
