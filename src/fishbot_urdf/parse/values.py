"""Numbers as urdfdom reads them."""

from __future__ import annotations

import math

_TRAILING = frozenset(" \t\n\r\v\f")


def to_double(text: str) -> float | None:
    """Parse a number the way urdfdom does, or return None.

    urdfdom reads with an iostream ``>> double`` in the classic locale and requires the whole
    text to be used: leading white space is skipped, anything after the number (a unit, a
    trailing space) is refused, and so are hex, ``inf`` and ``nan``. Values that overflow to
    infinity are refused too.
    """
    try:
        value = float(text)
    except ValueError:
        return None
    # float() is more liberal than iostreams: digit separators, non-ASCII digits, trailing
    # white space, inf and nan all pass it.
    if not math.isfinite(value) or text[-1] in _TRAILING or "_" in text or not text.isascii():
        return None
    return value
