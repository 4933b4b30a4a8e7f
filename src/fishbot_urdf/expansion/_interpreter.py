"""xacro's ``${...}`` and ``$(eval ...)`` interpreted over Python's ``ast``, by allowlist.

ROS's xacro hands each expression to Python's ``eval``, so a robot file runs code with the
rights of whoever expands it. Here an expression is parsed into a tree and walked; nothing
is compiled or run as Python. What a walk may do:

- literals; names, from the expression's lambdas and comprehensions, then xacro's symbol
  table (properties, macro parameters, ``math``, ``python``, ``xacro``);
- every operator, conditional expressions, subscripts and slices, f-strings,
  comprehensions and generator expressions, and lambdas (whose bodies are walked the same
  way when they are called);
- attributes only from :mod:`._allowlist` (a namespace's entries, and named methods and
  plain attributes of strings, containers and numbers);
- calls only of the functions in the symbol table when the expansion began (less
  ``python.type`` and ``python.vars``), of listed methods, and of the expression's own
  lambdas; ``str.format`` and ``%`` only with plain fields.

Anything else -- an attribute or a name that starts with ``_``, ``:=``, ``await``, a
function that is not listed -- is refused with :class:`UnsafeExpression` naming the
construct. All the expressions of one expansion draw on one :class:`._budget.Budget`:
every step (a node walked, an item a function goes through, the work of an operation on big
numbers by their size) and every value made (by its size, charged before it is made where
that can be known), with the deadline looked at every :data:`CHECK_EVERY` steps. One
expression may also take at most :data:`MAX_STEPS` steps, make no single value of more than
:data:`MAX_ITEMS` items, and nest its calls at most :data:`MAX_DEPTH` deep.
"""

from __future__ import annotations

import ast
import functools
import operator
import threading
import types
from collections.abc import Callable, Iterable, Iterator, Mapping
from typing import Any

from ._allowlist import allowed_attribute, allowed_callables, is_allowed_method
from ._bounds import (
    MAX_BITS,
    MAX_ITEMS,
    SIZED,
    UnsafeExpression,
    binary_size,
    binary_steps,
    call_steps,
    check_binary,
    check_printf,
    check_spec,
    check_str_method,
    too_big,
    too_long,
    weight,
)
from ._budget import CHECK_EVERY, Budget, size_of

__all__ = [
    "CHECK_EVERY",
    "MAX_DEPTH",
    "MAX_STEPS",
    "Lambda",
    "evaluate",
    "parsed",
]

MAX_STEPS = 1_000_000
"""The most steps (nodes walked, items iterated, 64 items weighed) one expression may take."""
MAX_DEPTH = 100
"""How deep an expression's lambdas may call each other."""

_SCALARS = (int, float, complex, bool, type(None), range, slice)
_SUBSCRIPTABLE = (str, bytes, list, tuple, dict, range)
# Functions that look at their arguments' top level only: no need to weigh them first.
_SHALLOW = frozenset(
    """abs all any append bool clear copy divmod enumerate filter float get insert int
    isinstance issubclass items keys len list map ord pop popitem range reverse reversed
    round setdefault slice tuple values zip""".split()  # noqa: SIM905
)
_KINDS_TAKEN = (isinstance, issubclass)  # functions whose arguments may be classes as such
# Functions that go through an iterable they are given, in C: each item they take is
# counted as a step (a list of ten million zeros is made in one step; summing it is not).
# Some go through each argument; the rest only the first, and min and max only when it is
# the only one.
_CONSUMING_ALL = frozenset(
    """difference difference_update intersection intersection_update isdisjoint issubset
    issuperset symmetric_difference symmetric_difference_update union update""".split()  # noqa: SIM905
)
_CONSUMING_FIRST = frozenset(
    """all any dict extend frozenset fromkeys fsum list prod set sorted sum tuple""".split()  # noqa: SIM905
)  # str.join is in neither: its parts are taken (and counted) before it is called
_CONSUMING_ALONE = frozenset(("max", "min"))
_UNBOUND = (types.MethodDescriptorType, types.ClassMethodDescriptorType)
_ACTIVE = threading.local()  # the evaluations running in this thread, innermost last


