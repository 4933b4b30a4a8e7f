"""Quick constructors of frozen dataclasses, for the objects a big robot has many of."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import fields
from typing import ParamSpec, TypeVar

_P = ParamSpec("_P")
_T = TypeVar("_T")


def builder(cls: Callable[_P, _T]) -> Callable[_P, _T]:
    """A constructor for the frozen dataclass ``cls`` taking every field, in order, by position.

    It sets the slots directly, which is about twice as fast as the generated ``__init__``
    (that goes through ``object.__setattr__`` for each field). Readers of big files use it.
    It is typed as ``cls`` itself, so that its arguments are checked, but it has no defaults:
    every field must be given.
    """
    names = [f.name for f in fields(cls)]  # type: ignore[arg-type]
    scope: dict[str, object] = {"_new": object.__new__, "_cls": cls}
    lines = [f"def build({', '.join(names)}):", "    obj = _new(_cls)"]
    for index, name in enumerate(names):
        scope[f"_set{index}"] = getattr(cls, name).__set__
        lines.append(f"    _set{index}(obj, {name})")
    lines.append("    return obj")
    exec("\n".join(lines), scope)  # the dataclasses module builds __init__ the same way
    return scope["build"]  # type: ignore[return-value]
