"""One call for the links one line of a macro's body makes: where several links lack an
<inertial> that is written in one place, one call must fit every call of the macro."""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ..location import Location
from ._suggestions import InertialSuggestion, call_text, number_text, place_dict

__all__ = ["SharedInertial", "shared_inertials"]

# The names a parameter that carries a mass goes by: m, mass, wheel_mass, mass_kg.
_MASS_NAME = re.compile(r"(?i)m|mass|\w+_mass|mass_\w+")


@dataclass(frozen=True, slots=True)
class SharedInertial:
    """What to write once in a macro's body for the links its one <link> makes.

    The links lack an <inertial>, one per call of the macro; one call of the robot's
    inertia macro, written there, is to fit every call.

    Attributes:
        suggestions: One per link, in file order (each names its own call, ``made_by``).
        arguments: The call to write's parameters and values: the sizes as the macro's
            body writes them, the mass as ``${PARAM}`` (its parameter that carries the
            mass), or one number when every link has that mass.
        parameter: The macro's parameter that carries the mass: in every call, a number,
            and named like one (``m``, ``mass``, ``*_mass``); None when it has none.
        added: The parameter to add to the macro, when it has none and the masses
            differ: ``arguments`` then writes ``${added}`` and each call must give it.
        fits: Whether ``arguments`` gives each link its own sizes (False when the sizes
            are numbers that differ from call to call: then write each link's own call,
            which fits only that call).
    """

    suggestions: tuple[InertialSuggestion, ...]
    arguments: tuple[tuple[str, str], ...]
    parameter: str | None
    added: str | None
    fits: bool

    @property
    def source(self) -> Location | None:
        """Where the macro's body writes the <link>."""
        return self.suggestions[0].source

    @property
    def line(self) -> int | None:
        """The line to write the call at (see `InertialSuggestion.line`)."""
        return self.suggestions[0].line

    @property
    def one_site(self) -> bool:
        """Whether the calls that made the links are one line written once, in another
        macro's body (made once per call of that macro): an argument changed there
        changes it for every link."""
        sites = [s.made_by[0][1] for s in self.suggestions]
        return len(set(sites)) < len(sites)

    @property
    def macro_name(self) -> str:
        """The macro whose body makes the links."""
        return self.suggestions[0].made_by[0][0]

    @property
    def text(self) -> str:
        """The call to write, once (with a final line break)."""
        macro = self.suggestions[0].macro
        assert macro is not None
        return call_text(macro, self.arguments)

    def calls(self) -> tuple[dict[str, Any], ...]:
        """Per link: its call's site, the mass it is filled with (kg), what its call gives
        the mass parameter (as written, and its value), and what to write in the call
        instead (``mass="0.2"``) when that is not the link's mass, or when the parameter
        is to be added; None where nothing is to change, or where the call is written
        once for several links (see `one_site`; its ``outer`` call, the one that made it,
        is then where each link's mass differs)."""
        found = []
        one_site = self.one_site
        for suggestion in self.suggestions:
            _, site = suggestion.made_by[0]
            mass = suggestion.inertial.mass
            given = dict(suggestion.given).get(self.parameter or "")
            name = self.parameter or self.added
            change = None
            if (
                name is not None
                and not one_site
                and (given is None or given.number is None or not _same(given.number, mass))
            ):
                change = f'{name}="{number_text(mass)}"'
            found.append(
                {
                    "link": suggestion.link,
                    "call": site,
                    "mass": mass,
                    "argument": None if given is None else given.text,
                    "value": None if given is None else given.number,
                    "write": change,
                    "outer": suggestion.made_by[1] if len(suggestion.made_by) > 1 else None,
                }
            )
        return tuple(found)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""
        return {
            "links": [s.link for s in self.suggestions],
            "source": place_dict(self.source),
            "line": self.line,
            "macro": self.macro_name,
            "text": self.text,
            "arguments": dict(self.arguments),
            "mass_parameter": self.parameter,
            "add_parameter": self.added,
            "fits_every_call": self.fits,
            "one_site": self.one_site,
            "calls": [
                {
                    **c,
                    "call": place_dict(c["call"]),
                    "outer": None
                    if c["outer"] is None
                    else {"macro": c["outer"][0], "call": place_dict(c["outer"][1])},
                }
                for c in self.calls()
            ],
        }


def shared_inertials(suggestions: Sequence[InertialSuggestion]) -> tuple[SharedInertial, ...]:
    """The places where several of ``suggestions`` are to be written, one call for all.

    Such a place is a macro's one <link>, which makes a link per call of the macro: the
    links get one call of the robot's inertia macro that fits every call of it.

    Links written outside a macro, or the only link without an <inertial> a macro's line
    makes, or written out as an <inertial>, share with no other.
    """
    places: dict[Location, list[InertialSuggestion]] = {}
    for suggestion in suggestions:
        if suggestion.made_by and suggestion.source is not None and suggestion.macro:
            places.setdefault(Location(*suggestion.source), []).append(suggestion)
    return tuple(_shared(tuple(group)) for group in places.values() if len(group) > 1)


def _shared(group: tuple[InertialSuggestion, ...]) -> SharedInertial:
    first = group[0]
    macro = first.macro
    assert macro is not None
    parameter = _mass_parameter(group)
    masses = [s.inertial.mass for s in group]
    added = None
    if parameter is not None:
        mass_text = f"${{{parameter}}}"
    elif all(_same(m, masses[0]) for m in masses):
        mass_text = number_text(masses[0])
    else:
        taken = set(first.maker.params if first.maker else ()) | {n for n, _ in first.given}
        added = next(n for n in ("mass", "link_mass", "inertia_mass") if n not in taken)
        mass_text = f"${{{added}}}"
    # The sizes (place, turn) as the macro's body writes them fit every call; numbers fit
    # only when every call has the same.
    sizes = [dict(s.written or s.arguments) for s in group]
    for made in sizes:
        made.pop(macro.mass, None)
    fits = all(made == sizes[0] for made in sizes)
    arguments = tuple(
        (name, mass_text if name == macro.mass else value)
        for name, value in (first.written or first.arguments)
    )
    return SharedInertial(group, arguments, parameter, added, fits)


def _mass_parameter(group: Sequence[InertialSuggestion]) -> str | None:
    """The parameter of the macro that made the links that carries their mass: one that
    every call gives a number, named like a mass (one named ``mass`` or ``m`` first)."""
    named = [
        name
        for name, _ in group[0].given
        if _MASS_NAME.fullmatch(name)
        and all(
            (given := dict(s.given).get(name)) is not None and given.number is not None
            for s in group
        )
    ]
    for name in named:
        if name in ("mass", "m"):
            return name
    return named[0] if len(named) == 1 else None


def _same(a: float, b: float) -> bool:
    return math.isclose(a, b, rel_tol=1e-9)
