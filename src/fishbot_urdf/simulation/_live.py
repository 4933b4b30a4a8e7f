"""A robot driven live in MuJoCo, as a learner drives it in Gazebo with a teleop keyboard:
its wheels turned as its drive plugin turns them for each (v, omega) command, its other
joints held by their servos, its lidars' scans cast at their rate and range, in a room
of four walls so that the rays hit something.

Thread-safe: one lock around MuJoCo's state; a caller steps it with `Live.advance` (in
real time: as many seconds as have passed) and reads the links' poses and the scans from
any thread.
"""

from __future__ import annotations

import math
import threading
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..analysis import Analysis, of
from ..analysis.sensors import RAYS, Scan, Sensor
from ..errors import RobotError
from ..export.mjcf import COLLISION_GROUP, export_mjcf, motors
from ..model import Robot
from ._driving import _apart, wheels_of
from ._holding import held_joints, servos, start, tune
from ._watch import RAMP
from ._world import _GROUND, _ROBOT, SAMPLE, World, load_mujoco

__all__ = ["ROOM", "LaserScan", "Live", "Obstacle"]

ROOM = 3.0
"""The inner width of the square room a wheeled robot drives in (m): walls 1.5 m each way
from where it starts, so that its lidar's rays hit something at a distance one can check."""
WALL_HEIGHT, WALL_THICKNESS = 0.5, 0.05
"""The walls' height and thickness (m): above a small robot's lidar."""
DROP = 0.005
"""How high above the floor the robot's lowest point starts (m), as `simulate` drops it."""
_GROUP = 0
"""The walls' geom group (the floor's too): the rays see it and the robot's collision
shapes, not its visuals."""

# sdformat's defaults of what a <ray> does not write (sdf/1.9/ray.sdf): 640 samples, every
# angle 0, and an update rate of 0 (each step: here, each `advance`)
_SAMPLES, _VERTICAL_SAMPLES = 640, 1


@dataclass(frozen=True, slots=True)
class Obstacle:
    """A box in the world (a wall).

    Attributes:
        centre: Its centre (m, in the world).
        size: Its lengths along x, y and z (m).
    """

    centre: tuple[float, float, float]
    size: tuple[float, float, float]


@dataclass(frozen=True, slots=True)
class LaserScan:
    """One scan of a lidar, as sensor_msgs/LaserScan has it, and where its rays went.

    Attributes:
        sensor: The sensor's name.
        link: Its link.
        time: When it was cast (s of simulated time).
        origin: Where the sensor is (m, in the world).
        ranges: Each ray's distance from the sensor to what it hit (m), row after row of
            the scan (one row for a 2D lidar); ``range_max`` when it hit nothing.
        ends: Where each ray ends (m, in the world): what it hit, or ``range_max`` away.
        range_min, range_max: Where the rays start and end, from the sensor (m).
    """

    sensor: str
    link: str
    time: float
    origin: tuple[float, float, float]
    ranges: tuple[float, ...]
    ends: Any  # numpy (N, 3)
    range_min: float
    range_max: float


@dataclass
class _Lidar:
    sensor: Sensor
    body: int
    pose: Any  # 4x4 in the link's frame
    ways: Any  # unit directions (N, 3) in the sensor's frame
    near: float
    far: float
    period: float
    due: float = 0.0


