"""Which rules apply and how severe they are: ``[tool.fishbot]`` in pyproject.toml, or a
fishbot.toml, found upward from the checked file, and options on top.

Keys (the same as the command-line options): ``select``, ``extend-select`` and ``ignore``
(lists of rule ids, family names, or ``ALL``), ``severity`` (a table: rule id -> ``error``,
``warning`` or ``note``), ``strict`` (warnings fail too), ``ground-tolerance`` (mm) and
``allow-read`` (folders, from the configuration file's own, that xacro files may read in
besides the robot's tree: see :mod:`fishbot_urdf.expansion`) and ``targets`` (the programs
the robots are for: see :mod:`fishbot_urdf.targets`).

Selections are resolved as ruff resolves them: within one layer (the file, then the command
line) the more specific name wins (a rule id over a family, a family over ``ALL``; an
``ignore`` over a ``select`` of the same rank); a later layer's ``select`` starts the
selection again (the earlier ``ignore`` still holds), its ``extend-select`` and ``ignore``
change what the earlier layers chose.
"""

from __future__ import annotations

import os
import re
import sys
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from types import MappingProxyType
from typing import Any

from .catalog import Family, all_rules, ids
from .diagnostics import Diagnostic, Severity
from .errors import ConfigError, InputError, UnknownNameError
from .inputs import read_input
from .targets import target_name
from .wording import did_you_mean, listing

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10
    import tomli as tomllib

__all__ = [
    "CONFIG_FILES",
    "Config",
    "Selection",
    "check_selectors",
    "check_severities",
    "find_config",
    "load_config",
]

CONFIG_FILES = ("fishbot.toml", "pyproject.toml")
"""The files searched for in each folder, in this order (pyproject.toml only counts when it
has a ``[tool.fishbot]`` table)."""

_KEYS = (
    "select",
    "extend-select",
    "ignore",
    "severity",
    "strict",
    "ground-tolerance",
    "allow-read",
    "targets",
)
_ALL = "ALL"
_LEVELS = tuple(s.value for s in Severity)
# A line that opens [tool.fishbot] (or a table in it), or sets a tool.fishbot key.
_TABLE = re.compile(r"\s*\[?\s*tool\s*\.\s*[\"']?fishbot\b")


@dataclass(frozen=True, slots=True)
class Selection:
    """One layer of rule choices laid over a configuration (the command line's options).

    Attributes:
        select: The rules to apply instead of those chosen so far, or None to keep them.
        extend_select: Rules applied as well.
        ignore: Rules not applied.
    """

    select: tuple[str, ...] | None = None
    extend_select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()


