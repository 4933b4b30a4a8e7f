"""What a xacro expression may call and read: the allowlist, and the bounded functions.

An expression reaches nothing but what is listed here: the functions xacro puts in its
symbol table (the builtins it exposes, ``math``, the ``xacro`` namespace), less
``python.type`` and ``python.vars``; named methods of ``str``, ``list``, ``dict``,
``tuple``, ``set`` and the numbers that read no attribute of another object; and a few
plain attributes (``real``, ``start``, ...). Functions that could run for minutes or fill
the memory with one call (``math.factorial``, ``math.prod``, ``range``, ``sum`` of lists,
padding and replacing strings) check the size of what they would make first.
"""

from __future__ import annotations

import re
import string
import types
from collections.abc import Callable, Iterable
from typing import Any

from ..errors import FishbotUrdfError

__all__ = [
    "MAX_BITS",
    "MAX_ITEMS",
    "UnsafeExpression",
    "allowed_attribute",
    "allowed_callables",
    "check_format",
    "check_printf",
    "check_spec",
    "is_allowed_method",
    "prepare_symbols",
    "too_big",
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

    rule = "xacro-unsafe"

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


# -- methods and attributes ---------------------------------------------------------------
_SEQUENCE = ("count", "index")
_STR = frozenset(
    """capitalize casefold center count endswith expandtabs find format index isalnum isalpha
    isascii isdecimal isdigit isidentifier islower isnumeric isprintable isspace istitle
    isupper join ljust lower lstrip partition removeprefix removesuffix replace rfind rindex
    rjust rpartition rsplit rstrip split splitlines startswith strip swapcase title upper
    zfill""".split()  # noqa: SIM905
)
_LIST = frozenset(
    """append clear copy count extend index insert pop remove reverse sort""".split()  # noqa: SIM905
)
_DICT = frozenset(
    """clear copy fromkeys get items keys pop popitem setdefault update values""".split()  # noqa: SIM905
)
_SET = frozenset(
    """add clear copy difference difference_update discard intersection intersection_update
    isdisjoint issubset issuperset pop remove symmetric_difference
    symmetric_difference_update union update""".split()  # noqa: SIM905
)
_NUMBER = frozenset(
    """as_integer_ratio bit_count bit_length conjugate denominator imag is_integer numerator
    real""".split()  # noqa: SIM905
)
_METHODS: dict[type, frozenset[str]] = {
    str: _STR,
    bytes: frozenset(("decode", *_SEQUENCE)),
    list: _LIST,
    tuple: frozenset(_SEQUENCE),
    dict: _DICT,
    set: _SET,
    frozenset: _SET
    - {"add", "clear", "discard", "pop", "remove"}
    - {n for n in _SET if n.endswith("update")},
    int: _NUMBER,
    bool: _NUMBER,
    float: _NUMBER,
    complex: frozenset(("conjugate", "imag", "real")),
    range: frozenset(("count", "index", "start", "step", "stop")),
    slice: frozenset(("indices", "start", "step", "stop")),
}
"""Each type's attributes an expression may read (its subclasses' too)."""


def allowed_attribute(value: Any, name: str) -> bool:
    """Whether ``value.name`` is on the allowlist (a namespace's entries are not asked here)."""
    owner = value if isinstance(value, type) else type(value)
    for kind in owner.__mro__:
        listed = _METHODS.get(kind)
        if listed is not None:
            return name in listed
    return False


def is_allowed_method(function: Any) -> bool:
    """Whether ``function`` is a listed method of a listed type, bound or not."""
    if isinstance(function, types.BuiltinMethodType):
        owner = function.__self__
    elif isinstance(function, types.MethodDescriptorType | types.ClassMethodDescriptorType):
        owner = function.__objclass__
    else:
        return False
    if owner is None or isinstance(owner, types.ModuleType):
        return False
    return allowed_attribute(owner, function.__name__)


# -- what a format may do -------------------------------------------------------------------
_FIELD = re.compile(r"\d*|[^\W\d]\w*")
_WIDTHS = re.compile(r"(\d+)")


def check_format(template: str, args: Iterable[Any] = (), kwargs: Iterable[Any] = ()) -> None:
    """Refuse a ``str.format`` template whose fields read an attribute or an item, at any
    depth of nested specs, or whose widths and precisions would pass :data:`MAX_ITEMS`.

    Raises:
        UnsafeExpression: The template is refused.
    """
    total = len(template)
    for spec in _fields(template):
        total += _spec_size(spec)
    total += sum(_size(a) for a in args) + sum(_size(a) for a in kwargs)
    if total > MAX_ITEMS:
        raise too_big(f"a value of more than {MAX_ITEMS:,} items")


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
def _bounded_range(function: Callable[..., Any]) -> Callable[..., Any]:
    """xacro's ``range`` (the deprecated one keeps its warning), up to ``MAX_ITEMS`` items:
    making a range is quick, going through ``range(10**12)`` is not."""

    def run(*args: Any) -> range:
        made: range = function(*args)
        if len(made) > MAX_ITEMS:
            raise too_big(f"a range of more than {MAX_ITEMS:,} items")
        return made

    return run


def _bounded_count(function: Callable[..., Any], name: str) -> Callable[..., Any]:
    """``math.factorial``, ``comb`` and ``perm`` up to ``MAX_COUNT``: past it they run for
    minutes."""

    def run(*args: Any) -> Any:
        if any(isinstance(a, int) and a > MAX_COUNT for a in args):
            raise too_big(f"a math.{name} of a number past {MAX_COUNT:,}")
        return function(*args)

    return run


def _bounded_prod(function: Callable[..., Any]) -> Callable[..., Any]:
    """``math.prod``, its whole numbers' bits added up before it multiplies them."""

    def run(iterable: Iterable[Any], *, start: Any = 1) -> Any:
        items = list(iterable)
        bits = sum(abs(v).bit_length() for v in (*items, start) if isinstance(v, int))
        if bits > MAX_BITS:
            raise too_big(f"a number of more than {MAX_BITS:,} bits")
        return function(items, start=start)

    return run


def _bounded_lcm(function: Callable[..., Any]) -> Callable[..., Any]:
    def run(*args: Any) -> Any:
        if sum(abs(v).bit_length() for v in args if isinstance(v, int)) > MAX_BITS:
            raise too_big(f"a number of more than {MAX_BITS:,} bits")
        return function(*args)

    return run


def _bounded_sum(function: Callable[..., Any]) -> Callable[..., Any]:
    """``sum``: numbers as Python adds them; lists, tuples and strings (``sum(x, [])``
    copies at every step) with the length checked at every step."""

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


def _refusing(name: str) -> Callable[..., Any]:
    def run(*args: Any, **kwargs: Any) -> Any:
        raise UnsafeExpression("", name)

    run.__name__ = name
    return run


def prepare_symbols(symbols: dict[str, Any]) -> None:
    """Put the bounded functions in xacro's fresh symbol table, and take out ``type`` and
    ``vars`` (``python.type(x)`` hands out classes and their attributes)."""
    python = symbols.get("python")
    if python is not None:
        for name in ("type", "vars"):
            if name in python:
                python[name] = _refusing(f"python.{name}")
        if "range" in python:
            python["range"] = _bounded_range(python["range"])
        if "sum" in python:
            python["sum"] = _bounded_sum(python["sum"])
    if "range" in symbols:  # the deprecated name outside the namespace
        symbols["range"] = _bounded_range(symbols["range"])
    for table in (symbols, symbols.get("math")):
        if table is None:
            continue
        for name in ("factorial", "comb", "perm"):
            if name in table:
                table[name] = _bounded_count(table[name], name)
        if "prod" in table:
            table["prod"] = _bounded_prod(table["prod"])
        if "lcm" in table:
            table["lcm"] = _bounded_lcm(table["lcm"])


def allowed_callables(symbols: dict[str, Any]) -> frozenset[int]:
    """The ids of every function and class in a prepared symbol table and its namespaces:
    what an expression may call besides listed methods and its own lambdas."""
    found: set[int] = set()
    for table in (symbols, *(v for v in symbols.values() if _is_namespace(v))):
        for value in dict.values(table):
            if callable(value) and not _is_namespace(value):
                found.add(id(value))
    found.update(id(kind) for kind in _METHODS)
    return frozenset(found)


def _is_namespace(value: Any) -> bool:
    return isinstance(value, dict) and hasattr(value, "parent") and hasattr(value, "root")