class Live:
    """The robot of ``robot`` in MuJoCo, driven by `command` and stepped by `advance`.

    A robot with a differential drive (``analysis.drives``) stands on the floor in a
    square room (`ROOM` wide), its wheels driven by velocity motors as its plugin drives
    them; any other robot is held by its root link, with no floor and no walls. Every
    joint not driven is held by a servo (see `fishbot_urdf.simulation._holding`).

    Args:
        robot: The robot, or its analysis.
        walls: Whether a wheeled robot is in the room (else the floor is endless and bare).

    Attributes:
        drive: The drive its wheels are turned as (None: the robot is held).
        obstacles: The room's walls.
        speed, turn: The last command (m/s, rad/s).
        since: When it was given (s of simulated time).
        exploded: When the state blew up (s), if it did: it is stepped no further.

    Raises:
        ToolNotFoundError: mujoco is not installed.
        RobotError: A body MuJoCo would refuse (its ``mjcf-refused`` findings).
        ConversionError: MuJoCo refuses the model.
        StructureError: The robot cannot be built as a tree of bodies.
    """

    def __init__(self, robot: Robot | Analysis, *, walls: bool = True) -> None:
        load_mujoco()
        analysis = of(robot)
        self.analysis = analysis
        pair = analysis.drives[0] if analysis.drives else None
        wheels = wheels_of(analysis, pair) if pair is not None else None
        self.drive = pair if wheels is not None else None
        wheel_motors = motors(analysis, drives=(self.drive,)) if self.drive is not None else ()
        rolling = self.drive is not None
        held = held_joints(analysis, {m.joint for m in wheel_motors}, rolling=rolling)
        floating = self.drive is not None
        made = export_mjcf(
            analysis,
            base="floating" if floating else "fixed",
            driven=(*wheel_motors, *servos(analysis, held)),
        )
        refused = [d for d in made.findings if d.is_error]
        if refused:  # (mjcf-refused: a body MuJoCo would refuse, said where it is written)
            raise RobotError(refused)
        self.obstacles: tuple[Obstacle, ...] = _room() if floating and walls else ()
        self.world = World(analysis, _with(made.text, self.obstacles), floor=floating)
        world = self.world
        target = start(analysis, world, held)
        world.apart()
        if floating:
            world.lift(DROP - world.lowest())
        tune(world, target)
        self._lock = threading.Lock()
        self._wheels: tuple[int, int] = (-1, -1)
        self._radius = self._separation = 0.0
        self._forward = (1.0, 1.0)
        if self.drive is not None and wheels is not None:
            left, right = wheels
            self._forward = (left.forward, right.forward)
            self._wheels = (world.actuator(left.joint.name), world.actuator(right.joint.name))
            self._radius = self.drive.radius or left.radius
            self._separation = self.drive.separation or _apart(world, left, right)
        self._from = (0.0, 0.0)
        self._to = (0.0, 0.0)
        self.since = 0.0  # when the last command was given (s of simulated time)
        self._owed = 0.0  # simulated time asked for and not stepped yet (s)
        self.speed, self.turn = 0.0, 0.0
        self.exploded: float | None = None
        self._bodies = {link: body for link in analysis.links if (body := world.body(link)) >= 0}
        self._lidars = [lidar for s in analysis.sensors if (lidar := _lidar(world, s))]
        self._scans: dict[str, LaserScan] = {}
        self._cast(force=True)

    # -- driving ------------------------------------------------------------------------

    def command(self, speed: float, turn: float) -> None:
        """Drive at ``speed`` (m/s, forward) and ``turn`` (rad/s, to the left), as a Twist's
        linear.x and angular.z: each wheel is turned at (speed -+ turn * separation / 2) /
        radius, reached over `RAMP` seconds, as the drive plugin does. Nothing for a robot
        without a drive."""
        if not (math.isfinite(speed) and math.isfinite(turn)):
            return
        with self._lock:
            self.speed, self.turn = speed, turn
            if self.drive is None or self._radius <= 0:
                return
            data = self.world.data
            self._from = tuple(  # type: ignore[assignment]
                float(data.ctrl[a]) if a >= 0 else 0.0 for a in self._wheels
            )
            half = turn * self._separation / 2.0
            left, right = self._forward
            self._to = (
                left * (speed - half) / self._radius,
                right * (speed + half) / self._radius,
            )
            self.since = self.world.time

    def advance(self, seconds: float) -> None:
        """Step ``seconds`` of simulated time (nothing once the state blew up), casting the
        lidars' scans as they fall due. MuJoCo steps in whole time steps: what is left of
        ``seconds`` is stepped with the next call's, so the simulated time keeps to the
        sum of ``seconds``."""
        with self._lock:
            world = self.world
            tick = float(world.model.opt.timestep)
            self._owed += max(seconds, 0.0)
            steps = int(self._owed / tick + 1e-9)
            self._owed -= steps * tick
            chunk = max(1, round(SAMPLE / tick))
            while steps > 0 and self.exploded is None:
                now = min(chunk, steps)
                steps -= now
                share = min(1.0, (world.time + now * tick - self.since) / RAMP)
                controls = {
                    actuator: was + (to - was) * share
                    for actuator, was, to in zip(self._wheels, self._from, self._to, strict=True)
                    if actuator >= 0
                }
                world.run(now * tick, controls)
                if world.broken():
                    self.exploded = world.time
                    break
                self._cast()

    @property
    def time(self) -> float:
        """The simulated time (s)."""
        with self._lock:
            return self.world.time

    # -- reading ------------------------------------------------------------------------

    def poses(self) -> dict[str, tuple[tuple[float, float, float], tuple[float, ...]]]:
        """Each link's pose in the world: its position (m) and orientation (a unit
        quaternion w, x, y, z)."""
        with self._lock:
            data = self.world.data
            return {
                link: (
                    (float(data.xpos[b][0]), float(data.xpos[b][1]), float(data.xpos[b][2])),
                    tuple(float(q) for q in data.xquat[b]),
                )
                for link, b in self._bodies.items()
            }

    def scans(self) -> tuple[LaserScan, ...]:
        """The latest scan of each lidar."""
        with self._lock:
            return tuple(self._scans.values())

    def _cast(self, *, force: bool = False) -> None:
        world = self.world
        for lidar in self._lidars:
            if not force and world.time + 1e-9 < lidar.due:
                continue
            self._scans[lidar.sensor.name] = _scan(world, lidar)
            lidar.due = (world.time if force else lidar.due) + lidar.period
            if lidar.due <= world.time:  # fallen behind (or a rate of 0): from now on
                lidar.due = world.time + lidar.period


