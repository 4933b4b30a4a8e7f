"""viser's server for the viewer: bound where asked or refused with the reason, answering
only the viewer's own page, and printing nothing."""

from __future__ import annotations

import asyncio
import errno
import http
import ipaddress
import logging
import os
import reprlib
import socket
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any
from urllib.parse import urlsplit

from ..errors import InputError, ToolError, ToolNotFoundError

__all__ = ["ServeError", "authority", "control_id", "script", "serve"]

_log = logging.getLogger(
    "fishbot_urdf.drawing.viewer"
)  # the viewer's one channel for what it refuses

_LOOPBACK = frozenset({"127.0.0.1", "localhost", "::1"})
_EVERYWHERE = frozenset({"", "0.0.0.0", "::"})
_HOOK_SECONDS = 10.0  # for the server's own thread to take the checks in
shown = reprlib.Repr()
shown.maxstring = shown.maxother = 40  # a value in a log line: short, and on one line


class ServeError(InputError):
    """The viewer cannot serve on an address: ``host`` and ``port`` as given, ``reason`` in
    the system's words (not an address of this machine, a port that needs privileges, ...)."""

    def __init__(self, host: str, port: int, reason: str) -> None:
        super().__init__(f"cannot serve on {authority(host, port)}: {reason}")
        self.host = host
        self.port = port
        self.reason = reason


def _viser() -> Any:
    try:
        import viser  # the view extra (optional): ~540 ms to load
    except ImportError:
        raise ToolNotFoundError(
            "fishbot view needs the viser package",
            tool="viser",
            hint="pip install 'fishbot-urdf[view]'",
        ) from None
    return viser


def serve(host: str, port: int, accepts: Callable[[Any], bool]) -> Any:
    """A viser server on ``host`` and ``port`` (0: any free port; a port in use: the next
    free one) that answers only its own page and prints nothing.

    Args:
        host, port: Where to serve.
        accepts: Whether a change of a control the page sends (viser's ``GuiUpdateMessage``,
            with ``uuid`` and ``updates``) may reach viser; called on the server's thread.

    Raises:
        ToolNotFoundError: viser is not installed.
        ServeError: ``host`` and ``port`` cannot be served on.
        ToolError: viser is of a version whose requests cannot be checked (the server is
            stopped again).
    """
    viser = _viser()
    _probe(host, port)
    console = _console()
    with console.capture():  # viser's banner (this thread's output only)
        server = viser.ViserServer(host=host, port=port, verbose=False)
    try:
        _guard(server, _Origin.of(host, server.get_port()), accepts, console)
    except BaseException:
        server.stop()
        raise
    return server


def control_id(handle: Any) -> str:
    """The id viser gives a control on the page, as in its messages (it has no public name
    for it)."""
    return str(handle._impl.uuid)


def script(server: Any, source: str) -> None:
    """Run the JavaScript ``source`` in every page of ``server``, those open and those opened
    later (viser keeps the message for them), as viser itself sends plotly.js: it has no
    public call for it, and no other way to hear the page's keys.

    Raises:
        ToolError: viser is of a version that cannot be sent a script.
    """
    try:
        from viser._messages import RunJavascriptMessage  # viser (optional)

        server.gui._websock_interface.queue_message(RunJavascriptMessage(source=source))
    except Exception as exc:  # any surprise: a viser whose insides are not these
        raise ToolError(
            f"the viewer cannot send the page a script with this viser (version "
            f"{_viser().__version__}): {exc}",
            tool="viser",
        ) from None


def authority(host: str, port: int) -> str:
    """``host:port``, an IPv6 address in brackets."""
    return f"[{host}]:{port}" if ":" in host else f"{host}:{port}"


