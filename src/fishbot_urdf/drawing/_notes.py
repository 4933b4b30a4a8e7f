"""What the viewer page says besides the robot: why a load failed, and what the robot's
drawing could not show as it is."""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import replace

from ..catalog.meshes import NOTHING_DRAWN
from ..diagnostics import Diagnostic, Severity, from_error, sort_key
from ..errors import FishbotUrdfError, RobotError
from .scene import Scene

__all__ = ["failure_note", "findings_of", "viewed"]


def findings_of(exc: FishbotUrdfError) -> tuple[Diagnostic, ...]:
    """The findings that say why a load failed: a `RobotError`'s, or the error's own."""
    if isinstance(exc, RobotError) and exc.diagnostics:
        return exc.diagnostics
    return (from_error(exc),)


def failure_note(found: Sequence[Diagnostic], *, shown: bool) -> str:
    """The page's note of a failed load: what it says, and its findings' lines as they are
    printed, as code (the text is the robot's, never markup)."""
    lines = "\n".join(f.format() for f in found)
    fence = "`" * max(3, 1 + max((len(run) for run in re.findall("`+", lines)), default=0))
    kept = "The robot read last is shown" if shown else "No robot can be shown"
    return (
        f"**The robot cannot be read.** {kept} until the file is fixed:\n\n"
        f"{fence}\n{lines}\n{fence}"
    )


def viewed(visual: Scene, collision: Scene, marks: Scene) -> tuple[Diagnostic, ...]:
    """What the page cannot show as it is, once each, in the order of their places: the
    shapes not drawn as they are, each link's mass or inertia mark not drawn (``marks``,
    whatever the toggles: why a box is missing when Inertia is ticked); a robot with no
    visual shape to draw still shows its link frames (a warning here, after the findings it
    sums up), and one without collision shapes or inertials has nothing on their toggles
    (no finding)."""
    scenes = (visual, collision, marks)
    found = [f for scene in scenes for f in scene.findings if f.rule != NOTHING_DRAWN.id]
    found.sort(key=sort_key)
    found += [
        replace(f, severity=Severity.WARNING) for f in visual.findings if f.rule == NOTHING_DRAWN.id
    ]
    return tuple(dict.fromkeys(found))
