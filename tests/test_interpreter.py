"""The expression interpreter, by property: generated expressions from its allowlist grammar,
mixed with hostile fragments, are walked under instruments that see everything that runs.

How the walk is watched (all of it scoped to one ``evaluate`` call):

- Every callable in the symbol table is replaced by a recorder before the interpreter
  computes what it may call, but the classes other than ``map`` and ``filter`` (which call
  back): ``python.int`` and the others stay themselves, as robots pass them to
  ``python.isinstance``.
- ``sys.setprofile`` sees every Python frame that runs (a ``call`` event, whoever calls it:
  bytecode, a C slot such as ``__getattr__`` or ``__format__``, a C function calling back)
  and every C function or method called from Python code (``c_call``). A zone is kept per
  frame: the interpreter's own modules are the *walker*; a recorder and whatever runs
  beneath it is a *symbol* (the implementation of an allowed function). A Python frame that
  the walker runs must be the walker's, a recorder, or one of a few named helpers (xacro's
  namespace and YAML wrapper methods, ``string.Formatter.parse``, ``ast.unparse`` for a
  message, the deadline and the error classes). A C function the walker calls must be one
  of its machinery builtins (``isinstance``, ``len``, ``getattr``, the ``operator``
  functions, ...) or a method of plain data (no dunder but ``__contains__`` and
  ``__getitem__``, never ``format_map`` or ``mro``); ``str.format`` only with plain fields.
- What the profile cannot see is a class called, or a C function called by another C
  function (``python.map(f, ...)`` calling ``f``). So every value any step of the walk
  makes (``_Evaluation.value`` is wrapped) must be a value of the allowed types, a
  recorder, a class of the table, a listed method or one of the interpreter's lambdas, with
  no string or container past ``MAX_ITEMS`` and no number past ``MAX_BITS``; and a method
  handed to a symbol function as a callback is handed over watched: it may not format
  with attribute or item fields and may not make a value past the bounds.
- An audit hook (``sys.addaudithook`` cannot be removed: it is installed once and records
  only while a walk runs in this thread) fails on any audit event: ``exec``, ``compile``,
  ``open``, ``import``, ``os.system``, ``object.__getattr__`` of a function's code, ...

A second property is differential: for expressions in the plain grammar (no hostile
fragment), the interpreter's value (or error type) is Python's ``eval`` of the same text in
a copy of the same table, as xacro's ``safe_eval`` runs it.

``FISHBOT_FUZZ=long`` (or ``FISHBOT_FUZZ_EXAMPLES=N``) runs many more examples, randomized,
as in ``tests/test_fuzz.py``.
"""

from __future__ import annotations

import abc
import ast
import functools
import gc
import math
import operator
import os
import re
import string
import sys
import threading
import time
import types
import warnings
from collections.abc import Callable
from typing import Any
from unittest import mock

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from fishbot_urdf.expansion import _interpreter
from fishbot_urdf.expansion._allowlist import MAX_BITS, MAX_ITEMS, UnsafeExpression, prepare_symbols
from fishbot_urdf.expansion._interpreter import Lambda, evaluate, parsed
from fishbot_urdf.inputs import TimeLimitError

# -- how many examples (the same knob as tests/test_fuzz.py) ---------------------------------
_LONG = os.environ.get("FISHBOT_FUZZ") == "long" or "FISHBOT_FUZZ_EXAMPLES" in os.environ
_EXAMPLES = int(os.environ.get("FISHBOT_FUZZ_EXAMPLES", "5000")) if _LONG else 0


def _examples(suite: int) -> settings:
    return settings(
        max_examples=_EXAMPLES or suite,
        derandomize=not _LONG,
        phases=[Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink],  # no tracer
        database=None,
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )


# -- the symbol table ----------------------------------------------------------------------
PROPERTIES: dict[str, Any] = {
    "n": 3,
    "x": 0.5,
    "neg": -2,
    "s": "left_wheel",
    "t": "{}_link",
    "flag": True,
    "items": [1, 2, 3],
    "words": ["a", "b_c", ""],
    "pair": (4, 5),
    "d": {"a": 1, "b": 2},
}