def _probe(host: str, port: int) -> None:
    """Bind what the server will bind (every address ``host`` names, as asyncio does) and
    let it go, to stop here with the reason: viser, when it cannot bind, tries the next
    1,000 ports and then waits forever for a server that never started. A port in use is
    left to viser, which serves on the next free one."""
    try:
        found = socket.getaddrinfo(
            host or None, port, type=socket.SOCK_STREAM, flags=socket.AI_PASSIVE
        )
    except (OSError, UnicodeError) as exc:
        raise ServeError(host, port, _reason(exc)) from None
    held: list[socket.socket] = []
    try:
        for family, kind, proto, _, address in found:
            held.append(probe := socket.socket(family, kind, proto))
            if os.name == "posix":  # as asyncio's server: a port in TIME_WAIT is free
                probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            if family == socket.AF_INET6 and hasattr(socket, "IPV6_V6ONLY"):
                probe.setsockopt(socket.IPPROTO_IPV6, socket.IPV6_V6ONLY, 1)
            try:
                probe.bind(address)
            except OSError as exc:
                if exc.errno != errno.EADDRINUSE:
                    raise
    except OSError as exc:
        raise ServeError(host, port, _reason(exc)) from None
    finally:
        for probe in held:
            probe.close()


def _reason(exc: BaseException) -> str:
    return (exc.strerror if isinstance(exc, OSError) else None) or str(exc)


def _console() -> Any:
    """rich's console, which viser prints to (stdout); its captures are per thread."""
    import rich  # comes with viser (optional)

    return rich.get_console()


def _guard(server: Any, origin: _Origin, accepts: Callable[[Any], bool], console: Any) -> None:
    """Put the viewer's checks in front of viser's own handling of the page's requests and
    messages, on the server's thread, before the robot is loaded.

    viser offers no hook for either, so two of its objects are wrapped, for this server
    alone (nothing of the process changes):

    - the websockets ``Server`` viser serves with, held by its one serving task: its
      ``process_request``, which websockets calls with every HTTP request and every
      websocket upgrade before anything else, gets the ``Host``/``Origin`` check in front of
      viser's (a connection accepted before the check, which can have had nothing of the
      robot yet, is closed);
    - the handler of GUI updates viser registers for its controls (``GuiUpdateMessage``) is
      replaced by one that lets through only the values the viewer accepts.

    The server's thread also captures what viser prints there ("Server stopped"). If
    anything is not found as expected (another viser), the viewer refuses to serve rather
    than serve unchecked.
    """
    try:
        hub = server._websock_server
        loop = hub._background_event_loop
        future = asyncio.run_coroutine_threadsafe(
            _hook(hub, server.gui, origin, accepts, console), loop
        )
        hooked = future.result(timeout=_HOOK_SECONDS)
    except Exception as exc:  # any surprise: a viser whose insides are not these
        raise ToolError(
            f"the viewer cannot check the requests of this viser (version "
            f"{_viser().__version__}): {exc}",
            tool="viser",
        ) from None
    if not hooked:
        raise ToolError(
            f"the viewer cannot check the requests of this viser (version "
            f"{_viser().__version__}): its websocket server was not found",
            tool="viser",
        )


async def _hook(
    hub: Any, gui: Any, origin: _Origin, accepts: Callable[[Any], bool], console: Any
) -> bool:
    from viser._messages import GuiUpdateMessage  # viser (optional)
    from websockets.asyncio.server import Server  # comes with viser (optional)

    console.begin_capture()  # never ended: what viser prints on this thread goes nowhere
    serving = [
        value
        for task in asyncio.all_tasks()
        for frame in _frames(task.get_coro())
        for value in frame.f_locals.values()
        if isinstance(value, Server)
    ]
    if len(serving) != 1:
        return False
    websockets_server = serving[0]
    websockets_server.process_request = _checked(websockets_server.process_request, origin)
    for connection in list(websockets_server.handlers):
        connection.transport.abort()
    viser_updates = gui._handle_gui_updates

    async def updates(client: Any, message: Any) -> None:
        if accepts(message):
            await viser_updates(client, message)

    hub.unregister_handler(GuiUpdateMessage, viser_updates)
    hub.register_handler(GuiUpdateMessage, updates)
    return True


