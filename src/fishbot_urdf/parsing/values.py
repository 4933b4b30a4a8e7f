"""Numbers as urdfdom reads them."""

from __future__ import annotations

import math
from collections.abc import Sequence

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


def to_doubles(texts: Sequence[str]) -> list[float] | None:
    """``to_double`` of every text when each is a number, else None; checked all at once.

    Texts that hold no white space (as the pieces of a vector split at spaces do, unless a tab
    or line break was written in) are numbers by ``to_double``'s rules exactly when ``float``
    takes each, none is infinite or nan, and none holds ``_`` or anything but ASCII.
    """
    try:
        values = list(map(float, texts))
    except ValueError:
        return None
    total = sum(values)  # inf or nan if a value is (or, rarely, if the sum overflows)
    joined = "".join(texts)
    if total - total == 0.0 and joined.isascii() and joined.isprintable() and "_" not in joined:
        return values
    checked: list[float] = []  # the rare rest, one by one
    for text in texts:
        number = to_double(text)
        if number is None:
            return None
        checked.append(number)
    return checked


def plain_numbers(texts: Sequence[str | None]) -> list[float] | None:
    """The numbers of ``texts`` when every one is a number written plainly, with no white
    space at all (nearly always); else None, and each is to be read by ``to_double``, which
    then gives these same numbers or refuses one."""
    if None in texts:
        return None
    joined = "".join(texts)  # type: ignore[arg-type]
    if not joined.isascii() or not joined.isprintable() or " " in joined or "_" in joined:
        return None
    try:
        numbers = list(map(float, texts))  # type: ignore[arg-type]
    except ValueError:
        return None
    total = sum(numbers)  # inf or nan if a number is (or, rarely, if the sum overflows)
    return numbers if total - total == 0.0 else None