def _table(record: list[str] | None = None) -> Any:
    """A fresh xacro symbol table, prepared as an expansion prepares it, with properties and
    a YAML mapping; with ``record``, every function in it (not the classes) recorded."""
    import xacro  # type: ignore[import-untyped]

    symbols = xacro.create_global_symbols()
    prepare_symbols(symbols)
    if record is not None:
        for table in (symbols, symbols["python"], symbols["math"], symbols["xacro"]):
            for name, value in list(dict.items(table)):
                if (
                    callable(value)
                    and not isinstance(value, dict)
                    and (not isinstance(value, type) or value in (map, filter))
                ):
                    dict.__setitem__(table, name, _recorder(name, value, record))
    table = xacro.Table(symbols)
    for name, value in PROPERTIES.items():
        table._setitem(name, _copy(value), False)
    yaml = {"wheel": {"radius": 0.03, "names": ["l", "r"]}, "mass": 2}
    table._setitem("props", xacro.YamlDictWrapper(yaml), False)
    return table


def _copy(value: Any) -> Any:
    return type(value)(value) if isinstance(value, list | dict) else value


class _Violation(BaseException):
    """Something outside the allowlist ran (a BaseException: nothing on the way catches it)."""


def _recorder(name: str, function: Callable[..., Any], record: list[str]) -> Callable[..., Any]:
    @functools.wraps(function)  # the same __name__: the interpreter reads it
    def recorded(*args: Any, **kwargs: Any) -> Any:
        record.append(name)
        args = tuple(_watched(a, name) for a in args)
        kwargs = {k: _watched(v, name) for k, v in kwargs.items()}
        return function(*args, **kwargs)

    return recorded


_RECORDER_CODE = _recorder("", len, []).__code__


def _watched(value: Any, caller: str) -> Any:
    """A method handed to a symbol function as a callback, watched when it is called."""
    if not isinstance(value, _BUILTIN_METHODS):
        return value

    def watched(*args: Any, **kwargs: Any) -> Any:
        template = _template(value, args)
        if template is not None:
            _check_fields(template, f"{caller} calling {_named(value)}")
        made = value(*args, **kwargs)
        problem = _too_big(made)
        if problem:
            raise _Violation(f"{caller} calling {_named(value)} made {problem}")
        return made

    return watched


def _template(method: Any, args: tuple[Any, ...]) -> str | None:
    name = getattr(method, "__name__", "")
    if name not in ("format", "format_map"):
        return None
    owner = getattr(method, "__self__", None)
    if isinstance(owner, str):
        return owner
    return args[0] if args and isinstance(args[0], str) else ""


def _check_fields(template: str, where: str) -> None:
    """Raise when ``str.format`` would read an attribute or an item (at any spec depth)."""
    try:
        parsed_fields = list(string.Formatter().parse(template))
    except ValueError:
        return
    for _, field, spec, _ in parsed_fields:
        if field is not None and ("." in field or "[" in field):
            raise _Violation(f"{where}: format field {{{field}}} reads an attribute or item")
        if spec:
            _check_fields(spec, where)


def _named(value: Any) -> str:
    owner = getattr(value, "__self__", None) or getattr(value, "__objclass__", None)
    kind = owner.__name__ if isinstance(owner, type) else type(owner).__name__
    return f"{kind}.{getattr(value, '__name__', '?')}"


# -- what may run ----------------------------------------------------------------------------
_BUILTIN_METHODS = (
    types.BuiltinMethodType,
    types.MethodDescriptorType,
    types.ClassMethodDescriptorType,
    types.WrapperDescriptorType,
    types.MethodWrapperType,
)
_DATA = (str, bytes, list, tuple, dict, set, frozenset, int, float, complex, range, slice)
_LISTED = frozenset(
    """capitalize casefold center count endswith expandtabs find format index isalnum isalpha
    isascii isdecimal isdigit isidentifier islower isnumeric isprintable isspace istitle
    isupper join ljust lower lstrip partition removeprefix removesuffix replace rfind rindex
    rjust rpartition rsplit rstrip split splitlines startswith strip swapcase title upper
    zfill decode append clear copy extend insert pop remove reverse sort fromkeys get items
    keys popitem setdefault update values add difference difference_update discard
    intersection intersection_update isdisjoint issubset issuperset symmetric_difference
    symmetric_difference_update union as_integer_ratio bit_count bit_length conjugate
    is_integer indices""".split()  # noqa: SIM905
)
"""Methods of plain data an expression may call: the module docstring's list, by name."""
# What the walker itself calls on its own data (dict lookups, regular expressions, ...).
_WALKER_METHODS = _LISTED | {"__contains__", "__getitem__", "fullmatch", "findall", "finditer",
                             "groups", "group", "parse"}  # fmt: skip
