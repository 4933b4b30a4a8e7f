"""`fishbot view` in a real headless browser, what the page shows: a transparent part
inside another, the robot filling the view, and a robot that cannot be read (from the
start, or after an edit) said on the terminal as check says it and on the page, until
it is fixed."""

from __future__ import annotations

import os
import subprocess
import sys
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import FISHBOT, REQUIRE_TOOLS

if not REQUIRE_TOOLS:  # on a user's machine without the [view] extra: skipped, with a reason
    pytest.importorskip("viser", reason="fishbot view needs the [view] extra")
    pytest.importorskip("selenium", reason="the browser tests need selenium ([test] extra)")
from selenium.webdriver.common.by import By
from test_view import _free_port, _settled, _wait, headless_chromium
from test_view_serving import _loader

from fishbot_urdf.cli import cli
from fishbot_urdf.drawing.viewer import Viewer

# A white body, half transparent, around a magenta box, half transparent too, 3 cm up
# (nearer the camera, which looks from above: three.js draws it after the body).
NESTED = """\
<robot name="nested">
  <link name="base_link">
    <visual>
      <geometry><cylinder radius="0.10" length="0.12"/></geometry>
      <material name="white"><color rgba="1 1 1 0.5"/></material>
    </visual>
  </link>
  <link name="inner_link">
    <visual>
      <geometry><box size="0.05 0.05 0.05"/></geometry>
      <material name="magenta"><color rgba="1 0 1 0.5"/></material>
    </visual>
  </link>
  <joint name="inner_joint" type="fixed">
    <parent link="base_link"/><child link="inner_link"/><origin xyz="0 0 0.03"/>
  </joint>
</robot>
"""


def _magenta(pixels: np.ndarray) -> float:
    """The share of magenta pixels (red and blue well above green: no link frame's axis)."""
    r, g, b = (pixels[..., i].astype(int) for i in range(3))
    return float(((r > g + 60) & (b > g + 60)).mean())


@pytest.fixture(scope="module")
def driver() -> Iterator[Any]:
    made = headless_chromium()
    yield made
    made.quit()


def _open(driver: Any, url: str) -> None:
    driver.get(url)
    _wait(lambda: "Connected" in _text(driver))


def _text(driver: Any) -> str:
    return str(driver.find_element(By.TAG_NAME, "body").text)


def test_a_transparent_part_inside_another_is_seen(driver: Any, tmp_path: Path) -> None:
    robot = tmp_path / "nested.urdf"
    robot.write_text(NESTED, encoding="utf-8")

    shown = Viewer(_loader(robot), port=_free_port())
    try:
        _open(driver, shown.url)
        pixels = _settled(driver)
        # The box is 5 cm inside a body 20 cm wide that fills the view: some 2% of it.
        assert _magenta(pixels) > 0.005
    finally:
        shown.close()


def test_the_robot_fills_the_view(driver: Any, tmp_path: Path) -> None:
    robot = tmp_path / "box.urdf"
    robot.write_text(
        '<robot name="box"><link name="a"><visual><geometry><box size="0.4 0.2 0.1"/>'
        '</geometry><material name="m"><color rgba="1 0 1 1"/></material></visual></link>'
        "</robot>",
        encoding="utf-8",
    )

    shown = Viewer(_loader(robot), port=_free_port())
    try:
        _open(driver, shown.url)
        pixels = _settled(driver)
        r, g, b = (pixels[..., i].astype(int) for i in range(3))
        rows, columns = np.nonzero((r > g + 60) & (b > g + 60))  # the box's, no axis's
        height, width = pixels.shape[:2]
        # The box's corners reach 85% of the way from the middle to the edge of a square
        # view: the box is some 80% of the view's height (the view is wider than high).
        assert (rows.max() - rows.min()) / height > 0.7
        assert abs((rows.max() + rows.min()) / 2 - height / 2) < 0.05 * height  # centred
        assert abs((columns.max() + columns.min()) / 2 - width / 2) < 0.05 * width
    finally:
        shown.close()


class _Lines:
    """What a running process writes on a stream, line by line, read by a thread."""

    def __init__(self, stream: Any) -> None:
        self.lines: list[str] = []
        self._thread = threading.Thread(target=self._read, args=(stream,), daemon=True)
        self._thread.start()

    def _read(self, stream: Any) -> None:
        for line in stream:
            self.lines.append(line.rstrip("\n"))


