"""The robot in MuJoCo, as a learner would try it in Gazebo: dropped on a floor and driven, or
held at a configuration, and what went wrong said as findings in the robot's files.

`simulate` picks the trial from the robot's description:

- **drive**: a robot with a differential drive (its plugin's wheels, or two continuous
  wheel joints) floats on the floor, settles, drives straight, stops and turns on the spot;
- **hold**: any other robot is held by its root, as an arm stands on its table, its joints
  held by servos at a configuration within their limits (see
  `fishbot_urdf.simulation._holding`);
- **drop**: with ``base="floating"``, a robot without wheels is dropped on the floor with
  its joints so held.

`Live` drives a robot live (a command, real-time steps, the links' poses and the lidars'
scans), and `stream` shows it on the viewer's page, driven by its keys (`fishbot sim
--view`).

Every trial watches for a state that blows up, a base that tips over, shapes deep in the
floor, and links whose collision shapes overlap at the start. MuJoCo is the ``sim``
extra (``pip install 'fishbot-urdf[sim]'``).
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from ..analysis import Analysis, of
from ..analysis.drive import Drive
from ..catalog import simulation as catalog
from ..catalog.meshes import MJCF_MESH_CONVERTED
from ..diagnostics import Diagnostic
from ..errors import ArgumentError
from ..export.mjcf import motors, write_mjcf
from ..inputs import deadline
from ..model import Robot
from . import _findings as say
from ._driving import SETTLE, drive, wheels_of
from ._holding import held_joints, hold, servos, start, tune
from ._live import ROOM, LaserScan, Live, Obstacle
from ._outcome import Measure, Outcome, Trial
from ._watch import Watch
from ._world import INSTALL, Refused, World, load_mujoco, quiet_mujoco

if TYPE_CHECKING:
    from ._streaming import Stream, stream

__all__ = [
    "INSTALL",
    "ROOM",
    "LaserScan",
    "Live",
    "Measure",
    "Obstacle",
    "Outcome",
    "Stream",
    "Trial",
    "load_mujoco",
    "quiet_mujoco",
    "simulate",
    "stream",
]

TIPPED = 30.0
"""How far the base may lean from upright (degrees)."""
DEEP = 0.01
"""How deep a shape may sink into the floor (m)."""
DROP = 0.005
"""How high above the floor a floating robot's lowest point starts (m)."""


