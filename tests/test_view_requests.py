"""`fishbot view` answers only its own page: HTTP requests and websockets from another
origin, or addressed to another host (DNS rebinding), get 403; what a control sends is used
only when that control can hold it. Real clients, on 127.0.0.1 only."""

from __future__ import annotations

import logging
import math
import socket
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest
from conftest import REQUIRE_TOOLS

if not REQUIRE_TOOLS:  # on a user's machine without the [view] extra: skipped, with a reason
    pytest.importorskip("viser", reason="fishbot view needs the [view] extra")
import msgspec
import viser
from websockets.exceptions import InvalidStatus
from websockets.sync.client import ClientConnection, connect

from fishbot_urdf import ArgumentError, check_file
from fishbot_urdf.drawing._serving import _Origin, control_id
from fishbot_urdf.drawing.viewer import Viewer

ARM = """\
<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual></link>
  <link name="upper"><visual><geometry><box size="0.04 0.04 0.3"/></geometry></visual></link>
  <link name="wheel"><visual><geometry><sphere radius="0.05"/></geometry></visual></link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="spin" type="continuous">
    <parent link="upper"/><child link="wheel"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
  </joint>
</robot>
"""
SECONDS = 5.0  # for any one answer from the server
CAMERA = {
    "type": "ViewerCameraMessage",
    "wxyz": [1.0, 0.0, 0.0, 0.0],
    "position": [1.0, 1.0, 1.0],
    "fov": 1.0,
    "near": 0.01,
    "far": 100.0,
    "image_height": 100,
    "image_width": 100,
    "look_at": [0.0, 0.0, 0.0],
    "up_direction": [0.0, 0.0, 1.0],
}


@pytest.fixture(scope="module")
def viewer(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Viewer]:
    robot = tmp_path_factory.mktemp("requests") / "arm.urdf"
    robot.write_text(ARM, encoding="utf-8")

    def load() -> tuple[Any, tuple[str, ...]]:
        result = check_file(robot)
        return result.analysis, result.files

    shown = Viewer(load, port=0)
    yield shown
    shown.close()


def _port(viewer: Viewer) -> int:
    return int(viewer.server.get_port())


def _http(port: int, *headers: str) -> str:
    """The status line of a GET / with ``headers``, sent to 127.0.0.1."""
    request = "GET / HTTP/1.1\r\n" + "".join(f"{h}\r\n" for h in headers)
    with socket.create_connection(("127.0.0.1", port), timeout=SECONDS) as client:
        client.sendall((request + "Connection: close\r\n\r\n").encode("latin-1"))
        answer = b""
        while b"\r\n" not in answer and (chunk := client.recv(4096)):
            answer += chunk
    return answer.split(b"\r\n", 1)[0].decode("latin-1")


def _websocket(port: int, origin: str | None, host: str = "localhost") -> ClientConnection:
    """A websocket to the viewer on 127.0.0.1, sent as if to ``host`` from ``origin``."""
    sock = socket.create_connection(("127.0.0.1", port), timeout=SECONDS)
    return connect(
        f"ws://{host}:{port}",
        sock=sock,
        origin=origin,  # type: ignore[arg-type]
        subprotocols=[f"viser-v{viser.__version__}"],  # type: ignore[list-item]
        open_timeout=SECONDS,
        close_timeout=SECONDS,
    )


def _refusals(caplog: pytest.LogCaptureFixture) -> list[str]:
    return [r.getMessage() for r in caplog.records if r.name == "fishbot_urdf.drawing.viewer"]


@pytest.mark.parametrize(
    "headers",
    [
        ("Host: localhost:{port}",),
        ("Host: 127.0.0.1:{port}",),
        ("Host: [::1]:{port}",),
        ("Host: LOCALHOST:{port}", "Origin: http://localhost:{port}"),
        ("Host: localhost:{port}", "Origin: http://127.0.0.1:{port}"),
    ],
)
def test_the_page_is_served_to_its_own_origin(viewer: Viewer, headers: tuple[str, ...]) -> None:
    port = _port(viewer)
    assert _http(port, *(h.format(port=port) for h in headers)) == "HTTP/1.1 200 OK"


