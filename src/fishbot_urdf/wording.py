"""How names are offered back in messages: the closest of several (a likely misspelling),
``did you mean``, and a short listing, the names most like the one asked for first. Below
every other module, so that errors and findings word them alike."""

from __future__ import annotations

import re
from collections.abc import Iterable

__all__ = ["closest", "did_you_mean", "listing", "ranked"]


def closest(name: str, candidates: Iterable[str]) -> str | None:
    """The candidate that looks most like ``name`` (a likely misspelling), if any does.

    Alike are, best first: the same name in other case; the same name but for a ROS
    suffix, ``_link``, ``_joint`` or ``_frame`` (``imu`` and ``imu_link``); then a name a
    few edits away (letters put in, left out, changed or swapped: at most one edit in four
    letters, so that ``wheel_radus`` finds ``wheel_radius`` but ``wheel_radius`` does not
    find ``wheel_name``, which shares only its first word). Ties go to the name nearest in
    length, then the first in sorted order.
    """
    close = _close(name, candidates)
    return close[0] if close else None


def ranked(name: str, candidates: Iterable[str]) -> list[str]:
    """The candidates like ``name``, most alike first: those `closest` would offer, then
    those sharing a word with it (``left_wheel`` and ``right_wheel_link``), those sharing
    more words and nearer in length first."""
    unique = set(candidates)
    close = _close(name, unique)
    words = set(_words(name)) - _SUFFIXES
    sharing = []
    if words:
        for candidate in unique.difference(close):
            shared = len(words.intersection(_words(candidate)))
            if shared:
                sharing.append((-shared, abs(len(candidate) - len(name)), candidate))
    return close + [candidate for *_, candidate in sorted(sharing)]


def did_you_mean(name: str, candidates: Iterable[str]) -> str:
    """``did you mean 'x'? `` when a candidate looks like ``name``, else ``''``."""
    close = closest(name, candidates)
    return f"did you mean {close!r}? " if close else ""


def listing(names: Iterable[str], most: int = 8, *, near: str | None = None) -> str:
    """The names, comma-separated, at most ``most`` of them, then how many more there are:
    sorted, or, ``near`` a name, those like it first (see `ranked`), then the others
    sorted."""
    ordered = sorted(set(names))
    if near is not None:
        first = ranked(near, ordered)
        placed = set(first)
        ordered = first + [n for n in ordered if n not in placed]
    shown = ", ".join(ordered[:most])
    more = len(ordered) - most
    return f"{shown}, ... ({more} more)" if more > 0 else shown


_SUFFIXES = frozenset({"link", "joint", "frame"})  # ROS names of one part differ by these
_WORDS = re.compile(r"[^_\-./ ]+")


def _words(name: str) -> list[str]:
    return _WORDS.findall(name.lower())


def _stem(name: str) -> str:
    """``name`` in lower case, without a ROS suffix (``imu_link`` -> ``imu``)."""
    return _SUFFIX.sub("", name.lower(), count=1)


_SUFFIX = re.compile(r"(?<=.)[_-](?:link|joint|frame)$")


def _close(name: str, candidates: Iterable[str]) -> list[str]:
    """The candidates like ``name``, best first (see `closest`)."""
    low, stem = name.lower(), _stem(name)
    letters, stem_letters = set(low), set(stem)
    found: list[tuple[int, int, int, str]] = []
    for candidate in set(candidates):
        other = candidate.lower()
        gap = abs(len(candidate) - len(name))
        if other == low:
            found.append((0, 0, gap, candidate))
            continue
        other_stem = _stem(candidate)
        if other_stem == stem:
            found.append((1, 0, gap, candidate))
            continue
        # As many edits as one in four letters of the longer, not counting a ROS suffix:
        # two names that share one differ in what comes before it.
        allowed = max(1, max(len(stem), len(other_stem)) // 4)
        if min(gap, abs(len(other_stem) - len(stem))) > allowed:
            continue  # each letter more or fewer is an edit
        if (
            len(letters.symmetric_difference(other)) > 2 * allowed
            and len(stem_letters.symmetric_difference(other_stem)) > 2 * allowed
        ):
            continue  # an edit brings in, or takes away, at most one letter of each name
        edits = min(_distance(low, other, allowed), _distance(stem, other_stem, allowed))
        if edits <= allowed:
            found.append((2, edits, gap, candidate))
    return [candidate for *_, candidate in sorted(found)]


def _distance(a: str, b: str, bound: int) -> int:
    """The optimal string alignment distance of ``a`` and ``b``, or ``bound + 1`` once it
    is sure to be more than ``bound`` (names far apart cost little to turn down)."""
    if abs(len(a) - len(b)) > bound:
        return bound + 1
    before: list[int] = []
    previous = list(range(len(b) + 1))
    for i, x in enumerate(a, 1):
        row = [i] + [0] * len(b)
        for j, y in enumerate(b, 1):
            cost = 0 if x == y else 1
            row[j] = min(previous[j] + 1, row[j - 1] + 1, previous[j - 1] + cost)
            if i > 1 and j > 1 and x == b[j - 2] and a[i - 2] == y:
                row[j] = min(row[j], before[j - 2] + 1)
        if min(row) > bound:
            return bound + 1
        before, previous = previous, row
    return previous[-1]
