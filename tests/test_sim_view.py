"""`fishbot sim --view`: the fishbot live in MuJoCo on the viewer's page, in a real headless
browser: an arrow key drives it as far as the command says, and its lidar's rays, cast at
the sensor's rate and range, end on the room's walls where plane geometry puts them."""

from __future__ import annotations

import math
import os
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import DATA, FISHBOT, REQUIRE_TOOLS

if not REQUIRE_TOOLS:  # on a user's machine without the extras: skipped, with a reason
    pytest.importorskip("mujoco", reason="fishbot sim needs the [sim] extra")
    pytest.importorskip("viser", reason="fishbot sim --view needs the [view] extra")
    pytest.importorskip("selenium", reason="the browser tests need selenium ([test] extra)")
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from test_view import _free_port, _screenshot, _settled, _wait, headless_chromium
from test_view_page import _box_of, _orange, _tick

from fishbot_urdf import check_file
from fishbot_urdf.cli import cli
from fishbot_urdf.drawing.teleop import SPEED_STEP
from fishbot_urdf.kinematics import link_poses
from fishbot_urdf.simulation import ROOM, Live, stream

ROBOT = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"
# What laser.urdf.xacro writes of the fishbot's lidar.
SAMPLES, FIRST, LAST, NEAREST, FARTHEST, RATE = 360, 0.0, 6.28, 0.10, 30.0, 5.5


@pytest.fixture(scope="module")
def analysis() -> Any:
    return check_file(ROBOT).analysis


def _yaw(wxyz: Any) -> float:
    w, x, y, z = wxyz
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def _to_walls(x: float, y: float, heading: float) -> float:
    """How far a level ray from (x, y) along ``heading`` goes to the walls' inner faces,
    ROOM / 2 from the origin each way."""
    half = ROOM / 2
    c, s = math.cos(heading), math.sin(heading)
    found = []
    if abs(c) > 1e-12:
        found.append(((half if c > 0 else -half) - x) / c)
    if abs(s) > 1e-12:
        found.append(((half if s > 0 else -half) - y) / s)
    return min(t for t in found if t > 0)


def _rotation(wxyz: Any) -> np.ndarray:
    w, x, y, z = wxyz
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def test_the_lidar_hits_the_walls_where_geometry_says(analysis: Any) -> None:
    live = Live(analysis)
    live.advance(1.0)  # settled on its wheels
    live.command(0.2, 0.7)  # driven off the middle, turned
    live.advance(2.0)
    live.command(0.0, 0.0)
    live.advance(1.0)
    last = live.scans()[0].time
    live.advance(1.0 / RATE + 0.01)  # a new scan falls due
    scan = live.scans()[0]
    assert scan.time > last
    assert len(scan.ranges) == SAMPLES
    # Where the lidar is: the robot's root where MuJoCo has it, and the laser's place on it
    # from the description's joints.
    position, wxyz = live.poses()["base_footprint"]
    on_root = link_poses(analysis)["laser_link"].translation
    x, y, _ = np.array(position) + _rotation(wxyz) @ np.array(on_root)
    heading = _yaw(wxyz)
    assert math.hypot(x, y) > 0.1 and abs(heading) > 0.3  # (off the middle, turned)
    step = (LAST - FIRST) / (SAMPLES - 1)
    expected = [_to_walls(x, y, heading + FIRST + i * step) for i in range(SAMPLES)]
    error = np.abs(np.array(scan.ranges) - np.array(expected))
    assert error.max() < 0.001  # m (the robot leans a hair: well within)


def test_a_ray_that_hits_nothing_reads_the_maximum_range(analysis: Any) -> None:
    live = Live(analysis, walls=False)
    live.advance(0.5)
    scan = live.scans()[0]
    assert (scan.range_min, scan.range_max) == (NEAREST, FARTHEST)
    assert scan.ranges == (FARTHEST,) * SAMPLES


def test_a_robot_without_a_drive_is_held_and_the_keys_move_nothing() -> None:
    live = Live(check_file(FISHBOT / "urdf" / "first_robot.urdf").analysis)
    assert (live.drive, live.obstacles) == (None, ())
    before = live.poses()
    live.command(0.5, 1.0)
    live.advance(0.5)
    assert live.poses() == before  # (the robot has no joint that moves)


def test_scans_are_cast_at_the_sensors_rate(analysis: Any) -> None:
    live = Live(analysis, walls=False)
    times = []
    for _ in range(300):
        live.advance(1 / 100)
        times.append(live.scans()[0].time)
    steps = np.diff(sorted(set(times)))
    assert len(steps) >= 14
    assert np.abs(steps - 1 / RATE).max() <= 0.011  # cast at the first look once due