@pytest.mark.parametrize(
    "headers",
    [
        ("Host: localhost:{port}", "Origin: http://evil.example"),
        ("Host: localhost:{port}", "Origin: http://localhost:{port}.evil.example"),
        ("Host: localhost:{port}", "Origin: http://localhost:1"),
        ("Host: localhost:{port}", "Origin: https://localhost:{port}"),
        ("Host: localhost:{port}", "Origin: null"),
        ("Host: evil.example:{port}",),  # a name of the attacker's, pointed at 127.0.0.1
        ("Host: localhost:1",),
        ("Host: evil.example@localhost:{port}",),
        ("Host: localhost:{port}", "Host: evil.example:{port}"),
        (),
    ],
)
def test_a_request_from_another_origin_or_host_is_refused(
    viewer: Viewer, headers: tuple[str, ...], caplog: pytest.LogCaptureFixture
) -> None:
    port = _port(viewer)
    with caplog.at_level(logging.WARNING):
        assert _http(port, *(h.format(port=port) for h in headers)) == "HTTP/1.1 403 Forbidden"
    (refusal,) = _refusals(caplog)
    assert refusal.startswith("refused a request for '/': it ")


def test_a_websocket_from_another_origin_is_refused(
    viewer: Viewer, caplog: pytest.LogCaptureFixture
) -> None:
    port = _port(viewer)
    with _websocket(port, f"http://localhost:{port}") as own:
        assert own.recv(timeout=SECONDS)  # the scene comes
    with caplog.at_level(logging.WARNING):
        with pytest.raises(InvalidStatus) as forged:
            _websocket(port, "http://evil.example")
        assert forged.value.response.status_code == 403
        with pytest.raises(InvalidStatus) as rebound:
            _websocket(port, f"http://evil.example:{port}", host="evil.example")
        assert rebound.value.response.status_code == 403
    assert _refusals(caplog) == [
        "refused a websocket for '/': it comes from the page at 'http://evil.example', "
        "not this viewer's",
        f"refused a websocket for '/': it is addressed to ['evil.example:{port}'], "
        "not to this viewer",
    ]


def test_who_is_answered_when_serving_elsewhere() -> None:
    everywhere = _Origin.of("0.0.0.0", 8080)
    assert (
        everywhere.refusal(["192.168.1.5:8080"], ["http://192.168.1.5:8080"], "192.168.1.5") is None
    )
    assert everywhere.refusal(["192.168.1.5:8080"], [], "::ffff:192.168.1.5") is None
    assert everywhere.refusal(["localhost:8080"], [], "127.0.0.1") is None
    assert everywhere.refusal(["evil.example:8080"], [], "192.168.1.5")
    assert everywhere.refusal(["192.168.1.5:8080"], ["http://evil.example"], "192.168.1.5")
    assert _Origin.of("::1", 8080).refusal(["localhost:8080"], [], "::1") is None
    one = _Origin.of("192.168.1.5", 8080)
    assert one.refusal(["192.168.1.5:8080"], ["http://192.168.1.5:8080"], None) is None
    assert one.refusal(["localhost:8080"], [], "192.168.1.5")


# -- what the controls send --------------------------------------------------------------------
def _send(page: ClientConnection, uuid: str, updates: dict[str, Any]) -> None:
    page.send(
        msgspec.msgpack.encode({"type": "GuiUpdateMessage", "uuid": uuid, "updates": updates})
    )


def _wait(condition: Callable[[], Any]) -> Any:
    deadline = time.monotonic() + SECONDS
    while time.monotonic() < deadline:
        if value := condition():
            return value
        time.sleep(0.02)
    raise AssertionError("timed out")


@pytest.fixture
def page(viewer: Viewer) -> Iterator[ClientConnection]:
    """The viewer's own page, its camera sent (viser's clients count from then)."""
    port = _port(viewer)
    client = _websocket(port, f"http://localhost:{port}")
    try:
        client.send(msgspec.msgpack.encode(CAMERA))
        yield client
    finally:
        client.close()


BAD = ["abc", "nan", [1, 2], 1e308, math.nan, math.inf, True, None, {"a": 1}, 1.5, -2, 2**63]