_MACHINERY = {
    id(f)
    for f in (
        isinstance, issubclass, len, getattr, hasattr, id, callable, iter, next, repr, ascii,
        format, sum, any, all, min, max, abs, hash, sorted, ord, time.monotonic, *(
            getattr(operator, n) for n in dir(operator) if not n.startswith("_")
        ),
    )
}  # fmt: skip
_HELPER_FILES = {
    os.path.normcase(m.__file__ or "")
    for m in (ast, string, re, types, __import__("fishbot_urdf.inputs").inputs)
} | {
    os.path.normcase(__import__("fishbot_urdf.errors").errors.__file__ or ""),
    os.path.normcase(abc.ABCMeta.__instancecheck__.__code__.co_filename),  # isinstance(_, Mapping)
}
_INTERPRETER_FILE = os.path.normcase(_interpreter.__file__ or "")
# The interpreter and the modules of the expand package it takes its checks from.
_WALKER_FILES = {_INTERPRETER_FILE} | {
    os.path.normcase(getattr(sys.modules[v.__module__], "__file__", "") or "")
    for v in vars(_interpreter).values()
    if getattr(v, "__module__", "").startswith("fishbot_urdf.expansion.")
}
_THIS_FILE = os.path.normcase(__file__)


def _xacro_methods() -> set[types.CodeType]:
    import xacro

    found: set[types.CodeType] = set()
    for kind in (xacro.Table, xacro.NameSpace, xacro.YamlDictWrapper, xacro.YamlListWrapper):
        for value in vars(kind).values():
            function = getattr(value, "__func__", value)
            if isinstance(function, types.FunctionType):
                found.add(function.__code__)
    return found


_XACRO_CODE = _xacro_methods()


def _data_method(function: Any, names: frozenset[str] | set[str]) -> bool:
    """A method of plain data or of its class (``dict.fromkeys``), named in ``names``; not
    a method of a module, a function, or any other class."""
    if not isinstance(function, types.BuiltinMethodType | types.MethodDescriptorType):
        return False
    if hasattr(function, "__self__"):
        owner = function.__self__
    else:
        owner = getattr(function, "__objclass__", None)
    kind = owner if isinstance(owner, type) else type(owner)
    plain = (*_DATA, re.Pattern, re.Match, string.Formatter)
    return issubclass(kind, plain) and getattr(function, "__name__", "") in names


class _Watch:
    """The profile and the audit hook of one walk: what ran that should not have."""

    def __init__(self) -> None:
        self.zones: list[str] = ["outside"]
        self.found: list[str] = []
        self.inside = False

    def profile(self, frame: types.FrameType, event: str, arg: Any) -> None:
        self.inside = True  # reading a frame's code is itself an audit event
        try:
            self._event(frame, event, arg)
        finally:
            self.inside = False

    def _event(self, frame: types.FrameType, event: str, arg: Any) -> None:
        if event == "call":
            self.zones.append(self._zone(frame))
        elif event == "return":
            if len(self.zones) > 1:
                self.zones.pop()
        elif event == "c_call" and self.zones[-1] == "walker":
            self._c_call(arg)

    def _zone(self, frame: types.FrameType) -> str:
        code = frame.f_code
        if code is _RECORDER_CODE:
            return "symbol"
        file = os.path.normcase(code.co_filename)
        if file == _THIS_FILE:
            return "instrument"  # this file's recorders and checks: not the walk
        if file == _INTERPRETER_FILE:
            return "walker"  # also a lambda called back by a symbol function
        above = self.zones[-1]
        if above in ("symbol", "outside"):
            return above  # the implementation of an allowed function (bounded ones too)
        if file in _WALKER_FILES:
            return "walker"
        if above in ("helper", "instrument"):
            return "helper"
        if code in _XACRO_CODE:
            return "walker"  # a namespace's or YAML wrapper's lookup: watched like the walk
        if file in _HELPER_FILES:
            return "helper"
        self.found.append(f"the walk ran Python code {code.co_qualname} ({code.co_filename})")
        return "helper"

    def _c_call(self, function: Any) -> None:
        if id(function) in _MACHINERY:
            return
        if _data_method(function, _WALKER_METHODS):
            if getattr(function, "__name__", "") == "format":
                try:
                    _check_fields(function.__self__, "the walk calling str.format")
                except _Violation as exc:
                    self.found.append(str(exc))
            return
        self.found.append(f"the walk called {function!r}")

    def audit(self, event: str, args: tuple[Any, ...]) -> None:
        if self.inside or event in _HARMLESS_EVENTS:
            return
        if event == "object.__getattr__" and isinstance(args[0], types.FrameType):
            return  # a tracer (coverage, hypothesis) reading a frame; a walk never holds one
        self.found.append(f"audit event {event} {args!r:.80}")


