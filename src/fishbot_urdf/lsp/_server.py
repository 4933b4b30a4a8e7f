"""The server: the protocol's messages turned into the session's changes and questions."""

from __future__ import annotations

from typing import BinaryIO

from lsprotocol import types
from pygls.exceptions import JsonRpcException
from pygls.lsp.server import LanguageServer

from .. import __version__
from . import features
from ._convert import code_actions, path_of
from ._hover import Hovers
from ._session import Session

__all__ = ["Server", "is_robot_file", "make_server"]

ROBOT_FILES = (".urdf", ".xacro")
"""The files checked as you type (``.urdf.xacro`` among them); any other file the editor
opens (a YAML file a xacro file loads) is read as the editor holds it, unchecked."""

# the files whose change on disk may change a robot's findings (meshes, YAML, manifests)
WATCHED = "**/*.{urdf,xacro,yaml,yml,toml,xml,stl,STL,dae,obj,OBJ}"


class Server:
    """The language server and its one session."""

    def __init__(self, debounce: float) -> None:
        self.server = LanguageServer(
            "fishbot", __version__, text_document_sync_kind=types.TextDocumentSyncKind.Incremental
        )
        self.session = Session(self.server, debounce)
        self.hovers = Hovers()
        _register(self)
        features.register(self.server, self.session, self.hovers)

    def serve(self, stdin: BinaryIO | None = None, stdout: BinaryIO | None = None) -> bool:
        """Serve until the client says exit; True when it asked for a shutdown first."""
        try:
            self.server.start_io(stdin, stdout)
        finally:
            self.session.stop()
        return bool(getattr(self.server.protocol, "_shutdown", True))


def make_server(debounce: float) -> Server:
    """A server whose checks start ``debounce`` seconds after the last change."""
    return Server(debounce)


def is_robot_file(path: str) -> bool:
    """Whether ``path`` is checked as you type."""
    return path.lower().endswith(ROBOT_FILES)


def _register(it: Server) -> None:
    server, session = it.server, it.session

    @server.feature(types.TEXT_DOCUMENT_DID_OPEN)
    def did_open(params: types.DidOpenTextDocumentParams) -> None:
        _hold(params.text_document.uri, params.text_document.version)

    @server.feature(types.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(params: types.DidChangeTextDocumentParams) -> None:
        _hold(params.text_document.uri, params.text_document.version)

    def _hold(uri: str, version: int) -> None:
        path = path_of(uri)
        if path is None:
            return
        text = server.workspace.get_text_document(uri).source  # the changes applied
        session.opened(path, text, version, robot=is_robot_file(path))

    @server.feature(types.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(params: types.DidCloseTextDocumentParams) -> None:
        path = path_of(params.text_document.uri)
        if path is not None:
            session.closed(path)

    @server.feature(types.TEXT_DOCUMENT_DID_SAVE)
    def did_save(params: types.DidSaveTextDocumentParams) -> None:
        path = path_of(params.text_document.uri)
        if path is not None:
            session.disk_changed([path])

    @server.feature(types.WORKSPACE_DID_CHANGE_WATCHED_FILES)
    def did_change_watched_files(params: types.DidChangeWatchedFilesParams) -> None:
        paths = [p for p in (path_of(change.uri) for change in params.changes) if p]
        if paths:
            session.disk_changed(paths)

    @server.feature(types.INITIALIZED)
    async def initialized(params: types.InitializedParams) -> None:
        watching = server.client_capabilities.workspace
        changes = watching and watching.did_change_watched_files
        if not (changes and changes.dynamic_registration):
            return
        watchers = [types.FileSystemWatcher(glob_pattern=WATCHED)]
        options = types.DidChangeWatchedFilesRegistrationOptions(watchers=watchers)
        registration = types.Registration(
            id="fishbot-watched-files",
            method=types.WORKSPACE_DID_CHANGE_WATCHED_FILES,
            register_options=options,
        )
        try:
            await server.client_register_capability_async(types.RegistrationParams([registration]))
        except JsonRpcException:  # refused: a save in the editor is still seen
            return

    @server.feature(types.TEXT_DOCUMENT_HOVER)
    async def hover(params: types.HoverParams) -> types.Hover | None:
        path = path_of(params.text_document.uri)
        return None if path is None else await it.hovers.hover(session, path, params.position)

    @server.feature(
        types.TEXT_DOCUMENT_CODE_ACTION,
        types.CodeActionOptions(code_action_kinds=[types.CodeActionKind.QuickFix]),
    )
    def code_action(params: types.CodeActionParams) -> list[types.CodeAction] | None:
        path = path_of(params.text_document.uri)
        if path is None or path in session.unheard:
            # (changed since its findings were shown: their edits' places are the old text's)
            return None
        actions: dict[tuple[str, str], types.CodeAction] = {}
        for shown in session.findings_in(path, params.range):
            for action in code_actions(shown, session.lines):
                # two calls of one macro: two findings, one fix
                actions.setdefault((action.title, repr(action.edit)), action)
        return list(actions.values())

    @server.feature(types.SHUTDOWN)
    def shutdown(params: None) -> None:
        session.stop()
