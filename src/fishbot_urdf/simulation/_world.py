"""A robot on a floor in MuJoCo: the model `fishbot_urdf.export.mjcf` writes, a floor under
it, and what the trials read of each step.

MuJoCo is an optional part (the ``sim`` extra), loaded here on first use.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

from ..analysis import Analysis
from ..errors import ConversionError, ToolNotFoundError
from ..export.mjcf import COLLISION_GROUP

__all__ = ["FLOOR", "INSTALL", "Refused", "World", "load_mujoco", "quiet_mujoco"]

INSTALL = "pip install 'fishbot-urdf[sim]'"
"""How to install what `fishbot sim` needs."""
FLOOR = "floor"
"""The floor's geom: an endless plane at z = 0. Its friction is 0, so that each of the
robot's shapes slides or grips with its own (MuJoCo takes the greater of two), as Gazebo's
ground plane leaves it to the robot's."""
_ROBOT, _GROUND = 1, 2
"""The contact bits: the robot's shapes collide with the floor, not with each other, as
Gazebo leaves a URDF robot's links (``<self_collide>`` is off unless a link turns it on)."""
SAMPLE = 0.01
"""How often the trials look at the simulation (s of simulated time)."""


def quiet_mujoco() -> None:
    """Have MuJoCo keep its warnings to itself, for the whole process: by default it prints
    each (a blow-up's ``Nan, Inf or huge value in QACC``) and appends it to
    ``MUJOCO_LOG.TXT`` in the current folder. A simulation says what MuJoCo warns of as its
    findings (`sim-exploded`); a front end calls this once, the library never does.

    Raises:
        ToolNotFoundError: mujoco is not installed.
    """
    load_mujoco().set_mju_user_warning(_ignored)


def _ignored(message: str) -> None:
    """A MuJoCo warning, said elsewhere."""


class Refused(ConversionError):
    """MuJoCo refuses the model; ``why`` is what it says."""

    def __init__(self, why: str) -> None:
        super().__init__(f"MuJoCo refuses the model: {why}", target="mjcf")
        self.why = why


def load_mujoco() -> ModuleType:
    """The mujoco package.

    Raises:
        ToolNotFoundError: It is not installed.
    """
    try:
        import mujoco  # the sim extra: loaded only by the commands that simulate
    except ImportError as exc:
        if exc.name != "mujoco":
            raise
        raise ToolNotFoundError(
            "the mujoco package is not installed", tool="mujoco", hint=INSTALL
        ) from exc
    if not hasattr(mujoco, "MjModel"):  # a folder left behind by an uninstall
        raise ToolNotFoundError("the mujoco package is not installed", tool="mujoco", hint=INSTALL)
    module: ModuleType = mujoco
    return module


