"""The files an expansion reaches by pattern or by YAML, within the deadline and the bounds.

``<xacro:include filename="parts/*.xacro"/>`` is globbed one folder at a time, the deadline
looked at before each, so a pattern over ``/proc/*/*/...`` stops with the time limit, and
each folder asked first whether it may be looked in (see ``_scope``). A
YAML file's aliases are counted before its values are built: 272 bytes of aliases to
aliases name billions of items, which writing out or walking would then go through.
"""

from __future__ import annotations

import fnmatch
import glob
import os
from collections.abc import Callable, Mapping
from typing import Any

from ..catalog.xacro import XACRO_ERROR
from ..errors import FishbotUrdfError, LimitError
from ._bounds import MAX_ITEMS
from ._budget import Budget

__all__ = ["MAX_MATCHES", "Globbing", "YamlError", "load_yaml_bounded"]

MAX_MATCHES = 100_000
"""The most files one include pattern may match."""


class YamlError(FishbotUrdfError):
    """A YAML file is not YAML, or nests deeper than can be built."""

    rule = XACRO_ERROR.id


class Globbing:
    """Stands in for the ``glob`` module in xacro: ``glob(pattern)`` within the expansion's
    budget (its deadline, and a cancellation)."""

    def __init__(self, budget: Budget, looking: Callable[[str, str], None] | None = None) -> None:
        self.budget = budget
        # Called with a folder and the pattern before the folder is looked in; raises to
        # refuse it.
        self.looking = looking

    def glob(self, pattern: str) -> list[str]:
        """The paths ``pattern`` matches, as :func:`glob.glob` finds them (hidden names only
        for a part that starts with a dot; no ``**``)."""
        root, parts = _split(pattern)
        magic = next((i for i, part in enumerate(parts) if glob.has_magic(part)), len(parts))
        if self.looking is not None:  # the folder the pattern starts from, there or not
            self.looking(os.path.join(root, *parts[:magic]), pattern)
        found = [root]
        for index, part in enumerate(parts):
            last = index == len(parts) - 1
            found = self._step(found, part, last, pattern if index >= magic else None)
        return found

    def _step(self, bases: list[str], part: str, last: bool, pattern: str | None) -> list[str]:
        matched: list[str] = []
        for base in bases:
            self.budget.check()
            if pattern is not None and self.looking is not None:
                self.looking(base, pattern)
            if not part:  # a doubled or trailing separator
                matched.append(os.path.join(base, ""))
                continue
            if not glob.has_magic(part):
                path = os.path.join(base, part)
                if os.path.lexists(path) if last else os.path.isdir(path):
                    matched.append(path)
                continue
            matched.extend(os.path.join(base, n) for n in _names(base, part, last))
            if len(matched) > MAX_MATCHES:
                raise LimitError(f"an include pattern matches more than {MAX_MATCHES:,} files")
        return matched


def _split(pattern: str) -> tuple[str, list[str]]:
    drive, rest = os.path.splitdrive(pattern)
    separators = os.sep + (os.altsep or "")
    if rest[:1] and rest[0] in separators:
        return drive + os.sep, [p for p in _parts(rest.lstrip(separators))]
    return drive, _parts(rest)


def _parts(path: str) -> list[str]:
    if os.altsep:
        path = path.replace(os.altsep, os.sep)
    return path.split(os.sep)


def _names(base: str, part: str, last: bool) -> list[str]:
    try:
        with os.scandir(base or os.curdir) as entries:
            names = []
            for entry in entries:
                try:
                    if last or entry.is_dir():
                        names.append(entry.name)
                except OSError:
                    continue
    except OSError:
        return []
    if not part.startswith("."):
        names = [n for n in names if not n.startswith(".")]
    return fnmatch.filter(names, part)


def load_yaml_bounded(
    data: bytes,
    units: Mapping[str, float],
    unit: Callable[[str], float],
    budget: Budget,
) -> Any:
    """One YAML document read safely (PyYAML's SafeLoader), its unit tags (``!degrees``,
    ...) evaluated by ``unit`` and scaled, and its aliases counted first: the values it
    stands for are charged to the budget before they are built.

    Raises:
        YamlError: The text is not YAML, or nests deeper than Python can build.
        LimitError: Its aliases name more than :data:`MAX_ITEMS` items.
    """
    import yaml  # comes with xacro

    class Loader(yaml.SafeLoader):  # type: ignore[misc]
        pass

    for tag, factor in units.items():

        def construct(loader: Any, node: Any, factor: float = factor) -> float:
            return unit(loader.construct_scalar(node)) * factor

        Loader.add_constructor(tag, construct)
    loader = Loader(data)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        nodes = _expanded(node, {}, budget)
        if nodes > MAX_ITEMS:
            raise LimitError(
                f"the YAML file's aliases name more than {MAX_ITEMS:,} items "
                "(aliases of aliases, each naming the one before many times?)"
            )
        budget.spend(nodes * _NODE_BYTES, "YAML values")
        return loader.construct_document(node)
    except yaml.YAMLError as exc:
        raise YamlError(str(exc)) from exc
    except RecursionError as exc:
        raise YamlError("it nests deeper than can be read") from exc
    finally:
        loader.dispose()


_NODE_BYTES = 64  # what one YAML value built takes, about (a short string, a float)


def _expanded(node: Any, sizes: dict[int, int], budget: Budget) -> int:
    """How many nodes ``node`` stands for with every alias written out (each distinct node
    looked at once; a node that holds itself counts once)."""
    key = id(node)
    known = sizes.get(key)
    if known is not None:
        return known
    sizes[key] = 1
    if not len(sizes) & 1023:
        budget.check()
    total = 1
    value = node.value
    if isinstance(value, list):
        for item in value:
            if isinstance(item, tuple):  # a mapping's (key, value)
                total += _expanded(item[0], sizes, budget) + _expanded(item[1], sizes, budget)
            else:
                total += _expanded(item, sizes, budget)
            if total > MAX_ITEMS:
                break
    sizes[key] = total
    return total
