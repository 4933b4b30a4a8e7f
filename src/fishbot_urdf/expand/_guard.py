"""What a xacro expression may do: checked before it runs, at every depth.

xacro evaluates ``${...}`` with Python's ``eval`` and no builtins, and refuses names that
start with ``__`` -- but only in the outermost code, so a lambda or a comprehension reaches
``().__class__`` and from there every class and module of the process. Here every
expression is parsed first and the whole tree is walked; it is refused when it names
anything that leads out of the symbol table:

- a name or a keyword argument that starts with ``__``;
- an attribute that starts with ``_`` (``__class__``, ``_wrap_close``, ...);
- an attribute that reaches frames, code or globals without an underscore (``gi_frame``,
  ``f_globals``, ``tb_frame``, ``co_code``, ``func_globals``, ...);
- ``str.format`` and ``format_map`` other than on a written string whose fields name no
  ``_`` attribute (a format field can read any attribute).

What the checker cannot see, values built while the expression runs, is closed in the
symbol table itself: ``python.vars`` hides the entries that start with ``_``, and
``python.type`` makes no new classes (its one-argument form is kept).

This is defence in depth, not a proof: a xacro file is a program, as it is in ROS.
"""

from __future__ import annotations

import ast
import functools
import string
from types import CodeType
from typing import Any

from ..errors import FishbotUrdfError

__all__ = ["UnsafeExpression", "check_expression", "guard_symbols", "guarded"]

_REACHING = ("gi_", "cr_", "ag_", "f_", "tb_", "co_", "func_", "im_")
"""Attribute prefixes of generators, coroutines, frames, tracebacks, code and functions."""


class UnsafeExpression(FishbotUrdfError):
    """An expression was refused; ``what`` names the part refused."""

    rule = "xacro-unsafe"

    def __init__(self, expression: str, what: str, *, too_big: bool = False) -> None:
        said = f"would make {what}" if too_big else f"'{what}' is not allowed"
        super().__init__(f"{said} in an expression")
        self.expression = expression
        self.what = what
        self.too_big = too_big  # a value past the bounds, not a name refused


def check_expression(expression: str) -> ast.Expression:
    """Parse one expression and refuse it if it reaches past the symbol table.

    Raises:
        SyntaxError: The text is not a Python expression.
        UnsafeExpression: The expression names something refused (see the module).
    """
    tree = _parsed(expression)
    _scan(tree, expression)
    return tree


def guarded(
    expression: str, globals: Any, locals: Any = None, builtins: dict[str, Any] | None = None
) -> Any:
    """Check an expression, then evaluate it (xacro's ``safe_eval``), with no builtins but
    ``builtins``.

    As few frames deep as can be (no helper but the check, and none while the expression
    runs): xacro evaluates at the bottom of its recursion, and the frames here count against
    how deep macros may nest.
    """
    code = _checked(expression)
    globals["__builtins__"] = {**(builtins or {}), _ARITH: _arithmetic}
    try:
        return eval(code, globals, locals)  # checked in _checked
    except UnsafeExpression as exc:  # a bound, met while it ran: name the whole expression
        raise UnsafeExpression(expression, exc.what, too_big=exc.too_big) from None


@functools.lru_cache(maxsize=4096)
def _checked(expression: str) -> CodeType:
    """The expression checked and compiled (a macro's expressions come again at each call).

    Raises:
        SyntaxError: The text is not a Python expression.
        UnsafeExpression: The expression names something refused.
    """
    tree = _parsed(expression)
    if _scan(tree, expression):  # arithmetic that can grow without bound: counted
        tree = ast.fix_missing_locations(_Bounded().visit(tree))
    return compile(tree, "<expression>", "eval")


def _parsed(expression: str) -> ast.Expression:
    tree = compile(expression.strip(), "<expression>", "eval", ast.PyCF_ONLY_AST)
    assert isinstance(tree, ast.Expression)
    return tree


def _scan(tree: ast.AST, expression: str) -> bool:
    """Refuse what the expression must not name; whether it holds growing arithmetic."""
    found: list[tuple[int, int, str]] = []
    growing = False
    todo = [tree]
    while todo:
        node = todo.pop()
        refused = _refused(node)
        if refused is not None:
            found.append((getattr(node, "lineno", 0), getattr(node, "end_col_offset", 0), refused))
        growing = growing or (isinstance(node, ast.BinOp) and isinstance(node.op, _GROWING))
        todo.extend(ast.iter_child_nodes(node))
    if found:
        raise UnsafeExpression(expression, min(found)[2])  # the first, as it is written
    return growing


# -- bounds on what one expression may build -----------------------------------------
_GROWING = (ast.Pow, ast.Mult, ast.LShift)
_ARITH = "__fishbot_arithmetic__"  # a name no expression can write (it starts with __)
MAX_ITEMS = 10_000_000
"""The longest string or list, and the most items of a range, one expression may make."""
MAX_BITS = 1_000_000
"""The largest whole number one expression may make, in bits (about 300,000 digits)."""


