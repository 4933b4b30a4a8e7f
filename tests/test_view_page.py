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
from conftest import REQUIRE_TOOLS

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
