"""Where the features beyond the findings join the server: the navigation of a robot's names
(go to definition, references, rename, completion, hover over a name, the document's
symbols), made by the library, is registered with the server here."""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import TypeVar

from lsprotocol import types
from pygls.exceptions import JsonRpcException
from pygls.lsp.server import LanguageServer

from ..errors import ArgumentError, FishbotUrdfError
from ..navigation import Index, symbols
from ._answers import (
    LinesOf,
    completion_items,
    document_symbols,
    locations,
    span_range,
    workspace_edit,
)
from ._checking import index_of, lines_reader
from ._convert import path_of
from ._hover import Hovers
from ._session import Session

__all__ = ["TRIGGERS", "register"]

TRIGGERS = ["<", '"', "{", ":", "[", "(", " "]
"""What starts a completion: a tag, an attribute's value, ``${``, ``xacro:``, a
suppression's ``ignore[``, ``$(``, and ``$(arg `` or the next attribute."""

logger = logging.getLogger(__name__)

T = TypeVar("T")

Place = tuple[str, int, int]
"""A file's absolute path, a 1-based line and a character column in it."""

Question = Callable[[Index, Place, LinesOf], T]
"""What is asked of the index at a place, with each file's lines to answer in."""


def register(server: LanguageServer, session: Session, hovers: Hovers) -> None:
    """Register the navigation features with ``server``.

    Each feature is a handler of ``server`` that turns the request's URI into an absolute
    path (`_convert.path_of`) and its position into a 1-based line and character column,
    asks the library with ``session.workspace`` (the editor's unsaved texts over the disk,
    and its caches) in the session's worker (`Session.ask`: after the check under way,
    with the editor's latest texts), and converts the answer (`_answers`). A hover over a
    name is a provider added to ``hovers``, shown after the findings'. Anything that goes
    wrong answers nothing (a file that cannot be read quietly, a fault of the server's own
    logged), but a rename the library refuses, whose reason is the request's error.
    """

    async def at(path: str | None, position: types.Position, question: Question[T], empty: T) -> T:
        if path is None:
            return empty
        units = session.units()

        def asked() -> T:
            lines_of = lines_reader(session.workspace, units)
            line, column = lines_of(path).place(position)
            return question(index_of(path, session.workspace), (path, line, column), lines_of)

        try:
            answer = await session.ask(asked)
        except ArgumentError as exc:  # a rename refused: the client shows why
            raise JsonRpcException(str(exc), code=types.LSPErrorCodes.RequestFailed) from exc
        except FishbotUrdfError:  # the file is gone, or cannot be read: nothing to say
            return empty
        except Exception:  # a fault of the server's own: said, and nothing answered
            logger.exception("answering at %s:%s", path, position)
            return empty
        return empty if answer is None else answer

    @server.feature(types.TEXT_DOCUMENT_DEFINITION)
    async def definition(params: types.DefinitionParams) -> list[types.Location]:
        def found(index: Index, where: Place, lines_of: LinesOf) -> list[types.Location]:
            return locations(index.definition(*where), lines_of)

        return await at(path_of(params.text_document.uri), params.position, found, [])

    @server.feature(types.TEXT_DOCUMENT_REFERENCES)
    async def references(params: types.ReferenceParams) -> list[types.Location]:
        declaration = params.context.include_declaration

        def found(index: Index, where: Place, lines_of: LinesOf) -> list[types.Location]:
            return locations(index.references(*where, declaration=declaration), lines_of)

        return await at(path_of(params.text_document.uri), params.position, found, [])

    @server.feature(types.TEXT_DOCUMENT_PREPARE_RENAME)
    async def prepare_rename(params: types.PrepareRenameParams) -> types.Range | None:
        def name(index: Index, where: Place, lines_of: LinesOf) -> types.Range | None:
            span = index.prepare_rename(*where)
            if span is not None:
                return span_range(span, lines_of)
            refusal = index.rename_refusal(*where)
            if refusal is not None:  # a name is there: the client shows why not
                raise ArgumentError(refusal)
            return None

        return await at(path_of(params.text_document.uri), params.position, name, None)

    @server.feature(types.TEXT_DOCUMENT_RENAME)
    async def rename(params: types.RenameParams) -> types.WorkspaceEdit | None:
        def edits(index: Index, where: Place, lines_of: LinesOf) -> types.WorkspaceEdit | None:
            return workspace_edit(index.rename(*where, params.new_name), lines_of)

        return await at(path_of(params.text_document.uri), params.position, edits, None)

    @server.feature(
        types.TEXT_DOCUMENT_COMPLETION, types.CompletionOptions(trigger_characters=TRIGGERS)
    )
    async def completion(params: types.CompletionParams) -> list[types.CompletionItem]:
        def offered(index: Index, where: Place, _: LinesOf) -> list[types.CompletionItem]:
            return completion_items(index.completion(*where))

        return await at(path_of(params.text_document.uri), params.position, offered, [])

    @server.feature(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    async def document_symbol(params: types.DocumentSymbolParams) -> list[types.DocumentSymbol]:
        path = path_of(params.text_document.uri)
        if path is None:
            return []
        units = session.units()

        def outline() -> list[types.DocumentSymbol]:
            lines = lines_reader(session.workspace, units)(path)
            return document_symbols(symbols(session.workspace, path), lines)

        try:
            return await session.ask(outline) or []
        except FishbotUrdfError:  # the file is gone, or cannot be read
            return []
        except Exception:  # a fault of the server's own: said, and nothing answered
            logger.exception("the symbols of %s", path)
            return []

    async def name_hover(_: Session, path: str, position: types.Position) -> str | None:
        def said(index: Index, where: Place, _: LinesOf) -> str | None:
            return index.hover(*where)

        return await at(path, position, said, None)

    hovers.add(name_hover)
