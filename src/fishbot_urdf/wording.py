"""How names are offered back in messages: the closest of several (a likely misspelling),
``did you mean``, and a short sorted listing. Below every other module, so that errors and
findings word them alike."""

from __future__ import annotations

import difflib
from collections.abc import Iterable

__all__ = ["closest", "did_you_mean", "listing"]


def closest(name: str, candidates: Iterable[str]) -> str | None:
    """The candidate that looks most like ``name`` (a likely misspelling), if any does: the
    one ``difflib.get_close_matches(name, candidates, n=1)`` gives.

    The full comparison is costly, so candidates are compared in the order of difflib's
    cheap upper bound on it, and no further once that bound is below the best found.
    """
    matcher = difflib.SequenceMatcher()
    matcher.set_seq2(name)
    bounded: list[tuple[float, str]] = []
    for candidate in set(candidates):
        matcher.set_seq1(candidate)
        if matcher.real_quick_ratio() >= _CLOSE and matcher.quick_ratio() >= _CLOSE:
            bounded.append((matcher.quick_ratio(), candidate))
    bounded.sort(reverse=True)
    best: tuple[float, str] | None = None
    for bound, candidate in bounded:
        if best is not None and bound < best[0]:
            break
        matcher.set_seq1(candidate)
        found = (matcher.ratio(), candidate)
        if found[0] >= _CLOSE and (best is None or found > best):
            best = found
    return None if best is None else best[1]


_CLOSE = 0.6  # difflib's cutoff for a close match


def did_you_mean(name: str, candidates: Iterable[str]) -> str:
    """``did you mean 'x'? `` when a candidate looks like ``name``, else ``''``."""
    close = closest(name, candidates)
    return f"did you mean {close!r}? " if close else ""


def listing(names: Iterable[str], most: int = 8) -> str:
    """Sorted names, comma-separated, the first ``most`` of them then '...'."""
    ordered = sorted(set(names))
    return ", ".join(ordered[:most]) + (", ..." if len(ordered) > most else "")
