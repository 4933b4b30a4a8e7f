"""`fishbot view`: the robot in a real headless browser (Debian's chromium and chromedriver):
the page loads, the robot is in the screenshot's pixels, a slider moves a link, and an edit
of the robot's files reloads it with the sliders kept."""

from __future__ import annotations

import io
import shutil
import socket
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import FISHBOT, REQUIRE_TOOLS, require_tool
from PIL import Image

from fishbot_urdf import ToolNotFoundError, check_file
from fishbot_urdf.cli import cli

if not REQUIRE_TOOLS:  # on a user's machine without the [view] extra: skipped, with a reason
    pytest.importorskip("viser", reason="fishbot view needs the [view] extra")
    pytest.importorskip("selenium", reason="the browser tests need selenium ([test] extra)")
from selenium import webdriver
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys

from fishbot_urdf.drawing.viewer import Viewer

CHROME_FLAGS = (
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--use-angle=swiftshader",  # WebGL in software: no GPU here
    "--enable-unsafe-swiftshader",
    "--window-size=1200,900",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",
)


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def _wait(condition: Callable[[], Any], seconds: float = 20.0) -> Any:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        value = condition()
        if value is not None and value is not False:
            return value
        time.sleep(0.2)
    raise AssertionError("timed out")


@pytest.fixture(scope="module")
def robot(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A copy of the fishbot package, to edit."""
    folder = tmp_path_factory.mktemp("view") / "fishbot"
    shutil.copytree(FISHBOT, folder)
    return folder / "urdf" / "fishbot" / "fishbot.urdf.xacro"


@pytest.fixture(scope="module")
def viewer(robot: Path) -> Iterator[Viewer]:
    def load() -> tuple[Any, tuple[str, ...]]:
        result = check_file(robot)
        return result.analysis, result.files

    shown = Viewer(load, port=_free_port())
    yield shown
    shown.close()


def headless_chromium() -> Any:
    """Debian's chromium, headless, driven by its chromedriver (a test skips without them,
    or fails in CI)."""
    chromium = require_tool("chromium", "chromium")
    driver_path = require_tool("chromedriver", "chromium-driver")
    options = webdriver.ChromeOptions()
    for flag in CHROME_FLAGS:
        options.add_argument(flag)
    options.binary_location = chromium
    return webdriver.Chrome(service=webdriver.ChromeService(driver_path), options=options)


@pytest.fixture(scope="module")
def browser(viewer: Viewer) -> Iterator[Any]:
    driver = headless_chromium()
    driver.get(viewer.url)
    _wait(lambda: "Connected" in driver.find_element(By.TAG_NAME, "body").text)
    yield driver
    driver.quit()


def _screenshot(driver: Any) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(driver.get_screenshot_as_png())).convert("RGB"))


def _blue(pixels: np.ndarray) -> float:
    """The share of pixels of the fishbot's blue body (blue well above red and green)."""
    r, g, b = (pixels[..., i].astype(int) for i in range(3))
    return float(((b > 150) & (b > r + 60) & (b > g + 60)).mean())


def _settled(driver: Any) -> np.ndarray:
    """A screenshot once two in a row agree (the page has drawn what it was sent)."""
    last = _screenshot(driver)
    for _ in range(40):
        time.sleep(0.25)
        now = _screenshot(driver)
        if np.array_equal(now, last):
            return now
        last = now
    return last


def test_the_page_shows_the_robot(browser: Any) -> None:
    pixels = _settled(browser)
    assert _blue(pixels) > 0.02  # the body is there, framed by the first camera
    text = browser.find_element(By.TAG_NAME, "body").text
    for label in ("left_wheel_joint", "right_wheel_joint", "Collision shapes", "Link frames"):
        assert label in text


def test_a_slider_moves_its_link(browser: Any, viewer: Viewer) -> None:
    before = _settled(browser)
    frame_before = tuple(viewer._frames["left_wheel_link"].wxyz)
    slider = browser.find_elements(By.CSS_SELECTOR, '[role="slider"]')[0]  # left_wheel_joint
    slider.click()
    slider.send_keys(Keys.END)  # to its upper limit, as a person would with the keyboard
    _wait(lambda: viewer.values["left_wheel_joint"] == pytest.approx(np.pi))
    assert tuple(viewer._frames["left_wheel_link"].wxyz) != pytest.approx(frame_before)
    after = _settled(browser)
    changed = (np.abs(after.astype(int) - before.astype(int)).max(axis=2) > 40).mean()
    assert changed > 0.0005  # the wheel's axes turned on screen


def test_an_edit_reloads_the_robot_and_keeps_the_sliders(
    browser: Any, viewer: Viewer, robot: Path
) -> None:
    held = viewer.values["left_wheel_joint"]
    blue = _blue(_settled(browser))
    base = robot.parent / "base.urdf.xacro"
    text = base.read_text(encoding="utf-8")
    assert 'rgba="0.1 0.1 1.0 0.5"' in text
    base.write_text(text.replace('rgba="0.1 0.1 1.0 0.5"', 'rgba="1.0 0.1 0.1 0.5"'))
    _wait(lambda: viewer.reloads >= 1)
    assert viewer.values["left_wheel_joint"] == held
    # (what blue is left: the link frames' z axes)
    pixels = _wait(lambda: (lambda p: p if _blue(p) < blue / 10 else None)(_screenshot(browser)))
    r, g, b = (pixels[..., i].astype(int) for i in range(3))
    assert ((r > 150) & (r > g + 60) & (r > b + 60)).mean() > 0.02  # now red


def test_without_viser_one_line_says_how_to_install(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "viser", None)
    with pytest.raises(ToolNotFoundError) as caught:
        Viewer(lambda: (None, ()))
    assert caught.value.hint == "pip install 'fishbot-urdf[view]'"
    result = CliRunner().invoke(cli, ["view", str(FISHBOT / "urdf" / "first_robot.urdf")])
    # The setup's fault, not the robot's: said of the command, exit 2 as a missing dot.
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr == (
        "fishbot view: error: setup: the viser package, an optional part of fishbot-urdf that "
        "the viewer needs, is not installed (install it: pip install 'fishbot-urdf[view]') "
        "[tool-missing]\n"
    )
