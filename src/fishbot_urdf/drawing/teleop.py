"""A robot driven from the viewer's page, as a learner drives it in Gazebo with a teleop
keyboard: the arrow keys (or the buttons they press) step the speed and the turn rate,
space or ``k`` stops; the page shows the robot where its simulation has it, on a ground
grid among the world's walls, with each lidar's latest scan as rays to what they hit.

The page's keys reach the server through its buttons: viser tells the server nothing of
the keys pressed in its page (its own key handling only moves the camera), so a small
script sent to the page presses the button of each key (`Viewer.run_script`), and the
press travels as any button's does, through the viewer's checks of what the page sends.
The script takes the arrow keys from viser's camera, which turns with them otherwise.

The simulation is anything with the `Source` calls (`fishbot_urdf.simulation` gives one):
this module steps it in real time and draws what it reads.
"""

from __future__ import annotations

import json
import logging
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from typing import Any, Protocol

from ._sensors import LIDAR
from .viewer import _LINE_WIDTH, Viewer

__all__ = ["KEYS", "MAX_SPEED", "MAX_TURN", "SPEED_STEP", "TURN_STEP", "Source", "Teleop"]

_log = logging.getLogger("fishbot_urdf.drawing.viewer")  # the viewer's one channel

SPEED_STEP = 0.1
"""How much one press of Up or Down changes the speed (m/s)."""
TURN_STEP = 0.5
"""How much one press of Left or Right changes the turn rate (rad/s)."""
MAX_SPEED, MAX_TURN = 1.0, 3.0
"""The most speed (m/s) and turn rate (rad/s) the keys give, either way."""
FPS = 30.0
"""How often the page is sent the robot's pose (Hz); the lidars' rays at their own rate."""
_LONGEST = 0.1
"""The most simulated time one frame steps (s): a slow machine runs behind real time rather
than in ever longer steps."""
_STILL = 1e-5
"""How far a link must move (m, or in a quaternion's parts) for its new pose to be sent: a
hundredth of a millimetre, a thousandth of a degree, well under a pixel."""
_WALL = (170, 170, 170)

KEYS = {
    "up": ("Faster (Up)", ("ArrowUp",)),
    "down": ("Slower (Down)", ("ArrowDown",)),
    "left": ("Left (Left)", ("ArrowLeft",)),
    "right": ("Right (Right)", ("ArrowRight",)),
    "stop": ("Stop (space, k)", (" ", "k", "K")),
}
"""The page's buttons, and the keys (``KeyboardEvent.key``) that press each."""

_SCRIPT = """(() => {
  const keys = %s;
  const typing = (e) => e && (e.tagName === "TEXTAREA" || e.isContentEditable ||
    (e.tagName === "INPUT" && !["checkbox", "radio", "button"].includes(e.type)));
  window.addEventListener("keydown", (event) => {
    const id = keys[event.key];
    if (id === undefined || typing(event.target) || event.ctrlKey || event.metaKey) return;
    event.preventDefault();
    event.stopImmediatePropagation();
    const button = document.getElementById(id);
    if (button !== null) button.click();
  }, true);
  window.addEventListener("keyup", (event) => {
    if (keys[event.key] !== undefined && !typing(event.target)) event.stopImmediatePropagation();
  }, true);
})();"""


class Source(Protocol):
    """A simulation the page can drive and show."""

    def command(self, speed: float, turn: float) -> None:
        """Drive at ``speed`` (m/s) and ``turn`` (rad/s, to the left)."""

    def advance(self, seconds: float) -> None:
        """Step ``seconds`` of simulated time."""

    def poses(self) -> Mapping[str, tuple[Sequence[float], Sequence[float]]]:
        """Each link's position (m) and orientation (w, x, y, z) in the world."""

    def scans(self) -> Sequence[Any]:
        """Each lidar's latest scan: ``sensor``, ``time``, ``origin`` and ``ends`` (N, 3)."""

    @property
    def exploded(self) -> float | None:
        """When the simulation blew up (s of simulated time), if it did."""


