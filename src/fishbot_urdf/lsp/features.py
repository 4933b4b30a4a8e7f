"""Where the features beyond the findings join the server: the navigation of a robot's names
(go to definition, references, rename, completion, hover over a name, the document's
symbols), made by the library, is registered with the server here."""

from __future__ import annotations

from pygls.lsp.server import LanguageServer

from ._hover import Hovers
from ._session import Session

__all__ = ["register"]


def register(server: LanguageServer, session: Session, hovers: Hovers) -> None:
    """Register the navigation features with ``server``.

    Each feature is a handler of ``server`` (``@server.feature(types.TEXT_DOCUMENT_...)``)
    that turns the request's URI into an absolute path (`_convert.path_of`) and its
    position into a 1-based line and character column (``session.lines(path).place``;
    ``.position`` and `_convert.to_range` turn them back), asks the library with
    ``session.workspace`` (the editor's unsaved texts over the disk, and its caches), and
    converts the answer (`fishbot_urdf.lsp._convert` has the positions, ranges and edits).
    A hover over a name is a provider added to ``hovers``, shown after the findings'.
    Requests are answered on the event loop: a feature that may take long runs in a thread
    (``@server.thread()``). None is registered yet.
    """
    del server, session, hovers
