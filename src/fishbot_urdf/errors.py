"""The exception tree of fishbot_urdf: every error the library raises is a FishbotUrdfError."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

from .wording import did_you_mean, listing

if TYPE_CHECKING:
    from .diagnostics import Diagnostic


class FishbotUrdfError(Exception):
    """Base class of every error raised by fishbot_urdf.

    Attributes:
        path: The file the error is about, or None for text that came from memory.
        line: 1-based line in ``path``, when known.
        column: 1-based column in ``path``, when known.
        rule: A short stable id for the kind of problem (``xml-syntax``, ``io``, ...).
    """

    rule = "error"

    def __init__(
        self,
        message: str,
        *,
        path: str | None = None,
        line: int | None = None,
        column: int | None = None,
    ) -> None:
        super().__init__(message)
        self.message = message
        self.path = path
        self.line = line
        self.column = column

    def __str__(self) -> str:
        where = ":".join(str(p) for p in (self.path, self.line, self.column) if p is not None)
        return f"{where}: {self.message}" if where else self.message


class InputError(FishbotUrdfError):
    """A file could not be read: it does not exist, is a folder, or is not readable."""

    rule = "io"


class LimitError(FishbotUrdfError):
    """A bound was reached: the work would take longer than the time limit, or need more
    memory or items than a limit allows (see :mod:`fishbot_urdf.inputs`)."""

    rule = "limit"


class ToolError(FishbotUrdfError):
    """A program the job runs (Graphviz's `dot`) failed; ``tool`` names it."""

    rule = "tool-failed"

    def __init__(
        self, message: str, *, tool: str, hint: str | None = None, path: str | None = None
    ) -> None:
        super().__init__(message, path=path)
        self.tool = tool
        self.hint = hint


class ToolTimeoutError(ToolError):
    """A program the job runs did not finish within ``seconds`` and was stopped."""

    def __init__(self, message: str, *, tool: str, seconds: float, path: str | None = None) -> None:
        super().__init__(message, tool=tool, path=path)
        self.seconds = seconds


class ToolNotFoundError(ToolError):
    """A program the job needs is not installed; ``hint`` says how to install it."""

    rule = "tool-missing"


class XmlSyntaxError(FishbotUrdfError):
    """The input is not well-formed XML (or uses XML features URDF never needs, like entities)."""

    rule = "xml-syntax"


class RobotError(FishbotUrdfError):
    """The robot description has errors; ``diagnostics`` lists every one of them."""

    rule = "invalid-robot"

    def __init__(self, diagnostics: Sequence[Diagnostic], *, path: str | None = None) -> None:
        self.diagnostics = tuple(diagnostics)
        first = self.diagnostics[0] if self.diagnostics else None
        count = len(self.diagnostics)
        summary = f"{first.message} [{first.rule}]" if first is not None else "invalid robot"
        if count > 1:
            summary += f" (and {count - 1} more)"
        super().__init__(
            summary,
            path=path if first is None else first.path,
            line=None if first is None else first.line,
            column=None if first is None else first.column,
        )


class StructureError(FishbotUrdfError):
    """The robot's links do not form the tree a question needs.

    No root, several roots (``roots`` lists them), or two links that are not connected."""

    rule = "structure"

    def __init__(self, message: str, *, roots: tuple[str, ...] = ()) -> None:
        super().__init__(message)
        self.roots = roots


class UnknownNameError(FishbotUrdfError, KeyError):
    """A name (of a link, a joint, a rule, ...) that is not known.

    Attributes:
        kind: What was looked for (``link``, ``joint``, ``rule``).
        name: The name given.
        known: Every name that is known, sorted.
    """

    rule = "unknown-name"

    def __init__(self, kind: str, name: str, known: Iterable[str]) -> None:
        self.kind = kind
        self.name = name
        self.known = tuple(sorted(set(known)))
        hint = did_you_mean(name, self.known)
        listed = (
            f"{kind}s: {listing(self.known, near=name)}" if self.known else f"there are no {kind}s"
        )
        super().__init__(f"no {kind} {name!r} ({hint}{listed})")


class ArgumentError(FishbotUrdfError, ValueError):
    """An argument a function was given is out of its range (``name`` names it)."""

    rule = "argument"

    def __init__(self, message: str, *, name: str | None = None) -> None:
        super().__init__(message)
        self.name = name


class ConversionError(FishbotUrdfError, ValueError):
    """A robot the target's own converter, or the reader of what it writes, refuses.

    ``target`` names the format (``sdf``), ``subject`` the link or joint at fault (None for
    the whole robot); ``path``, ``line`` and ``column`` where the value at fault is written,
    when it is known."""

    rule = "conversion"

    def __init__(
        self,
        message: str,
        *,
        target: str,
        subject: str | None = None,
        path: str | None = None,
        line: int | None = None,
        column: int | None = None,
    ) -> None:
        super().__init__(message, path=path, line=line, column=column)
        self.target = target
        self.subject = subject


class ShapeError(FishbotUrdfError, ValueError):
    """A shape has no volume to fill.

    An open mesh, a shape of size zero, or a geometry no formula covers."""

    rule = "shape"


class InertiaUnderflowError(ShapeError):
    """A shape too small for its inertia to be a float.

    A moment that is positive comes out 0, or below the smallest normal float (2.2e-308
    kg*m^2), where precision is lost.

    Attributes:
        shape: ``box``, ``cylinder``, ``sphere`` or ``mesh``.
        sizes: Each size given, as (name, metres): ``("radius", 1e-200)``.
        mass: The mass given (kg).
        moments: ixx, iyy and izz as they come out (kg*m^2).
    """

    def __init__(
        self,
        shape: str,
        sizes: tuple[tuple[str, float], ...],
        mass: float,
        moments: tuple[float, float, float],
        *,
        path: str | None = None,
    ) -> None:
        self.shape = shape
        self.sizes = sizes
        self.mass = mass
        self.moments = moments
        given = ", ".join(f"{name} {value:g} m" for name, value in sizes)
        super().__init__(
            f"the {shape}'s inertia underflows to {min(moments):g} kg*m^2 ({given}, mass "
            f"{mass:g} kg): too small for a float; give a larger size or mass",
            path=path,
        )


class ConfigError(FishbotUrdfError):
    """A configuration file or option is wrong.

    An unknown rule or key, or a value of the wrong type. ``path`` and ``line`` say where,
    when it came from a file.

    Attributes:
        key: The setting at fault (``select``, ``ignore``, ``severity``), when one is.
        problem: What is wrong with it; the message is ``key: problem``.
    """

    rule = "config"

    def __init__(
        self,
        problem: str,
        *,
        key: str | None = None,
        path: str | None = None,
        line: int | None = None,
        column: int | None = None,
    ) -> None:
        self.key = key
        self.problem = problem
        message = problem if key is None else f"{key}: {problem}"
        super().__init__(message, path=path, line=line, column=column)


class FieldTypeError(FishbotUrdfError, TypeError):
    """A field of a model built in Python holds a value of the wrong type.

    A str where a number is expected, a list where a tuple is, an int where a `JointType`
    is.

    Attributes:
        field: Where the value is, from the robot down (``robot.links[0].inertial.mass``).
        expected: What the field takes (``a number (int or float)``).
        value: The value found there.
    """

    rule = "field-type"

    def __init__(self, field: str, expected: str, value: object) -> None:
        self.field = field
        self.expected = expected
        self.value = value
        try:
            shown = " " + repr(value)
        except Exception:  # a value whose repr fails is still named by its type
            shown = ""
        if len(shown) > 41:
            shown = shown[:38] + "..."
        super().__init__(f"{field} is {type(value).__name__}{shown}, not {expected}")
