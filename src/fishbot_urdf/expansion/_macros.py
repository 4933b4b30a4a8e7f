"""The macros a document defines at its top level, and calls of them made after its walk."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, NamedTuple
from xml.dom import minidom

from ..errors import LimitError
from ..location import Location
from ._errors import source
from ._result import MacroDefinition

__all__ = ["Argument", "MacroTable"]


class Argument(NamedTuple):
    """What a macro call gave one parameter.

    Attributes:
        text: The attribute as written in the call (``${wheel_mass}``).
        number: Its value, when it is a finite number (else None).
    """

    text: str
    number: float | None


class MacroTable:
    """The top-level macros of a document just expanded, to be called as the document's own
    top level would call them (its properties in scope), within the expansion's budget.

    Handed to the ``probe`` of :func:`fishbot_urdf.expansion.probe_macros`; it is only good
    while the probe runs.
    """

    def __init__(
        self,
        xacro: Any,
        macros: Any,
        symbols: Any,
        given: Mapping[tuple[tuple[str, Location], ...], Mapping[str, tuple[str, Any]]]
        | None = None,
    ) -> None:
        self._xacro, self._macros, self._symbols = xacro, macros, symbols
        self._given = given or {}
        self.definitions: tuple[MacroDefinition, ...] = tuple(
            MacroDefinition(
                name,
                tuple(macro.params),
                frozenset(macro.defaultmap),
                source(macro.body),
            )
            for name, macro in macros.items()
            if isinstance(macro, xacro.Macro)  # (a namespace holds the macros of an include)
        )

    def call(self, name: str, values: dict[str, str]) -> str | None:
        """What ``<xacro:NAME key="value" .../>`` makes, as XML text (its elements one after
        the other), or None when xacro refuses the call (a parameter missing or unknown,
        an expression that fails on the values).

        Raises:
            LimitError: The expansion's budget or time ran out.
        """
        x = self._xacro
        document = minidom.Document()
        holder = document.createElement("robot")
        holder.setAttribute("xmlns:xacro", "http://www.ros.org/wiki/xacro")
        document.appendChild(holder)
        call = document.createElement(f"xacro:{name}")
        for key, value in values.items():
            call.setAttribute(key, value)
        holder.appendChild(call)
        try:
            x.eval_all(holder, self._macros, x.Table(self._symbols))
        except LimitError:
            raise
        except Exception:  # xacro refuses the call, or an expression fails: it made nothing
            return None
        return "".join(child.toxml() for child in holder.childNodes)

    def written(self, where: Location) -> dict[str, str] | None:
        """The attributes, as written (``${...}`` unexpanded), of the element of a macro's
        body that is written at ``where``; None when no top-level macro's body holds one."""
        for macro in self._macros.values():
            if not isinstance(macro, self._xacro.Macro):
                continue
            for element in macro.body.getElementsByTagName("*"):
                if source(element) == where:
                    return {name: value for name, value in element.attributes.items()}
        return None

    def arguments(self, calls: tuple[tuple[str, Location], ...]) -> dict[str, Argument] | None:
        """The arguments the call at the head of ``calls`` (a `MacroLocation`'s calls,
        innermost first) gave its macro, by parameter (those left to their defaults
        aside); None for a call the expansion did not make."""
        given = self._given.get(calls)
        if given is None:
            return None
        return {name: Argument(text, _number(value)) for name, (text, value) in given.items()}


def _number(value: Any) -> float | None:
    """``value`` as a finite number, if it is one (xacro keeps a literal as its text)."""
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        return None
    try:
        number = float(value)
    except (ValueError, OverflowError):
        return None
    return number if math.isfinite(number) else None
