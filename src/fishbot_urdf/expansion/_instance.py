"""A copy of xacro of its own for each expansion, its evaluator chosen once, when it is made.

xacro keeps its state in module globals (the file and macro stacks, the files read, the
substitution arguments, the symbol table) and calls ``safe_eval`` -- Python's ``eval`` --
by its module-global name. Swapping those globals in and out of the one imported module
around a run leaves a window where a walk still going on (on another thread, after an
interrupt) sees the other evaluator. Here each expansion runs xacro's own code in new
module objects instead: ``xacro``, ``xacro.substitution_args`` and ``xacro.color`` are
executed afresh (their compiled code is read once; making a copy takes about a
millisecond), and nothing in them is ever put back. For an untrusted expansion the copy's
``safe_eval`` and ``$(eval)`` are the allowlist interpreter's from the start, and the
builtins its code sees have no ``eval``, ``exec`` or ``compile`` at all: whatever path
through xacro an expression takes, it cannot reach Python's evaluator.

``xacro.xmlutils`` and ``xacro.cli`` hold no state and are shared with the imported
package; ``sys.modules`` is not touched.
"""

from __future__ import annotations

import builtins
import functools
import importlib.util
import types
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import xacro.cli  # type: ignore[import-untyped]  # shared by every copy, as is xmlutils
import xacro.xmlutils  # type: ignore[import-untyped]

from ..catalog.xacro import XACRO_UNSAFE
from ..errors import FishbotUrdfError

__all__ = ["Xacro", "load_xacro"]

_OWN = ("color", "substitution_args")  # executed afresh, in this order
_SHARED = ("cli", "xmlutils")  # stateless: the imported modules serve every copy
_NO_EVAL = ("eval", "exec", "compile", "breakpoint")


@dataclass(frozen=True, slots=True)
class Xacro:
    """One expansion's copy of xacro: ``xacro`` is the package's ``__init__``, ``subst``
    its ``substitution_args``, ``color`` its ``color``."""

    xacro: Any
    subst: Any
    color: Any


class EvaluatorRefused(FishbotUrdfError):
    """xacro's code reached for Python's evaluator in an untrusted expansion."""

    rule = XACRO_UNSAFE.id


def load_xacro(
    *,
    trust: bool,
    message: Callable[..., None],
    evaluate: Callable[[str, Any, Any], Any],
    substitution_eval: Callable[[str, dict[str, Any]], str],
) -> Xacro:
    """A new copy of xacro.

    Args:
        trust: Keep xacro's evaluator (Python's ``eval``); else ``evaluate`` and
            ``substitution_eval`` are its evaluators from the start, and its builtins have
            no ``eval``, ``exec`` or ``compile``.
        message: Stands in for ``xacro.color.message``, through which xacro prints.
        evaluate: xacro's ``safe_eval(expression, globals, locals)`` (untrusted only).
        substitution_eval: ``substitution_args._eval(text, context)`` (untrusted only).
    """
    modules: dict[str, types.ModuleType] = {}
    names = _builtins(modules, trust)
    for name in _OWN:
        module = modules[name] = _module(f"xacro.{name}", names)
        exec(_code(name), vars(module))  # xacro's own code, not a file's
        if name == "color":
            vars(module)["message"] = message  # before xacro imports it by name
        elif not trust:
            vars(module)["_eval"] = substitution_eval
    package = _module("xacro", names)
    package.__path__ = []
    exec(_code(""), vars(package))
    for name in _SHARED:  # a package's modules are its attributes
        setattr(package, name, _shared(name))
    for name, module in modules.items():
        setattr(package, name, module)
    if not trust:
        vars(package)["safe_eval"] = evaluate
    return Xacro(package, modules["substitution_args"], modules["color"])


def _module(name: str, names: dict[str, Any]) -> types.ModuleType:
    module = types.ModuleType(name)
    module.__dict__["__builtins__"] = names
    module.__package__ = "xacro"
    return module


def _builtins(own: dict[str, types.ModuleType], trust: bool) -> dict[str, Any]:
    """The builtins a copy's code sees: its relative imports find the copy's own modules,
    and, untrusted, Python's evaluator is not there."""
    names = dict(vars(builtins))

    def importing(
        name: str,
        globals: Any = None,
        locals: Any = None,
        fromlist: Any = (),
        level: int = 0,
    ) -> Any:
        if level == 1 and name in own:
            return own[name]
        if level == 1 and name in _SHARED:
            return _shared(name)
        if level == 0 and name == "yaml" and not fromlist:
            return _LAZY_YAML
        return builtins.__import__(name, globals, locals, fromlist, level)

    if not trust:
        for name in _NO_EVAL:
            names[name] = _refusing(name)
    names["__import__"] = importing
    return names


class _Lazy(types.ModuleType):
    """A module imported on first use of one of its names. (substitution_args imports yaml
    for the rare ``$(arg)`` it parses as YAML: loaded at once, yaml was a tenth of `fishbot
    sdf`'s time on the fishbot.)"""

    def __getattr__(self, attribute: str) -> Any:
        return getattr(importlib.import_module(self.__name__), attribute)


_LAZY_YAML = _Lazy("yaml")


def _refusing(name: str) -> Callable[..., Any]:
    def refuse(*args: Any, **kwargs: Any) -> Any:
        raise EvaluatorRefused(f"{name}() is not available to xacro in an untrusted expansion")

    refuse.__name__ = name
    return refuse


def _shared(name: str) -> types.ModuleType:
    module: types.ModuleType = {"cli": xacro.cli, "xmlutils": xacro.xmlutils}[name]
    return module


@functools.cache
def _code(name: str) -> types.CodeType:
    """The compiled code of xacro's ``__init__`` (``""``) or of one of its modules, as the
    import system caches it."""
    spec = importlib.util.find_spec(f"xacro.{name}" if name else "xacro")
    if spec is None or spec.loader is None:
        raise FishbotUrdfError(f"xacro{'.' + name if name else ''} is not installed")
    code: types.CodeType = spec.loader.get_code(spec.name)  # type: ignore[attr-defined]
    return code