def _check_errors(robot: Path) -> list[str]:
    """The error lines `fishbot check` prints for ``robot``."""
    result = CliRunner().invoke(cli, ["check", "--isolated", str(robot)])
    return [line for line in result.stderr.splitlines() if ": error: " in line]


def test_a_robot_that_cannot_be_read_is_said_and_shown_until_it_is_fixed(
    driver: Any, tmp_path: Path
) -> None:
    robot = tmp_path / "robot.urdf"
    broken = NESTED.replace("</link>\n  <link", "\n  <link", 1)  # base_link never closed
    robot.write_text(broken, encoding="utf-8")
    first_errors = _check_errors(robot)
    assert first_errors  # (the XML is not well formed)
    port = _free_port()
    with subprocess.Popen(
        [sys.executable, "-m", "fishbot_urdf", "view", str(robot), "--port", str(port)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "NO_COLOR": "1"},
    ) as process:
        try:
            _follow(process, driver, robot, port, first_errors)
        finally:
            process.terminate()
            process.wait(timeout=30)
    assert process.returncode == 143  # quietly, on SIGTERM


def _follow(process: Any, driver: Any, robot: Path, port: int, first_errors: list[str]) -> None:
    out, err = _Lines(process.stdout), _Lines(process.stderr)
    # Broken from the start: its errors as check prints them, and a page that says so.
    _wait(lambda: len(out.lines) > 0, 60)
    assert out.lines == [f"fishbot view: http://localhost:{port} (Ctrl-C stops)"]
    assert err.lines == first_errors
    assert process.poll() is None  # waiting for a fix
    _open(driver, f"http://localhost:{port}")
    _wait(lambda: "The robot cannot be read." in _text(driver))
    assert first_errors[0].split(": error: ", 1)[1] in _text(driver)
    assert _magenta(_settled(driver)) == 0.0
    # Fixed: the robot is shown, framed, and the terminal says so.
    robot.write_text(NESTED, encoding="utf-8")
    _wait(lambda: len(out.lines) > 1)
    assert out.lines[1] == f"fishbot view: {robot} is read again: the page shows it"
    _wait(lambda: _magenta(_settled(driver)) > 0.005)
    assert "The robot cannot be read." not in _text(driver)
    # Broken by an edit: said again, and the page keeps the robot read last.
    robot.write_text(NESTED.replace("<visual>", "<visual", 1), encoding="utf-8")
    again = _check_errors(robot)
    _wait(lambda: len(err.lines) >= len(first_errors) + len(again))
    assert err.lines[len(first_errors) :] == again
    _wait(lambda: "The robot cannot be read." in _text(driver))
    assert "The robot read last is shown" in _text(driver)
    assert _magenta(_settled(driver)) > 0.005


def _red(pixels: np.ndarray) -> np.ndarray:
    """Where the page shows RViz's mass and inertia red (or an x axis, when frames show)."""
    r, g, b = (pixels[..., i].astype(int) for i in range(3))
    return (r > 120) & (g < 60) & (b < 60) & _canvas(pixels)


def _tick(driver: Any, label: str) -> None:
    """Click the checkbox of ``label``, as a person would."""
    box = driver.find_element(
        By.XPATH, f"//*[normalize-space(text())='{label}']/following::input[@type='checkbox'][1]"
    )
    box.click()


def _box_of(where: np.ndarray) -> tuple[int, int, int, int]:
    rows, columns = np.nonzero(where)
    return int(rows.min()), int(rows.max()), int(columns.min()), int(columns.max())