@dataclass(frozen=True, slots=True)
class Config:
    """The rules to apply and their severities.

    Attributes:
        select: The rules to apply (ids, family names or ``ALL``); None means every rule.
        extend_select: Rules applied on top of ``select``.
        ignore: Rules not applied (fatal rules, which stop the reading, always apply).
        severity: Rule id -> the severity its findings get.
        strict: Warnings fail a robot too.
        ground_tolerance: How far (mm) the lowest collision point may be from the ground,
            or None for the default (2 mm).
        allow_read: Folders xacro files may read in besides the robot's tree and the
            packages ``$(find)`` finds (see :mod:`fishbot_urdf.expansion`); a file's are
            absolute, from its folder. A relative one is taken from the current folder.
        targets: The programs the robots are for (names of `fishbot_urdf.targets.TARGETS`),
            or None for each robot's default: an error that harms none of them is a
            warning.
        path: The file the configuration was read from, if any.
        overrides: Layers of choices laid over this one, in order (`updated` adds one).
        enabled: The ids of the rules that apply, resolved from all of the above.
    """

    select: tuple[str, ...] | None = None
    extend_select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    severity: Mapping[str, Severity] = field(default_factory=lambda: MappingProxyType({}))
    strict: bool = False
    ground_tolerance: float | None = None
    allow_read: tuple[str, ...] = ()
    targets: tuple[str, ...] | None = None
    path: str | None = None
    overrides: tuple[Selection, ...] = ()
    enabled: frozenset[str] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        layers = (Selection(self.select, self.extend_select, self.ignore), *self.overrides)
        for layer in layers:
            for key, names in (
                ("select", layer.select or ()),
                ("extend-select", layer.extend_select),
                ("ignore", layer.ignore),
            ):
                check_selectors(key, names, path=self.path)
        check_severities(self.severity, path=self.path)
        if self.targets is not None:
            object.__setattr__(self, "targets", _targets(self.targets, self.path))
        fatal = {r.id for r in all_rules() if r.fatal}
        object.__setattr__(self, "enabled", frozenset(_resolve(layers) | fatal))
        object.__setattr__(self, "severity", MappingProxyType(dict(self.severity)))

    def applies(self, rule: str) -> bool:
        """Whether findings of ``rule`` are reported."""
        return rule in self.enabled

    def apply(self, findings: Iterable[Diagnostic]) -> list[Diagnostic]:
        """The findings of the selected rules, each with its configured severity."""
        enabled, severity = self.enabled, self.severity
        kept: list[Diagnostic] = []
        for finding in findings:
            if finding.rule not in enabled:
                continue
            wanted = severity.get(finding.rule)
            kept.append(
                finding
                if wanted is None or wanted is finding.severity
                else replace(finding, severity=wanted)
            )
        return kept

    def updated(
        self,
        *,
        select: Iterable[str] | None = None,
        extend_select: Iterable[str] = (),
        ignore: Iterable[str] = (),
        severity: Mapping[str, Severity] | None = None,
        strict: bool | None = None,
        ground_tolerance: float | None = None,
        targets: Iterable[str] | None = None,
    ) -> Config:
        """This configuration with options on top, as the command line gives them:
        ``select`` replaces the selection (this configuration's ``ignore`` still holds),
        ``extend_select``, ``ignore`` and ``severity`` add to it, ``strict``,
        ``ground_tolerance`` and ``targets`` replace it unless None."""
        layer = Selection(
            None if select is None else tuple(select), tuple(extend_select), tuple(ignore)
        )
        return replace(
            self,
            severity={**self.severity, **(severity or {})},
            strict=self.strict if strict is None else strict,
            ground_tolerance=(
                self.ground_tolerance if ground_tolerance is None else ground_tolerance
            ),
            targets=self.targets if targets is None else tuple(targets),
            overrides=(*self.overrides, layer) if layer != Selection() else self.overrides,
        )


def check_selectors(key: str, names: Iterable[str], *, path: str | None = None) -> None:
    """Check the rule ids, family names or ``ALL`` given to ``key`` (``select``,
    ``extend-select`` or ``ignore``).

    Raises:
        ConfigError: A name is no rule and no family, or ``ignore`` names a fatal rule
            (one that stops the file from being read).
    """
    for name in names:
        _known(name, key, path, allow_groups=True)
        if key == "ignore":
            _changeable(name, key, path)


def check_severities(severity: Mapping[str, object], *, path: str | None = None) -> None:
    """Check a ``severity`` table: rule id -> ``error``, ``warning`` or ``note``.

    Raises:
        ConfigError: A key is no rule id, or names a fatal rule; a value is no severity.
    """
    for rule, level in severity.items():
        _known(rule, "severity", path, allow_groups=False)
        _changeable(rule, "severity", path)
        if isinstance(level, Severity):
            continue
        if level not in _LEVELS:
            raise ConfigError(
                f"severity of {rule!r} is {level!r}: it must be error, warning or note",
                path=path,
                line=_line_of(path, rule),
            )


def find_config(start: str | Path, known: dict[Path, Path | None] | None = None) -> Path | None:
    """The nearest fishbot.toml, or pyproject.toml with a ``[tool.fishbot]`` table.

    It is looked for in the folder ``start`` (or the folder of the file ``start``) and the
    folders above it.

    ``known`` (folder -> its answer) spares looking again in folders already searched:
    pass the same dict for the many files of one run.
    """
    here = Path(start).absolute()
    if not _stat_says(here, Path.is_dir):
        here = here.parent
    known = {} if known is None else known
    passed: list[Path] = []
    found: Path | None = None
    for folder in (here, *here.parents):
        if folder in known:
            found = known[folder]
            break
        passed.append(folder)
        found = next(
            (
                candidate
                for candidate in (folder / name for name in CONFIG_FILES)
                if _stat_says(candidate, Path.is_file)
                and (candidate.name != "pyproject.toml" or _has_table(candidate))
            ),
            None,
        )
        if found is not None:
            break
    for folder in passed:
        known[folder] = found
    return found


