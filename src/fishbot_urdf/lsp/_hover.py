"""Hover: what several providers say about a place, joined; the first says what the rule of
a finding there is about."""

from __future__ import annotations

import inspect
from collections.abc import Awaitable, Callable

from lsprotocol import types

from ..catalog import Rule, get
from ..catalog.docs import markdown_explanation
from ..errors import FishbotUrdfError
from ._convert import Shown
from ._session import Session

__all__ = ["HoverProvider", "Hovers", "finding_hover"]

HoverProvider = Callable[[Session, str, types.Position], "str | Awaitable[str | None] | None"]
"""Markdown about a place (the session, a file's absolute path, a position in it), or None;
a provider that asks the session's worker is a coroutine function."""


class Hovers:
    """The hover providers, asked in the order added; what each says is shown, ruled off."""

    def __init__(self) -> None:
        self.providers: list[HoverProvider] = [finding_hover]

    def add(self, provider: HoverProvider) -> None:
        """Ask ``provider`` too, after those added before it."""
        self.providers.append(provider)

    async def hover(
        self, session: Session, path: str, position: types.Position
    ) -> types.Hover | None:
        """What the providers say about ``position`` in ``path``, or None."""
        parts = []
        for ask in self.providers:
            text = ask(session, path, position)
            if inspect.isawaitable(text):
                text = await text
            if text:
                parts.append(text)
        if not parts:
            return None
        markdown = types.MarkupContent(
            kind=types.MarkupKind.Markdown, value="\n\n---\n\n".join(parts)
        )
        return types.Hover(contents=markdown)


def finding_hover(session: Session, path: str, position: types.Position) -> str | None:
    """Each finding shown at ``position``: its message, and its rule explained as the rule's
    page explains it."""
    parts = []
    for shown in session.findings_at(path, position):
        parts.append(f"**{shown.diagnostic.message}**")
        rule = _rule(shown)
        if rule is not None:
            parts.append(markdown_explanation(rule).strip())
    return "\n\n".join(parts) or None


def _rule(shown: Shown) -> Rule | None:
    if shown.finding.definition is not None:
        return shown.finding.definition
    try:  # an error that stopped the reading names its rule by id
        return get(shown.finding.rule)
    except FishbotUrdfError:
        return None