def test_mass_and_inertia_show_as_rviz_shows_them(driver: Any) -> None:
    shown = Viewer(_loader(FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"), port=_free_port())
    try:
        _open(driver, shown.url)
        body = _settled(driver)
        r, g, b = (body[..., i].astype(int) for i in range(3))
        robot = _box_of((b > r + 60) & (b > g + 60))  # the blue body
        # As the notes do it in RViz: the visuals off (and the frames, whose x axes are red)...
        _tick(driver, "Visual")
        _tick(driver, "Link frames")
        _wait(lambda: not _red(_settled(driver)).any())
        # ... then Mass: a red ball of lead per link, inside the robot's outline.
        _tick(driver, "Mass")
        balls = _wait(lambda: (lambda p: p if _red(p).mean() > 0.001 else None)(_settled(driver)))
        top, bottom, left, right = _box_of(_red(balls))
        assert robot[0] - 5 <= top and bottom <= robot[1] + 40  # (the wheels hang lower)
        assert robot[2] - 40 <= left and right <= robot[3] + 40
        # ... then Inertia: the boxes, bigger than the balls (the body's: 0.17 m across,
        # its ball 0.055 m).
        _tick(driver, "Inertia")
        both = _wait(
            lambda: (lambda p: p if _red(p).mean() > 4 * _red(balls).mean() else None)(
                _settled(driver)
            )
        )
        assert _red(both).any()
        _tick(driver, "Mass")
        _tick(driver, "Inertia")
        _wait(lambda: not _red(_settled(driver)).any())
    finally:
        shown.close()


# A blue post 0.3 m tall whose <inertial> was pasted from another part: 0.3 m beside it.
MISPLACED = """\
<robot name="misplaced">
  <link name="post">
    <visual>
      <geometry><cylinder radius="0.04" length="0.3"/></geometry>
      <material name="blue"><color rgba="0 0 1 1"/></material>
    </visual>
    <inertial>
      <origin xyz="0.3 0 0"/>
      <mass value="2"/>
      <inertia ixx="0.0158" iyy="0.0158" izz="0.0016" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
</robot>
"""


def test_an_inertia_off_its_part_is_seen_beside_it(driver: Any, tmp_path: Path) -> None:
    robot = tmp_path / "misplaced.urdf"
    robot.write_text(MISPLACED, encoding="utf-8")
    shown = Viewer(_loader(robot), port=_free_port())
    try:
        _open(driver, shown.url)
        _tick(driver, "Link frames")
        post = _wait(lambda: (lambda p: p if not _red(p).any() else None)(_settled(driver)))
        r, g, b = (post[..., i].astype(int) for i in range(3))
        _, _, left, right = _box_of((b > r + 60) & (b > g + 60) & _canvas(post))
        _tick(driver, "Inertia")
        boxed = _wait(lambda: (lambda p: p if _red(p).mean() > 0.001 else None)(_settled(driver)))
        _, _, box_left, box_right = _box_of(_red(boxed))
        # The box (0.07 x 0.07 x 0.3 m: its moments are the post's) stands clear of the
        # post, on one side: the first view, which frames the marks too, shows it (0.3 m
        # apart is 3.75 posts' widths, less as the camera sees it from the front left).
        width = right - left
        gap = box_left - right if box_left > right else left - box_right
        assert gap > width / 2, (left, right, box_left, box_right)
    finally:
        shown.close()


def test_the_first_view_frames_the_whole_robot_and_its_axes(driver: Any) -> None:
    shown = Viewer(_loader(FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"), port=_free_port())
    try:
        _open(driver, shown.url)
        pixels = _settled(driver)
        height, width = pixels.shape[:2]
        # Between the note at the top left and the controls at the top right: the laser's
        # z axis, the robot's highest point, stays clear of the top edge.
        drawn = (pixels < 235).any(axis=2)
        middle = drawn[:, int(0.3 * width) : int(0.7 * width)]
        top, bottom, _, _ = _box_of(middle)
        assert top > 0.03 * height and bottom < 0.9 * height
    finally:
        shown.close()


TINY_ARM = """\
<robot name="tiny">
  <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
  {links}
  <!-- written from the tip back to the root -->
  <joint name="wrist" type="revolute"><parent link="forearm"/><child link="hand"/>
    <origin xyz="0 0 0.005"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="forearm"/>
    <origin xyz="0 0 0.005"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.005"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
"""
TINY_LINK = (
    '<link name="{0}"><visual><origin xyz="0 0 0.0025"/><geometry><box size="0.002 0.002 0.005"/>'
    '</geometry><material name="grey"/></visual></link>'
)


def test_a_tiny_arm_has_small_axes_and_its_sliders_root_first(driver: Any, tmp_path: Path) -> None:
    robot = tmp_path / "tiny.urdf"
    links = "".join(TINY_LINK.format(n) for n in ("hand", "forearm", "upper", "base"))
    robot.write_text(TINY_ARM.format(links=links), encoding="utf-8")
    shown = Viewer(_loader(robot), port=_free_port())
    try:
        _open(driver, shown.url)
        # The sliders come from the root outwards, as tf lists the joints.
        text = _text(driver)
        assert text.index("shoulder") < text.index("elbow") < text.index("wrist")
        arm = _settled(driver)
        _tick(driver, "Visual")
        axes = _wait(lambda: (lambda p: p if _is_grey_free(p) else None)(_settled(driver)))
        # An arm of four links 5 mm tall: each frame's axes are a tenth of its size (the
        # diagonal of its box, 2 cm: 2 mm), shorter than a link, where the viewer's old
        # axes (6 mm, its least) or RViz's (10 cm) outgrew the parts.
        spread = np.abs(arm.astype(int) - arm[..., :1].astype(int)).max(axis=2)
        top, bottom, _, _ = _box_of((spread < 8) & (arm[..., 0] < 200) & _canvas(arm))
        _, _, left, right = _box_of((axes < 235).any(axis=2) & _canvas(axes))
        assert right - left < (bottom - top) / 4
    finally:
        shown.close()


def _is_grey_free(pixels: np.ndarray) -> bool:
    spread = np.abs(pixels.astype(int) - pixels[..., :1].astype(int)).max(axis=2)
    return not ((spread < 8) & (pixels[..., 0] < 200) & _canvas(pixels)).any()


def _canvas(pixels: np.ndarray) -> np.ndarray:
    """The middle of the page, where the robot is: clear of the note on its left, the
    controls on its right and the axes in its corner."""
    height, width = pixels.shape[:2]
    inside = np.zeros((height, width), dtype=bool)
    inside[:, int(0.27 * width) : int(0.7 * width)] = True
    return inside


GAZEBO_FISHBOT = Path(__file__).parent / "data" / "gazebo" / "fishbot_description" / "urdf"


def _orange(pixels: np.ndarray) -> np.ndarray:
    """Where the page shows a lidar's orange rays."""
    r, g, b = (pixels[..., i].astype(int) for i in range(3))
    return (r > 150) & (g > 0.3 * r) & (g < 0.7 * r) & (b < 0.3 * r) & _canvas(pixels)


def _gazebo_blue(pixels: np.ndarray) -> np.ndarray:
    """Where the page shows the first Gazebo link's blue (not a z axis' pure blue)."""
    r, g, b = (pixels[..., i].astype(int) for i in range(3))
    return (b > 100) & (r < 0.4 * b) & (g > 0.45 * b) & (g < 0.85 * b) & _canvas(pixels)


def test_the_sensors_and_the_lumped_links_show_when_ticked(driver: Any) -> None:
    shown = Viewer(_loader(GAZEBO_FISHBOT / "fishbot.urdf.xacro"), port=_free_port())
    try:
        _open(driver, shown.url)
        before = _settled(driver)
        assert not _orange(before).any()
        # The lidar's rays, 8 m long, reach out of the robot (framed, 0.2 m across) all round.
        _tick(driver, "Sensors")
        rays = _wait(lambda: (lambda p: p if _orange(p).mean() > 0.002 else None)(_settled(driver)))
        top, bottom, _, _ = _box_of(_orange(rays))
        height = rays.shape[0]
        assert bottom - top > 0.5 * height  # beyond the robot, up and down the view
        changed = np.abs(rays.astype(int) - before.astype(int)).max(axis=2) > 40
        assert (changed & _orange(rays)).sum() > 0.99 * _orange(rays).sum()  # new, the fan
        # The links sdformat lumps into base_footprint (labelled so): the body, the laser
        # and the camera in the first Gazebo link's blue, in place of their grey.
        _tick(driver, "Sensors")
        _wait(lambda: not _orange(_settled(driver)).any())
        assert not _gazebo_blue(_settled(driver)).any()
        _tick(driver, "Gazebo: lumped links")
        _wait(lambda: (lambda p: p if _gazebo_blue(p).mean() > 0.02 else None)(_settled(driver)))
    finally:
        shown.close()