def _stat_says(path: Path, test: Callable[[Path], bool]) -> bool:
    """``test(path)``, False when the path cannot even be looked at (a name too long, a
    folder without permission): the file's own read reports that, as one finding."""
    try:
        return test(path)
    except OSError:
        return False


def load_config(path: str | Path) -> Config:
    """Read a fishbot.toml or a pyproject.toml.

    A fishbot.toml has its keys at the top, a pyproject.toml under ``[tool.fishbot]`` (one
    without that table is the default configuration). Any other file name is read as a
    fishbot.toml.

    The file is read as every input is (:func:`fishbot_urdf.inputs.read_input`): a
    regular file within the size limit.

    Raises:
        ConfigError: The file cannot be read (or is no regular file, or is too big), is not
            TOML (or nests too deeply), or has an unknown key, rule or severity, or a value
            of the wrong type.
    """
    name = str(path)
    try:
        text = read_input(name).decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ConfigError("cannot read the configuration: not UTF-8 text", path=name) from exc
    except InputError as exc:  # not there, a folder, a FIFO, a device, too big
        raise ConfigError(f"cannot read the configuration: {exc.message}", path=name) from exc
    document = _parse(text, name)
    table: Any = document
    if Path(path).name == "pyproject.toml":
        tool = document.get("tool")
        table = tool.get("fishbot", {}) if isinstance(tool, dict) else {}
        if not isinstance(table, dict):
            raise ConfigError(
                "[tool.fishbot] must be a table", path=name, line=_line_of(name, "fishbot")
            )
    return _from_table(table, name)


def _parse(text: str, path: str) -> dict[str, Any]:
    try:
        document: dict[str, Any] = tomllib.loads(text)
    except RecursionError as exc:  # tomllib reads nested arrays and tables recursively
        raise ConfigError(
            "not valid TOML: arrays or tables nested too deeply to read (nest them less)",
            path=path,
        ) from exc
    except ValueError as exc:  # tomllib.TOMLDecodeError
        where = re.search(r"\(at line (\d+), column (\d+)\)", str(exc))
        raise ConfigError(
            f"not valid TOML: {str(exc).split(' (at ')[0]}",
            path=path,
            line=int(where[1]) if where else None,
            column=int(where[2]) if where else None,
        ) from exc
    return document


def _from_table(table: dict[str, Any], path: str) -> Config:
    for key in table:
        if key not in _KEYS:
            raise ConfigError(
                f"unknown key {key!r} ({did_you_mean(key, _KEYS)}keys: {', '.join(_KEYS)})",
                path=path,
                line=_line_of(path, key),
            )
    lists = {key: _names(table, key, path) for key in ("select", "extend-select", "ignore")}
    given = table.get("severity", {})
    if not isinstance(given, dict):
        raise _wrong(path, "severity", 'a table of rule = "error|warning|note"')
    check_severities(given, path=path)
    strict = table.get("strict", False)
    if not isinstance(strict, bool):
        raise _wrong(path, "strict", "true or false")
    tolerance = table.get("ground-tolerance")
    if tolerance is not None and (
        isinstance(tolerance, bool)
        or not isinstance(tolerance, int | float)
        or not 0 <= tolerance < float("inf")
    ):
        raise _wrong(path, "ground-tolerance", "a number of millimetres, >= 0")
    folders = table.get("allow-read", [])
    if not isinstance(folders, list) or not all(isinstance(f, str) and f for f in folders):
        raise _wrong(path, "allow-read", "a list of folders")
    targets = table.get("targets")
    if targets is not None and (
        not isinstance(targets, list) or not all(isinstance(t, str) for t in targets)
    ):
        raise _wrong(path, "targets", 'a list of programs ("ros", "gazebo", ...)')
    here = os.path.dirname(os.path.abspath(path))
    return Config(
        select=lists["select"] if "select" in table else None,
        extend_select=lists["extend-select"],
        ignore=lists["ignore"],
        severity={rule: Severity(level) for rule, level in given.items()},
        strict=strict,
        ground_tolerance=None if tolerance is None else float(tolerance),
        allow_read=tuple(os.path.normpath(os.path.join(here, f)) for f in folders),
        targets=None if targets is None else tuple(targets),
        path=path,
    )


