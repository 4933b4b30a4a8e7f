"""Renaming a name everywhere it is written, or saying why it cannot be."""

from __future__ import annotations

import keyword
import re

from ..errors import ArgumentError
from ._names import Entry, Key
from ._table import Table
from .answers import Span

__all__ = ["renamable", "rename"]

RENAMABLE = frozenset({"link", "joint", "material", "macro", "property", "param", "arg"})
# A link, joint or material name that xacro and XML take as written.
_NAME = re.compile(r"[^\s\"'<>&${}]+")
_IDENTIFIER = re.compile(r"[A-Za-z_]\w*")


def renamable(table: Table, entries: list[Entry]) -> tuple[Key, list[Entry]]:
    """The name the entries at a place write and every place it is written.

    Raises:
        ArgumentError: Nothing renamable is written there, or some place builds the name
            with an expression that a text edit cannot rewrite.
    """
    keys = list(dict.fromkeys(e.key for e in entries))
    if not keys:
        raise ArgumentError(
            "no link, joint, material, macro, property, parameter or argument name is written here"
        )
    if len(keys) > 1:
        names = ", ".join(key[1] for key in keys)
        raise ArgumentError(
            f"this expression builds several names ({names}): rename the part it is built from"
        )
    key = keys[0]
    if all(entry.via for entry in entries):
        raise ArgumentError(
            f"{_kind(key)} '{key[1]}' is handed to this macro by its call: rename it there"
        )
    if key[0] not in RENAMABLE:
        raise ArgumentError(f"a {key[0]} cannot be renamed")
    every = [e for e in table.by_key.get(key, []) if not e.via]
    for entry in every:
        if not entry.literal:
            doc = table.files[entry.path].document
            line, column = doc.position(entry.start)
            written = doc.text[entry.start : entry.end]
            raise ArgumentError(
                f"{_kind(key)} '{key[1]}' is built by the expression '{written}' at "
                f"{entry.path}:{line}:{column}: a text edit cannot rename it there"
            )
    if key[0] in ("link", "joint", "material") and not any(e.definition for e in every):
        pass  # a name used but defined nowhere (a typo): its uses may still be renamed
    return key, every


def rename(table: Table, entries: list[Entry], new_name: str) -> dict[str, list[tuple[Span, str]]]:
    key, every = renamable(table, entries)
    pattern = _IDENTIFIER if key[0] in ("macro", "property", "param", "arg") else _NAME
    if not pattern.fullmatch(new_name) or keyword.iskeyword(new_name):
        what = (
            "an identifier"
            if pattern is _IDENTIFIER
            else "a name without spaces, quotes, '<', '>', '&', '$', '{' or '}'"
        )
        raise ArgumentError(f"'{new_name}' cannot name a {_kind(key)}: write {what}")
    taken = (key[0], new_name, key[2])
    if (
        new_name != key[1]
        and table.by_key.get(taken)
        and any(e.definition for e in table.by_key[taken])
    ):
        raise ArgumentError(f"{_kind(key)} '{new_name}' is already defined")
    edits: dict[str, list[tuple[Span, str]]] = {}
    for entry in sorted(every, key=lambda e: (e.path, e.start)):
        edits.setdefault(entry.path, []).append((table.span(entry), new_name))
    return edits


def _kind(key: Key) -> str:
    return {"param": f"parameter of macro {key[2]}"}.get(key[0], key[0])
