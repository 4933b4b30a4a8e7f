"""Stepping a world while looking at it: what every trial watches at each look (tilt, depth
in the floor, who touches it, a state that blew up), and ramped commands."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..inputs import Deadline
from ._world import SAMPLE, World

__all__ = ["RAMP", "Watch"]

RUNAWAY = 1e4
"""A body turning faster than this (rad/s) has blown up, whatever its numbers still are."""
RAMP = 0.5
"""How long a change of command takes (s): drive plugins ramp their wheels, and a step from
rest to full speed makes a light robot jump."""


@dataclass
class Watch:
    """A world stepped in looks of `SAMPLE` seconds, and what was seen.

    Attributes:
        world: The world.
        root: The body whose tilt is watched (the robot's root link).
        tilt: The most the root leaned from upright (radians).
        depth: The deepest any shape sank into the floor (m), and which link's.
        exploded: When the state first blew up (s), if it did.
        touches: How many looks each link touched the floor at, since `count` began.
        looks: How many looks since `count` began.
        forces: Each link's floor forces (normal, tangential, N) summed over the looks since
            `count` began.
        heights: The lowest height each body of `track` was seen at (m).
        fastest: The link that turned fastest at the last look.
        deadline: When to stop (the time limit in force), looked at each look.
    """

    world: World
    root: int
    tilt: float = 0.0
    depth: tuple[float, str] = (0.0, "")
    exploded: float | None = None
    touches: dict[str, int] = field(default_factory=dict)
    looks: int = 0
    forces: dict[str, tuple[float, float]] = field(default_factory=dict)
    heights: dict[int, float] = field(default_factory=dict)
    fastest: str = ""
    deadline: Deadline | None = None

    def track(self, bodies: list[int]) -> None:
        """Watch how low ``bodies`` go, from now on."""
        self.heights = {body: math.inf for body in bodies}

    def count(self) -> None:
        """Begin counting touches and forces afresh."""
        self.touches, self.looks, self.forces = {}, 0, {}

    def run(
        self,
        seconds: float,
        controls: dict[int, float] | None = None,
        *,
        ramp: bool = True,
        each: Callable[[], None] | None = None,
    ) -> bool:
        """Step ``seconds``, moving the controls to ``controls`` over `RAMP` seconds (at once
        when not ``ramp``); False when the state blew up (the run stops there)."""
        world = self.world
        start = {a: float(world.data.ctrl[a]) for a in (controls or {})}
        elapsed = 0.0
        while elapsed < seconds - 1e-9:
            step = min(SAMPLE, seconds - elapsed)
            elapsed += step
            share = 1.0 if not ramp else min(1.0, elapsed / RAMP)
            now = {a: start[a] + (v - start[a]) * share for a, v in (controls or {}).items()}
            world.run(step, now)
            if not self._look():
                return False
            if each is not None:
                each()
        return True

    def _look(self) -> bool:
        world = self.world
        if self.deadline is not None:
            self.deadline.check("the simulation")
        spins = np.linalg.norm(world.data.cvel[:, :3], axis=1)
        if world.broken() or float(np.max(spins, initial=0.0)) > RUNAWAY:
            self.exploded = world.time
            return False
        self.fastest = world.links[int(np.argmax(spins))]
        upright = float(world.data.xmat[self.root][8])  # the root's z axis, up component
        self.tilt = max(self.tilt, math.acos(max(-1.0, min(1.0, upright))))
        self.looks += 1
        for body, low in self.heights.items():
            self.heights[body] = min(low, float(world.data.xpos[body][2]))
        for one, other, depth in world.contacts():
            if world.floor not in (one, other):
                continue
            link = world.link_of(other if one == world.floor else one)
            if depth > self.depth[0]:
                self.depth = (depth, link)
        for link, (normal, tangential) in world.floor_forces().items():
            self.touches[link] = self.touches.get(link, 0) + 1
            was = self.forces.get(link, (0.0, 0.0))
            self.forces[link] = (was[0] + normal, was[1] + tangential)
        return True

    def heading(self) -> tuple[np.ndarray, float]:
        """The root's position on the floor (x, y) and its heading (yaw, radians)."""
        data = self.world.data
        rotation = data.xmat[self.root].reshape(3, 3)
        return data.xpos[self.root][:2].copy(), math.atan2(rotation[1, 0], rotation[0, 0])
