"""The robot in a web browser, as RViz with joint_state_publisher_gui shows it: visuals in
their colours, collision shapes on a toggle, every link's frame as axes, one slider per
moving joint within its limits (mimic joints follow), reloaded when the robot's files change.

Built on viser (``pip install 'fishbot-urdf[view]'``), a maintained web 3D viewer that
serves its page and talks to it over a websocket. `Viewer` owns one viser server; the
library never prints: the caller shows the URL.
"""

from __future__ import annotations

import math
import os
import threading
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from .errors import ToolNotFoundError

__all__ = ["Viewer"]


def _viser() -> Any:
    try:
        import viser
    except ImportError:
        raise ToolNotFoundError(
            "fishbot view needs the viser package",
            tool="viser",
            hint="pip install 'fishbot-urdf[view]'",
        ) from None
    return viser


class Viewer:
    """A viser server showing one robot file, kept in step with its files.

    Args:
        load: Reads the robot: returns (analysis, the files it was read from). Called again
            when one of those files changes.
        host, port: Where to serve (port 0: any free port).
        packages: Folders of ROS packages, for ``package://`` meshes.
    """

    def __init__(
        self,
        load: Callable[[], tuple[Any, Sequence[str]]],
        *,
        host: str = "127.0.0.1",
        port: int = 8080,
        packages: Mapping[str, str | Path] | None = None,
    ) -> None:
        viser = _viser()
        self._load = load
        self._packages = dict(packages or {})
        self._lock = threading.RLock()
        self.server = viser.ViserServer(host=host, port=port, verbose=False)
        self.values: dict[str, float] = {}  # slider values by variable, kept over reloads
        self._sliders: dict[str, Any] = {}
        self._frames: dict[str, Any] = {}
        self._collisions: list[Any] = []
        self._nodes: list[Any] = []
        self._stamps: dict[str, float] = {}
        self._stop = threading.Event()
        self.reloads = 0
        self.warnings: tuple[str, ...] = ()
        gui = self.server.gui
        self._show_collision = gui.add_checkbox("Collision shapes", initial_value=False)
        self._show_collision.on_update(lambda _: self._toggle())
        self._show_frames = gui.add_checkbox("Link frames", initial_value=True)
        self._show_frames.on_update(lambda _: self._toggle())
        self.reload()
        self._watcher = threading.Thread(target=self._watch, daemon=True)
        self._watcher.start()

    @property
    def url(self) -> str:
        """Where the page is served."""
        host = self.server.get_host()
        shown = "localhost" if host in ("0.0.0.0", "127.0.0.1", "::") else host
        return f"http://{shown}:{self.server.get_port()}"

    def close(self) -> None:
        """Stop watching the files and stop the server."""
        self._stop.set()
        self.server.stop()

    # -- building -------------------------------------------------------------------------
    def reload(self) -> None:
        """Read the robot again and rebuild the scene and the sliders (slider values of
        joints that are still there are kept)."""
        import numpy as np

        from .kinematics import Kinematics
        from .scene import build_scene

        with self._lock:
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
            self.warnings = tuple(dict.fromkeys((*visual.warnings, *collision.warnings)))
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
            for name in kinematics.variables:
                low, high = _range(analysis, name)
                value = float(min(max(self.values.get(name, 0.0), low), high))
                self.values[name] = value
                slider = self.server.gui.add_slider(
                    name, min=low, max=high, step=(high - low) / 1000, initial_value=value
                )
                slider.on_update(lambda event, name=name: self._moved(name, event.target.value))
                self._sliders[name] = slider
            self._stamps = {f: _stamp(f) for f in files}
            self._pose()

    def set(self, name: str, value: float) -> None:
        """Move joint variable ``name`` (as its slider would)."""
        self._sliders[name].value = value  # viser calls on_update, which poses the robot
        self._moved(name, value)

    def _moved(self, name: str, value: float) -> None:
        with self._lock:
            self.values[name] = float(value)
            self._pose()

    def _pose(self) -> None:
        import numpy as np

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
            except Exception as exc:
                self.warnings = (f"the robot could not be read again: {exc}",)
                self._stamps = {f: _stamp(f) for f in self._stamps}
            else:
                self.reloads += 1


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
    from .model import JointType

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


def _frame_size(np: Any, scene: Any) -> float:
    low, high = scene.bounds()
    return float(max(np.max(high - low), 0.05)) / 8


def _wxyz(m: Any) -> tuple[float, float, float, float]:
    """A rotation matrix as viser's unit quaternion (w, x, y, z)."""
    from .spatial import quaternion

    x, y, z, w = quaternion(m)
    return (w, x, y, z)
