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

import types
from collections.abc import Callable
from typing import Any

from ._bounds import (
    MAX_BITS,
    MAX_ITEMS,
    UnsafeExpression,
    bounded_count,
    bounded_lcm,
    bounded_prod,
    bounded_range,
    bounded_sum,
    too_big,
)

__all__ = [
    "MAX_BITS",
    "MAX_ITEMS",
    "UnsafeExpression",
    "allowed_attribute",
    "allowed_callables",
    "is_allowed_method",
    "prepare_symbols",
    "too_big",
]

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
    bytes: frozenset({"decode", *(_STR & set(dir(bytes)))}),
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
            python["range"] = bounded_range(python["range"])
        if "sum" in python:
            python["sum"] = bounded_sum(python["sum"])
    if "range" in symbols:  # the deprecated name outside the namespace
        symbols["range"] = bounded_range(symbols["range"])
    for table in (symbols, symbols.get("math")):
        if table is None:
            continue
        for name in ("factorial", "comb", "perm"):
            if name in table:
                table[name] = bounded_count(table[name], name)
        if "prod" in table:
            table["prod"] = bounded_prod(table["prod"])
        if "lcm" in table:
            table["lcm"] = bounded_lcm(table["lcm"])


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
