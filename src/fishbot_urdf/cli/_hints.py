"""Hints that name a command or an option of `fishbot`: the library's findings say what to
do in general; here they learn how to do it from the command line."""

from __future__ import annotations

from collections.abc import Callable, Iterable

from ..catalog import Rule
from ..catalog.meshes import (
    MESH_NOT_FOUND,
    MJCF_LEFT_OUT,
    NOTHING_DRAWN,
    MeshNotFoundFacts,
    MjcfLeftOutFacts,
    NothingDrawnFacts,
)
from ..catalog.physics import (
    ABOVE_GROUND,
    BELOW_GROUND,
    INERTIA_MISMATCH,
    MASSLESS_LINK,
    MISSING_INERTIAL,
    CollisionFacts,
    GroundFacts,
    MassFacts,
)
from ..catalog.setup import FILL_SKIPPED, FillFacts
from ..diagnostics import Diagnostic
from ..errors import FishbotUrdfError, ToolTimeoutError
from ..expansion import ExpansionLimitError, ReadOutsideError, XacroError
from ..expansion._errors import TRUST_HINT
from ..inputs import InputTooLargeError, TimeLimitError
from ..packages import PackageNotFoundError


def phrased(finding: Diagnostic) -> Diagnostic:
    """``finding`` with the command line's way to act on it added to its hint."""
    hint = command_hint(finding)
    return finding if hint is finding.hint else finding.with_hint(hint)


def command_hint(finding: Diagnostic) -> str | None:
    """``finding``'s hint, with the command line's way to act on it added."""
    words = _BY_RULE.get(finding.definition, _nothing)(finding.data)
    if not words:
        return finding.hint
    return f"{finding.hint}; {words}" if finding.hint else words


def _nothing(facts: object) -> None:
    return None


def _numbers(values: Iterable[float]) -> str:
    return " ".join(f"{v:g}" for v in values)


def _shape_command(facts: object) -> str | None:
    if not isinstance(facts, CollisionFacts):
        return None
    if facts.size is not None:
        x, y, z = facts.size
        size = f"--size {x:g} {y:g} {z:g}"
    elif facts.length is not None:
        size = f"--radius {facts.radius:g} --length {facts.length:g}"
    else:
        size = f"--radius {facts.radius:g}"
    words = f"{facts.shape} --mass {facts.mass:g} {size}"
    if any(facts.xyz):
        words += f" --xyz {_numbers(facts.xyz)}"
    if any(facts.rpy):
        words += f" --rpy {_numbers(facts.rpy)}"
    return f"`fishbot inertia {words}` prints the inertial of the collision"


def _tolerance(facts: object) -> str | None:
    return "change it with --ground-tolerance MM" if isinstance(facts, GroundFacts) else None


def _fill(facts: object) -> str:
    return (
        "`fishbot inertia ROBOT --fill --mass LINK=KG` says what to write and where, and "
        "with -o OUT writes a filled copy"
    )


def _moments(facts: object) -> str | None:
    if not isinstance(facts, MassFacts) or facts.principal_moments is None:
        return None
    return "`fishbot inertia box|cylinder|sphere` prints those of a solid"


def _fill_skipped(facts: object) -> str | None:
    if isinstance(facts, FillFacts) and facts.reason == "no-mass":
        return "give --mass LINK=KG or --density KG_PER_M3"
    return None


def _package(facts: object) -> str | None:
    if not isinstance(facts, MeshNotFoundFacts) or facts.package is None:
        return None
    return f"give its folder with --package {facts.package}=PATH"


def _to_a_file(facts: object) -> str | None:
    if not isinstance(facts, MjcfLeftOutFacts) or not facts.convertible:
        return None
    return "or write the MJCF to a file (-o FILE), which converts it into a folder beside it"


def _other_shapes(facts: object) -> str | None:
    """How to say where the packages not found are, and how to draw the shapes of the
    other kind, when some of them can be drawn."""
    if not isinstance(facts, NothingDrawnFacts):
        return None
    words: list[str] = []
    if facts.packages:
        given = " ".join(f"--package {package}=PATH" for package in facts.packages)
        folders = "the folder of its package" if len(facts.packages) == 1 else "their folders"
        words.append(f"give {folders} with {given}")
    if facts.kind == "visual" and facts.other_drawable:
        drawn = _shapes(facts.other_drawable, facts.collisions, "collision")
        words.append(f"`fishbot render --collision` draws {drawn}")
    if facts.kind == "collision" and facts.other_drawable:
        drawn = _shapes(facts.other_drawable, facts.visuals, "visual")
        words.append(f"without --collision, `fishbot render` draws {drawn}")
    return "; ".join(words) or None


def _shapes(count: int, every: int, kind: str) -> str:
    shapes = f"{kind} shape{'s' if every != 1 else ''}"
    return f"its {count} {shapes}" if count == every else f"{count} of its {every} {shapes}"


# What a finding of each rule can add: chosen by the finding's rule and its typed facts.
_BY_RULE: dict[Rule | None, Callable[[object], str | None]] = {
    INERTIA_MISMATCH: _shape_command,
    BELOW_GROUND: _tolerance,
    ABOVE_GROUND: _tolerance,
    MISSING_INERTIAL: _fill,
    MASSLESS_LINK: _moments,
    FILL_SKIPPED: _fill_skipped,
    MESH_NOT_FOUND: _package,
    NOTHING_DRAWN: _other_shapes,
    MJCF_LEFT_OUT: _to_a_file,
}


def error_hint(exc: FishbotUrdfError) -> tuple[str, str | None] | None:
    """The message and hint of an error that stops a command, phrased for the command line,
    or None to keep the library's."""
    if isinstance(exc, InputTooLargeError):
        return exc.message, "raise the limit with --max-size MIB"
    if isinstance(exc, ToolTimeoutError):
        return exc.message, "allow it longer with --timeout SECONDS"
    if isinstance(exc, ExpansionLimitError):  # a bound of one expression has a hint of its own
        return exc.message, exc.hint or "raise the limits with --timeout SECONDS and --max-size MIB"
    if isinstance(exc, TimeLimitError):
        return exc.message, "allow it longer with --timeout SECONDS"
    if isinstance(exc, ReadOutsideError):
        return exc.message, (
            "if the robot should read it, allow a folder that holds it with --allow-read DIR "
            "or allow-read in [tool.fishbot]"
        )
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
