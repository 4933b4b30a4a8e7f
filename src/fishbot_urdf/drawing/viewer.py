"""The robot in a web browser, as RViz with joint_state_publisher_gui shows it: visuals in
their colours, collision shapes on a toggle, every link's frame as axes, one slider per
moving joint within its limits (mimic joints follow), reloaded when the robot's files change.

Built on viser (``pip install 'fishbot-urdf[view]'``), a maintained web 3D viewer that
serves its page and talks to it over a websocket. `Viewer` owns one viser server; the
library never prints: the caller shows the URL, and what is refused from the page is logged
(a warning of the ``fishbot_urdf.drawing.viewer`` logger, one line each).

Only the viewer's own page may talk to it: an HTTP request or websocket whose ``Host``, or
``Origin`` when it has one, is not the address served on gets 403 (another site open in the
same browser, or one that points its name at this machine, reaches nothing), and a value a
control sends is used only when it is one that control can hold.
"""

from __future__ import annotations

import contextvars
import logging
import math
import os
import threading
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from ..catalog.meshes import NOTHING_DRAWN
from ..diagnostics import Diagnostic, Severity
from ..errors import ArgumentError, UnknownNameError
from ..inputs import max_seconds, time_limit
from ..kinematics import Kinematics
from ..model import JointType
from ..spatial import quaternion
from ._serving import ServeError, authority, control_id, serve, shown
from .scene import Scene, build_scene

__all__ = ["ServeError", "Viewer"]

_log = logging.getLogger(__name__)

_SLACK = 1e-9  # a slider's end, reached in steps of (high - low) / 1000, may miss by a rounding