_ACTIVE = threading.local()
_HARMLESS_EVENTS = {"builtins.id", "sys.setprofile"}  # the walker's id(); the watch itself


def _audit(event: str, args: tuple[Any, ...]) -> None:
    watch = getattr(_ACTIVE, "watch", None)
    if watch is not None:
        watch.audit(event, args)


_HOOKED: list[bool] = []


def _too_big(value: Any) -> str:
    if isinstance(value, str | bytes | list | tuple | dict | set | frozenset):
        if len(value) > MAX_ITEMS:
            return f"a {type(value).__name__} of {len(value):,} items"
    elif isinstance(value, int) and value.bit_length() > MAX_BITS:
        return f"a number of {value.bit_length():,} bits"
    return ""


# Lazy values a walk may make (never iterated here).
_LAZY = [
    "map",
    "filter",
    "zip",
    "enumerate",
    "reversed",
    "generator",
    "list_iterator",
    "list_reverseiterator",
    "range_iterator",
    "longrange_iterator",
    "str_ascii_iterator",
    "tuple_iterator",
    "dict_keys",
    "dict_values",
    "dict_items",
    "dict_keyiterator",
    "dict_reversekeyiterator",
    "dict_valueiterator",
    "dict_itemiterator",
    "set_iterator",
    "str_iterator",
    "bytes_iterator",
]


def _value_problem(value: Any, allowed: set[int], seen: dict[int, int], budget: list[int]) -> str:
    """Why ``value`` is not a value a walk may hold ('' when it may)."""
    if value is None or isinstance(value, bool | int | float | complex | range | slice | Lambda):
        return _too_big(value)
    if isinstance(value, str | bytes):
        return _too_big(value)
    if id(value) in allowed:
        return ""  # a recorder or a class of the table
    if isinstance(value, list | tuple | dict | set | frozenset):
        problem = _too_big(value)
        if problem or seen.get(id(value)) == len(value):
            return problem
        seen[id(value)] = len(value)
        parts = (*value.keys(), *value.values()) if isinstance(value, dict) else value
        for part in parts:
            budget[0] -= 1
            if budget[0] < 0:
                return ""
            problem = _value_problem(part, allowed, seen, budget)
            if problem:
                return problem
        return ""
    if type(value).__name__ in _LAZY:
        return ""
    if _data_method(value, _LISTED) and not isinstance(
        getattr(value, "__self__", None), re.Pattern | re.Match | string.Formatter
    ):
        return ""
    return f"a {type(value).__name__}: {value!r:.80}"


def _allowed_ids(table: Any) -> set[int]:
    found = set()
    root = table.root
    for space in (root, root["python"], root["math"], root["xacro"]):
        found.add(id(space))
        found.update(id(v) for v in dict.values(space) if callable(v))
    return found


def watched_evaluate(expression: str, table: Any) -> Any:
    """``evaluate`` under the profile, the audit hook and the value check; raises
    AssertionError naming what ran that should not have."""
    if not _HOOKED:
        sys.addaudithook(_audit)
        _HOOKED.append(True)
    try:
        parsed(expression)  # parsing is not the walk (ast.parse is an audited compile)
    except (SyntaxError, RecursionError, MemoryError) as exc:
        with pytest.raises(SyntaxError):  # not walked at all
            evaluate(expression, table)
        return exc
    watch = _Watch()
    allowed = _allowed_ids(table)
    seen: dict[int, int] = {}
    budget = [200_000]
    walk = _interpreter._Evaluation.value

    def value(self: Any, node: ast.AST, frame: Any) -> Any:
        made = walk(self, node, frame)
        problem = _value_problem(made, allowed, seen, budget)
        if problem:
            raise _Violation(f"the walk made {problem} at {ast.unparse(node)[:60]!r}")
        return made

    outcome: Any = None
    with mock.patch.object(_interpreter._Evaluation, "value", value):
        _ACTIVE.watch = watch
        previous = sys.getprofile()
        gc.isenabled()
        gc.disable()  # a collection's callbacks (hypothesis has one) are not the walk
        sys.setprofile(watch.profile)
        try:
            outcome = evaluate(expression, table)
        except _Violation as exc:
            watch.found.append(str(exc))
        except Exception as exc:
            outcome = exc
        finally:
            sys.setprofile(previous)
            _ACTIVE.watch = None
    assert not watch.found, f"{expression!r}: " + "; ".join(dict.fromkeys(watch.found))
    if not isinstance(outcome, BaseException):
        problem = _value_problem(outcome, allowed, {}, [1_000_000])
        assert not problem, f"{expression!r} returned {problem}"
    return outcome


