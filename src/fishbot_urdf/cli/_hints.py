"""Hints that name a command or an option of `fishbot`: the library's findings say what to
do in general; here they learn how to do it from the command line."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..catalog import Rule
from ..catalog.meshes import MESH_NOT_FOUND, NOTHING_DRAWN
from ..catalog.physics import (
    ABOVE_GROUND,
    BELOW_GROUND,
    INERTIA_MISMATCH,
    MASSLESS_LINK,
    MISSING_INERTIAL,
)
from ..catalog.setup import FILL_SKIPPED
from ..diagnostics import Diagnostic
from ..errors import FishbotUrdfError, ToolTimeoutError
from ..expansion import ExpansionLimitError, XacroError
from ..expansion._errors import TRUST_HINT
from ..inputs import InputTooLargeError, TimeLimitError
from ..packages import PackageNotFoundError


def phrased(finding: Diagnostic) -> Diagnostic:
    """``finding`` with the command line's way to act on it added to its hint."""
    hint = command_hint(finding)
    if hint is finding.hint:
        return finding
    d = finding
    # (as dataclasses.replace would make it, in half the time: a check may phrase thousands)
    return Diagnostic(
        d.rule, d.severity, d.message, d.path, d.line, d.column, hint, d.subject, d.data
    )


def command_hint(finding: Diagnostic) -> str | None:
    """``finding``'s hint, with the command line's way to act on it added."""
    extra = _EXTRA.get(finding.rule)
    words = extra(finding.data) if extra is not None else None
    if not words:
        return finding.hint
    return f"{finding.hint}; {words}" if finding.hint else words


def _numbers(values: Any) -> str:
    return " ".join(f"{v:g}" for v in values)


def _shape_command(data: Any) -> str | None:
    shape = data.get("shape")
    if shape is None:
        return None
    if shape == "box":
        x, y, z = data["size"]
        size = f"--size {x:g} {y:g} {z:g}"
    elif shape == "cylinder":
        size = f"--radius {data['radius']:g} --length {data['length']:g}"
    else:
        size = f"--radius {data['radius']:g}"
    words = f"{shape} --mass {data['mass']:g} {size}"
    for name in ("xyz", "rpy"):
        if any(data.get(name, ())):
            words += f" --{name} {_numbers(data[name])}"
    return f"`fishbot inertia {words}` prints the inertial of the collision"


def _tolerance(data: Any) -> str | None:
    return "change it with --ground-tolerance MM" if "tolerance_mm" in data else None


def _fill(data: Any) -> str:
    return "`fishbot inertia ROBOT --fill --density KG_PER_M3 -o OUT` writes one"


def _moments(data: Any) -> str | None:
    if "principal_moments" not in data:
        return None
    return "`fishbot inertia box|cylinder|sphere` prints those of a solid"


def _fill_skipped(data: Any) -> str | None:
    if data.get("reason") == "no-mass":
        return "give --mass LINK=KG or --density KG_PER_M3"
    return None


def _package(data: Any) -> str | None:
    package = data.get("package")
    return None if package is None else f"give its folder with --package {package}=PATH"


def _other_shapes(data: Any) -> str | None:
    """How to draw the shapes of the other kind, when the robot has some."""
    if data.get("kind") == "visual" and data.get("collisions"):
        count = data["collisions"]
        return f"`fishbot render --collision` draws its {_shapes(count, 'collision')}"
    if data.get("kind") == "collision" and data.get("visuals"):
        return (
            f"without --collision, `fishbot render` draws its {_shapes(data['visuals'], 'visual')}"
        )
    return None


def _shapes(count: int, kind: str) -> str:
    return f"{count} {kind} shape{'s' if count != 1 else ''}"


_BY_RULE: dict[Rule, Callable[[Any], str | None]] = {
    INERTIA_MISMATCH: _shape_command,
    BELOW_GROUND: _tolerance,
    ABOVE_GROUND: _tolerance,
    MISSING_INERTIAL: _fill,
    MASSLESS_LINK: _moments,
    FILL_SKIPPED: _fill_skipped,
    MESH_NOT_FOUND: _package,
    NOTHING_DRAWN: _other_shapes,
}
_EXTRA = {rule.id: words for rule, words in _BY_RULE.items()}


def error_hint(exc: FishbotUrdfError) -> tuple[str, str | None] | None:
    """The message and hint of an error that stops a command, phrased for the command line,
    or None to keep the library's."""
    if isinstance(exc, InputTooLargeError):
        return exc.message, "raise the limit with --max-size MIB"
    if isinstance(exc, ToolTimeoutError):
        return exc.message, "allow it longer with --timeout SECONDS"
    if isinstance(exc, ExpansionLimitError):
        return exc.message, "raise the limits with --timeout SECONDS and --max-size MIB"
    if isinstance(exc, TimeLimitError):
        return exc.message, "allow it longer with --timeout SECONDS"
    if isinstance(exc, XacroError) and exc.hint and exc.hint.endswith(TRUST_HINT):
        opt_in = "or, for a file you trust, run its code as Python with --trust-expressions"
        return exc.message, exc.hint.removesuffix(TRUST_HINT) + opt_in
    if isinstance(exc, PackageNotFoundError):
        places = [f"--package ({', '.join(exc.given) or 'none given'})", *exc.searched[1:]]
        return (
            f"package {exc.package!r} not found (searched: {'; '.join(places)})",
            f"name its folder with --package {exc.package}=PATH",
        )
    return None