def test_a_button_takes_a_press_and_nothing_else(analysis: Any) -> None:
    shown = stream(analysis, port=_free_port())
    try:
        viewer = shown.viewer
        ids = [uuid for uuid, control in viewer._inputs.items() if control.button]
        assert len(ids) == 5
        for value, taken in ((True, True), (False, False), (1, False), ("true", False)):
            message = SimpleNamespace(uuid=ids[0], updates={"value": value})
            assert viewer._accepts(message) is taken
    finally:
        shown.close()


@pytest.fixture(scope="module")
def page(analysis: Any) -> Iterator[tuple[Any, Any]]:
    shown = stream(analysis, port=_free_port())
    driver = headless_chromium()
    try:
        driver.get(shown.url)
        _wait(lambda: "Connected" in driver.find_element(By.TAG_NAME, "body").text)
        yield shown, driver
    finally:
        driver.quit()
        shown.close()


def test_an_arrow_key_drives_the_robot_as_far_as_commanded(page: tuple[Any, Any]) -> None:
    shown, driver = page
    live, teleop = shown.live, shown.teleop
    _wait(lambda: live.time > 1.0)  # dropped and settled
    before = _settled(driver)
    start, wxyz = live.poses()["base_footprint"]
    heading = _yaw(wxyz)
    ActionChains(driver).send_keys(Keys.ARROW_UP).perform()
    _wait(lambda: teleop.speed == pytest.approx(SPEED_STEP))
    went = live.since
    time.sleep(1.5)
    moving = _screenshot(driver)
    ActionChains(driver).send_keys(Keys.SPACE).perform()
    _wait(lambda: teleop.speed == 0.0)
    stopped = live.since
    _wait(lambda: live.time > stopped + 1.0)  # the ramp down, and at rest
    end, _ = live.poses()["base_footprint"]
    moved = np.array(end[:2]) - np.array(start[:2])
    along = moved @ (math.cos(heading), math.sin(heading))
    # Ramped up and down alike: as far as the speed held for the time between the commands.
    commanded = SPEED_STEP * (stopped - went)
    assert commanded > 0.1
    assert along == pytest.approx(commanded, rel=0.05)
    assert abs(moved @ (-math.sin(heading), math.cos(heading))) < 0.005  # straight on
    after = _settled(driver)
    for pixels in (moving, after):
        changed = (np.abs(pixels.astype(int) - before.astype(int)).max(axis=2) > 40).mean()
        assert changed > 0.02  # the robot, some 20 cm across and filling the view, moved


def test_the_lidar_rays_show_when_sensors_is_ticked(page: tuple[Any, Any]) -> None:
    shown, driver = page
    assert not _orange(_screenshot(driver)).any()
    _tick(driver, "Sensors")
    # (a screenshot, not a settled one: the rays are drawn anew 5.5 times a second)
    rays = _wait(lambda: (lambda p: p if _orange(p).mean() > 0.002 else None)(_screenshot(driver)))
    # 1.5 m to the walls from a robot 0.2 m across that fills the view: out of it.
    top, bottom, _, _ = _box_of(_orange(rays))
    assert bottom - top > 0.5 * rays.shape[0]
    assert len(shown.live.scans()[0].ends) == SAMPLES
    _tick(driver, "Sensors")
    _wait(lambda: not _orange(_screenshot(driver)).any())


def test_sim_view_prints_its_url_and_serves_the_page(tmp_path: Any) -> None:
    port = _free_port()
    with subprocess.Popen(
        [sys.executable, "-m", "fishbot_urdf", "sim", str(ROBOT), "--view", "--port", str(port)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "NO_COLOR": "1"},
    ) as process:
        try:
            assert process.stdout is not None
            line = process.stdout.readline().rstrip("\n")
            assert line == f"fishbot sim: http://localhost:{port} (Ctrl-C stops)"
            with urllib.request.urlopen(f"http://localhost:{port}", timeout=30) as answer:
                assert answer.status == 200
        finally:
            process.terminate()
            process.wait(timeout=30)
    assert process.returncode == 143  # quietly, on SIGTERM


def test_without_viser_one_line_says_how_to_install(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "viser", None)
    result = CliRunner().invoke(cli, ["sim", str(ROBOT), "--view"])
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr == (
        "fishbot sim: error: setup: the viser package, an optional part of fishbot-urdf that "
        "the viewer needs, is not installed (install it: pip install 'fishbot-urdf[view]') "
        "[tool-missing]\n"
    )


def test_a_body_mujoco_refuses_is_said_where_it_is_written() -> None:
    robot = DATA / "physics" / "massless_wheel.urdf"
    result = CliRunner().invoke(cli, ["sim", str(robot), "--view", "--port", "0"])
    assert (result.exit_code, result.stdout) == (1, "")
    assert result.stderr == (
        f"{robot}:24:5: error: link 'left_wheel_link': it moves, and neither it nor a link "
        "fixed to it has mass: MuJoCo refuses the model (give it the mass and inertia of its "
        "shape) [mjcf-refused]\n"
    )