class Viewer:
    """A viser server showing one robot file, kept in step with its files.

    Each (re)load runs within the limits in force where the viewer is made (see
    :mod:`fishbot_urdf.inputs`: the size limit, trusted expressions, and a time limit that
    starts again for each load).

    Args:
        load: Reads the robot: returns (analysis, the files it was read from). Called again
            when one of those files changes.
        host, port: Where to serve (port 0: any free port; a port in use: the next free one).
        packages: Folders of ROS packages, for ``package://`` meshes.

    Raises:
        ServeError: ``host`` and ``port`` cannot be served on.
        ToolError: viser is of a version whose requests the viewer cannot check.
        FishbotUrdfError: The first load failed (whatever ``load`` raises); the server is
            stopped and its port free again.
    """

    def __init__(
        self,
        load: Callable[[], tuple[Any, Sequence[str]]],
        *,
        host: str = "127.0.0.1",
        port: int = 8080,
        packages: Mapping[str, str | Path] | None = None,
    ) -> None:
        self._load = load
        self._context = contextvars.copy_context()
        self._packages = dict(packages or {})
        self._lock = threading.RLock()
        self.values: dict[str, float] = {}  # slider values by variable, kept over reloads
        self._sliders: dict[str, Any] = {}
        self._ranges: dict[str, tuple[float, float]] = {}
        self._turns: frozenset[str] = frozenset()  # continuous joints: an angle wraps round
        self._inputs: dict[str, _Input] = {}  # the page's controls by viser's id
        self._frames: dict[str, Any] = {}
        self._collisions: list[Any] = []
        self._nodes: list[Any] = []
        self._stamps: dict[str, float] = {}
        self._stop = threading.Event()
        self.reloads = 0
        # What the scene could not draw as it is, with rules and places (the last load's).
        self.findings: tuple[Diagnostic, ...] = ()
        self.server = serve(host, port, self._accepts)
        try:
            gui = self.server.gui
            self._show_collision = gui.add_checkbox("Collision shapes", initial_value=False)
            self._show_collision.on_update(lambda _: self._toggle())
            self._show_frames = gui.add_checkbox("Link frames", initial_value=True)
            self._show_frames.on_update(lambda _: self._toggle())
            self._switches = {
                control_id(self._show_collision): _Input("Collision shapes", toggle=True),
                control_id(self._show_frames): _Input("Link frames", toggle=True),
            }
            self._inputs = dict(self._switches)
            self.reload()
        except BaseException:
            self.server.stop()  # joins its thread: the port is free again
            raise
        self._watcher = threading.Thread(target=self._watch, daemon=True)
        self._watcher.start()

    @property
    def warnings(self) -> tuple[str, ...]:
        """The findings' messages (deprecated: read ``findings``, which have their rule and
        place)."""
        warnings.warn(
            "Viewer.warnings is deprecated: read Viewer.findings", DeprecationWarning, stacklevel=2
        )
        return tuple(finding.message for finding in self.findings)

    @property
    def url(self) -> str:
        """Where the page is served."""
        host = self.server.get_host()
        name = "localhost" if host in ("0.0.0.0", "127.0.0.1", "::", "") else host
        return f"http://{authority(name, self.server.get_port())}"

    def close(self) -> None:
        """Stop watching the files and stop the server."""
        self._stop.set()
        self.server.stop()

    # -- building -------------------------------------------------------------------------
    def reload(self) -> None:
        """Read the robot again and rebuild the scene and the sliders (slider values of
        joints that are still there are kept)."""
        self._context.copy().run(self._reload)

    def _reload(self) -> None:
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        with self._lock, time_limit(max_seconds()):
            analysis, files = self._load()
            kinematics = Kinematics(analysis)
            visual = build_scene(analysis, collision=False, packages=self._packages)
            collision = build_scene(analysis, collision=True, packages=self._packages)
            for node in self._nodes:
                node.remove()
            for slider in self._sliders.values():
                slider.remove()
            self._nodes, self._collisions, self._frames, self._sliders = [], [], {}, {}
            self._kinematics = kinematics
            scale = _frame_size(np, visual)
            for link in kinematics.links:
                frame = self.server.scene.add_frame(
                    _node(link),
                    show_axes=self._show_frames.value,
                    axes_length=scale,
                    axes_radius=scale / 20,
                )
                self._frames[link] = frame
                self._nodes.append(frame)  # removing a frame removes what hangs below it
            for kind, scene in (("visual", visual), ("collision", collision)):
                for index, part in enumerate(scene.parts):
                    count = len(part.local)
                    mesh = self.server.scene.add_mesh_simple(
                        f"{_node(part.link)}/{kind}_{index}",
                        part.local.reshape(-1, 3).astype(np.float32),
                        np.arange(3 * count, dtype=np.uint32).reshape(-1, 3),
                        color=tuple(round(255 * c) for c in part.color[:3]),
                        opacity=part.color[3] if part.color[3] < 1.0 else None,
                        side="double",
                        flat_shading=True,
                        visible=kind == "visual" or self._show_collision.value,
                    )
                    if kind == "collision":
                        self._collisions.append(mesh)
            self.findings = _viewed(visual, collision)
            if not self.reloads:  # frame the robot, from the front left and above
                corner, far_corner = visual.bounds()
                centre = (corner + far_corner) / 2
                size = float(max(np.max(far_corner - corner), 0.05))
                eye = np.array([1.0, 0.75, 0.65]) / np.linalg.norm([1.0, 0.75, 0.65])
                camera = self.server.initial_camera
                camera.up = (0.0, 0.0, 1.0)
                camera.look_at = tuple(float(c) for c in centre)
                camera.position = tuple(float(c) for c in centre + 2.2 * size * eye)
                camera.near, camera.far = size / 100, size * 100
            ranges = {name: _range(analysis, name) for name in kinematics.variables}
            inputs = dict(self._switches)
            for name, (low, high) in ranges.items():
                value = float(min(max(self.values.get(name, 0.0), low), high))
                self.values[name] = value
                slider = self.server.gui.add_slider(
                    name, min=low, max=high, step=(high - low) / 1000, initial_value=value
                )
                slider.on_update(lambda event, name=name: self._moved(name, event.target.value))
                self._sliders[name] = slider
                inputs[control_id(slider)] = _Input(name, low, high)
            self._ranges = ranges
            self._turns = frozenset(
                name
                for name in kinematics.variables
                if (joint := analysis.joints.get(name)) is not None
                and joint.type is JointType.CONTINUOUS
            )
            self._inputs = inputs  # one assignment: the server's thread reads it
            self._stamps = {f: _stamp(f) for f in files}
            self._pose()

    def set(self, name: str, value: float) -> None:
        """Move joint variable ``name`` (as its slider would) to ``value`` (radians or
        metres; a continuous joint's angle is taken round to -pi .. pi).

        Raises:
            UnknownNameError: ``name`` is no joint variable.
            ArgumentError: ``value`` is not a finite number within the slider's range (the
                joint's limits, where it has them).
        """
        with self._lock:
            if name not in self._ranges:
                raise UnknownNameError("joint", name, self._ranges)
            low, high = self._ranges[name]
            if _position(value, -math.inf, math.inf) is None:
                raise ArgumentError(
                    f"joint {name!r}: position {shown.repr(value)} is not a finite number",
                    name=name,
                )
            if name in self._turns:
                value = math.remainder(value, 2 * math.pi)
            position = _position(value, low, high)
            if position is None:
                raise ArgumentError(
                    f"joint {name!r}: position {value:g} is outside its range {low:g} .. {high:g}",
                    name=name,
                )
            self._sliders[name].value = position  # viser calls on_update, which poses
            self._moved(name, position)  # (a value the slider already had calls nothing)

    def _moved(self, name: str, value: Any) -> None:
        """A slider moved (on viser's threads: never raises)."""
        with self._lock:
            limits = self._ranges.get(name)
            if limits is None:
                return  # a slider of the robot before a reload
            position = _position(value, *limits)
            if position is None:
                _dropped(name, value, *limits)
                return
            self.values[name] = position
            self._pose()

    def _accepts(self, message: Any) -> bool:
        """Whether a change the page sent may reach viser: a known control's value, one that
        control can hold (called on the server's thread, before viser looks at it)."""
        uuid, updates = getattr(message, "uuid", None), getattr(message, "updates", None)
        control = self._inputs.get(uuid) if isinstance(uuid, str) else None
        if control is None:
            _log.debug("dropped a change to a control the viewer does not have: %r", uuid)
            return False
        if not isinstance(updates, dict) or set(updates) != {"value"}:
            keys = sorted(map(str, updates)) if isinstance(updates, dict) else updates
            _log.warning(
                "%s: dropped a change sent by the page that is not of its value alone: %s",
                control.title,
                shown.repr(keys),
            )
            return False
        value = updates["value"]
        if control.toggle:
            if type(value) is bool:
                return True
            _log.warning(
                "%s: dropped %s sent by the page (not true or false)",
                control.title,
                shown.repr(value),
            )
            return False
        if _position(value, control.low, control.high) is None:
            _dropped(control.label, value, control.low, control.high)
            return False
        return True

    def _pose(self) -> None:
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        kinematics = self._kinematics
        q = np.array([self.values.get(v, 0.0) for v in kinematics.variables])
        poses = kinematics.forward(q)
        with self.server.atomic():
            for index, link in enumerate(kinematics.links):
                frame = self._frames[link]
                frame.position = poses[index, :3, 3]
                frame.wxyz = _wxyz(poses[index, :3, :3])

    def _toggle(self) -> None:
        with self._lock:
            for mesh in self._collisions:
                mesh.visible = self._show_collision.value
            for frame in self._frames.values():
                frame.show_axes = self._show_frames.value

    # -- watching -------------------------------------------------------------------------
    def _watch(self) -> None:
        while not self._stop.wait(0.3):
            changed = any(_stamp(f) != stamp for f, stamp in self._stamps.items())
            if not changed:
                continue
            try:
                self.reload()
            except Exception as exc:  # the page keeps the robot loaded last
                _log.warning("the robot could not be read again: %s", exc)
                self._stamps = {f: _stamp(f) for f in self._stamps}
            else:
                self.reloads += 1