# -- the grammar ---------------------------------------------------------------------------
_NUMBERS = ["0", "1", "2", "3", "-1", "0.5", "-2.5", "1e3", "True", "False"]
_PLAIN_LEAVES = [
    *_NUMBERS, "None", "''", "'ab'", "'a_b'", "b'xy'", "n", "x", "neg", "s", "t", "flag",
    "items", "words", "pair", "d", "props", "props.wheel", "props.wheel.radius",
    "props.wheel.names", "props.mass", "math.pi", "math.e", "math.inf", "python.abs(-1)",
    "[]", "()", "{}", "[1, 2]", "(1, 'a')", "{'k': 1}", "{1, 2}", "python.range(4)",
]  # fmt: skip
_BINARY = ["+", "-", "*", "/", "//", "%", "&", "|", "^", "and", "or", "==", "!=", "<",
           "<=", ">", ">=", "in", "not in"]  # fmt: skip
_CALL1 = [
    "python.len", "python.abs", "python.str", "python.int", "python.float", "python.bool",
    "python.list", "python.tuple", "python.sorted", "python.min", "python.max", "python.sum",
    "python.any", "python.all", "python.repr", "python.set", "python.frozenset",
    "python.round", "python.list(python.reversed", "python.list(python.enumerate",
    "python.hash", "math.sqrt", "math.sin", "math.floor", "math.ceil", "math.fabs", "math.log",
    "math.exp", "math.degrees", "math.isfinite", "math.trunc", "python.list(python.zip",
    "python.list(python.filter(None,", "python.list(python.map(lambda v: v,", "python.dict",
    "python.isinstance", "python.len(python.str", "python.ord", "python.divmod(7,",
]  # fmt: skip
_CALL2 = ["python.min", "python.max", "python.divmod", "math.atan2", "math.hypot",
          "math.isclose", "math.copysign", "python.round", "python.list(python.zip",
          "math.fmod", "math.pow"]  # fmt: skip
_METHODS = [
    ".upper()", ".split('_')", ".startswith('l')", ".replace('a', 'b')", ".zfill(4)",
    ".center(6, '*')", ".strip()", ".find('e')", ".count(1)", ".index(1)", ".get('a', 0)",
    ".is_integer()", ".bit_length()", ".real", ".imag", ".keys()", ".items()", ".copy()",
    ".as_integer_ratio()", ".isdigit()", ".title()", ".append(9)", ".pop()", ".values()",
    ".union({1})", ".decode()", ".start", ".stop", ".step", ".indices(3)",
]  # fmt: skip


