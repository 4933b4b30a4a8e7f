"""A property's value worked out when it is plain arithmetic of numbers and other
properties; nothing is evaluated as code (the expression's tree is walked, and anything
but numbers, names, + - * / // % ** and parentheses gives no value)."""

from __future__ import annotations

import ast
import math
import operator
import re
from collections.abc import Callable

__all__ = ["evaluate"]

_EXPRESSION = re.compile(r"\$\{([^}]*)\}")
_CONSTANTS = {"pi": math.pi}
_OPERATORS: dict[type, Callable[[float, float], float]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.Mod: operator.mod,
}
_DEPTH = 16  # how deep properties may be defined by others
_LONGEST = 400  # characters of one expression


class _NoValue(Exception):
    pass


def evaluate(written: str, lookup: Callable[[str], str | None]) -> str | None:
    """``written`` with each ``${...}`` replaced by its value, or None when one cannot be
    worked out; ``lookup`` gives the value written for another property."""
    try:
        return _substitute(written, lookup, 0, frozenset())
    except (_NoValue, ArithmeticError, ValueError, RecursionError):
        return None


def _substitute(
    written: str, lookup: Callable[[str], str | None], depth: int, seen: frozenset[str]
) -> str:
    if depth > _DEPTH:
        raise _NoValue
    if "$" not in written:
        return written
    parts, at = [], 0
    for match in _EXPRESSION.finditer(written):
        parts.append(written[at : match.start()])
        parts.append(_text(_number(match[1], lookup, depth, seen)))
        at = match.end()
    parts.append(written[at:])
    result = "".join(parts)
    if "$" in result:
        raise _NoValue
    return result


def _text(value: float) -> str:
    return str(value)


def _number(
    code: str, lookup: Callable[[str], str | None], depth: int, seen: frozenset[str]
) -> float:
    if len(code) > _LONGEST:
        raise _NoValue
    try:
        tree = ast.parse(code.strip(), mode="eval")
    except SyntaxError as exc:
        raise _NoValue from exc

    def walk(node: ast.AST) -> float:
        if isinstance(node, ast.Expression):
            return walk(node.body)
        if isinstance(node, ast.Constant) and type(node.value) in (int, float):
            number: float = node.value  # type: ignore[assignment]
            return number
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
            value = walk(node.operand)
            return -value if isinstance(node.op, ast.USub) else value
        if isinstance(node, ast.BinOp):
            left, right = walk(node.left), walk(node.right)
            if isinstance(node.op, ast.Pow):
                if abs(right) > 64 or abs(left) > 1e6:
                    raise _NoValue
                return float(left**right)
            apply = _OPERATORS.get(type(node.op))
            if apply is None:
                raise _NoValue
            return apply(left, right)
        if isinstance(node, ast.Name):
            return _named(node.id, lookup, depth, seen)
        raise _NoValue

    return walk(tree)


def _named(
    name: str, lookup: Callable[[str], str | None], depth: int, seen: frozenset[str]
) -> float:
    if name in _CONSTANTS:
        return _CONSTANTS[name]
    written = lookup(name)
    if written is None or name in seen:
        raise _NoValue
    value = _substitute(written, lookup, depth + 1, seen | {name})
    try:
        return float(value) if "." in value or "e" in value.lower() else int(value)
    except ValueError as exc:
        raise _NoValue from exc