@functools.lru_cache(maxsize=4096)
def parsed(expression: str) -> ast.expr:
    """The tree of one expression (a macro's expressions come again at each call).

    Raises:
        SyntaxError: The text is not a Python expression.
    """
    return ast.parse(expression.strip(), "<expression>", mode="eval").body


def evaluate(
    expression: str,
    globals: Any,
    locals: Mapping[str, Any] | None = None,
    builtins: Mapping[str, Any] | None = None,
    *,
    allowed: frozenset[int] | None = None,
    budget: Budget | None = None,
) -> Any:
    """Evaluate one expression as xacro's ``safe_eval`` would, by allowlist.

    Args:
        expression: The text between ``${`` and ``}``.
        globals: xacro's symbol table (names are looked up with ``[]``).
        locals: Names looked up first, in the expression's outermost scope only (as
            ``eval`` looks up its ``locals``: ``$(eval)`` keeps its arguments there).
        builtins: Names looked up last.
        allowed: The ids of the functions the expression may call (default: those in
            ``globals`` and its namespaces).
        budget: What the expansion has left to spend, shared by all its expressions
            (default: a budget of its own, with the limits in force).

    Raises:
        SyntaxError: The text is not a Python expression.
        UnsafeExpression: The expression does what the allowlist does not allow, or would
            pass a bound.
        LimitError: The budget ran out (TimeLimitError: the deadline passed).
        Exception: What Python raises for the same expression (NameError, TypeError, ...).
    """
    try:
        tree = parsed(expression)
    except (MemoryError, RecursionError):  # Python's parser gives up on deep nesting
        raise UnsafeExpression(expression, _TOO_DEEP, too_long=True) from None
    if allowed is None:
        allowed = allowed_callables(getattr(globals, "root", globals))
    run = _Evaluation(globals, locals, builtins or {}, allowed, budget or Budget())
    stack: list[_Evaluation] = _ACTIVE.__dict__.setdefault("stack", [])
    stack.append(run)
    try:
        result = run.value(tree, None)
        # xacro writes it out with str(), into the document or a property: a copy made
        # each time, charged each time.
        run.budget.spend(run.weigh(result), "expression results")
        return result
    except UnsafeExpression as exc:
        raise exc.named(expression) from None
    except RecursionError:
        raise UnsafeExpression(expression, "an expression nested this deep") from None
    finally:
        stack.pop()


_TOO_DEEP = "more nesting than Python's parser can read"


class _Frame:
    """The names of one lambda call or one comprehension, and the scope around it."""

    __slots__ = ("names", "parent")

    def __init__(self, parent: _Frame | None, names: dict[str, Any] | None = None) -> None:
        self.parent = parent
        self.names = {} if names is None else names


class Lambda:
    """A lambda an expression made: called, its body is walked by the evaluation running
    then (or the one that made it)."""

    __slots__ = ("defaults", "frame", "keywords", "maker", "node")

    def __init__(
        self,
        node: ast.Lambda,
        frame: _Frame | None,
        defaults: tuple[Any, ...],
        keywords: dict[str, Any],
        maker: _Evaluation,
    ) -> None:
        self.node = node
        self.frame = frame
        self.defaults = defaults
        self.keywords = keywords
        self.maker = maker

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        stack = _ACTIVE.__dict__.get("stack")
        run = stack[-1] if stack else self.maker
        return run.call_lambda(self, args, kwargs)

    def __repr__(self) -> str:
        return "<lambda>"


class _CalledBack:
    """A function of the allowlist handed to another, called back through the evaluation
    (``python.map('{0.x}'.format, ...)`` has its format looked at, ``sorted(key='x'.ljust)``
    its width)."""

    __slots__ = ("function", "run")

    def __init__(self, function: Any, run: _Evaluation) -> None:
        self.function = function
        self.run = run

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self.run.call(self.function, list(args), kwargs)

    def __repr__(self) -> str:
        return repr(self.function)


class _Counted:
    """An iterable whose items are counted as steps as they are taken."""

    __slots__ = ("items", "run")

    def __init__(self, items: Iterable[Any], run: _Evaluation) -> None:
        self.items = items
        self.run = run

    def __iter__(self) -> Iterator[Any]:
        tick = self.run.tick
        for item in self.items:
            tick()
            yield item