@dataclass(frozen=True, slots=True)
class _Input:
    """A control on the page: a joint's slider (``low`` .. ``high``), or, with ``toggle``,
    a checkbox."""

    label: str
    low: float = 0.0
    high: float = 0.0
    toggle: bool = False

    @property
    def title(self) -> str:
        """How a log line names it."""
        return f"{'checkbox' if self.toggle else 'joint'} {self.label!r}"


def _position(value: Any, low: float, high: float) -> float | None:
    """``value`` as a slider's position: a finite number (no bool, no text such as "nan")
    within ``low`` .. ``high`` (less a rounding error, taken in), else None."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    try:
        number = float(value)
    except OverflowError:  # an int beyond any float
        return None
    if not (math.isfinite(number) and low - _SLACK <= number <= high + _SLACK):
        return None
    return min(max(number, low), high)


def _dropped(label: str, value: Any, low: float, high: float) -> None:
    _log.warning(
        "joint %r: dropped %s sent by the page (not a number within %g .. %g)",
        label,
        shown.repr(value),
        low,
        high,
    )


def _stamp(path: str) -> float:
    try:
        return os.stat(path).st_mtime_ns
    except OSError:
        return -1.0


def _node(link: str) -> str:
    """A viser scene path for a link (``/`` would nest it)."""
    return "/robot/" + link.replace("/", "_")


def _range(analysis: Any, variable: str) -> tuple[float, float]:
    """A slider's range: the joint's limits, else a turn each way (or a metre, sliding)."""
    joint = analysis.joints.get(variable)
    if (
        joint is not None
        and joint.limit is not None
        and joint.type
        in (
            JointType.REVOLUTE,
            JointType.PRISMATIC,
        )
        and joint.limit.lower < joint.limit.upper
    ):
        return joint.limit.lower, joint.limit.upper
    if joint is not None and joint.type is JointType.PRISMATIC:
        return -1.0, 1.0
    part = variable.rsplit(".", 1)[-1]
    return (-1.0, 1.0) if part in ("x", "y", "z") else (-math.pi, math.pi)


def _viewed(visual: Scene, collision: Scene) -> tuple[Diagnostic, ...]:
    """What the page cannot show as it is, once each: a robot with no visual shape to draw
    still shows its link frames (a warning here), and one without collision shapes has
    nothing on their toggle (no finding)."""
    found = [
        replace(f, severity=Severity.WARNING) if f.rule == NOTHING_DRAWN.id else f
        for f in visual.findings
    ]
    found += [f for f in collision.findings if f.rule != NOTHING_DRAWN.id]
    return tuple(dict.fromkeys(found))


def _frame_size(np: Any, scene: Any) -> float:
    low, high = scene.bounds()
    return float(max(np.max(high - low), 0.05)) / 8


def _wxyz(m: Any) -> tuple[float, float, float, float]:
    """A rotation matrix as viser's unit quaternion (w, x, y, z)."""
    x, y, z, w = quaternion(m)
    return (w, x, y, z)
