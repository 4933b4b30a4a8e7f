"""The language server of `fishbot lsp`: the findings of `fishbot check` as an editor's
diagnostics as you type, their fixes as quick fixes, and each rule explained on hover, for
URDF and xacro files, and the navigation of a robot's names; a front end over the library,
like the command line."""

from __future__ import annotations

from typing import BinaryIO

from ..errors import ToolNotFoundError

__all__ = ["INSTALL", "serve"]

INSTALL = "pip install 'fishbot-urdf[lsp]'"
"""How to install what the server needs (pygls)."""


def serve(
    stdin: BinaryIO | None = None, stdout: BinaryIO | None = None, *, debounce: float = 0.075
) -> bool:
    """Serve one session over ``stdin`` and ``stdout`` (default: the process's) until the
    client says exit; True when it asked for a shutdown first, as the protocol wants.

    Args:
        stdin: Where the client's messages come from.
        stdout: Where the replies go.
        debounce: Seconds from the last change to the check.

    Raises:
        ToolNotFoundError: pygls is not installed.
    """
    try:
        # pygls, an optional part (the lsp extra), is loaded for a session only
        from ._server import make_server
    except ImportError as exc:
        if exc.name not in ("pygls", "lsprotocol") and not str(exc.name).startswith("pygls."):
            raise
        raise ToolNotFoundError(
            "the pygls package is not installed", tool="pygls", hint=INSTALL
        ) from exc
    return make_server(debounce).serve(stdin, stdout)
