"""The `Index`: what one robot's files say about names, asked by place."""

from __future__ import annotations

from ..errors import ArgumentError
from ..lint import CheckResult
from ..workspace import Workspace
from ._completion import completions
from ._hover import hover
from ._rename import renamable, rename
from ._table import Table, build
from .answers import Completion, Span

__all__ = ["Index"]


class Index:
    """Every link, joint, material, macro, property, parameter, argument and include a
    robot's files write, each place it is written, and what it is; built once per check
    result (`Index.of`) or for one file alone (`Index.of_file`).

    Places are 1-based lines and columns in characters; a query at a file the index does
    not hold answers nothing.
    """

    def __init__(self, table: Table) -> None:
        self._table = table

    @classmethod
    def of(cls, workspace: Workspace, result: CheckResult) -> Index:
        """The index of the robot ``result`` checked, its files read through ``workspace``
        (kept there until one of them changes)."""
        key = ("navigation.Index", id(result))
        made = workspace.memo(key, lambda: (result, cls._build(workspace, result)))
        if made[0] is not result:  # another result once had the same id
            return cls._build(workspace, result)
        return made[1]

    @classmethod
    def of_file(cls, workspace: Workspace, path: str) -> Index:
        """The index of one file that belongs to no robot checked: what it defines and
        uses itself."""
        return cls(build(workspace, [path], None))

    @classmethod
    def _build(cls, workspace: Workspace, result: CheckResult) -> Index:
        return cls(build(workspace, [result.path, *result.files], result.analysis))

    @property
    def files(self) -> tuple[str, ...]:
        """The files the index holds, as absolute paths."""
        return tuple(self._table.files)

    def definition(self, path: str, line: int, column: int) -> list[Span]:
        """Where the name written at the place is defined (a link's ``<link name>``, a
        macro's ``<xacro:macro name>``, an included file's start)."""
        found: list[Span] = []
        for key in dict.fromkeys(e.key for e in self._table.at(path, line, column)):
            if key[0] == "file":
                found.append(Span(key[1], 1, 1, 1, 1))
                continue
            found.extend(
                self._table.span(e) for e in self._table.by_key.get(key, ()) if e.definition
            )
        return list(dict.fromkeys(found))

    def references(
        self, path: str, line: int, column: int, *, declaration: bool = True
    ) -> list[Span]:
        """Every place the name written at the place is written (its definitions too,
        unless ``declaration`` is False), in file order."""
        found: list[Span] = []
        for key in dict.fromkeys(e.key for e in self._table.at(path, line, column)):
            for entry in self._table.by_key.get(key, ()):
                if declaration or not entry.definition:
                    found.append(self._table.span(entry))
        return sorted(dict.fromkeys(found), key=lambda s: (s.path, s.line, s.column))

    def prepare_rename(self, path: str, line: int, column: int) -> Span | None:
        """The name at the place, when renaming it can be done."""
        entries = self._table.at(path, line, column)
        try:
            renamable(self._table, entries)
        except ArgumentError:
            return None
        return self._table.span(entries[0])

    def rename_refusal(self, path: str, line: int, column: int) -> str | None:
        """Why the name at the place cannot be renamed (a name built by an expression, one
        handed to a macro by its call), or None when it can be or none is written there."""
        entries = self._table.at(path, line, column)
        if not entries:
            return None
        try:
            renamable(self._table, entries)
        except ArgumentError as exc:
            return str(exc)
        return None

    def rename(
        self, path: str, line: int, column: int, new_name: str
    ) -> dict[str, list[tuple[Span, str]]]:
        """The edits that rename the name at the place everywhere it is written, by file.

        Raises:
            ArgumentError: Nothing renamable is there, some place builds the name with an
                expression, or ``new_name`` cannot be such a name or is taken.
        """
        return rename(self._table, self._table.at(path, line, column), new_name)

    def completion(self, path: str, line: int, column: int) -> list[Completion]:
        """What may be written at the place."""
        return completions(self._table, path, line, column)

    def hover(self, path: str, line: int, column: int) -> str | None:
        """Markdown about the name at the place, or None."""
        return hover(self._table, path, line, column)