_BINARY: dict[type[ast.operator], Callable[[Any, Any], Any]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.MatMult: operator.matmul,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.Mod: operator.mod,
    ast.Pow: operator.pow,
    ast.LShift: operator.lshift,
    ast.RShift: operator.rshift,
    ast.BitOr: operator.or_,
    ast.BitXor: operator.xor,
    ast.BitAnd: operator.and_,
}
_UNARY: dict[type[ast.unaryop], Callable[[Any], Any]] = {
    ast.UAdd: operator.pos,
    ast.USub: operator.neg,
    ast.Not: operator.not_,
    ast.Invert: operator.invert,
}
_COMPARE: dict[type[ast.cmpop], Callable[[Any, Any], Any]] = {
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.Is: operator.is_,
    ast.IsNot: operator.is_not,
    ast.In: lambda a, b: a in b,
    ast.NotIn: lambda a, b: a not in b,
}
_REFUSED_NODES = {
    ast.NamedExpr: "':=' (an assignment)",
    ast.Await: "'await'",
    ast.Yield: "'yield'",
    ast.YieldFrom: "'yield from'",
}


class _Evaluation:
    """One expression's walk: its names, what it may call, and what it has spent."""

    def __init__(
        self,
        globals: Any,
        locals: Mapping[str, Any] | None,
        builtins: Mapping[str, Any],
        allowed: frozenset[int],
        budget: Budget,
    ) -> None:
        self.globals = globals
        self.locals = locals
        self.builtins = builtins
        self.allowed = allowed
        self.budget = budget
        self.last_step = budget.steps + MAX_STEPS  # this expression's own bound
        self.depth = 0

    # -- budget --------------------------------------------------------------------------
    def tick(self, count: int = 1) -> None:
        budget = self.budget
        budget.tick(count)
        if budget.steps > self.last_step:
            raise UnsafeExpression("", f"more than {MAX_STEPS:,} steps", too_long=True)

    def work(self, count: int, what: str) -> None:
        """Take ``count`` steps for one operation done in C, before it is begun: refused if
        it would pass this expression's steps or the deadline."""
        if count > CHECK_EVERY:
            if self.budget.steps + count > self.last_step:
                raise UnsafeExpression("", f"more than {MAX_STEPS:,} steps", too_long=True)
            self.budget.afford(count, what)
        elif count:
            self.tick(count)

    def made_value(self, value: Any) -> Any:
        """Count a value made against the bounds and the budget."""
        if isinstance(value, SIZED):
            if len(value) > MAX_ITEMS:
                raise too_big(f"a value of more than {MAX_ITEMS:,} items")
        elif isinstance(value, int) and value.bit_length() > MAX_BITS:
            raise too_big(f"a number of more than {MAX_BITS:,} bits")
        self.budget.spend(size_of(value))
        return value

    def weigh(self, value: Any) -> int:
        """Refuse a value that, written out or compared whole, would pass :data:`MAX_ITEMS`
        items: ``[[[0] * 1000] * 1000] * 1000`` is three small lists that hold a billion
        zeros. Each distinct container is looked at once; 64 of its items count as a step.
        Gives how many items it holds written out (a number's digits are not counted)."""
        if isinstance(value, _SCALARS):
            return 1
        if isinstance(value, str | bytes) and len(value) < 64:
            return len(value)
        weights: dict[int, int] = {}
        total = weight(value, weights, self.tick)
        if total > MAX_ITEMS:
            raise too_big(f"a value of more than {MAX_ITEMS:,} items when written out")
        return total

    # -- the walk ------------------------------------------------------------------------
    def value(self, node: ast.AST, frame: _Frame | None) -> Any:
        self.tick()
        step = _WALK.get(type(node))
        if step is None:
            raise UnsafeExpression("", _describe(node))
        return step(self, node, frame)

    def _constant(self, node: ast.Constant, frame: _Frame | None) -> Any:
        return node.value

    def _name(self, node: ast.Name, frame: _Frame | None) -> Any:
        name = node.id
        if name.startswith("__"):
            raise UnsafeExpression("", f"the name '{name}'")
        scope = frame
        while scope is not None:
            if name in scope.names:
                return scope.names[name]
            scope = scope.parent
        if frame is None and self.locals is not None:
            try:
                return self.locals[name]
            except KeyError:
                pass
        try:
            return self.globals[name]
        except KeyError:
            pass
        try:
            return self.builtins[name]
        except KeyError:
            raise NameError(f"name '{name}' is not defined", name=name) from None

    def _attribute(self, node: ast.Attribute, frame: _Frame | None) -> Any:
        owner = self.value(node.value, frame)
        return attribute(owner, node.attr)

    def _subscript(self, node: ast.Subscript, frame: _Frame | None) -> Any:
        owner = self.value(node.value, frame)
        key = self.value(node.slice, frame)
        if isinstance(owner, _SUBSCRIPTABLE):
            return owner[key]
        if isinstance(owner, type) or hasattr(type(owner), "__getitem__"):
            raise UnsafeExpression("", f"a subscript of {_kind(owner)}")
        raise TypeError(f"'{type(owner).__name__}' object is not subscriptable")

    def _slice(self, node: ast.Slice, frame: _Frame | None) -> slice:
        parts = (node.lower, node.upper, node.step)
        return slice(*(None if part is None else self.value(part, frame) for part in parts))

    def _call(self, node: ast.Call, frame: _Frame | None) -> Any:
        function = self.value(node.func, frame)
        args: list[Any] = []
        for item in node.args:
            if isinstance(item, ast.Starred):
                args.extend(self.items(self.value(item.value, frame)))
            else:
                args.append(self.value(item, frame))
        kwargs: dict[str, Any] = {}
        for keyword in node.keywords:
            given = self.value(keyword.value, frame)
            if keyword.arg is None:
                if not isinstance(given, Mapping):
                    raise TypeError("argument after ** must be a mapping")
                self.tick(len(given))
                kwargs.update(given)
            else:
                kwargs[keyword.arg] = given
        for key in kwargs:
            if not isinstance(key, str) or key.startswith("__"):
                raise UnsafeExpression("", f"the keyword argument '{key}'")
        return self.call(function, args, kwargs)

    def call(self, function: Any, args: list[Any], kwargs: dict[str, Any]) -> Any:
        """Call a function the allowlist names, after looking at what it would make and
        charging what it would do."""
        self.tick()
        if isinstance(function, Lambda):
            return self.call_lambda(function, tuple(args), kwargs)
        if id(function) not in self.allowed:
            if not is_allowed_method(function):
                if not callable(function):
                    raise TypeError(f"'{type(function).__name__}' object is not callable")
                raise UnsafeExpression("", f"a call of {_kind(function)}")
            args = self._method_arguments(function, args, kwargs)
        if function not in _KINDS_TAKEN:
            args = [self._called_back(given) for given in args]
            kwargs = {key: self._called_back(given) for key, given in kwargs.items()}
        name = getattr(function, "__name__", None)
        if name not in _SHALLOW:
            for given in (*args, *kwargs.values()):
                self.weigh(given)
        self.work(call_steps(name, args), f"{name}() of numbers this big")
        if name in _CONSUMING_ALL or name in _CONSUMING_FIRST or name in _CONSUMING_ALONE:
            args = self._consumed(function, name, args)
        return self.made_value(function(*args, **kwargs))

    def _consumed(self, function: Any, name: str, args: list[Any]) -> list[Any]:
        """The arguments of a function that goes through them, counted as it does."""
        first = 1 if isinstance(function, _UNBOUND) else 0  # a method's owner is not
        if name in _CONSUMING_ALL:
            return [*args[:first], *(self.counted(given) for given in args[first:])]
        if len(args) <= first or (name in _CONSUMING_ALONE and len(args) > first + 1):
            return args
        return [*args[:first], self.counted(args[first]), *args[first + 1 :]]

    def counted(self, given: Any) -> Any:
        """An iterable handed to a function that goes through it, each item it takes
        counted as a step (a mapping, which such functions read whole, by its size)."""
        if isinstance(given, Mapping):
            self.work(len(given), "reading a mapping this big")
            return given
        if isinstance(given, _SCALARS) and not isinstance(given, range):
            return given
        if not hasattr(given, "__iter__"):
            return given
        return _Counted(given, self)

    def _called_back(self, given: Any) -> Any:
        """A function handed to another (``map``'s, ``sorted``'s key), made to go through
        :meth:`call` when it is called back: its arguments are looked at as if the
        expression had called it."""
        if not callable(given) or isinstance(given, Lambda):
            return given
        if not self._may_call(given):
            raise UnsafeExpression("", f"passing {_kind(given)} to a function")
        return _CalledBack(given, self)

    def _may_call(self, function: Any) -> bool:
        return (
            isinstance(function, Lambda)
            or id(function) in self.allowed
            or is_allowed_method(function)
        )

    def _method_arguments(self, method: Any, args: list[Any], kwargs: dict[str, Any]) -> list[Any]:
        """Look at what a listed method would make before it makes it; the arguments,
        with an iterable to join made a list."""
        bound = hasattr(method, "__self__") and not isinstance(method.__self__, type)
        owner, rest = (method.__self__, args) if bound else (args[0] if args else None, args[1:])
        name = method.__name__
        if isinstance(owner, str | bytes):
            check_str_method(name, owner, rest, kwargs)
            if name == "join" and rest:
                parts = self.items(rest[0])
                total = sum(len(p) for p in parts if isinstance(p, str | bytes))
                if total + len(owner) * max(0, len(parts) - 1) > MAX_ITEMS:
                    raise too_big(f"a value of more than {MAX_ITEMS:,} items")
                return [parts] if bound else [owner, parts]
        elif name in ("extend", "update") and rest and too_long(owner, rest[0]):
            raise too_big(f"a value of more than {MAX_ITEMS:,} items")
        return args

    def call_lambda(self, function: Lambda, args: tuple[Any, ...], kwargs: dict[str, Any]) -> Any:
        if self.depth >= MAX_DEPTH:
            raise UnsafeExpression("", f"more than {MAX_DEPTH} nested lambda calls", too_long=True)
        names = _bind(function, args, kwargs)
        self.depth += 1
        try:
            return self.value(function.node.body, _Frame(function.frame, names))
        finally:
            self.depth -= 1

    def _lambda(self, node: ast.Lambda, frame: _Frame | None) -> Lambda:
        arguments = node.args
        for argument in (
            *arguments.posonlyargs,
            *arguments.args,
            *arguments.kwonlyargs,
            arguments.vararg,
            arguments.kwarg,
        ):
            if argument is not None and argument.arg.startswith("__"):
                raise UnsafeExpression("", f"the parameter '{argument.arg}'")
        defaults = tuple(self.value(d, frame) for d in arguments.defaults)
        keywords = {
            a.arg: self.value(d, frame)
            for a, d in zip(arguments.kwonlyargs, arguments.kw_defaults, strict=True)
            if d is not None
        }
        return Lambda(node, frame, defaults, keywords, self)

    def _binary(self, node: ast.BinOp, frame: _Frame | None) -> Any:
        left = self.value(node.left, frame)
        right = self.value(node.right, frame)
        kind = type(node.op)
        check_binary(kind, left, right)
        if kind is ast.Mod and isinstance(left, str | bytes):
            check_printf(left, right)
            self.weigh(right)
        # What it makes and what it does, charged before it is done.
        self.work(binary_steps(kind, left, right), "an operation on values this big")
        self.budget.spend(binary_size(kind, left, right))
        return _BINARY[kind](left, right)

    def _unary(self, node: ast.UnaryOp, frame: _Frame | None) -> Any:
        return _UNARY[type(node.op)](self.value(node.operand, frame))

    def _boolean(self, node: ast.BoolOp, frame: _Frame | None) -> Any:
        result: Any = None
        for part in node.values:
            result = self.value(part, frame)
            if isinstance(node.op, ast.And) != bool(result):
                return result
        return result

    def _compare(self, node: ast.Compare, frame: _Frame | None) -> Any:
        left = self.value(node.left, frame)
        for op, part in zip(node.ops, node.comparators, strict=True):
            right = self.value(part, frame)
            self.weigh(left)
            self.weigh(right)
            if isinstance(op, ast.In | ast.NotIn):
                right = self._searched(right)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True

    def _searched(self, container: Any) -> Any:
        """What ``in`` looks through, its work charged: a list item by item, a string 64
        characters a step, an iterator each item it takes."""
        if isinstance(container, list | tuple):
            self.work(len(container), "searching a sequence this long")
        elif isinstance(container, str | bytes):
            self.work(len(container) // 64, "searching a string this long")
        elif not isinstance(container, Mapping | set | frozenset | range):
            return self.counted(container)
        return container

    def _conditional(self, node: ast.IfExp, frame: _Frame | None) -> Any:
        chosen = node.body if self.value(node.test, frame) else node.orelse
        return self.value(chosen, frame)

    def _elements(self, nodes: list[ast.expr], frame: _Frame | None) -> list[Any]:
        found: list[Any] = []
        for item in nodes:
            if isinstance(item, ast.Starred):
                found.extend(self.items(self.value(item.value, frame)))
            else:
                found.append(self.value(item, frame))
        return found

    def _list(self, node: ast.List, frame: _Frame | None) -> list[Any]:
        return self.made_value(self._elements(node.elts, frame))  # type: ignore[no-any-return]

    def _tuple(self, node: ast.Tuple, frame: _Frame | None) -> tuple[Any, ...]:
        return self.made_value(tuple(self._elements(node.elts, frame)))  # type: ignore[no-any-return]

    def _set(self, node: ast.Set, frame: _Frame | None) -> set[Any]:
        items = self._elements(node.elts, frame)
        for item in items:
            self.weigh(item)
        return self.made_value(set(items))  # type: ignore[no-any-return]

    def _dict(self, node: ast.Dict, frame: _Frame | None) -> dict[Any, Any]:
        made: dict[Any, Any] = {}
        for key, item in zip(node.keys, node.values, strict=True):
            if key is None:
                given = self.value(item, frame)
                if not isinstance(given, Mapping):
                    raise TypeError(f"'{type(given).__name__}' object is not a mapping")
                self.tick(len(given))
                made.update(given)
            else:
                name = self.value(key, frame)
                self.weigh(name)
                made[name] = self.value(item, frame)
        return self.made_value(made)  # type: ignore[no-any-return]

    def items(self, iterable: Any) -> list[Any]:
        """An iterable's items, each counted as a step."""
        found: list[Any] = []
        for item in iterable:
            self.tick()
            found.append(item)
        return self.made_value(found)  # type: ignore[no-any-return]

    # -- comprehensions ------------------------------------------------------------------
    def _scopes(
        self, generators: list[ast.comprehension], frame: _Frame | None, first: Any
    ) -> Iterator[_Frame]:
        """The scope of each item a comprehension makes (one scope for all its loops, as in
        Python); ``first`` is the outermost iterable, taken in the scope around it."""
        scope = _Frame(frame)

        def loop(index: int, iterable: Iterable[Any]) -> Iterator[_Frame]:
            generator = generators[index]
            if generator.is_async:
                raise UnsafeExpression("", "'async for'")
            for item in iterable:
                self.tick()
                self._assign(generator.target, item, scope)
                if all(self.value(test, scope) for test in generator.ifs):
                    if index + 1 == len(generators):
                        yield scope
                    else:
                        yield from loop(index + 1, self.value(generators[index + 1].iter, scope))

        return loop(0, first)

    def _first(self, node: Any, frame: _Frame | None) -> Iterator[_Frame]:
        generators: list[ast.comprehension] = node.generators
        return self._scopes(generators, frame, iter(self.value(generators[0].iter, frame)))

    def _list_comprehension(self, node: ast.ListComp, frame: _Frame | None) -> list[Any]:
        made: list[Any] = []
        for scope in self._first(node, frame):
            made.append(self.value(node.elt, scope))
            if len(made) > MAX_ITEMS:
                raise too_big(f"a value of more than {MAX_ITEMS:,} items")
        return self.made_value(made)  # type: ignore[no-any-return]

    def _set_comprehension(self, node: ast.SetComp, frame: _Frame | None) -> set[Any]:
        made: set[Any] = set()
        for scope in self._first(node, frame):
            item = self.value(node.elt, scope)
            self.weigh(item)
            made.add(item)
        return self.made_value(made)  # type: ignore[no-any-return]

    def _dict_comprehension(self, node: ast.DictComp, frame: _Frame | None) -> dict[Any, Any]:
        made: dict[Any, Any] = {}
        for scope in self._first(node, frame):
            key = self.value(node.key, scope)
            self.weigh(key)
            made[key] = self.value(node.value, scope)
        return self.made_value(made)  # type: ignore[no-any-return]

    def _generator(self, node: ast.GeneratorExp, frame: _Frame | None) -> Iterator[Any]:
        scopes = self._first(node, frame)
        return (self.value(node.elt, scope) for scope in scopes)

    def _assign(self, target: ast.expr, value: Any, scope: _Frame) -> None:
        if isinstance(target, ast.Name):
            if target.id.startswith("__"):
                raise UnsafeExpression("", f"the name '{target.id}'")
            scope.names[target.id] = value
            return
        if not isinstance(target, ast.Tuple | ast.List):
            raise UnsafeExpression("", f"assigning to {_describe(target)}")
        items = self.items(value)
        starred = [i for i, t in enumerate(target.elts) if isinstance(t, ast.Starred)]
        wanted = len(target.elts)
        if not starred:
            if len(items) != wanted:
                few = len(items) < wanted
                raise ValueError(
                    f"not enough values to unpack (expected {wanted}, got {len(items)})"
                    if few
                    else f"too many values to unpack (expected {wanted})"
                )
            for part, item in zip(target.elts, items, strict=True):
                self._assign(part, item, scope)
            return
        at = starred[0]
        after = wanted - at - 1
        if len(items) < wanted - 1:
            raise ValueError(
                f"not enough values to unpack (expected at least {wanted - 1}, got {len(items)})"
            )
        for part, item in zip(target.elts[:at], items[:at], strict=True):
            self._assign(part, item, scope)
        rest = target.elts[at]
        assert isinstance(rest, ast.Starred)
        self._assign(rest.value, items[at : len(items) - after], scope)
        for part, item in zip(target.elts[at + 1 :], items[len(items) - after :], strict=True):
            self._assign(part, item, scope)

    # -- f-strings -----------------------------------------------------------------------
    def _joined(self, node: ast.JoinedStr, frame: _Frame | None) -> str:
        parts = [str(self.value(part, frame)) for part in node.values]
        total = sum(len(p) for p in parts)
        if total > MAX_ITEMS:
            raise too_big(f"a value of more than {MAX_ITEMS:,} items")
        return self.made_value("".join(parts))  # type: ignore[no-any-return]

    def _formatted(self, node: ast.FormattedValue, frame: _Frame | None) -> str:
        shown = self.value(node.value, frame)
        self.weigh(shown)
        if node.conversion == ord("r"):
            shown = repr(shown)
        elif node.conversion == ord("s"):
            shown = str(shown)
        elif node.conversion == ord("a"):
            shown = ascii(shown)
        spec = "" if node.format_spec is None else self.value(node.format_spec, frame)
        check_spec(spec)
        return format(shown, spec)


_WALK: dict[type[ast.AST], Callable[[_Evaluation, Any, _Frame | None], Any]] = {
    ast.Constant: _Evaluation._constant,
    ast.Name: _Evaluation._name,
    ast.Attribute: _Evaluation._attribute,
    ast.Subscript: _Evaluation._subscript,
    ast.Call: _Evaluation._call,
    ast.BinOp: _Evaluation._binary,
    ast.UnaryOp: _Evaluation._unary,
    ast.BoolOp: _Evaluation._boolean,
    ast.Compare: _Evaluation._compare,
    ast.IfExp: _Evaluation._conditional,
    ast.List: _Evaluation._list,
    ast.Tuple: _Evaluation._tuple,
    ast.Set: _Evaluation._set,
    ast.Dict: _Evaluation._dict,
    ast.ListComp: _Evaluation._list_comprehension,
    ast.SetComp: _Evaluation._set_comprehension,
    ast.DictComp: _Evaluation._dict_comprehension,
    ast.GeneratorExp: _Evaluation._generator,
    ast.Lambda: _Evaluation._lambda,
    ast.JoinedStr: _Evaluation._joined,
    ast.FormattedValue: _Evaluation._formatted,
    ast.Slice: _Evaluation._slice,
}
"""The step for each kind of node; a kind not here is refused."""


def attribute(owner: Any, name: str) -> Any:
    """``owner.name``, if the allowlist lets an expression read it.

    Raises:
        UnsafeExpression: The attribute is not on the allowlist.
        AttributeError: ``owner`` has no such attribute (or a namespace no such entry).
    """
    if name.startswith("_"):
        raise UnsafeExpression("", f"the attribute '{name}'")
    if isinstance(owner, dict) and not isinstance(owner, type):
        entry = _entry(owner, name)
        if entry is not _NOTHING:
            return entry
    if allowed_attribute(owner, name):
        return getattr(owner, name)
    if isinstance(owner, type):
        if not hasattr(owner, name):  # a typo: as Python says it
            raise AttributeError(f"type object '{owner.__name__}' has no attribute '{name}'")
    elif not hasattr(type(owner), name):
        raise AttributeError(f"'{type(owner).__name__}' object has no attribute '{name}'")
    raise UnsafeExpression("", f"the attribute '{name}' of {_kind(owner)}")


_NOTHING = object()


def _entry(owner: dict[Any, Any], name: str) -> Any:
    """A namespace's entry read as an attribute (``math.pi``, a YAML mapping's ``a.b``):
    through the class's own ``__getattr__``, as Python reaches it when no real attribute of
    that name is found; a dict's listed methods come first, as in Python."""
    lookup = getattr(type(owner), "__getattr__", None)
    if lookup is None or allowed_attribute(owner, name):
        return _NOTHING
    return lookup(owner, name)


def _bind(function: Lambda, args: tuple[Any, ...], kwargs: dict[str, Any]) -> dict[str, Any]:
    """The names of one call of a lambda, bound as Python binds them."""
    spec = function.node.args
    positional = [a.arg for a in (*spec.posonlyargs, *spec.args)]
    keyword_only = [a.arg for a in spec.kwonlyargs]
    names: dict[str, Any] = dict(zip(positional, args, strict=False))
    if len(args) > len(positional) and spec.vararg is None:
        raise TypeError(
            f"<lambda>() takes {len(positional)} positional arguments but {len(args)} were given"
        )
    if spec.vararg is not None:
        names[spec.vararg.arg] = tuple(args[len(positional) :])
    extra: dict[str, Any] = {}
    by_name = set(positional[len(spec.posonlyargs) :]) | set(keyword_only)
    for key, value in kwargs.items():
        if key in by_name:
            if key in names:
                raise TypeError(f"<lambda>() got multiple values for argument '{key}'")
            names[key] = value
        elif spec.kwarg is not None:
            extra[key] = value
        else:
            raise TypeError(f"<lambda>() got an unexpected keyword argument '{key}'")
    first_default = len(positional) - len(function.defaults)
    for index, name in enumerate(positional):
        if name not in names:
            if index < first_default:
                raise TypeError(f"<lambda>() missing 1 required positional argument: '{name}'")
            names[name] = function.defaults[index - first_default]
    for name in keyword_only:
        if name not in names:
            if name not in function.keywords:
                raise TypeError(f"<lambda>() missing 1 required keyword-only argument: '{name}'")
            names[name] = function.keywords[name]
    if spec.kwarg is not None:
        names[spec.kwarg.arg] = extra
    return names


def _kind(value: Any) -> str:
    if isinstance(value, type):
        return f"the class '{value.__name__}'"
    name = getattr(value, "__qualname__", None) or getattr(value, "__name__", None)
    if callable(value) and isinstance(name, str):
        return f"'{name}'"
    return f"a '{type(value).__name__}'"


def _describe(node: ast.AST) -> str:
    refused = _REFUSED_NODES.get(type(node))
    if refused is not None:
        return refused
    return (
        f"'{type(node).__name__}' ({ast.unparse(node)[:40]})"
        if isinstance(node, ast.expr)
        else f"'{type(node).__name__}'"
    )
