"""How big what a xacro expression makes may grow: sizes measured before values are made.

A value is bounded before it is made wherever its size can be known first: whole numbers
by their bits (``**``, ``*``, ``<<``, ``math.prod``), strings and lists by their items
(``*``, ``+``, padding, ``replace``, ``expandtabs``, ``join``, ``%`` and ``format``
widths), ``range`` by its length, ``math.factorial``, ``comb`` and ``perm`` by their
arguments; a value made of shared parts by what it holds when written out.
"""

from __future__ import annotations

import ast
import functools
import re
import string
from collections.abc import Callable, Iterable, Mapping
from typing import Any

from ..catalog.xacro import XACRO_UNSAFE
from ..errors import FishbotUrdfError

__all__ = [
    "CONTAINERS",
    "MAX_BITS",
    "MAX_COUNT",
    "MAX_ITEMS",
    "SIZED",
    "UnsafeExpression",
    "binary_size",
    "binary_steps",
    "bounded_count",
    "bounded_lcm",
    "bounded_prod",
    "bounded_range",
    "bounded_sum",
    "call_steps",
    "check_binary",
    "check_format",
    "check_printf",
    "check_spec",
    "check_str_method",
    "too_big",
    "too_long",
    "weight",
]

MAX_ITEMS = 10_000_000
"""The longest string or list, and the most items of a range, one value may have."""
MAX_BITS = 1_000_000
"""The largest whole number one expression may make, in bits (about 300,000 digits)."""
MAX_COUNT = 100_000
"""The largest argument of ``math.factorial``, ``comb`` and ``perm``."""


class UnsafeExpression(FishbotUrdfError):
    """An expression was refused.

    Attributes:
        expression: The expression, as written (empty while it is not known yet).
        what: What was refused: a construct (``attribute '__class__'``), or, with
            ``too_big``, the value it would have made, or, with ``too_long``, the work.
        too_big: A value past the bounds, not a construct refused.
        too_long: Work past the step budget, not a construct refused.
    """

    rule = XACRO_UNSAFE.id

    def __init__(
        self, expression: str, what: str, *, too_big: bool = False, too_long: bool = False
    ) -> None:
        if too_big:
            said = f"would make {what}"
        elif too_long:
            said = f"takes {what}"
        else:
            said = f"{what} is not allowed"
        super().__init__(f"{said} in an expression")
        self.expression = expression
        self.what = what
        self.too_big = too_big
        self.too_long = too_long

    def named(self, expression: str) -> UnsafeExpression:
        """The same refusal, naming the whole expression."""
        return UnsafeExpression(expression, self.what, too_big=self.too_big, too_long=self.too_long)


def too_big(what: str) -> UnsafeExpression:
    """A refusal of a value past the bounds."""
    return UnsafeExpression("", what, too_big=True)


CONTAINERS = (list, tuple, dict, set, frozenset)
SIZED = (str, bytes, *CONTAINERS)


# -- what a format may do -------------------------------------------------------------------
_FIELD = re.compile(r"\d*|[^\W\d]\w*")
_WIDTHS = re.compile(r"(\d+)")


def check_format(
    template: str, args: Iterable[Any] = (), kwargs: Mapping[str, Any] | None = None
) -> None:
    """Refuse a ``str.format`` template whose fields read an attribute or an item, at any
    depth of nested specs, or whose widths and precisions would pass :data:`MAX_ITEMS`:
    a width taken from an argument (``'{0:>{1}}'``) as well as one written in it, each
    looked at before its field is made.

    Raises:
        UnsafeExpression: The template is refused.
    """
    for _ in _fields(template):
        pass  # refuses a field that reads an attribute or an item
    sizing = _Sizing()
    try:
        sizing.vformat(template, tuple(args), dict(kwargs or {}))
    except UnsafeExpression:
        raise
    except Exception:  # str.format refuses it too, and says why
        pass