def _combine(children: st.SearchStrategy[str]) -> st.SearchStrategy[str]:
    c = children
    pow_or_shift = st.tuples(c, st.sampled_from(["**", "<<", ">>"]),
                             st.sampled_from(["0", "1", "2", "3", "-1", "0.5"]))  # fmt: skip
    return st.one_of(
        st.builds(lambda a, op, b: f"({a} {op} {b})", c, st.sampled_from(_BINARY), c),
        pow_or_shift.map(lambda t: f"({t[0]} {t[1]} {t[2]})"),
        st.builds(lambda op, a: f"({op}{a})", st.sampled_from(["-", "+", "not ", "~"]), c),
        st.builds(lambda a, b, k: f"({a} if {b} else {k})", c, c, c),
        st.builds(lambda a, b: f"{a}[{b}]", c, st.sampled_from(["0", "1", "-1", "'a'", "5"])),
        st.builds(
            lambda a, b, k: f"{a}[{b}:{k}]",
            c,
            st.sampled_from(["", "1", "-2", "None"]),
            st.sampled_from(["", "2", "-1"]),
        ),
        st.builds(lambda a: f"{a}[::-1]", c),
        st.builds(lambda f, a: _call(f, a), st.sampled_from(_CALL1), c),
        st.builds(lambda f, a, b: _call(f, f"{a}, {b}"), st.sampled_from(_CALL2), c, c),
        st.builds(lambda a, m: f"{a}{m}", c, st.sampled_from(_METHODS)),
        st.builds(lambda a, b: f"[{a}, {b}]", c, c),
        st.builds(lambda a, b: f"({a}, {b})", c, c),
        st.builds(lambda a, b: f"{{{a}: {b}}}", c, c),
        st.builds(lambda a: f"{{{a}}}", c),
        st.builds(lambda a: f"[*{a}]", c),
        # {**a} of a non-mapping: an open divergence (test_unpacking_a_non_mapping_...)
        st.builds(lambda a, b: f"{{**{a}, 'z': {b}}}", st.sampled_from(["d", "props", "{}"]), c),
        st.builds(lambda e, a: f"[{e} for v in {a}]", st.sampled_from(["v", "v * 2", "(v, v)"]), c),
        st.builds(lambda a, b: f"[v for v in {a} if {b}]", c, c),
        st.builds(lambda a: f"{{v for v in {a}}}", c),
        st.builds(lambda a: f"{{k: v for k, v in python.enumerate({a})}}", c),
        st.builds(lambda a: f"python.list(v for v in {a})", c),
        st.builds(lambda a, b: f"[[w for w in {a}] for v in {b}]", c, c),
        st.builds(lambda a, b: f"[(v, w) for v in {a} for w in {b}]", c, c),
        st.builds(
            lambda b, a: f"(lambda v: {b})({a})",
            st.sampled_from(["v", "v * n", "[v, v]", "v + x", "(lambda w: v)(1)", "python.len(v)"]),
            c,
        ),
        st.builds(lambda a, b: f"(lambda v, w=2: (v, w))({a}, w={b})", c, c),
        st.builds(lambda a, b: f"(lambda *r, **k: (r, k))({a}, z={b})", c, c),
        st.builds(lambda a: f"python.sorted({a}, key=lambda v: -v)", c),
        st.builds(
            lambda a, spec: _fstring(a, spec),
            c,
            st.sampled_from(["", ":>5", ":.2f", "!r", ":^7", ":x"]),
        ),
        st.builds(lambda a, b: f"'{{}}_{{}}'.format({a}, {b})", c, c),
        st.builds(lambda a, b: f"'{{0}}-{{1:>4}}'.format({a}, {b})", c, c),
        st.builds(lambda a: f"'{{k}}'.format(k={a})", c),
        st.builds(lambda a: f"'_'.join({a})", c),
        st.builds(lambda a: f"('%s-%r' % ({a}, 1))", c),
        st.builds(lambda a: f"t.format({a})", c),
    )


def _call(function: str, args: str) -> str:
    if function == "python.isinstance":
        return f"python.isinstance({args}, (python.int, python.str))"
    if function.endswith(","):
        return f"{function} {args}" + ")" * function.count("(")
    return f"{function}({args}" + ")" * (function.count("(") + 1)


def _fstring(inner: str, spec: str) -> str:
    if '"' in inner or "\\" in inner or "{" in inner:
        return f"python.str({inner})"
    return f'f"<{{{inner}{spec}}}>"'


PLAIN = st.recursive(st.sampled_from(_PLAIN_LEAVES), _combine, max_leaves=8)