def simulate(
    robot: Robot | Analysis,
    *,
    seconds: float = 2.0,
    speed: float = 0.5,
    turn: float = 1.0,
    base: Literal["auto", "fixed", "floating"] = "auto",
) -> Outcome:
    """Simulate ``robot`` in MuJoCo and say what went wrong.

    Args:
        robot: The robot, or its analysis.
        seconds: How long each drive (straight, then turning), or the hold, lasts after the
            commands are reached (s of simulated time).
        speed: The straight run's speed (m/s), as ``linear.x`` of a Twist.
        turn: The turn's rate (rad/s, positive to the left), as ``angular.z``.
        base: ``auto``: a wheeled robot floats on the floor, any other is held by its root;
            ``fixed``: held by its root; ``floating``: on the floor.

    Raises:
        ToolNotFoundError: mujoco is not installed.
        ArgumentError: ``seconds`` is not positive, or a number is not finite.
        StructureError: The robot cannot be built as a tree of bodies.
    """
    if not (seconds > 0 and math.isfinite(seconds)):
        raise ArgumentError(f"seconds must be above 0, not {seconds}", name="seconds")
    if not (math.isfinite(speed) and math.isfinite(turn)):
        raise ArgumentError("the speed and turn rate must be finite numbers", name="drive")
    load_mujoco()
    analysis = of(robot)
    pairs = analysis.drives
    pair = pairs[0] if pairs and base != "fixed" else None
    trial: Trial = "drive" if pair is not None else "drop" if base == "floating" else "hold"
    if pair is not None:
        faults = say.undrivable(analysis, pair)
        if faults:
            why = "the drive's wheels cannot be driven"
            return Outcome(analysis.robot.name, trial, 0.0, 0, (), tuple(faults), why)
    wheel_motors = motors(analysis, drives=(pair,)) if pair is not None else ()
    held = held_joints(analysis, {m.joint for m in wheel_motors}, rolling=pair is not None)
    driven = (*wheel_motors, *servos(analysis, held))
    with tempfile.TemporaryDirectory(prefix="fishbot-sim-") as folder:
        # the meshes MuJoCo cannot read are converted there, and read as it compiles
        model = Path(folder) / "robot.xml"
        base_of: Literal["fixed", "floating"] = "fixed" if trial == "hold" else "floating"
        made = write_mjcf(analysis, model, base=base_of, driven=driven)
        conversion = tuple(d for d in made.findings if d.rule != MJCF_MESH_CONVERTED.id)
        if any(d.is_error for d in conversion):
            why = "MuJoCo refuses the model"
            return Outcome(analysis.robot.name, trial, 0.0, 0, (), conversion, why)
        try:
            world = World(
                analysis,
                made.text,
                floor=trial != "hold",
                folder=Path(folder),
                tyres=_tyres(analysis, pair),
            )
        except Refused as exc:
            refusal = (*conversion, say.refused(analysis, exc.why))
            why = "MuJoCo refuses the model"
            return Outcome(analysis.robot.name, trial, 0.0, 0, (), refusal, why)
    root = _root(analysis)
    watch = Watch(world, world.body(root), deadline=deadline())
    found: list[Diagnostic] = list(conversion)
    target = start(analysis, world, held)
    for one, other, depth in world.overlaps():
        found.append(say.self_contact(analysis, one, other, depth, _at(trial)))
    world.apart()
    measures: list[Measure] = []
    if trial != "hold":
        world.lift(DROP - world.lowest())
    tune(world, target)
    if pair is not None:
        more, faults = drive(analysis, world, watch, pair, speed=speed, turn=turn, seconds=seconds)
    elif trial == "drop":
        # a robot without wheels left on the floor: tilt, depth and blow-up are its measures
        watch.run(SETTLE + seconds, ramp=False)
        more, faults = [], []
    else:
        more, faults = hold(analysis, world, watch, held, seconds=seconds)
    measures += more
    found += faults
    if watch.exploded is not None:
        found.append(say.exploded(analysis, watch.exploded, watch.fastest))
    else:
        if trial != "hold":
            tilt = math.degrees(watch.tilt)
            ok = tilt <= TIPPED
            measures.append(Measure("largest tilt", tilt, None, "degrees", ok, most=TIPPED))
            if not ok:
                # what went wrong while it lay over follows from its fall: the fall first,
                # and those findings left out
                fell = say.tipped(analysis, root, tilt, wheeled=pair is not None)
                found = [fell, *(d for d in found if d.rule not in _FALLEN)]
            depth, link = watch.depth
            measures.append(
                Measure("deepest in the floor", depth, None, "m", depth <= DEEP, link, most=DEEP)
            )
            if depth > DEEP:
                found.append(say.penetration(analysis, link, depth))
    steps = round(world.time / world.model.opt.timestep)
    seconds_run = round(world.time, 9)  # (a sum of time steps)
    return Outcome(analysis.robot.name, trial, seconds_run, steps, tuple(measures), tuple(found))


_FALLEN = frozenset(
    rule.id
    for rule in (
        catalog.SIM_SANK,
        catalog.SIM_WHEEL_OFF_FLOOR,
        catalog.SIM_BODY_ON_FLOOR,
        catalog.SIM_CASTER_DRAG,
        catalog.SIM_SPEED,
        catalog.SIM_TURN,
    )
)
"""The findings of a drive that a fall explains."""


def _tyres(analysis: Analysis, pair: Drive | None) -> dict[str, float]:
    """The drive's wheels that roll about their axles, and the radius each rolls on."""
    wheels = wheels_of(analysis, pair) if pair is not None else None
    if wheels is None:
        return {}
    return {w.link.name: w.radius for w in wheels if w.along and w.radius > 0}


def _root(analysis: Analysis) -> str:
    """The link whose body is the robot's base in MuJoCo."""
    plan = analysis.plan
    root = plan.roots[0]
    if root == "world" and plan.steps:
        return plan.links[plan.steps[0].link]
    return root


def _at(trial: Trial) -> str:
    return "at the configuration the robot is held at" if trial == "hold" else "as it stands"


def __getattr__(name: str) -> Any:
    if name in ("Stream", "stream"):
        # the viewer's modules (~100 ms): only for --view
        from . import _streaming

        return getattr(_streaming, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