def _frames(coroutine: Any) -> list[Any]:
    """The frames of a coroutine and of those it awaits, down the chain."""
    frames = []
    while coroutine is not None:
        frame = getattr(coroutine, "cr_frame", None)
        if frame is not None:
            frames.append(frame)
        coroutine = getattr(coroutine, "cr_await", None)
    return frames


def _checked(process_request: Any, origin: _Origin) -> Callable[[Any, Any], Any]:
    """``process_request`` behind the ``Host``/``Origin`` check (403 for a refusal)."""

    def check(connection: Any, request: Any) -> Any:
        headers = request.headers
        local = connection.local_address
        refusal = origin.refusal(
            headers.get_all("Host"),
            headers.get_all("Origin"),
            None if local is None else str(local[0]),
        )
        if refusal is not None:
            kind = "websocket" if headers.get("Upgrade", "").lower() == "websocket" else "request"
            _log.warning("refused a %s for %s: %s", kind, shown.repr(request.path), refusal)
            return connection.respond(http.HTTPStatus.FORBIDDEN, "Forbidden\n")
        return None if process_request is None else process_request(connection, request)

    return check


@dataclass(frozen=True, slots=True)
class _Origin:
    """Whom the viewer answers: requests addressed to it (``Host``) from its own page
    (``Origin``, which browsers send with every websocket and with scripts' requests).

    Attributes:
        names: The host names and addresses the page is served under, in lower case.
        port: The port served on.
        everywhere: Served on every address of the machine: the address a request came in on
            is one of its own too.
    """

    names: frozenset[str]
    port: int
    everywhere: bool = False

    @classmethod
    def of(cls, host: str, port: int) -> _Origin:
        """The origin of a server on ``host`` and ``port``: for a loopback address, all
        three spellings of it; for every address, those and this machine's name."""
        name = _normal(host.strip("[]"))
        if name in _LOOPBACK:
            return cls(_LOOPBACK, port)
        mine = frozenset({_normal(socket.gethostname())})
        if name in _EVERYWHERE:
            return cls(_LOOPBACK | mine, port, everywhere=True)
        return cls(frozenset({name}) | mine, port)

    def refusal(
        self, hosts: Sequence[str], origins: Sequence[str], local: str | None
    ) -> str | None:
        """Why a request with these ``Host`` and ``Origin`` headers, come in on address
        ``local``, is refused, or None when it is the viewer's own."""
        names = self.names | ({_normal(local)} if self.everywhere and local else set())
        if len(hosts) != 1 or _place(hosts[0], names) != self.port:
            return f"it is addressed to {shown.repr(hosts)}, not to this viewer"
        if len(origins) > 1:
            return "it has several origins"
        if origins:
            parts = _split(origins[0])
            if parts is None or parts[0] != "http" or _place(parts[1], names) != self.port:
                return f"it comes from the page at {shown.repr(origins[0])}, not this viewer's"
        return None


def _split(origin: str) -> tuple[str, str] | None:
    """An ``Origin`` header's scheme and host:port (None: none, as in "null")."""
    try:
        parts = urlsplit(origin)
    except ValueError:
        return None
    if not parts.scheme or parts.path or parts.query or parts.fragment or "@" in parts.netloc:
        return None
    return parts.scheme.lower(), parts.netloc


def _place(authority: str, names: frozenset[str] | set[str]) -> int | None:
    """The port of a ``host[:port]`` naming one of ``names`` (None: another host, or not a
    host and port at all)."""
    try:
        parts = urlsplit(f"//{authority}")
        port = parts.port
    except ValueError:
        return None
    if parts.netloc != authority or "@" in authority or parts.hostname is None:
        return None
    if _normal(parts.hostname) not in names:
        return None
    return 80 if port is None else port


def _normal(name: str) -> str:
    """A host name in lower case, an address as Python writes it (an IPv4 address mapped
    into IPv6 as IPv4)."""
    try:
        address = ipaddress.ip_address(name.split("%", 1)[0])
    except ValueError:
        return name.lower().rstrip(".")
    if isinstance(address, ipaddress.IPv6Address) and address.ipv4_mapped is not None:
        return str(address.ipv4_mapped)
    return str(address)
