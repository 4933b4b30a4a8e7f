"""`fishbot view` serves where it is asked or says in one line why it cannot, frees its port
when the robot cannot be read, prints nothing from the library, and reads the robot within
the limits of --timeout and --max-size, each (re)load afresh."""

from __future__ import annotations

import errno
import os
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner
from conftest import REQUIRE_TOOLS
from test_render import NO_BOXES as RENDERED_NO_BOXES
from test_view_requests import ARM, SECONDS, _http, _websocket

if not REQUIRE_TOOLS:  # on a user's machine without the [view] extra: skipped, with a reason
    pytest.importorskip("viser", reason="fishbot view needs the [view] extra")

from fishbot_urdf import FishbotUrdfError, InputError, check_file
from fishbot_urdf.cli import cli
from fishbot_urdf.drawing.viewer import ServeError, Viewer
from fishbot_urdf.inputs import InputTooLargeError, size_limit, time_limit

UNROUTED = "192.0.2.1"  # TEST-NET-1: never an address of this machine, so never bound


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def _loader(robot: Path) -> Callable[[], tuple[Any, tuple[str, ...]]]:
    def load() -> tuple[Any, tuple[str, ...]]:
        result = check_file(robot)
        return result.analysis, result.files

    return load


@pytest.fixture
def arm(tmp_path: Path) -> Path:
    robot = tmp_path / "arm.urdf"
    robot.write_text(ARM, encoding="utf-8")
    return robot


def test_a_host_that_cannot_be_bound_is_one_line_and_status_2(arm: Path) -> None:
    port = _free_port()
    started = time.monotonic()
    command = ["view", str(arm), "--host", UNROUTED, "--port", str(port)]
    run = subprocess.run(
        [sys.executable, "-m", "fishbot_urdf", *command],
        capture_output=True,
        text=True,
        timeout=60,  # it used to wait forever
        check=False,
    )
    assert time.monotonic() - started < 30
    assert run.returncode == 2
    assert run.stdout == ""
    reason = os.strerror(errno.EADDRNOTAVAIL)
    assert run.stderr == f"<input>: error: cannot serve on {UNROUTED}:{port}: {reason} [io]\n"


def test_serve_error_says_where_and_why(arm: Path) -> None:
    with pytest.raises(ServeError) as caught:
        Viewer(_loader(arm), host=UNROUTED, port=8080)
    error = caught.value
    assert isinstance(error, InputError)
    assert (error.host, error.port, error.rule) == (UNROUTED, 8080, "io")
    assert error.reason == os.strerror(errno.EADDRNOTAVAIL)
    assert error.message == f"cannot serve on {UNROUTED}:8080: {error.reason}"
    with pytest.raises(ServeError) as ipv6:
        Viewer(_loader(arm), host="2001:db8::1", port=8080)
    assert ipv6.value.message.startswith("cannot serve on [2001:db8::1]:8080: ")


def test_a_failing_first_load_frees_the_port(tmp_path: Path) -> None:
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='x'><link name='a'>", encoding="utf-8")
    port = _free_port()
    with pytest.raises(FishbotUrdfError):
        Viewer(_loader(broken), port=port)
    with socket.socket() as again:  # no SO_REUSEADDR: the viewer's socket is closed
        again.bind(("127.0.0.1", port))
    # (`fishbot view` waits for a fix instead: see test_view_page.py)