def _targets(names: Iterable[str], path: str | None) -> tuple[str, ...]:
    """The targets ``names`` stand for, each once."""
    found: list[str] = []
    for name in names:
        try:
            found.append(target_name(name))
        except UnknownNameError as exc:
            raise ConfigError(
                exc.message, key="targets", path=path, line=_line_of(path, name)
            ) from None
    return tuple(dict.fromkeys(found))


def _names(table: dict[str, Any], key: str, path: str) -> tuple[str, ...]:
    value = table.get(key, [])
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise _wrong(path, key, "a list of rule ids or family names")
    return tuple(value)


def _wrong(path: str, key: str, wanted: str) -> ConfigError:
    return ConfigError(f"{key} must be {wanted}", path=path, line=_line_of(path, key))


def _known(name: str, key: str, path: str | None, *, allow_groups: bool) -> None:
    rules = ids()
    families = {f.value for f in Family}
    known = rules | families | {_ALL} if allow_groups else rules
    if name in known:
        return
    if allow_groups:
        what, listed = "rule or family", f"families: {', '.join(f.value for f in Family)}"
    else:
        what, listed = "rule", f"rules: {listing(rules, 6, near=name)}"
        if name in families or name == _ALL:
            listed = f"a severity is set per rule, not for {name!r}"
    raise ConfigError(
        f"no {what} {name!r} ({did_you_mean(name, known)}{listed}; "
        "`fishbot rules` lists the rules)",
        key=key,
        path=path,
        line=_line_of(path, name),
    )


def _changeable(name: str, key: str, path: str | None) -> None:
    if any(rule.id == name and rule.fatal for rule in all_rules()):
        raise ConfigError(
            f"rule {name!r} cannot be changed: it stops the file from being read",
            key=key,
            path=path,
            line=_line_of(path, name),
        )


def _resolve(layers: Iterable[Selection]) -> set[str]:
    """The rules the layers choose, the more specific name winning within a layer."""
    rules = all_rules()
    enabled = {rule.id for rule in rules}
    earlier_ignores: tuple[str, ...] = ()
    for layer in layers:
        if layer.select is not None:
            chosen = (*layer.select, *layer.extend_select)
            ignored = (*earlier_ignores, *layer.ignore)
            enabled = {rule.id for rule in rules if _rank(rule, chosen) > _rank(rule, ignored)}
        else:
            for rule in rules:
                chosen_rank = _rank(rule, layer.extend_select)
                ignored_rank = _rank(rule, layer.ignore)
                if chosen_rank > ignored_rank:
                    enabled.add(rule.id)
                elif ignored_rank:
                    enabled.discard(rule.id)
        earlier_ignores += layer.ignore
    return enabled


def _rank(rule: Any, names: Iterable[str]) -> int:
    """How specifically ``names`` name ``rule``: 3 by id, 2 by family, 1 by ALL, else 0."""
    best = 0
    for name in names:
        if name == rule.id:
            return 3
        if name == rule.family.value:
            best = 2
        elif name == _ALL:
            best = max(best, 1)
    return best


def _line_of(path: str | None, word: str) -> int | None:
    """The first line of ``path`` that names ``word`` (for the error's location)."""
    if path is None:
        return None
    text = _text_or_none(path)
    if text is None:
        return None
    lines = text.splitlines()
    pattern = re.compile(rf"(^|[\s\"'\[,{{.]){re.escape(word)}([\s\"'\],=}}.]|$)")
    start = 0
    if Path(path).name == "pyproject.toml":
        start = next((i for i, t in enumerate(lines) if _TABLE.match(t)), 0)
    for number in range(start, len(lines)):
        if pattern.search(lines[number].split("#")[0]):
            return number + 1
    return None


def _has_table(pyproject: Path) -> bool:
    """Whether a pyproject.toml has a ``[tool.fishbot]`` table (one that is not TOML
    counts when a line opens that table, so that reading it reports the fault)."""
    text = _text_or_none(pyproject)
    if text is None or "fishbot" not in text:
        return False
    try:
        document = tomllib.loads(text)
    except (ValueError, RecursionError):
        return any(_TABLE.match(line) for line in text.splitlines())
    tool = document.get("tool")
    return isinstance(tool, dict) and "fishbot" in tool


def _text_or_none(path: str | Path) -> str | None:
    """The text of a configuration file, or None when it cannot be read (as `load_config`
    reads it)."""
    try:
        return read_input(path).decode("utf-8")
    except (InputError, UnicodeDecodeError):
        return None
