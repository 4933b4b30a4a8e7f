"""The trial of a wheeled robot: dropped on the floor, left to settle, driven straight, then
turned on the spot, as a learner drives it in Gazebo with teleop_twist_keyboard.

Each wheel is turned as its drive plugin turns it: at (v -+ omega * separation / 2) / radius
for the left and right wheel, with the separation and radius the plugin is told (measured
from the joints and cylinders for wheels no plugin drives). What the robot then does is
held to what its description says: each wheel's centre rests at its radius, the robot
moves at its wheels' turning times their radius and at the commanded speed, it turns at
the commanded rate and the rate its wheels' speeds and separation give.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..analysis import Analysis
from ..analysis.drive import Drive, rolling_radius
from ..diagnostics import Diagnostic
from ..model import Collision, Cylinder, Joint, JointType, Link, Sphere
from ..spatial import mat_vec
from . import _findings as say
from ._outcome import Measure
from ._watch import RAMP, Watch
from ._world import World

__all__ = ["SETTLE", "Wheel", "drive", "wheels_of"]

SETTLE = 1.0
"""How long the robot is left on the floor before it is driven (s)."""
STOP = 0.5
"""How long it is stopped between the straight run and the turn (s)."""
SPEED_TOLERANCE = 0.1
"""How far off (relative) the speed may be."""
TURN_TOLERANCE = 0.15
"""How far off (relative) the turn rate may be: a wheel's contact is a patch, which scrubs
as the robot turns on the spot."""
TOUCHING = 0.5
"""The share of the looks a driven wheel must touch the floor at."""
VEER = 0.05
"""The most a robot driven straight may turn (rad/s): 3 degrees a second."""
LEAST_OFF = 0.02
"""The least a speed (m/s) or turn rate (rad/s) may be off before it is wrong."""
DRAG = 0.05
"""The share of the robot's weight a caster may hold it back with."""
_CAUSES = ("sim-sank", "sim-wheel-off-floor", "sim-body-on-floor", "sim-caster-drag")
"""The findings that explain a wrong speed or turn rate, the likeliest first."""


@dataclass(frozen=True, slots=True)
class Wheel:
    """A driven wheel, as its description has it.

    Attributes:
        joint: Its joint.
        link: Its link.
        radius: The radius it rolls on (`fishbot_urdf.analysis.drive.rolling_radius`), else
            that of its largest collision cylinder; 0 when it has neither.
        along: Whether it rolls on that radius about the joint's axis.
        collision: That cylinder's collision.
        forward: The sign of a speed that rolls the wheel forward: -1 for a wheel no plugin
            drives whose joint turns about -y (a mirrored motor: a controller is told so),
            else 1 (a plugin turns each joint as it is told, whichever way it rolls).
    """

    joint: Joint
    link: Link
    radius: float
    along: bool
    collision: Collision | None
    forward: float = 1.0


def wheels_of(analysis: Analysis, drive: Drive) -> tuple[Wheel, Wheel] | None:
    """The left and right wheel of ``drive``; None when a joint or link is not there."""
    found = []
    for name in (drive.left, drive.right):
        joint = analysis.joints.get(name)
        link = analysis.links.get(joint.child) if joint is not None else None
        if joint is None or link is None:
            return None
        cylinders = [c for c in link.collisions if isinstance(c.geometry, Cylinder)]
        largest = max(cylinders, key=lambda c: c.geometry.radius, default=None)  # type: ignore[union-attr]
        rolling = rolling_radius(link, joint.axis, analysis.mesh_bounds)
        radius = (
            rolling
            if rolling is not None
            else (
                largest.geometry.radius if largest is not None else 0.0  # type: ignore[union-attr]
            )
        )
        forward = 1.0
        if drive.plugin is None and joint.child in analysis.zero_poses:
            axis = mat_vec(analysis.zero_poses[joint.child].rotation, joint.axis)
            forward = -1.0 if axis[1] < 0 else 1.0
        found.append(Wheel(joint, link, radius, rolling is not None, largest, forward))
    return found[0], found[1]