class _Bounded(ast.NodeTransformer):
    """``a ** b``, ``a * b`` and ``a << b`` become calls that check the result's size first."""

    def visit_BinOp(self, node: ast.BinOp) -> ast.AST:
        self.generic_visit(node)
        if not isinstance(node.op, _GROWING):
            return node
        call = ast.Call(
            func=ast.Name(_ARITH, ast.Load()),
            args=[ast.Constant(type(node.op).__name__), node.left, node.right],
            keywords=[],
        )
        return ast.copy_location(call, node)


def _arithmetic(op: str, a: Any, b: Any) -> Any:
    whole = _whole(a) and _whole(b)
    if op == "Pow":
        if whole and b > 0 and abs(a) > 1 and b * (abs(a).bit_length() - 1) > MAX_BITS:
            raise _too_big(f"a number of more than {MAX_BITS:,} bits")
        return a**b
    if op == "LShift":
        if whole and a and b > MAX_BITS:
            raise _too_big(f"a number of more than {MAX_BITS:,} bits")
        return a << b
    for sequence, count in ((a, b), (b, a)):
        repeated = isinstance(sequence, str | bytes | list | tuple) and _whole(count)
        if repeated and len(sequence) * count > MAX_ITEMS:
            raise _too_big(f"a value of more than {MAX_ITEMS:,} items")
    if whole and a.bit_length() + b.bit_length() > MAX_BITS:
        raise _too_big(f"a number of more than {MAX_BITS:,} bits")
    return a * b


def _too_big(what: str) -> UnsafeExpression:
    return UnsafeExpression("", what, too_big=True)


def _whole(value: Any) -> bool:
    return isinstance(value, int)


def _bounded_range(function: Any) -> Any:
    """xacro's ``range`` (the deprecated one keeps its warning), up to ``MAX_ITEMS`` items:
    making a range is quick, going through ``range(10**12)`` is not."""

    def run(*args: Any) -> range:
        made: range = function(*args)
        if len(made) > MAX_ITEMS:
            raise _too_big(f"a range of more than {MAX_ITEMS:,} items")
        return made

    return run


def _bounded_count(function: Any, most: int) -> Any:
    """``math.factorial``, ``comb`` and ``perm`` up to ``most``: past it they run for
    minutes."""

    def run(*args: Any) -> Any:
        if any(_whole(a) and a > most for a in args):
            raise _too_big(f"a math.{function.__name__} of a number past {most:,}")
        return function(*args)

    return run


def guard_symbols(symbols: dict[str, Any]) -> None:
    """Close what a running expression could reach through xacro's ``python`` functions."""
    python = symbols.get("python")
    if python is not None:
        if "vars" in python:
            python["vars"] = _vars
        if "type" in python:
            python["type"] = _type
        if "range" in python:
            python["range"] = _bounded_range(python["range"])
    if "range" in symbols:  # the deprecated name outside the namespace
        symbols["range"] = _bounded_range(symbols["range"])
    for table in (symbols, symbols.get("math")):
        if table is None:
            continue
        for name in ("factorial", "comb", "perm"):
            if name in table:
                table[name] = _bounded_count(table[name], 100_000)


def _refused(node: ast.AST) -> str | None:
    if isinstance(node, ast.Name) and node.id.startswith("__"):
        return node.id
    if isinstance(node, ast.keyword) and node.arg is not None and node.arg.startswith("__"):
        return node.arg
    if isinstance(node, ast.arg) and node.arg.startswith("__"):
        return node.arg
    if isinstance(node, ast.Attribute):
        attr = node.attr
        if attr.startswith("_") or attr.startswith(_REACHING):
            return attr
        if attr == "format_map":
            return attr
        if attr == "format" and not _plain_format(node.value):
            return attr
    return None


def _plain_format(value: ast.AST) -> bool:
    """A written format string whose fields read no attribute that starts with ``_``."""
    if not (isinstance(value, ast.Constant) and isinstance(value.value, str)):
        return False
    try:
        fields = [field for _, field, _, _ in string.Formatter().parse(value.value) if field]
    except ValueError:
        return True  # str.format refuses it before reading anything
    return not any("._" in "." + field or "[_" in field for field in fields)


def _vars(*args: Any) -> dict[str, Any]:
    found = vars(*args)
    return {key: value for key, value in found.items() if not str(key).startswith("_")}


def _type(*args: Any) -> type:
    if len(args) != 1:
        raise UnsafeExpression("python.type(...)", "python.type with three arguments")
    found = type(args[0])
    return _type if issubclass(found, type) else found  # type: ignore[return-value]
