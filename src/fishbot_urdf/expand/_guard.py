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
import string
from typing import Any

from ..errors import FishbotUrdfError

__all__ = ["UnsafeExpression", "check_expression", "guard_symbols", "guarded"]

_REACHING = ("gi_", "cr_", "ag_", "f_", "tb_", "co_", "func_", "im_")
"""Attribute prefixes of generators, coroutines, frames, tracebacks, code and functions."""


class UnsafeExpression(FishbotUrdfError):
    """An expression was refused; ``what`` names the part refused."""

    rule = "xacro-unsafe"

    def __init__(self, expression: str, what: str) -> None:
        super().__init__(f"'{what}' is not allowed in an expression")
        self.expression = expression
        self.what = what


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

    As few frames deep as can be (no helper but the scan): xacro evaluates at the bottom
    of its recursion, and the frames here count against how deep macros may nest.
    """
    tree = _parsed(expression)
    _scan(tree, expression)
    globals["__builtins__"] = dict(builtins or {})
    return eval(compile(tree, "<expression>", "eval"), globals, locals)  # checked above


def _parsed(expression: str) -> ast.Expression:
    tree = compile(expression.strip(), "<expression>", "eval", ast.PyCF_ONLY_AST)
    assert isinstance(tree, ast.Expression)
    return tree


def _scan(tree: ast.AST, expression: str) -> None:
    found: list[tuple[int, int, str]] = []
    todo = [tree]
    while todo:
        node = todo.pop()
        refused = _refused(node)
        if refused is not None:
            found.append((getattr(node, "lineno", 0), getattr(node, "end_col_offset", 0), refused))
        todo.extend(ast.iter_child_nodes(node))
    if found:
        raise UnsafeExpression(expression, min(found)[2])  # the first, as it is written


def guard_symbols(symbols: dict[str, Any]) -> None:
    """Close what a running expression could reach through xacro's ``python`` functions."""
    python = symbols.get("python")
    if python is None:
        return
    if "vars" in python:
        python["vars"] = _vars
    if "type" in python:
        python["type"] = _type


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