@pytest.mark.parametrize("value", BAD, ids=repr)
def test_a_bad_slider_value_is_dropped_with_one_line(
    viewer: Viewer, page: ClientConnection, value: Any, caplog: pytest.LogCaptureFixture
) -> None:
    slider = control_id(viewer._sliders["shoulder"])
    _send(page, slider, {"value": 0.25})
    _wait(lambda: viewer.values["shoulder"] == 0.25)
    pose = tuple(viewer._frames["upper"].wxyz)
    with caplog.at_level(logging.WARNING):
        _send(page, slider, {"value": value})
        _wait(lambda: caplog.records)
        time.sleep(0.1)  # for anything else it would have logged
    (line,) = caplog.records  # one line, and nothing else (no traceback from viser)
    assert line.levelno == logging.WARNING
    assert line.getMessage().startswith("joint 'shoulder': dropped ")
    assert line.getMessage().endswith(" sent by the page (not a number within -1 .. 1)")
    assert "\n" not in line.getMessage() and line.exc_info is None
    assert viewer.values["shoulder"] == 0.25
    assert viewer._sliders["shoulder"].value == 0.25
    assert tuple(viewer._frames["upper"].wxyz) == pose


def test_a_good_slider_value_moves_its_link(viewer: Viewer, page: ClientConnection) -> None:
    slider = control_id(viewer._sliders["shoulder"])
    _send(page, slider, {"value": 0.0})
    _wait(lambda: viewer.values["shoulder"] == 0.0)
    pose = tuple(viewer._frames["upper"].wxyz)
    _send(page, slider, {"value": -1})  # its lower limit, sent as an integer
    _wait(lambda: viewer.values["shoulder"] == -1.0)
    assert tuple(viewer._frames["upper"].wxyz) != pytest.approx(pose)


def test_only_a_value_of_a_control_may_change(
    viewer: Viewer, page: ClientConnection, caplog: pytest.LogCaptureFixture
) -> None:
    frames = control_id(viewer._toggles["frames"])
    with caplog.at_level(logging.WARNING):
        _send(page, control_id(viewer._sliders["shoulder"]), {"min": -5})
        _send(page, frames, {"value": "abc"})
        _send(page, "no-such-control", {"value": 1})
        _wait(lambda: len(caplog.records) == 2)
        time.sleep(0.1)
    assert [r.getMessage() for r in caplog.records] == [
        "joint 'shoulder': dropped a change sent by the page that is not of its value alone: "
        "['min']",
        "checkbox 'Link frames': dropped 'abc' sent by the page (not true or false)",
    ]
    assert viewer._sliders["shoulder"].min == -1
    assert viewer._toggles["frames"].value is True
    _send(page, frames, {"value": False})
    _wait(lambda: viewer._toggles["frames"].value is False)
    _send(page, frames, {"value": True})
    _wait(lambda: viewer._toggles["frames"].value is True)


def test_set_takes_a_position_within_the_range_only(viewer: Viewer) -> None:
    viewer.set("spin", 2 * math.pi + 0.5)  # a continuous joint: the same angle, within -pi .. pi
    assert viewer.values["spin"] == pytest.approx(0.5)
    for value, message in [
        (math.nan, "position nan is not a finite number"),
        ("0.5", "position '0.5' is not a finite number"),
        (True, "position True is not a finite number"),
        (1.5, "position 1.5 is outside its range -1 .. 1"),
    ]:
        with pytest.raises(ArgumentError) as caught:
            viewer.set("shoulder", value)  # type: ignore[arg-type]
        assert caught.value.name == "shoulder"
        assert caught.value.rule == "argument"
        assert caught.value.message == f"joint 'shoulder': {message}"
    viewer.set("spin", 0.0)


def test_what_is_refused_is_logged_not_printed(
    viewer: Viewer, capfd: pytest.CaptureFixture[str], caplog: pytest.LogCaptureFixture
) -> None:
    port = _port(viewer)
    with caplog.at_level(logging.WARNING):
        assert _http(port, "Host: evil.example") == "HTTP/1.1 403 Forbidden"
    out, err = capfd.readouterr()
    assert (out, err) == ("", "")  # pytest's handler has it; the library printed nothing
    assert len(caplog.records) == 1