def _lidar(world: World, sensor: Sensor) -> _Lidar | None:
    """What casting ``sensor``'s rays needs; None for no lidar, or one with no range."""
    if sensor.kind not in RAYS or not sensor.rays or sensor.link is None:
        return None
    body = world.body(sensor.link)
    rays = sensor.rays[0]
    near = max(rays.range_min or 0.0, 0.0)
    far = rays.range_max
    if body < 0 or far is None or not far > near:
        return None
    columns = np.array(_angles(rays.horizontal, _SAMPLES))[None, :]
    rows = np.array(_angles(rays.vertical, _VERTICAL_SAMPLES))[:, None]
    ways = np.stack(
        [
            np.cos(rows) * np.cos(columns),
            np.cos(rows) * np.sin(columns),
            np.sin(rows) * np.ones_like(columns),
        ],
        axis=-1,
    ).reshape(-1, 3)
    rate = sensor.update_rate if sensor.update_rate and sensor.update_rate > 0 else 0.0
    period = 1.0 / rate if rate else 0.0
    return _Lidar(sensor, body, np.array(sensor.pose.matrix()), ways, near, far, period)


def _angles(scan: Scan | None, default: int) -> list[float]:
    """The angles of a scan's samples (radians), from ``min_angle`` to ``max_angle``."""
    if scan is None:
        return [0.0]
    samples = int(scan.samples if scan.samples is not None and scan.samples >= 1 else default)
    low = scan.min_angle or 0.0
    high = scan.max_angle if scan.max_angle is not None else 0.0
    if samples == 1:
        return [low]
    step = (high - low) / (samples - 1)
    return [low + i * step for i in range(samples)]


def _scan(world: World, lidar: _Lidar) -> LaserScan:
    """Cast ``lidar``'s rays now, from its minimum range out, as Gazebo casts them: against
    the floor, the walls and the robot's collision shapes, except its own link's."""
    mujoco, data = world.mujoco, world.data
    link = np.eye(4)
    link[:3, :3] = data.xmat[lidar.body].reshape(3, 3)
    link[:3, 3] = data.xpos[lidar.body]
    placed = link @ lidar.pose
    origin, turn = placed[:3, 3], placed[:3, :3]
    ways = lidar.ways @ turn.T
    groups = np.zeros(6, dtype=np.uint8)
    groups[_GROUP] = groups[COLLISION_GROUP] = 1
    geom = np.zeros(1, dtype=np.int32)
    reach = lidar.far - lidar.near
    ranges = np.full(len(ways), lidar.far)
    for index, way in enumerate(ways):
        way = np.ascontiguousarray(way)
        hit = mujoco.mj_ray(
            world.model, data, origin + lidar.near * way, way, groups, 1, lidar.body, geom
        )
        if 0 <= hit <= reach:
            ranges[index] = lidar.near + hit
    ends = origin + ways * ranges[:, None]
    return LaserScan(
        lidar.sensor.name,
        lidar.sensor.link or "",
        world.time,
        (float(origin[0]), float(origin[1]), float(origin[2])),
        tuple(float(r) for r in ranges),
        ends,
        lidar.near,
        lidar.far,
    )


def _room() -> tuple[Obstacle, ...]:
    """Four walls whose inner faces are `ROOM` / 2 from the origin each way."""
    half, thick, high = ROOM / 2.0, WALL_THICKNESS, WALL_HEIGHT
    across = ROOM + 2.0 * thick
    middle = half + thick / 2.0
    return (
        Obstacle((middle, 0.0, high / 2.0), (thick, across, high)),
        Obstacle((-middle, 0.0, high / 2.0), (thick, across, high)),
        Obstacle((0.0, middle, high / 2.0), (across, thick, high)),
        Obstacle((0.0, -middle, high / 2.0), (across, thick, high)),
    )


def _with(mjcf: str, obstacles: tuple[Obstacle, ...]) -> str:
    """``mjcf`` with ``obstacles`` as boxes the robot bumps into, as it does the floor."""
    if not obstacles:
        return mjcf
    root = ET.fromstring(mjcf)
    world = root.find("worldbody")
    assert world is not None
    for index, obstacle in enumerate(obstacles):
        box = ET.SubElement(world, "geom", name=f"wall_{index}", type="box")
        box.set("pos", " ".join(f"{x:g}" for x in obstacle.centre))
        box.set("size", " ".join(f"{x / 2:g}" for x in obstacle.size))
        box.set("group", str(_GROUP))
        box.set("contype", str(_GROUND))
        box.set("conaffinity", str(_ROBOT))
    return ET.tostring(root, encoding="unicode")
