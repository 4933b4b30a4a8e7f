"""Holding a robot's joints at a configuration within their limits, as a position controller
does under ros2_control: a servo on each joint, limited to its ``<limit effort>``, that
gives gravity's torque at the configuration and springs back from any drift.

The configuration is each joint at 0, or at the limit nearer 0 when 0 is outside them (a
zero configuration outside the limits is no pose the robot can take). The servo answers
in a tenth of a second whatever the links' inertia (its gain is the joint's own inertia at
that configuration times (2 pi 10 Hz)^2, critically damped), so only its effort limit can
make a joint sag.
"""

from __future__ import annotations

import math

import numpy as np

from ..analysis import Analysis
from ..diagnostics import Diagnostic
from ..export.mjcf import Motor
from ..model import JointType
from . import _findings as say
from ._outcome import Measure
from ._watch import Watch
from ._world import World

__all__ = ["DRIFT", "held_joints", "hold", "servos", "start"]

FREQUENCY = 10.0
"""How fast the servos answer (Hz)."""
DRIFT = 0.05
"""How far (rad, or m / 5 for a prismatic joint) a held joint may drift."""

_ONE_NUMBER = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)


def held_joints(analysis: Analysis, driven: set[str], *, rolling: bool = False) -> list[str]:
    """The joints held by servos: every joint that moves along one number, is not in
    ``driven``, and follows no other (a mimic joint follows by its equality constraint);
    with ``rolling``, a continuous joint is left free: on a wheeled robot, it is a wheel or
    a caster that rolls or swivels as it is pushed."""
    plan = analysis.plan
    return [
        step.joint.name
        for step in plan.steps
        if step.kind in _ONE_NUMBER
        and step.joint.name not in driven
        and step.joint.name not in plan.mimics
        and not (rolling and step.kind is JointType.CONTINUOUS)
    ]


def servos(analysis: Analysis, joints: list[str]) -> tuple[Motor, ...]:
    """Position servos for ``joints``, limited to their effort limits."""
    found = []
    for name in joints:
        limit = analysis.joints[name].limit
        effort = limit.effort if limit is not None and limit.effort > 0 else None
        if effort is not None and not math.isfinite(effort):
            effort = None
        found.append(Motor(name, "position", effort, "fishbot sim"))
    return tuple(found)


def start(analysis: Analysis, world: World, joints: list[str]) -> dict[str, float]:
    """Put ``joints`` at the configuration they are held at; that configuration."""
    target: dict[str, float] = {}
    data, model = world.data, world.model
    for name in joints:
        joint = analysis.joints[name]
        value = 0.0
        limit = joint.limit
        if (
            joint.type is not JointType.CONTINUOUS
            and limit is not None
            and limit.lower <= limit.upper
        ):
            value = min(max(0.0, limit.lower), limit.upper)
        target[name] = value
        data.qpos[model.jnt_qposadr[world.joint(name)]] = value
    world.mujoco.mj_forward(model, data)
    return target


def tune(world: World, target: dict[str, float]) -> dict[str, float]:
    """Give each servo its gain at the configuration ``target`` (which the robot is at) and
    the command that holds it there against gravity; gravity's torque on each joint."""
    mujoco, model, data = world.mujoco, world.model, world.data
    data.qvel[:] = 0.0
    mujoco.mj_forward(model, data)
    full = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, full)
    omega = 2.0 * math.pi * FREQUENCY
    gravity: dict[str, float] = {}
    for name, value in target.items():
        joint, actuator = world.joint(name), world.actuator(name)
        dof = model.jnt_dofadr[joint]
        inertia = max(float(full[dof, dof]), 1e-9)
        stiffness, damping = inertia * omega**2, 2.0 * inertia * omega
        model.actuator_gainprm[actuator, 0] = stiffness
        model.actuator_biasprm[actuator, 1] = -stiffness
        model.actuator_biasprm[actuator, 2] = -damping
        model.actuator_ctrlrange[actuator] = (-math.inf, math.inf)
        model.actuator_ctrllimited[actuator] = 0
        pull = float(data.qfrc_bias[dof])  # at rest: gravity's torque, to be given
        gravity[name] = pull
        data.ctrl[actuator] = value + pull / stiffness
    return gravity


def hold(
    analysis: Analysis, world: World, watch: Watch, joints: list[str], *, seconds: float
) -> tuple[list[Measure], list[Diagnostic]]:
    """Hold ``joints`` ``seconds``; how far each drifted, and which sagged."""
    measures: list[Measure] = []
    found: list[Diagnostic] = []
    target = start(analysis, world, joints)
    gravity = tune(world, target)
    ids = [world.joint(name) for name in joints]
    drifts = dict.fromkeys(joints, 0.0)  # the farthest each went, at any look

    def look() -> None:
        for name, value in zip(joints, world.positions(ids), strict=True):
            drifts[name] = max(drifts[name], abs(value - target[name]))

    if not watch.run(seconds, ramp=False, each=look):
        return measures, found
    worst, most = 0.0, ""
    sagged: list[tuple[str, float, float | None]] = []  # (joint, drift, effort limit)
    for name in joints:
        joint = analysis.joints[name]
        scale = 5.0 if joint.type is JointType.PRISMATIC else 1.0
        moved = drifts[name]
        if moved * scale > worst:
            worst, most = moved * scale, name
        if moved * scale > DRIFT:
            actuator = world.actuator(name)
            limited = bool(world.model.actuator_forcelimited[actuator])
            effort = float(world.model.actuator_forcerange[actuator][1]) if limited else None
            unit = "m" if scale != 1.0 else "rad"
            measures.append(Measure("drift", moved, 0.0, unit, False, name))
            sagged.append((name, moved, effort))
    # the joints gravity overcomes; a joint only dragged along by them is not at fault
    weak = [s for s in sagged if s[2] is not None and abs(gravity[s[0]]) > s[2]]
    for name, moved, effort in weak or sagged[:1]:
        found.append(say.sag(analysis, name, moved, gravity[name], effort))
    largest = Measure("largest drift", worst, None, "rad", worst <= DRIFT, most, most=DRIFT)
    return [largest, *measures], found
