"""The navigation's answers as the protocol writes them: spans as locations and ranges, a
file's symbols as nested document symbols, completions as completion items, a rename's
edits as a workspace edit."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence

from lsprotocol import types

from ..navigation import Completion, Span, Symbol
from ._convert import Lines, to_range, uri_of

__all__ = ["completion_items", "document_symbols", "locations", "span_range", "workspace_edit"]

LinesOf = Callable[[str], Lines]
"""Each file's lines, by absolute path."""

_SYMBOLS = {
    "robot": types.SymbolKind.Module,
    "link": types.SymbolKind.Class,
    "joint": types.SymbolKind.Interface,
    "material": types.SymbolKind.Object,
    "macro": types.SymbolKind.Function,
    "property": types.SymbolKind.Property,
    "arg": types.SymbolKind.Variable,
    "include": types.SymbolKind.File,
}

_COMPLETIONS = {
    "link": types.CompletionItemKind.Class,
    "joint": types.CompletionItemKind.Interface,
    "material": types.CompletionItemKind.Color,
    "macro": types.CompletionItemKind.Function,
    "parameter": types.CompletionItemKind.Variable,
    "property": types.CompletionItemKind.Property,
    "arg": types.CompletionItemKind.Variable,
    "element": types.CompletionItemKind.Keyword,
    "attribute": types.CompletionItemKind.Field,
    "rule": types.CompletionItemKind.EnumMember,
}


def span_range(span: Span, lines_of: LinesOf) -> types.Range:
    """The range of ``span`` in the client's units."""
    return to_range(lines_of(span.path), span.line, span.column, span.end_line, span.end_column)


def locations(spans: Iterable[Span], lines_of: LinesOf) -> list[types.Location]:
    """Each span as a location."""
    return [types.Location(uri_of(s.path), span_range(s, lines_of)) for s in spans]


def workspace_edit(
    edits: Mapping[str, Sequence[tuple[Span, str]]], lines_of: LinesOf
) -> types.WorkspaceEdit:
    """A rename's edits, by file."""
    changes = {
        uri_of(path): [types.TextEdit(span_range(span, lines_of), text) for span, text in pairs]
        for path, pairs in edits.items()
    }
    return types.WorkspaceEdit(changes=changes)


def document_symbols(symbols: Iterable[Symbol], lines: Lines) -> list[types.DocumentSymbol]:
    """A file's symbols, each with what it holds as its children."""
    return [_document_symbol(symbol, lines) for symbol in symbols]


def _document_symbol(symbol: Symbol, lines: Lines) -> types.DocumentSymbol:
    whole = _range(symbol.span, lines)
    selection = _range(symbol.selection, lines)
    if not (_key(whole.start) <= _key(selection.start) <= _key(selection.end) <= _key(whole.end)):
        selection = types.Range(whole.start, whole.start)  # the protocol wants it inside
    return types.DocumentSymbol(
        name=symbol.name or symbol.kind,  # the protocol wants a name
        kind=_SYMBOLS.get(symbol.kind, types.SymbolKind.Object),
        range=whole,
        selection_range=selection,
        detail=symbol.detail or None,
        children=document_symbols(symbol.children, lines) or None,
    )


def _range(span: Span, lines: Lines) -> types.Range:
    return to_range(lines, span.line, span.column, span.end_line, span.end_column)


def _key(position: types.Position) -> tuple[int, int]:
    return (position.line, position.character)


def completion_items(completions: Iterable[Completion]) -> list[types.CompletionItem]:
    """Each completion as a completion item (its documentation as Markdown)."""
    return [
        types.CompletionItem(
            label=c.label,
            kind=_COMPLETIONS.get(c.kind, types.CompletionItemKind.Text),
            detail=c.detail or None,
            documentation=(
                types.MarkupContent(kind=types.MarkupKind.Markdown, value=c.documentation)
                if c.documentation
                else None
            ),
            insert_text=c.insert_text,
        )
        for c in completions
    ]