def drive(
    analysis: Analysis,
    world: World,
    watch: Watch,
    pair: Drive,
    *,
    speed: float,
    turn: float,
    seconds: float,
) -> tuple[list[Measure], list[Diagnostic]]:
    """Settle, drive straight at ``speed`` (m/s) and turn at ``turn`` (rad/s), ``seconds``
    each after the ramp; what was measured, and what went wrong."""
    measures: list[Measure] = []
    found: list[Diagnostic] = []
    wheels = wheels_of(analysis, pair)
    if wheels is None:
        return measures, found
    left, right = wheels
    actuators = (world.actuator(left.joint.name), world.actuator(right.joint.name))
    radius = pair.radius if pair.radius else left.radius
    separation = pair.separation if pair.separation else _apart(world, left, right)
    if not watch.run(SETTLE):
        return measures, found
    watch.track([world.body(w.link.name) for w in wheels])
    run = _Run(world, watch, wheels, actuators, radius, separation)
    straight = run.go(speed, 0.0, seconds)
    if straight is None:
        return measures, found
    forward, rolled = straight.forward, straight.rolled
    drags = dict(watch.forces)
    touched_straight, looks_straight = dict(watch.touches), watch.looks
    if not watch.run(STOP, dict.fromkeys(actuators, 0.0)):
        return measures, found
    turned = run.go(0.0, turn, seconds)
    if turned is None:
        return measures, found
    rate = turned.rate
    touches = {
        k: touched_straight.get(k, 0) + watch.touches.get(k, 0)
        for k in {*touched_straight, *watch.touches}
    }
    looks = looks_straight + watch.looks
    for wheel in wheels:
        _rest(analysis, world, watch, wheel, measures, found)
    measures.append(_near("straight speed", forward, speed, "m/s", SPEED_TOLERANCE))
    veer = straight.rate
    measures.append(Measure("turn while straight", veer, 0.0, "rad/s", abs(veer) <= VEER))
    measures.append(_near("speed from the wheels", forward, rolled, "m/s", SPEED_TOLERANCE))
    measures.append(_near("turn rate", rate, turn, "rad/s", TURN_TOLERANCE))
    measures.append(
        _near("turn rate from the wheels", rate, turned.wheels_rate, "rad/s", TURN_TOLERANCE)
    )
    off = [w for w in wheels if touches.get(w.link.name, 0) < TOUCHING * looks]
    for wheel in off:
        share = touches.get(wheel.link.name, 0) / max(looks, 1)
        measures.append(
            Measure("on the floor", share, 1.0, "share of the time", False, wheel.link.name)
        )
        found.append(say.wheel_off(analysis, world, wheel, share, wheels))
    names = {left.link.name, right.link.name}
    weight = float(world.model.body_subtreemass[0] * -world.model.opt.gravity[2])
    for link, count in sorted(touches.items()):
        if link in names or count < 0.2 * looks:
            continue
        if _caster(analysis, link):
            tangential = drags.get(link, (0.0, 0.0))[1]
            pull = tangential / max(looks_straight, 1)
            if weight > 0 and pull > DRAG * weight:
                measures.append(Measure("caster drag", pull, 0.0, "N", False, link))
                found.append(say.caster_drag(analysis, link, pull, weight))
        else:
            measures.append(
                Measure("on the floor", count / looks, 0.0, "share of the time", False, link)
            )
            found.append(say.body_on_floor(analysis, link, count / looks, wheels))
    seen = next((d.rule for d in found if d.rule in _CAUSES), "")
    if not _ok(measures, "straight speed"):
        grip = min(_grip(world, wheel) for wheel in wheels)
        found.append(say.speed(analysis, pair, wheels, forward, speed, rolled, radius, seen, grip))
    elif not _ok(measures, "speed from the wheels"):
        found.append(say.slip(analysis, pair, wheels, forward, rolled))
    if not _ok(measures, "turn while straight"):
        found.append(say.veered(analysis, pair, wheels, speed, veer))
    if not _ok(measures, "turn rate"):
        apart = _apart(world, left, right)
        found.append(say.turn(analysis, pair, wheels, rate, turn, separation, apart, seen))
    return measures, found