class Teleop:
    """``source`` on ``viewer``'s page (a `Viewer` made with ``live=True``), stepped in real
    time and driven by the page's keys and buttons until `close`.

    Args:
        viewer: The page.
        source: The simulation.
        obstacles: Boxes to draw in the world: each with ``centre`` and ``size`` (m).
        ground: How wide the ground grid is (m).

    Raises:
        ToolError: viser is of a version that cannot be sent the keys' script.
    """

    def __init__(
        self,
        viewer: Viewer,
        source: Source,
        *,
        obstacles: Sequence[Any] = (),
        ground: float = 4.0,
    ) -> None:
        self.viewer, self.source = viewer, source
        self.speed, self.turn = 0.0, 0.0
        self.frames = 0  # the poses sent to the page so far
        self._lock = threading.Lock()
        self._drawn: dict[str, float] = {}
        self._rays: dict[str, Any] = {}
        self._broken = False  # said on the page once the simulation blew up
        self._sent: dict[str, tuple[Sequence[float], Sequence[float]]] = {}
        scene, gui = viewer.server.scene, viewer.server.gui
        scene.add_grid("/ground", ground, ground, cell_size=0.1, section_size=1.0)
        for index, box in enumerate(obstacles):
            scene.add_box(
                f"/obstacles/box_{index}", _WALL, tuple(box.size), position=tuple(box.centre)
            )
        self._readout = gui.add_markdown(self._said())
        ids = {
            name: viewer.add_button(label, self._presser(name)) for name, (label, _) in KEYS.items()
        }
        keys = {key: ids[name] for name, (_, pressed) in KEYS.items() for key in pressed}
        viewer.run_script(_SCRIPT % json.dumps(keys))
        viewer.on_toggle(self._show)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def press(self, name: str) -> None:
        """What a key's button does: ``up``, ``down``, ``left``, ``right`` step the speed
        and turn rate (within `MAX_SPEED` and `MAX_TURN`), ``stop`` stops."""
        with self._lock:
            speed, turn = self.speed, self.turn
            if name == "up":
                speed += SPEED_STEP
            elif name == "down":
                speed -= SPEED_STEP
            elif name == "left":
                turn += TURN_STEP
            elif name == "right":
                turn -= TURN_STEP
            elif name == "stop":
                speed = turn = 0.0
            else:
                return
            self.speed = round(max(-MAX_SPEED, min(MAX_SPEED, speed)), 9)
            self.turn = round(max(-MAX_TURN, min(MAX_TURN, turn)), 9)
            self.source.command(self.speed, self.turn)
            self._readout.content = self._said()

    def _presser(self, name: str) -> Callable[[], None]:
        return lambda: self.press(name)

    def close(self) -> None:
        """Stop stepping the simulation (the viewer is the caller's to close)."""
        self._stop.set()
        if self._thread is not threading.current_thread():
            self._thread.join()

    def _said(self) -> str:
        if self._broken:
            return (
                f"**The simulation blew up** at {self.source.exploded:.2f} s (see `fishbot "
                "sim` without --view for why): the robot is shown as it was then."
            )
        return (
            f"**Drive**: {self.speed:+.2f} m/s, {self.turn:+.2f} rad/s. Keys: Up and Down "
            "change the speed, Left and Right the turn, space or k stops."
        )

    def _run(self) -> None:
        period = 1.0 / FPS
        last = time.monotonic()
        while not self._stop.wait(period):
            now = time.monotonic()
            try:
                self.source.advance(min(now - last, _LONGEST))
                self.viewer.place(self._moved(self.source.poses()))
                self._scan()
            except Exception as exc:  # a fault of the page's or the simulation's: said once
                _log.warning("the simulation stopped: %s", exc)
                return
            last = now
            self.frames += 1
            if self.source.exploded is not None and not self._broken:
                self._broken = True
                self._readout.content = self._said()

    def _moved(
        self, poses: Mapping[str, tuple[Sequence[float], Sequence[float]]]
    ) -> dict[str, tuple[Sequence[float], Sequence[float]]]:
        """The links of ``poses`` that moved since they were last sent (by more than
        `_STILL`): a robot at rest costs the page nothing."""
        moved = {}
        for link, (position, wxyz) in poses.items():
            was = self._sent.get(link)
            if (
                was is None
                or max(
                    max(abs(a - b) for a, b in zip(position, was[0], strict=True)),
                    max(abs(a - b) for a, b in zip(wxyz, was[1], strict=True)),
                )
                > _STILL
            ):
                moved[link] = self._sent[link] = (position, wxyz)
        return moved

    def _scan(self) -> None:
        """Draw each lidar's scan that is newer than the one on the page."""
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        shown = self.viewer.showing("sensors")
        rgb = tuple(round(255 * c) for c in LIDAR[:3])
        for scan in self.source.scans():
            if self._drawn.get(scan.sensor) == scan.time:
                continue
            ends = np.asarray(scan.ends, dtype=np.float32)
            starts = np.broadcast_to(np.asarray(scan.origin, dtype=np.float32), ends.shape)
            self._rays[scan.sensor] = self.viewer.server.scene.add_line_segments(
                f"/scans/{scan.sensor or 'lidar'}",
                np.stack([starts, ends], axis=1),
                rgb,
                thickness=_LINE_WIDTH,
                thickness_units="screen",
                visible=shown,
            )
            self._drawn[scan.sensor] = scan.time

    def _show(self) -> None:
        shown = self.viewer.showing("sensors")
        for rays in list(self._rays.values()):
            rays.visible = shown
