"""The robot in a web browser, as RViz with joint_state_publisher_gui shows it: visuals in
their colours, and on toggles the collision shapes, each link's mass and inertia as RViz's
"Mass Properties" show them (`fishbot_urdf.drawing.scene`), its frame as axes, and what
Gazebo will simulate: its sensors' rays and frustums, its links as sdformat lumps them; one slider
per moving joint within its limits (mimic joints follow), from the root outwards; reloaded
when the robot's files change.

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
from pathlib import Path
from typing import Any

from ..diagnostics import Diagnostic
from ..errors import ArgumentError, FishbotUrdfError, UnknownNameError
from ..inputs import max_seconds, time_limit
from ..kinematics import Kinematics
from ..kinematics.positions import check_value
from ..model import JointType
from ..spatial import quaternion
from ._camera import aim, corners, framing
from ._controls import Input as _Input
from ._controls import dropped as _dropped
from ._controls import position as _position
from ._controls import slider_range
from ._glb import glb
from ._lumping import notes
from ._notes import failure_note, findings_of, viewed
from ._sensors import LIDAR
from ._serving import ServeError, authority, control_id, script, serve, shown
from .scene import Scene, build_scene, in_gazebo_colours

__all__ = ["TOGGLES", "ServeError", "Viewer"]

_log = logging.getLogger(__name__)
_LINE_WIDTH = 2.0  # pixels: a sensor's rays and a frustum's edges (their thin boxes drawn by
# the browser's software renderer took a minute a frame where the rays pass the camera)

TOGGLES = {
    "visual": "Visual",
    "collision": "Collision shapes",
    "mass": "Mass",
    "inertia": "Inertia",
    "frames": "Link frames",
    "sensors": "Sensors",
    "gazebo": "Gazebo: lumped links",
}
"""The page's checkboxes, by the scene's layer each shows: the visuals and the link frames
start ticked. Mass and Inertia are RViz's "Mass Properties" (a ball of lead of the link's
mass, the box of its inertia, both red); untick Visual to see them inside the robot.
Sensors are the Gazebo lidars' rays and cameras' frustums; "Gazebo: lumped links" shows
the visuals in one colour per link of the Gazebo model (in place of their own colours),
each link lumped into another or left out labelled so."""


class Viewer:
    """A viser server showing one robot file, kept in step with its files.

    Each (re)load runs within the limits in force where the viewer is made (see
    :mod:`fishbot_urdf.inputs`: the size limit, trusted expressions, and a time limit that
    starts again for each load).

    A load that fails (``load`` raises a FishbotUrdfError: a `RobotError` with the robot's
    errors, or the error that stopped the reading) leaves the robot read last on the page,
    with the failure's findings shown above the controls until a load succeeds; the
    viewer keeps watching the files of the last good load, those in ``watch`` and those the
    failure names.

    Args:
        load: Reads the robot: returns (analysis, the files it was read from). Called again
            when one of those files changes.
        host, port: Where to serve (port 0: any free port; a port in use: the next free one).
        packages: Folders of ROS packages, for ``package://`` meshes.
        watch: Files to watch whatever a load gives (the robot's own file).
        wait: Whether a first load that fails with this error waits for a fix (the page
            shows the error, and the robot once a load succeeds) rather than raise it;
            None: never.
        report: Called after every load the viewer makes on its own (after an edit, and
            a first load that waits) with the error that stopped it, or None when the
            robot is shown; on the thread that watches the files.
        live: The links are posed by something else (a simulation, through `place`): no
            joint sliders, and no lidar fans of the robot's description (the live scans
            are drawn in their place).

    Raises:
        ServeError: ``host`` and ``port`` cannot be served on.
        ToolError: viser is of a version whose requests the viewer cannot check.
        FishbotUrdfError: The first load failed (whatever ``load`` raises) and ``wait`` does
            not wait for it; the server is stopped and its port free again.
    """

    def __init__(
        self,
        load: Callable[[], tuple[Any, Sequence[str]]],
        *,
        host: str = "127.0.0.1",
        port: int = 8080,
        packages: Mapping[str, str | Path] | None = None,
        watch: Sequence[str] = (),
        wait: Callable[[FishbotUrdfError], bool] | None = None,
        report: Callable[[FishbotUrdfError | None], None] | None = None,
        live: bool = False,
    ) -> None:
        self._load = load
        self.live = live
        self._watched = tuple(watch)
        self._report = report
        self._points: Any = None  # the robot's, framed by the first load that succeeds
        # The error of the last load, shown on the page; None while the robot is shown.
        self.error: FishbotUrdfError | None = None
        self._context = contextvars.copy_context()
        self._packages = dict(packages or {})
        self._lock = threading.RLock()
        self.values: dict[str, float] = {}  # slider values by variable, kept over reloads
        self._sliders: dict[str, Any] = {}
        self._ranges: dict[str, tuple[float, float]] = {}
        self._turns: frozenset[str] = frozenset()  # continuous joints: an angle wraps round
        self._inputs: dict[str, _Input] = {}  # the page's controls by viser's id
        self._frames: dict[str, Any] = {}
        self._shown: dict[str, list[Any]] = {}  # the page's meshes by layer
        self._nodes: list[Any] = []
        self._stamps: dict[str, float] = {}
        self._stop = threading.Event()
        self.reloads = 0
        # What the scene could not draw as it is, with rules and places (the last load's):
        # its shapes, and its links' mass and inertia marks.
        self.findings: tuple[Diagnostic, ...] = ()
        self.server = serve(host, port, self._accepts)
        try:
            gui = self.server.gui
            self._toggles = {
                layer: gui.add_checkbox(label, initial_value=layer in ("visual", "frames"))
                for layer, label in TOGGLES.items()
            }
            for toggle in self._toggles.values():
                toggle.on_update(lambda _: self._toggle())
            self._switches = {
                control_id(self._toggles[layer]): _Input(label, toggle=True)
                for layer, label in TOGGLES.items()
            }
            self._inputs = dict(self._switches)
            self._trouble = gui.add_markdown("", order=-1.0, visible=False)
            self.server.on_client_connect(self._greet)
            try:
                self.reload()
            except FishbotUrdfError as exc:
                if wait is None or not wait(exc):
                    raise
                self._failed(exc)
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
        """Stop watching the files and stop the server (once a reload under way is done:
        it would tell the page a server stopped under it)."""
        self._stop.set()
        watcher = getattr(self, "_watcher", None)  # (none yet, if the first load failed)
        if watcher is not None and watcher is not threading.current_thread():
            watcher.join()
        self.server.stop()

    # -- building -------------------------------------------------------------------------
    def reload(self) -> None:
        """Read the robot again and rebuild the scene and the sliders (slider values of
        joints that are still there are kept)."""
        self._context.copy().run(self._reload)

    def _reload(self) -> None:
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        live = self.live
        with self._lock, time_limit(max_seconds()):
            analysis, files = self._load()
            kinematics = Kinematics(analysis)
            visual = build_scene(analysis, packages=self._packages)
            collision = build_scene(analysis, collision=True, packages=self._packages)
            marks = build_scene(analysis, show=("mass", "inertia"), packages=self._packages)
            # (no sensor is no finding, for a toggle: nothing-drawn is left unsaid)
            sensors = build_scene(analysis, show=("sensors",), packages=self._packages)
            gazebo = in_gazebo_colours(analysis, visual.parts)  # the visuals, recoloured
            for node in self._nodes:
                node.remove()
            for slider in self._sliders.values():
                slider.remove()
            self._nodes, self._frames, self._sliders = [], {}, {}
            self._shown = {layer: [] for layer in TOGGLES}
            self._kinematics = kinematics
            length = visual.axes_length if visual.parts else collision.axes_length
            for link in kinematics.links:
                frame = self.server.scene.add_frame(
                    _node(link),
                    show_axes=self._toggles["frames"].value,
                    axes_length=length,
                    axes_radius=length / 20,
                )
                self._frames[link] = frame
                self._nodes.append(frame)  # removing a frame removes what hangs below it
            drawn = [p for p in sensors.parts if not (live and p.color == LIDAR)]
            for parts in (visual.parts, collision.parts, marks.parts, drawn, gazebo):
                for index, part in enumerate(parts):
                    mesh = self._mesh(
                        np,
                        f"{_node(part.link)}/{part.layer}_{index}",
                        part,
                        visible=self._visible(part.layer),
                    )
                    self._shown[part.layer].append(mesh)
            for link, note in notes(analysis.gazebo_lumping).items():
                if link in self._frames:
                    label = self.server.scene.add_label(
                        f"{_node(link)}/gazebo_note", note, visible=self._visible("gazebo")
                    )
                    self._shown["gazebo"].append(label)
            self.findings = viewed(visual, collision, marks)
            if self._points is None:
                self._frame(np, (visual, collision, marks), length)
            ranges = {
                name: slider_range(analysis, name)
                for name in ([] if self.live else analysis.plan.outwards())
            }
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
            self._stamps = {f: _stamp(f) for f in (*files, *self._watched)}
            self._pose()
            self.error = None
            self._trouble.visible = False

    def _mesh(self, np: Any, name: str, part: Any, *, visible: bool) -> Any:
        """A part on the page: a transparent one as a GLB file, which three.js blends
        without hiding what is behind or inside it (see `fishbot_urdf.drawing._glb`)."""
        red, green, blue, alpha = part.color
        rgb = (round(255 * red), round(255 * green), round(255 * blue))
        if part.lines is not None:  # lines a pixel or two wide, however near: as RViz draws
            return self.server.scene.add_line_segments(
                name,
                part.lines.astype(np.float32),
                rgb,
                thickness=_LINE_WIDTH,
                thickness_units="screen",
                visible=visible,
            )
        if alpha < 1.0:
            return self.server.scene.add_glb(name, glb(np, part.local, part.color), visible=visible)
        count = len(part.local)
        return self.server.scene.add_mesh_simple(
            name,
            part.local.reshape(-1, 3).astype(np.float32),
            np.arange(3 * count, dtype=np.uint32).reshape(-1, 3),
            color=rgb,
            side="double",
            flat_shading=True,
            visible=visible,
        )

    def _frame(self, np: Any, scenes: Sequence[Scene], axes: float) -> None:
        """Point the camera at the robot: the pages open already too (the robot was not
        there to be seen before), each framed for its own view's width. What is framed is
        the box around the robot: its visual and collision shapes, its links' mass and inertia
        marks (an inertial written far from its part is in view when ticked), and its link
        frames' axes (``axes`` long), whatever is toggled on."""
        parts = [part.triangles.reshape(-1, 3) for scene in scenes for part in scene.parts]
        poses = np.array(list(scenes[0].poses.values())).reshape(-1, 4, 4)
        origins = poses[:, :3, 3]
        tips = origins[:, None, :] + axes * poses[:, :3, :3].transpose(0, 2, 1)  # x, y, z
        every = np.concatenate([*parts, origins, tips.reshape(-1, 3)])
        self._points = corners(np, every).astype(np.float32)
        aim(self.server.initial_camera, framing(np, self._points))  # for a square view
        for client in self.server.get_clients().values():
            self._greet(client)

    def _greet(self, client: Any) -> None:
        """Frame the robot in a page that opens (viser has its view's size by then)."""
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        with self._lock:
            if self._points is not None:
                aim(client.camera, framing(np, self._points, client.camera.aspect))

    def _failed(self, exc: FishbotUrdfError) -> None:
        """Show a load's error on the page (the robot read last stays), and watch the files
        it names too."""
        found = findings_of(exc)
        named = [f.path for f in found if f.path and os.path.isfile(f.path)]
        with self._lock:
            self.error = exc
            self._stamps = {f: _stamp(f) for f in (*self._stamps, *self._watched, *named)}
            self._trouble.content = failure_note(found, shown=bool(self._frames))
            self._trouble.visible = True
        if self._report is not None:
            self._report(exc)

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
            value = check_value(None, name, value)  # a number: the slider holds its range
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
        if control.button:
            if value is True:
                return True
            _log.warning(
                "%s: dropped %s sent by the page (not a press)", control.title, shown.repr(value)
            )
            return False
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

        if not self._frames:
            return  # no robot read yet
        kinematics = self._kinematics
        q = np.array([self.values.get(v, 0.0) for v in kinematics.variables])
        poses = kinematics.forward(q)
        with self.server.atomic():
            for index, link in enumerate(kinematics.links):
                frame = self._frames[link]
                frame.position = poses[index, :3, 3]
                frame.wxyz = _wxyz(poses[index, :3, :3])

    def place(self, poses: Mapping[str, tuple[Sequence[float], Sequence[float]]]) -> None:
        """Put links where ``poses`` says (in the world: position in metres, orientation as a
        unit quaternion w, x, y, z), as a simulation moves them; links not named stay."""
        with self._lock, self.server.atomic():
            for link, (position, wxyz) in poses.items():
                frame = self._frames.get(link)
                if frame is not None:
                    frame.position = tuple(position)
                    frame.wxyz = tuple(wxyz)

    def showing(self, layer: str) -> bool:
        """Whether the page shows ``layer`` (one of `TOGGLES`) now."""
        return self._visible(layer)

    def on_toggle(self, call: Callable[[], None]) -> None:
        """Call ``call`` (on viser's thread) whenever a checkbox changes."""
        for toggle in self._toggles.values():
            toggle.on_update(lambda _: call())

    def add_button(self, label: str, press: Callable[[], None]) -> str:
        """A button below the checkboxes that calls ``press`` (on viser's thread) when
        pressed; the id of its element on the page (for a script to press it)."""
        button = self.server.gui.add_button(label)
        button.on_click(lambda _: press())
        uuid = control_id(button)
        with self._lock:
            self._switches[uuid] = _Input(label, button=True)
            self._inputs = {**self._inputs, uuid: self._switches[uuid]}
        return uuid

    def run_script(self, source: str) -> None:
        """Run the JavaScript ``source`` in every page, open now or later.

        Raises:
            ToolError: viser is of a version that cannot be sent a script.
        """
        script(self.server, source)

    def _visible(self, layer: str) -> bool:
        """Whether a layer's parts show: the visuals give way to their Gazebo colours."""
        if layer == "visual" and self._toggles["gazebo"].value:
            return False
        return bool(self._toggles[layer].value)

    def _toggle(self) -> None:
        with self._lock:
            for layer, meshes in self._shown.items():
                for mesh in meshes:
                    mesh.visible = self._visible(layer)
            for frame in self._frames.values():
                frame.show_axes = self._toggles["frames"].value

    # -- watching -------------------------------------------------------------------------
    def _watch(self) -> None:
        while not self._stop.wait(0.3):
            changed = any(_stamp(f) != stamp for f, stamp in self._stamps.items())
            if not changed:
                continue
            try:
                self.reload()
            except FishbotUrdfError as exc:  # the page keeps the robot loaded last
                self._failed(exc)
            except Exception as exc:  # a fault of the viewer's: said, and watched again
                _log.warning("the robot could not be read again: %s", exc)
                self._stamps = {f: _stamp(f) for f in self._stamps}
            else:
                self.reloads += 1
                if self._report is not None:
                    self._report(None)


def _stamp(path: str) -> float:
    try:
        return os.stat(path).st_mtime_ns
    except OSError:
        return -1.0


def _node(link: str) -> str:
    """A viser scene path for a link (``/`` would nest it)."""
    return "/robot/" + link.replace("/", "_")


def _wxyz(m: Any) -> tuple[float, float, float, float]:
    """A rotation matrix as viser's unit quaternion (w, x, y, z)."""
    x, y, z, w = quaternion(m)
    return (w, x, y, z)