class World:
    """The robot of ``analysis``, written as ``mjcf`` (in ``folder``, which its ``meshdir``
    is relative to), in MuJoCo over a floor; the collision cylinders and meshes of the links
    ``tyres`` names (wheels, with the radius they roll on) touch it as balls of that radius
    (see `_round`).

    Attributes:
        model: MuJoCo's model.
        data: Its one state, stepped by `run`.
        links: Each body's link name, by body id.
        collisions: The geom ids of the robot's collision shapes.
    """

    def __init__(
        self,
        analysis: Analysis,
        mjcf: str,
        *,
        floor: bool = True,
        folder: Path | None = None,
        tyres: Mapping[str, float] | None = None,
    ) -> None:
        mujoco = load_mujoco()
        root = ET.fromstring(mjcf)
        compiler = root.find("compiler")
        meshdir = compiler.get("meshdir") if compiler is not None else None
        if compiler is not None and meshdir is not None and folder is not None:
            compiler.set("meshdir", str(folder / meshdir))  # relative to the model's folder
        world = root.find("worldbody")
        assert world is not None
        _round(world, tyres or {})
        ground = ET.Element("geom", name=FLOOR, type="plane", size="0 0 1")
        ground.set("friction", "0 0.005 0.0001")
        ground.set("contype", str(_GROUND) if floor else "0")
        ground.set("conaffinity", str(_ROBOT) if floor else "0")
        world.insert(0, ground)
        try:
            self.model: Any = mujoco.MjModel.from_xml_string(ET.tostring(root, encoding="unicode"))
        except ValueError as exc:  # what the conversion's findings did not foresee
            raise Refused(str(exc)) from None
        self.mujoco = mujoco
        self.data: Any = mujoco.MjData(self.model)
        model = self.model
        self.floor = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, FLOOR)
        self.links = [
            mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) or "" for b in range(model.nbody)
        ]
        self.collisions = [
            g
            for g in range(model.ngeom)
            if g != self.floor and model.geom_group[g] == COLLISION_GROUP
        ]
        mujoco.mj_forward(model, self.data)

    def apart(self) -> None:
        """From now on, the robot's shapes collide with the floor only (until now they also
        collided with each other, for `overlaps`)."""
        for geom in self.collisions:
            self.model.geom_contype[geom] = _ROBOT
            self.model.geom_conaffinity[geom] = _GROUND
        self.mujoco.mj_forward(self.model, self.data)

    # -- names ---------------------------------------------------------------------------

    def body(self, link: str) -> int:
        """The body id of ``link`` (-1 when it has none)."""
        return int(self.mujoco.mj_name2id(self.model, self.mujoco.mjtObj.mjOBJ_BODY, link))

    def joint(self, name: str) -> int:
        """The joint id of joint ``name`` (-1 when the model has none of that name)."""
        return int(self.mujoco.mj_name2id(self.model, self.mujoco.mjtObj.mjOBJ_JOINT, name))

    def actuator(self, joint: str) -> int:
        """The actuator id of the motor on joint ``joint`` (-1 when there is none)."""
        return int(self.mujoco.mj_name2id(self.model, self.mujoco.mjtObj.mjOBJ_ACTUATOR, joint))

    def link_of(self, geom: int) -> str:
        """The link whose shape geom ``geom`` is."""
        return self.links[int(self.model.geom_bodyid[geom])]

    # -- state ---------------------------------------------------------------------------

    @property
    def time(self) -> float:
        return float(self.data.time)

    def lowest(self) -> float:
        """The height of the lowest point of the robot's collision shapes (their bounding
        boxes, as placed now)."""
        data, model = self.data, self.model
        low = math.inf
        for g in self.collisions:
            centre, half = model.geom_aabb[g][:3], model.geom_aabb[g][3:]
            rotation = data.geom_xmat[g].reshape(3, 3)
            z = data.geom_xpos[g][2] + rotation[2] @ centre
            low = min(low, z - float(np.abs(rotation[2]) @ half))
        return low

    def lift(self, height: float) -> None:
        """Move a free-floating robot up by ``height`` (down for a negative one)."""
        model = self.model
        for joint in range(model.njnt):
            if model.jnt_type[joint] == self.mujoco.mjtJoint.mjJNT_FREE:
                self.data.qpos[model.jnt_qposadr[joint] + 2] += height
        self.mujoco.mj_forward(model, self.data)

    def broken(self) -> bool:
        """Whether the state holds a number that is infinite or not a number, or MuJoCo
        found the accelerations so (it then resets the state and warns)."""
        data = self.data
        bad = self.mujoco.mjtWarning.mjWARN_BADQACC
        finite = np.isfinite(data.qpos).all() and np.isfinite(data.qvel).all()
        return not finite or int(data.warning[bad].number) > 0

    def run(self, seconds: float, controls: dict[int, float] | None = None) -> None:
        """Step ``seconds`` of simulated time with the actuators' controls held."""
        for actuator, value in (controls or {}).items():
            self.data.ctrl[actuator] = value
        steps = max(1, round(seconds / self.model.opt.timestep))
        self.mujoco.mj_step(self.model, self.data, nstep=steps)

    def contacts(self) -> list[tuple[int, int, float]]:
        """The contacts now: each one's two geoms and how deep they overlap (m, >= 0)."""
        data = self.data
        return (
            [
                (int(c.geom1), int(c.geom2), max(-float(c.dist), 0.0))
                for c in data.contact[: data.ncon]
            ]
            if data.ncon
            else []
        )

    def floor_forces(self) -> dict[str, tuple[float, float]]:
        """The force the floor puts on each link now: (normal, tangential) in newtons."""
        mujoco, data = self.mujoco, self.data
        found: dict[str, tuple[float, float]] = {}
        force = np.zeros(6)
        for index in range(data.ncon):
            contact = data.contact[index]
            pair = (int(contact.geom1), int(contact.geom2))
            if self.floor not in pair:
                continue
            geom = pair[1] if pair[0] == self.floor else pair[0]
            mujoco.mj_contactForce(self.model, data, index, force)
            link = self.link_of(geom)
            normal, tangential = found.get(link, (0.0, 0.0))
            found[link] = (normal + abs(force[0]), tangential + math.hypot(force[1], force[2]))
        return found

    def overlaps(self) -> list[tuple[str, str, float]]:
        """The pairs of the robot's links whose collision shapes overlap now by more than a
        millimetre, with the depth (before `apart`)."""
        found: dict[tuple[str, str], float] = {}
        for one, other, depth in self.contacts():
            if self.floor in (one, other) or self._joined(one, other):
                continue
            first, second = sorted((self.link_of(one), self.link_of(other)))
            found[first, second] = max(found.get((first, second), 0.0), depth)
        return [(a, b, depth) for (a, b), depth in sorted(found.items()) if depth > 0.001]

    def _joined(self, one: int, other: int) -> bool:
        """Whether two geoms' bodies are one rigid body, or a body and its parent's, which
        MuJoCo lets overlap (but for the world's bodies, whose children it collides)."""
        model = self.model
        weld = model.body_weldid
        first, second = int(model.geom_bodyid[one]), int(model.geom_bodyid[other])
        up_first, up_second = model.body_parentid[first], model.body_parentid[second]
        return bool(
            weld[first] == weld[second]
            or weld[up_first] == weld[second]
            or weld[up_second] == weld[first]
        )

    def positions(self, joints: Sequence[int]) -> list[float]:
        """The positions of one-number joints."""
        return [float(self.data.qpos[self.model.jnt_qposadr[j]]) for j in joints]


def _round(world: ET.Element, tyres: Mapping[str, float]) -> None:
    """Make the collision cylinders and meshes of the bodies named in ``tyres`` balls of the
    radius given for each.

    A wheel rolling on a cylinder touches a floor along a line, which MuJoCo holds at its
    two ends (a mesh, at the corners of its hull): turned on the spot, the ends scrub, and
    the robot turns a fifth slower than its wheels' speeds say (tiago), where a tyre touches
    at one point. The ball touches the floor where the wheel's middle does, at its radius."""
    for body in world.iter("body"):
        radius = tyres.get(body.get("name") or "")
        if radius is None:
            continue
        for geom in body.findall("geom"):
            kind = geom.get("type")
            if kind in ("cylinder", "mesh") and geom.get("group") == str(COLLISION_GROUP):
                geom.set("type", "sphere")
                geom.set("size", repr(radius))
                geom.attrib.pop("mesh", None)