def test_a_failing_load_is_shown_and_reported_until_a_load_succeeds(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text("<robot name='x'><link name='a'>", encoding="utf-8")
    reported: list[FishbotUrdfError | None] = []
    shown = Viewer(
        _loader(robot), port=0, watch=(str(robot),), wait=lambda _: True, report=reported.append
    )
    try:
        [error] = reported
        assert shown.error is error
        assert (error.rule, error.path) == ("xml-syntax", str(robot))
        note = shown._trouble
        assert note.visible
        assert note.content.startswith(
            "**The robot cannot be read.** No robot can be shown until the file is fixed:\n\n```\n"
        )
        assert f"{robot}:1:" in note.content and "[xml-syntax]" in note.content
        assert shown._frames == {}
        robot.write_text(ARM, encoding="utf-8")
        _wait(lambda: len(reported) == 2)
        assert reported[1] is None
        assert shown.error is None and not note.visible
        assert "upper" in shown._frames
        robot.write_text(ARM.replace("</robot>", ""), encoding="utf-8")  # broken again
        _wait(lambda: len(reported) == 3)
        assert reported[2] is not None and shown.error is reported[2]
        assert note.visible and "The robot read last is shown" in note.content
        assert "upper" in shown._frames  # still there
    finally:
        shown.close()


def test_a_first_load_that_fails_with_an_error_not_waited_for_is_raised(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text("<robot name='x'><link name='a'>", encoding="utf-8")
    reported: list[FishbotUrdfError | None] = []
    port = _free_port()
    with pytest.raises(FishbotUrdfError):
        Viewer(_loader(robot), port=port, wait=lambda _: False, report=reported.append)
    assert reported == []
    with socket.socket() as again:
        again.bind(("127.0.0.1", port))


def _wait(condition: Callable[[], Any], seconds: float = 20.0) -> None:
    deadline = time.monotonic() + seconds
    while not condition():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.1)


def test_the_library_prints_nothing(arm: Path, capfd: pytest.CaptureFixture[str]) -> None:
    capfd.readouterr()
    shown = Viewer(_loader(arm), port=0)  # viser's banner went to stdout
    try:
        port = int(shown.server.get_port())
        assert _http(port, f"Host: localhost:{port}") == "HTTP/1.1 200 OK"
        with _websocket(port, f"http://localhost:{port}") as page:
            assert page.recv(timeout=SECONDS)
    finally:
        shown.close()  # and "(viser) Server stopped" too
    assert capfd.readouterr() == ("", "")


def test_view_takes_the_limit_options() -> None:
    result = CliRunner().invoke(cli, ["view", "--help"])
    assert result.exit_code == 0
    for option in ("--timeout SECONDS", "--max-size MIB", "--trust-expressions"):
        assert option in result.stdout


def test_max_size_bounds_the_first_load(arm: Path) -> None:
    port = _free_port()
    result = CliRunner().invoke(
        cli, ["view", str(arm), "--port", str(port), "--max-size", str(100 / 1024 / 1024)]
    )
    assert result.exit_code == 2
    assert result.stdout == ""
    size = len(ARM.encode())
    assert result.stderr == (
        f"{arm}: error: is {size} bytes, more than the limit of 100 bytes "
        "(raise the limit with --max-size MIB) [io]\n"
    )
    with socket.socket() as again:
        again.bind(("127.0.0.1", port))


def test_every_reload_is_within_the_limits_the_viewer_was_made_in(arm: Path) -> None:
    with size_limit(4096), time_limit(0.5):
        shown = Viewer(_loader(arm), port=0)
    try:
        time.sleep(0.6)  # past the first deadline: each load has the time limit afresh
        shown.reload()
        arm.write_text(ARM + "<!--" + "x" * 4096 + "-->\n", encoding="utf-8")
        with pytest.raises(InputTooLargeError):  # the size limit of then, not of now
            shown.reload()
    finally:
        shown.close()


def test_a_fixed_joint_given_a_position_is_said_to_be_fixed(tmp_path: Path) -> None:
    robot = tmp_path / "arm.urdf"
    robot.write_text(ARM.replace("</robot>", FIXED_TOOL + "</robot>"), encoding="utf-8")
    port = _free_port()
    result = CliRunner().invoke(cli, ["view", str(robot), "--port", str(port), "-j", "tool=1"])
    assert result.exit_code == 2
    assert result.stdout == ""
    assert "joint 'tool' is fixed: it takes no position" in result.stderr
    with socket.socket() as again:  # and the viewer's port is free again
        again.bind(("127.0.0.1", port))


FIXED_TOOL = (
    '<link name="tool"/><joint name="tool" type="fixed"><parent link="base"/>'
    '<child link="tool"/></joint>'
)


def test_a_robot_whose_only_fault_is_an_inertial_is_shown_with_its_findings(
    tmp_path: Path,
) -> None:
    robot = tmp_path / "arm.urdf"
    robot.write_text(
        ARM.replace(
            '<link name="base">', '<link name="base"><inertial><mass value="1"/></inertial>'
        ),
        encoding="utf-8",
    )
    command = [sys.executable, "-m", "fishbot_urdf", "view", str(robot), "shoulder:=0.5"]
    command += ["--port", "0"]
    shown = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert shown.stdout is not None and shown.stderr is not None
        assert shown.stdout.readline().startswith("fishbot view: http://localhost:")
    finally:
        shown.terminate()
        _, err = shown.communicate(timeout=60)
    said, line, no_box = err.splitlines()
    assert said == (
        f"{robot}: warning: argument 'shoulder' is given, but a URDF file takes no arguments "
        "('shoulder' is a joint: did you mean `-j shoulder=0.5`?) [xacro-unknown-arg]"
    )
    assert line.startswith(f"{robot}:3:")
    assert line.endswith("error: link 'base': <inertial> has no <inertia> " + INERTIA_HINT)
    # The drawing's findings after check's: an inertia of 0 has no box on the Inertia toggle.
    assert no_box.startswith(f"{robot}:3:")
    assert no_box.endswith(
        "warning: link 'base': inertial has no inertia box drawn (RViz draws none either): its "
        "inertia is not positive definite: ixx, ixx*iyy - ixy^2 and the determinant are not "
        "all above 0 (a moment is negative or 0, or a product too large: compute the inertia "
        "again, from the part's shape and mass) [shape-not-drawn]"
    )


INERTIA_HINT = (
    '(write <inertia ixx=".." ixy="0" ixz="0" iyy=".." iyz="0" izz=".."/>) [missing-element]'
)


def test_a_robot_with_no_visual_shows_its_frames_with_a_warning(tmp_path: Path) -> None:
    robot = tmp_path / "frames.urdf"
    robot.write_text(
        '<robot name="frames"><link name="a"/><link name="b"/>'
        '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>',
        encoding="utf-8",
    )
    shown = Viewer(_loader(robot), port=0)
    try:
        [finding] = shown.findings  # the visuals' (the collision shapes' toggle says nothing)
        assert (finding.rule, finding.severity.value, finding.where) == (
            "nothing-drawn",
            "warning",
            f"{robot}:1:1",
        )
        assert (
            finding.message
            == "robot 'frames': no link has a visual shape: there is nothing to draw"
        )
        assert set(shown._frames) == {"a", "b"}
    finally:
        shown.close()


# render's robot whose links get no inertia box, its base given a shape to show
NO_BOXES = RENDERED_NO_BOXES.replace(
    '<link name="base"/>',
    '<link name="base">\n    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>\n'
    "  </link>",
)


def _no_box(robot: Path, line: int, link: str, why: str) -> str:
    return (
        f"{robot}:{line}:5: warning: link {link!r}: inertial has no inertia box drawn (RViz "
        f"draws none either): {why} [shape-not-drawn]"
    )


def test_view_says_why_a_link_has_no_inertia_box_at_each_load(tmp_path: Path) -> None:
    robot = tmp_path / "bad.urdf"
    robot.write_text(NO_BOXES, encoding="utf-8")
    negative = _no_box(
        robot,
        6,
        "negative",
        "its inertia is not positive definite: ixx, ixx*iyy - ixy^2 and the determinant are "
        "not all above 0 (a moment is negative or 0, or a product too large: compute the "
        "inertia again, from the part's shape and mass)",
    )
    triangle = _no_box(
        robot,
        12,
        "triangle",
        "a principal moment of its inertia is larger than the other two together (no solid "
        "has such moments: compute the inertia again, from the part's shape and mass)",
    )
    massless = _no_box(
        robot,
        18,
        "massless",
        "its mass, 0 kg, is not positive (give the link its mass in kg; a link that carries "
        "no mass needs no <inertial>)",
    )
    command = [sys.executable, "-m", "fishbot_urdf", "view", str(robot), "--port", "0"]
    env = {**os.environ, "NO_COLOR": "1"}
    shown = subprocess.Popen(
        command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env
    )
    said: list[str] = []
    try:
        assert shown.stdout is not None and shown.stderr is not None
        reader = threading.Thread(target=lambda: said.extend(shown.stderr), daemon=True)
        reader.start()
        assert shown.stdout.readline().startswith("fishbot view: http://localhost:")
        _wait_for(lambda: len(said) >= 3)  # (printed before the URL, read by the thread)
        # Each link whose box the Inertia toggle cannot show, and why, once: the check
        # that view runs reads no inertial (its faults do not stop the robot being shown).
        assert [line.rstrip("\n") for line in said] == [negative, triangle, massless]
        # An edit that gives the massless link its mass: read again, the findings said anew.
        robot.write_text(NO_BOXES.replace('<mass value="0"/>', '<mass value="1"/>'))
        _wait_for(lambda: len(said) >= 5)
        assert [line.rstrip("\n") for line in said[3:]] == [negative, triangle]
    finally:
        shown.terminate()
        shown.communicate(timeout=60)


def _wait_for(done: Callable[[], bool]) -> None:
    waited = time.monotonic() + 6 * SECONDS
    while not done() and time.monotonic() < waited:
        time.sleep(0.1)