class _Sizing(string.Formatter):
    """Goes through a template as ``str.format`` does, nested fields resolved, and refuses
    it as soon as its fields would pass :data:`MAX_ITEMS` in all, before each is made."""

    def __init__(self) -> None:
        self.total = 0

    def format_field(self, value: Any, format_spec: str) -> str:
        size = _spec_size(format_spec) + _size(value)
        if any(len(n) >= 12 for n in _WIDTHS.findall(format_spec)):
            size = MAX_ITEMS + 1
        self.total += size
        if self.total > MAX_ITEMS:
            raise too_big(f"a value of more than {MAX_ITEMS:,} items")
        return str(format(value, format_spec))

    def check_unused_args(self, used_args: Any, args: Any, kwargs: Any) -> None:
        return None


def _fields(template: str, depth: int = 0) -> Iterable[str]:
    try:
        parsed = list(string.Formatter().parse(template))
    except ValueError:
        return  # str.format refuses it before reading anything
    for _, field, spec, _ in parsed:
        if field is None:
            continue
        if not _FIELD.fullmatch(field):
            raise UnsafeExpression("", f"the format field '{{{field}}}'")
        if spec:
            if depth > 1:  # str.format allows two levels; let it say so
                continue
            yield spec
            yield from _fields(spec, depth + 1)


def _spec_size(spec: str) -> int:
    return sum(int(number) for number in _WIDTHS.findall(spec) if len(number) < 12) if spec else 0


def check_spec(spec: str) -> None:
    """Refuse a format spec (an f-string's) whose widths would pass :data:`MAX_ITEMS`."""
    if any(len(n) >= 12 or int(n) > MAX_ITEMS for n in _WIDTHS.findall(spec)):
        raise too_big(f"a value of more than {MAX_ITEMS:,} items")


_PRINTF = re.compile(r"%(?:\([^)]*\))?[-#0 +]*(\*|\d+)?(?:\.(\*|\d+))?")


def check_printf(template: str | bytes, values: Any) -> None:
    """Refuse ``template % values`` when its widths and precisions would pass
    :data:`MAX_ITEMS` (``*`` takes its width from the values)."""
    text = template if isinstance(template, str) else template.decode("latin-1")
    given = values if isinstance(values, tuple) else (values,)
    total = len(text) + sum(_size(v) for v in given)
    starred = False
    for match in _PRINTF.finditer(text):
        for number in match.groups():
            if number == "*":
                starred = True
            elif number:
                total += int(number) if len(number) < 12 else MAX_ITEMS + 1
    if starred:
        total += sum(abs(v) for v in given if type(v) is int and abs(v) <= 10 * MAX_ITEMS)
        total += sum(MAX_ITEMS for v in given if type(v) is int and abs(v) > 10 * MAX_ITEMS)
    if total > MAX_ITEMS:
        raise too_big(f"a value of more than {MAX_ITEMS:,} items")


def _size(value: Any) -> int:
    return len(value) if isinstance(value, str | bytes) else 24


# -- bounded functions ----------------------------------------------------------------------
def bounded_range(function: Callable[..., Any]) -> Callable[..., Any]:
    """xacro's ``range`` (the deprecated one keeps its warning), up to ``MAX_ITEMS`` items:
    making a range is quick, going through ``range(10**12)`` is not."""

    @functools.wraps(function)
    def run(*args: Any) -> range:
        made: range = function(*args)
        if len(made) > MAX_ITEMS:
            raise too_big(f"a range of more than {MAX_ITEMS:,} items")
        return made

    return run


def bounded_count(function: Callable[..., Any], name: str) -> Callable[..., Any]:
    """``math.factorial``, ``comb`` and ``perm`` up to ``MAX_COUNT``: past it they run for
    minutes."""

    @functools.wraps(function)
    def run(*args: Any) -> Any:
        if any(isinstance(a, int) and a > MAX_COUNT for a in args):
            raise too_big(f"a math.{name} of a number past {MAX_COUNT:,}")
        return function(*args)

    return run


def bounded_prod(function: Callable[..., Any]) -> Callable[..., Any]:
    """``math.prod``, its whole numbers' bits added up before it multiplies them."""

    @functools.wraps(function)
    def run(iterable: Iterable[Any], *, start: Any = 1) -> Any:
        items = list(iterable)
        bits = sum(abs(v).bit_length() for v in (*items, start) if isinstance(v, int))
        if bits > MAX_BITS:
            raise too_big(f"a number of more than {MAX_BITS:,} bits")
        return function(items, start=start)

    return run


