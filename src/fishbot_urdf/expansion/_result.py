"""What an expansion gives: the expanded document, or the error that stopped it."""

from __future__ import annotations

from dataclasses import dataclass

from ..catalog.setup import LIMIT
from ..catalog.xacro import XACRO_ERROR
from ..diagnostics import Rule
from ..errors import FishbotUrdfError
from ..location import Location

__all__ = ["Expansion", "ExpansionLimitError", "MacroDefinition", "XacroError"]


class XacroError(FishbotUrdfError):
    """A xacro file could not be expanded.

    Attributes:
        rule: ``xacro-include`` (an include names no file), ``xacro-undefined`` (a name,
            macro, parameter or argument that is not defined), ``xacro-namespace`` (the
            ``xacro:`` prefix is not declared), ``xacro-syntax`` (not well-formed XML),
            ``xacro-circular`` (properties defined by each other), ``xacro-unsafe`` (an
            expression the allowlist refuses), ``xacro-read-outside`` (a file outside the
            folders the expansion may read), or ``xacro-error`` (anything else xacro
            refuses).
        hint: What to do, or the closest defined names.
        calls: The macro calls that led to the error, innermost first, as
            (macro name, where it was called).
    """

    rule = XACRO_ERROR.id

    def __init__(
        self,
        message: str,
        *,
        rule: Rule | None = None,
        hint: str | None = None,
        where: Location | None = None,
        calls: tuple[tuple[str, Location | None], ...] = (),
    ) -> None:
        self.rule = type(self).rule if rule is None else rule.id
        self.hint = hint
        self.calls = calls
        for name, site in calls:
            message += f", in macro {name} called from {_place(site)}"
        super().__init__(
            message,
            path=where.path if where else None,
            line=where.line if where else None,
            column=where.column if where else None,
        )


class ExpansionLimitError(XacroError):
    """An expansion was stopped by a bound: it would make more than the size limit allows
    (values, files read, elements parsed or cloned, all counted together), or take longer
    than the time limit (see :mod:`fishbot_urdf.inputs`), or one expression would pass a
    bound of its own. Its rule is ``limit``."""

    rule = LIMIT.id


@dataclass(frozen=True, slots=True)
class Expansion:
    """A xacro file expanded to URDF.

    Attributes:
        path: The input file, as named by the caller.
        text: The URDF document, exactly as the ``xacro`` command prints it.
        dependencies: Every other file the expansion read (includes, YAML), in the order
            first read.
        sources: Where each element of ``text`` was written, in document order.
        messages: The warnings xacro gave, one per entry.
    """

    path: str
    text: str
    dependencies: tuple[str, ...]
    sources: tuple[Location, ...]
    messages: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class MacroDefinition:
    """A macro defined at a document's top level (or by an include without a namespace).

    Attributes:
        name: Its name, as a call writes it after ``xacro:``.
        params: Its parameters, in order (a block parameter keeps its ``*``).
        optional: Those of ``params`` that have a default.
        source: Where its ``<xacro:macro>`` is written.
    """

    name: str
    params: tuple[str, ...]
    optional: frozenset[str]
    source: Location | None

    @property
    def required(self) -> tuple[str, ...]:
        """The parameters a call must give: those without a default, blocks aside."""
        return tuple(p for p in self.params if p not in self.optional and not p.startswith("*"))


def _place(site: Location | None) -> str:
    return "?" if site is None else f"{site.path}:{site.line}"
