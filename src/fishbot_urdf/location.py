"""Where something is written: a file, a line and a column."""

from __future__ import annotations

from typing import Any, NamedTuple


class Location(NamedTuple):
    """Where an element starts in its source file (1-based line and column).

    A small immutable value like a vector, so a NamedTuple rather than a dataclass: a big
    file has hundreds of thousands of them, and tuples are made three times faster.
    """

    path: str
    line: int
    column: int


class MacroLocation(Location):
    """Where an element a xacro macro call made is written (in the macro's body), with the
    calls that made it: ``(macro name, where it was called)``, innermost first.

    It compares, hashes and prints as the plain `Location` it extends: the calls tell
    apart the elements two calls of one macro make, for the findings that name them.
    """

    calls: tuple[tuple[str, Location], ...] = ()

    def __new__(
        cls, path: str, line: int, column: int, calls: tuple[tuple[str, Location], ...] = ()
    ) -> MacroLocation:
        made = super().__new__(cls, path, line, column)
        made.calls = calls
        return made

    def __reduce__(self) -> tuple[type[MacroLocation], tuple[str, int, int, tuple[Any, ...]]]:
        return (MacroLocation, (self.path, self.line, self.column, self.calls))


def calls_of(where: Location | None) -> tuple[tuple[str, Location], ...]:
    """The macro calls that made the element written at ``where``, innermost first (none
    for an element not made by a macro call)."""
    return where.calls if isinstance(where, MacroLocation) else ()


def call_chain(calls: tuple[tuple[str, Location], ...]) -> str:
    """Macro calls, innermost first, as a finding names them: ``macro cylinder_inertia
    called at wheel.urdf.xacro:13, in macro wheel_xacro called at fishbot.urdf.xacro:60``."""
    return ", in ".join(f"macro {name} called at {site.path}:{site.line}" for name, site in calls)


def passed_through(where: Location | None) -> str:
    """For a value a macro call wrote (in the macro's body): ``, or what macro ... called at
    ... passes for it``, the place the learner edits; "" for a value written where it is."""
    calls = calls_of(where)
    if not calls:
        return ""
    return f", or what {call_chain(calls)} passes for it"