class _Run:
    """Driving at one command, measured once it is reached."""

    def __init__(
        self,
        world: World,
        watch: Watch,
        wheels: tuple[Wheel, Wheel],
        actuators: tuple[int, int],
        radius: float,
        separation: float,
    ) -> None:
        self.world, self.watch, self.wheels = world, watch, wheels
        self.actuators, self.radius, self.separation = actuators, radius, separation

    def go(self, speed: float, turn: float, seconds: float) -> _Went | None:
        """Ramp to the command, then hold it ``seconds``: what the robot did over that time;
        None when the state blew up."""
        half = turn * self.separation / 2.0
        controls = {}
        if self.radius > 0:
            left, right = self.wheels
            controls = {
                self.actuators[0]: left.forward * (speed - half) / self.radius,
                self.actuators[1]: right.forward * (speed + half) / self.radius,
            }
        controls = {a: v for a, v in controls.items() if a >= 0}
        watch = self.watch
        # ramped to the command, then held as long again before it is measured: the robot
        # overshoots the speed it is given, and settles to it
        if not watch.run(RAMP, controls) or not watch.run(RAMP, controls, ramp=False):
            return None
        watch.count()
        start, yaw = watch.heading()
        turned, rolled = [0.0], [0.0, 0.0, 0]

        def look() -> None:
            _, now = watch.heading()
            step = (now - yaw_at[0] + math.pi) % (2 * math.pi) - math.pi
            turned[0] += step
            yaw_at[0] = now
            on_left, on_right = self._rolling(now)
            rolled[0] += on_left
            rolled[1] += on_right
            rolled[2] += 1

        yaw_at = [yaw]
        if not watch.run(seconds, controls, ramp=False, each=look):
            return None
        end, _ = watch.heading()
        middle = yaw + turned[0] / 2.0
        forward = float(np.dot(end - start, (math.cos(middle), math.sin(middle)))) / seconds
        looks = max(int(rolled[2]), 1)
        on_left, on_right = rolled[0] / looks, rolled[1] / looks
        apart = _apart(self.world, *self.wheels)
        wheels_turn = (on_right - on_left) / apart if apart > 0 else 0.0
        return _Went(forward, (on_left + on_right) / 2.0, turned[0] / seconds, wheels_turn)

    def _rolling(self, yaw: float) -> tuple[float, float]:
        """How fast each wheel's turning, relative to the body, would carry it forward
        now (m/s): the left's, the right's."""
        world = self.world
        base = world.data.cvel[self.watch.root][:3]
        heading = np.array((math.cos(yaw), math.sin(yaw), 0.0))
        speeds = []
        for wheel in self.wheels:
            body = world.body(wheel.link.name)
            spin = world.data.cvel[body][:3] - base
            speeds.append(float(np.dot(np.cross(spin, (0.0, 0.0, wheel.radius)), heading)))
        return speeds[0], speeds[1]


class _Went(NamedTuple):
    """What the robot did at one command, measured."""

    forward: float
    """Its speed forward (m/s)."""
    rolled: float
    """The speed its wheels' turning gives (m/s), their radius times their spin."""
    rate: float
    """Its turn rate (rad/s)."""
    wheels_rate: float
    """The turn rate its wheels' speeds give over the distance between them (rad/s)."""


def _rest(
    analysis: Analysis,
    world: World,
    watch: Watch,
    wheel: Wheel,
    measures: list[Measure],
    found: list[Diagnostic],
) -> None:
    """How low the wheel's centre came as it rolled, against its radius."""
    if wheel.radius <= 0:
        return
    height = watch.heights.get(world.body(wheel.link.name), math.inf)
    if not math.isfinite(height):
        return
    low = wheel.radius - height
    tolerance = max(0.003, 0.1 * wheel.radius)
    measures.append(
        Measure("lowest wheel centre", height, wheel.radius, "m", low <= tolerance, wheel.link.name)
    )
    if low > tolerance:
        found.append(say.sank(analysis, wheel, low))


def _grip(world: World, wheel: Wheel) -> float:
    """The greatest friction of the wheel's collision shapes (what it grips the floor with:
    the floor's is 0)."""
    model, body = world.model, world.body(wheel.link.name)
    grips = [
        float(model.geom_friction[g][0]) for g in world.collisions if model.geom_bodyid[g] == body
    ]
    return max(grips, default=1.0)


def _apart(world: World, left: Wheel, right: Wheel) -> float:
    """How far apart the two wheels are now (m)."""
    data = world.data
    one, other = data.xpos[world.body(left.link.name)], data.xpos[world.body(right.link.name)]
    return float(np.linalg.norm(one - other))


def _caster(analysis: Analysis, name: str) -> bool:
    """Whether link ``name`` is a caster: named so, rolling on a ball, or on a continuous
    joint (a wheel no drive turns, or a swivel)."""
    link = analysis.links.get(name)
    if link is None:
        return False
    joint = analysis.parent_joint.get(name)
    return (
        "caster" in name.lower()
        or any(isinstance(c.geometry, Sphere) for c in link.collisions)
        or (joint is not None and joint.type is JointType.CONTINUOUS)
    )


def _near(name: str, value: float, expected: float, unit: str, tolerance: float) -> Measure:
    """``value`` held to ``expected`` within ``tolerance`` of it, and never closer than
    `LEAST_OFF` (a robot told to stand still may creep a millimetre)."""
    ok = abs(value - expected) <= max(tolerance * abs(expected), LEAST_OFF)
    return Measure(name, value, expected, unit, ok)


def _ok(measures: list[Measure], name: str) -> bool:
    return all(m.ok for m in measures if m.name == name)