_HOSTILE_LEAVES = [
    # attributes, names and calls outside the allowlist
    "().__class__", "[].__class__.__mro__", "''.__class__.__base__.__subclasses__()",
    "(lambda: 0).__globals__", "(lambda: 0).__code__", "xacro.arg.__globals__",
    "xacro.arg.__closure__", "xacro.load_yaml.__globals__['os']", "xacro.arg.func_globals",
    "xacro.tokenize.__globals__", "math.__dict__", "math.parent", "math.root", "__builtins__",
    "__import__('os')", "python.type(1)", "python.vars()", "python.type", "getattr",
    "python.getattr", "open", "eval", "props.__class__", "props.wheel.__getattr__",
    "props.keys.__self__", "(1).__class__", "math.pi.__class__", "python.range(3).__reduce__()",
    "python.str.maketrans", "'a'.translate", "'ab'.encode", "python.list.mro()",
    "python.int.__subclasses__()", "python.dict.__dict__", "python.map.__call__",
    "python.len.__self__", "python.str.format.__call__('{0.x}', 1)", "math.sin.__self__",
    "(v for v in [1]).gi_frame", "(v for v in [1]).gi_code",
    "[g.gi_frame.f_globals for g in [(v for v in [1])]]", "(y := 1)",
    "python.dict(__class__=1)", "python.dict(**{'__x': 1})", "(lambda __x: 0)(1)",
    "(lambda **k: k)(**{'__class__': 1})", "[__x for __x in [1]]", "xacro.fatal('x')",
    "xacro.arg('x')", "xacro.tokenize('a,b;c')", "xacro.dotify(python.dict(a=1)).a",
    "python.issubclass(python.bool, python.int)", "python.slice(1, 5).indices",
    # format fields
    "'{0.__class__}'.format(1)", "'{0[0]}'.format([1])", "'{0:{1.real}}'.format(1, 2)",
    "'{0.real}'.format(1)", "'{:{}{}}'.format(1, '>', 5)", "'{x}'.format_map(d)",
    "python.str.format('{0.__class__}', 1)", "python.str.format_map", "f'{().__class__}'",
    # callbacks handed to functions
    "python.list(python.map(python.type, [1]))", "python.sorted([1], key=python.vars)",
    "python.list(python.map(xacro.arg, ['x']))", "python.list(python.map(math.factorial, [10**6]))",
    # values past the bounds
    "'a' * 10**10", "'ab' * 6000000", "[0] * 10**8", "[[0] * 1000] * 1000",
    "[[[0] * 1000] * 1000] * 1000", "python.str([[[0] * 1000] * 1000] * 1000)",
    "f'{[[0] * 1000] * 1000}'", "python.repr([[0] * 1000] * 1000)",
    "'{:>30000000}'.format(1)", "f'{1:>30000000}'", "'%30000000d' % 1", "'%*d' % (30000000, 1)",
    "'x'.ljust(30000000)", "'x'.zfill(30000000)", "'\\t'.expandtabs(30000000)",
    "('a' * 5000).replace('', 'b' * 5000)", "'-'.join(['ab' * 3000] * 3000)",
    "10**10**8", "2**10**6", "1 << 10**9", "(10**200000) * (10**200000)", "-(2**999999) - 1",
    "math.factorial(10**7)", "math.comb(10**6, 5 * 10**5)", "math.prod([10**100000] * 20)",
    "math.lcm(*[10**100000 + v for v in python.range(20)])",
    "python.sum([[0] * 3000000] * 4, [])", "python.range(10**12)",
    "python.list(python.range(10**12))", "python.len(python.range(10**12))",
    "[v for v in python.range(10**6) for w in python.range(10**6)]",
    "python.sum(v for v in python.range(10**7))", "[*python.range(10**8)]",
    "python.list(python.zip(*[[0] * 100] * 100))", "{v: [0] * 1000 for v in python.range(9)}",
    "python.sorted([[0] * 1000] * 1000)", "[[0] * 1000] * 1000 == [[0] * 1000] * 1000",
    # recursion
    "(lambda f: f(f))(lambda f: f(f))", "(lambda f: f(f, 0))(lambda f, k: f(f, k + 1))",
    "-" * 300 + "1", "(" * 150 + "1" + ")" * 150, "[" * 90 + "]" * 90,
    "python.sorted([1, 2], key=lambda v: (lambda f: f(f))(lambda f: f(f)))",
]  # fmt: skip

ANY = st.recursive(
    st.one_of(st.sampled_from(_PLAIN_LEAVES), st.sampled_from(_HOSTILE_LEAVES)),
    _combine,
    max_leaves=6,
)

ALLOWED_ERRORS = (
    UnsafeExpression, TimeLimitError, NameError, TypeError, ValueError, ArithmeticError,
    AttributeError, KeyError, IndexError, SyntaxError, LookupError,
)  # fmt: skip


def _xacro_exception() -> type[Exception]:
    import xacro

    return xacro.XacroException  # type: ignore[no-any-return]


# -- the properties ----------------------------------------------------------------------------
# Listed methods handed to a function as callbacks are called back through the interpreter:
# their format fields and pads are looked at as if the expression had called them.
CALLED_BACK = [
    "python.list(python.map('{0.__globals__[os]}'.format, [xacro.tokenize]))",
    "python.list(python.map(python.str.format, ['{0.__class__}'], [1]))",
    "python.list(python.filter('{0[0]}'.format, [[1]]))",
    "python.len(python.list(python.map('a'.ljust, [30000000])))",
    "python.any(python.map(python.str.zfill, ['1'], [30000000]))",
    "python.max([30000000], key=' '.rjust)",
    "python.sorted([30000000], key='x'.center)",
]


@pytest.mark.parametrize("expression", CALLED_BACK)
def test_a_method_handed_over_as_a_callback_is_checked(expression: str) -> None:
    outcome = watched_evaluate(expression, _table(record=[]))
    assert isinstance(outcome, UnsafeExpression)