def bounded_lcm(function: Callable[..., Any]) -> Callable[..., Any]:
    @functools.wraps(function)
    def run(*args: Any) -> Any:
        if sum(abs(v).bit_length() for v in args if isinstance(v, int)) > MAX_BITS:
            raise too_big(f"a number of more than {MAX_BITS:,} bits")
        return function(*args)

    return run


def bounded_sum(function: Callable[..., Any]) -> Callable[..., Any]:
    """``sum``: numbers as Python adds them; lists, tuples and strings (``sum(x, [])``
    copies at every step) with the length checked at every step."""

    @functools.wraps(function)
    def run(iterable: Iterable[Any], start: Any = 0) -> Any:
        if not isinstance(start, list | tuple | str | bytes):
            return function(iterable, start)
        total = start
        for item in iterable:
            if isinstance(item, list | tuple | str | bytes) and len(total) + len(item) > MAX_ITEMS:
                raise too_big(f"a value of more than {MAX_ITEMS:,} items")
            total = total + item
        return total

    return run


def check_binary(kind: type[ast.operator], a: Any, b: Any) -> None:
    """Refuse ``a op b`` when it would make a value past the bounds, before it does."""
    whole = isinstance(a, int) and isinstance(b, int)
    if kind is ast.Pow:
        if whole and b > 0 and abs(a) > 1 and b * (abs(a).bit_length() - 1) > MAX_BITS:
            raise too_big(f"a number of more than {MAX_BITS:,} bits")
    elif kind is ast.LShift:
        if whole and a and b > MAX_BITS:
            raise too_big(f"a number of more than {MAX_BITS:,} bits")
    elif kind is ast.Mult:
        for sequence, count in ((a, b), (b, a)):
            repeated = isinstance(sequence, SIZED) and isinstance(count, int)
            if repeated and len(sequence) * count > MAX_ITEMS:
                raise too_big(f"a value of more than {MAX_ITEMS:,} items")
        if whole and a.bit_length() + b.bit_length() > MAX_BITS:
            raise too_big(f"a number of more than {MAX_BITS:,} bits")
    elif kind is ast.Add and too_long(a, b):
        raise too_big(f"a value of more than {MAX_ITEMS:,} items")


def too_long(a: Any, b: Any) -> bool:
    """Whether ``a`` and ``b`` together hold more than :data:`MAX_ITEMS` items."""
    return isinstance(a, SIZED) and isinstance(b, SIZED) and len(a) + len(b) > MAX_ITEMS


# -- what an operation costs ----------------------------------------------------------------
_DIGIT = 30  # bits in one of CPython's digits
_MULTIPLY = 4096  # digit products per step when multiplying (measured: 1M x 500k bits, 60 ms)
_DIVIDE = 2000  # digit products per step when dividing (measured: 1M / 500k bits, 270 ms)
_QUADRATIC = frozenset(
    """comb divmod factorial gcd isqrt lcm perm pow prod round""".split()  # noqa: SIM905
)


def _digits(value: Any) -> int:
    return abs(value).bit_length() // _DIGIT + 1 if isinstance(value, int) else 1


def binary_steps(kind: type[ast.operator], a: Any, b: Any) -> int:
    """The steps ``a op b`` takes: one for small values; for whole numbers, by their size
    (multiplying and dividing go by the product of their digits); for a string or a list
    made or joined, by its length."""
    if isinstance(a, int) and isinstance(b, int):
        da, db = _digits(a), _digits(b)
        if da + db < 64:
            return 1
        if kind is ast.Mult:
            return da * db // _MULTIPLY + 1
        if kind in (ast.FloorDiv, ast.Mod, ast.Div):
            return da * db // _DIVIDE + 1
        if kind is ast.Pow:
            # the digits of the result; its last squaring dominates
            made = max(0, b) * abs(a).bit_length() // _DIGIT + 1
            return made * made // (2 * _MULTIPLY) + 1
        return (da + db) // 64 + 1
    return _items_made(kind, a, b) // 64 + 1