@_examples(150)
@given(expression=ANY)
def test_a_walk_runs_nothing_outside_the_allowlist(expression: str) -> None:
    # A smaller step budget than an expansion's: the property holds for any budget, and
    # the profile makes each step slow.
    with mock.patch.object(_interpreter, "MAX_STEPS", 5_000):
        outcome = watched_evaluate(expression, _table(record=[]))
    if isinstance(outcome, BaseException):
        assert isinstance(outcome, (*ALLOWED_ERRORS, _xacro_exception())), (
            f"{expression!r} raised {outcome!r}"
        )
        if isinstance(outcome, UnsafeExpression):
            assert outcome.expression == expression
            assert outcome.what


@_examples(1000)
@given(expression=PLAIN)
def test_the_plain_grammar_evaluates_as_python_does(expression: str) -> None:
    try:
        mine: Any = evaluate(expression, _table())
    except UnsafeExpression as exc:
        # A bound: Python would go on making the value. An attribute refused where Python
        # finds none either (``None.upper``): the allowlist says so before Python would.
        theirs = _python_eval(expression) if not (exc.too_big or exc.too_long) else None
        assert theirs is None or (
            isinstance(theirs, AttributeError) and exc.what.startswith("the attribute")
        ), f"{expression!r} refused: {exc.what}; Python: {theirs!r}"
        return
    except Exception as exc:
        mine = exc
    theirs = _python_eval(expression)
    if isinstance(mine, BaseException) or isinstance(theirs, BaseException):
        assert type(mine) is type(theirs), f"{expression!r}: {mine!r} but Python: {theirs!r}"
        return
    assert _same(mine, theirs), f"{expression!r}: {mine!r} but Python: {theirs!r}"


@pytest.mark.parametrize("expression", ["{**''}", "{**[(1, 2)]}", "{**[]}"])
def test_unpacking_a_non_mapping_into_a_dict_is_a_type_error(expression: str) -> None:
    assert isinstance(_python_eval(expression), TypeError)
    with pytest.raises(TypeError):
        evaluate(expression, _table())


def _python_eval(expression: str) -> Any:
    """Python's eval of ``expression`` as xacro's safe_eval runs it (no builtins)."""
    table = _table()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # "perhaps you missed a comma?"
            code = compile(expression.strip(), "<expression>", "eval")
        table.update(__builtins__={})
        return eval(code, table)  # the differential's reference
    except Exception as exc:
        return exc


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, Lambda):
        return isinstance(b, types.FunctionType) and b.__name__ == "<lambda>"
    if type(a) is not type(b):
        return False
    if isinstance(a, float):
        return (a == b and math.copysign(1, a) == math.copysign(1, b)) or (a != a and b != b)
    if isinstance(a, complex):
        return _same(a.real, b.real) and _same(a.imag, b.imag)
    if isinstance(a, list | tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, dict):
        return list(a) == list(b) and all(_same(a[k], b[k]) for k in a)
    if type(a).__name__ in _LAZY:
        return True  # not iterated: both the same kind of lazy value
    if callable(a):
        return a is b
    return bool(a == b) or repr(a) == repr(b)


# -- the instruments see what they claim to see -------------------------------------------
def test_the_profile_sees_the_walk_call_a_function_that_is_not_recorded() -> None:
    table = _table(record=[])
    dict.__setitem__(table.root["math"], "sin", math.sin)  # in the table, but not recorded
    with pytest.raises(AssertionError, match="the walk called <built-in function sin>"):
        watched_evaluate("math.sin(1)", table)


def test_the_value_check_sees_the_walk_make_a_value_outside_the_table() -> None:
    real = _interpreter.attribute

    def leaking(owner: Any, name: str) -> Any:
        return int.__subclasses__ if name == "real" else real(owner, name)

    with (
        mock.patch.object(_interpreter, "attribute", leaking),
        pytest.raises(AssertionError, match="the walk made a builtin_function_or_method"),
    ):
        watched_evaluate("(1).real", _table(record=[]))


def test_the_audit_hook_sees_a_compile_during_the_walk() -> None:
    table = _table(record=[])
    # A symbol table entry that compiles: the walk runs it beneath a recorder (allowed),
    # but the audit hook still reports it.
    dict.__setitem__(
        table.root["python"],
        "compiles",
        _recorder("compiles", lambda: compile("1", "", "eval"), []),
    )
    with pytest.raises(AssertionError, match="audit event compile"):
        watched_evaluate("python.compiles()", table)


def test_a_recorded_function_is_recorded() -> None:
    record: list[str] = []
    assert evaluate("python.len(python.sorted([2, 1]))", _table(record)) == 2
    assert record == ["sorted", "len"]