def binary_size(kind: type[ast.operator], a: Any, b: Any) -> int:
    """About how many bytes ``a op b`` makes (checked against the bounds before it is
    made, by :func:`check_binary`)."""
    if isinstance(a, int) and isinstance(b, int):
        bits = max(abs(a).bit_length(), abs(b).bit_length())
        if kind is ast.Mult:
            bits = abs(a).bit_length() + abs(b).bit_length()
        elif kind is ast.Pow and b > 0:
            bits = b * abs(a).bit_length()
        elif kind is ast.LShift and b > 0:
            bits += b
        return bits // 8 + 28
    made = _items_made(kind, a, b)
    if isinstance(a, list | tuple) or isinstance(b, list | tuple):
        return 8 * made + 56
    return made + 48


def _items_made(kind: type[ast.operator], a: Any, b: Any) -> int:
    if kind is ast.Mult:
        for sequence, count in ((a, b), (b, a)):
            if isinstance(sequence, SIZED) and isinstance(count, int):
                return len(sequence) * max(0, count)
    if kind is ast.Add and isinstance(a, SIZED) and isinstance(b, SIZED):
        return len(a) + len(b)
    if kind is ast.Mod and isinstance(a, str | bytes):
        return len(a) + sum(_size(v) for v in (b if isinstance(b, tuple) else (b,)))
    return 0


def call_steps(name: str | None, args: Iterable[Any]) -> int:
    """The steps a function of the allowlist takes on whole numbers, by their size: the
    ones that divide or multiply (``divmod``, ``round`` to tens, ``math.gcd``, ...) by the
    square of the digits of the largest; any other, by its digits."""
    digits = max((_digits(a) for a in args if isinstance(a, int)), default=1)
    if digits < 64:
        return 0
    if name in _QUADRATIC:
        return digits * digits // _DIVIDE + 1
    return digits // 64 + 1


def check_str_method(
    name: str, owner: str | bytes, args: list[Any], kwargs: dict[str, Any]
) -> None:
    """Refuse a method of a string (or bytes) whose result would pass :data:`MAX_ITEMS`,
    before it runs."""
    limit = f"a value of more than {MAX_ITEMS:,} items"
    if name == "format" and isinstance(owner, str):
        check_format(owner, args, kwargs)
    elif name in ("ljust", "rjust", "center", "zfill"):
        width = args[0] if args else kwargs.get("width", 0)
        if isinstance(width, int) and width > MAX_ITEMS:
            raise too_big(limit)
    elif name == "expandtabs":
        size = args[0] if args else kwargs.get("tabsize", 8)
        tabs = owner.count("\t") if isinstance(owner, str) else owner.count(b"\t")
        if isinstance(size, int) and len(owner) + tabs * max(size, 0) > MAX_ITEMS:
            raise too_big(limit)
    elif name == "replace" and len(args) >= 2:
        old, new = args[0], args[1]
        if isinstance(old, type(owner)) and isinstance(new, type(owner)):
            found = owner.count(old) if old else len(owner) + 1  # type: ignore[arg-type]
            if len(args) > 2 and isinstance(args[2], int) and args[2] >= 0:
                found = min(found, args[2])
            if len(owner) + found * (len(new) - len(old)) > MAX_ITEMS:
                raise too_big(limit)


def weight(value: Any, weights: dict[int, int], tick: Callable[[int], None]) -> int:
    """How many items ``value`` holds when written out, shared parts counted each time they
    appear; a container that holds itself counts once (Python writes it ``[...]``)."""
    if isinstance(value, str | bytes):
        return len(value) + 1
    if not isinstance(value, CONTAINERS):
        return 1
    key = id(value)
    known = weights.get(key)
    if known is not None:
        return known
    weights[key] = 1  # while it is weighed: a cycle back to it counts one
    tick(len(value) // 64 + 1)
    total = len(value) + 1
    parts: Iterable[Any] = (*value.keys(), *value.values()) if isinstance(value, dict) else value
    for part in parts:
        total += weight(part, weights, tick)
        if total > MAX_ITEMS:
            break
    weights[key] = total
    return total
