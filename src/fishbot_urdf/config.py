"""Which rules apply and how severe they are: ``[tool.fishbot]`` in pyproject.toml, or a
fishbot.toml, found upward from the checked file, and options on top.

Keys (the same as the command-line options): ``select``, ``extend-select`` and ``ignore``
(lists of rule ids, family names, or ``ALL``), ``severity`` (a table: rule id -> ``error``,
``warning`` or ``note``), ``strict`` (warnings fail too) and ``ground-tolerance`` (mm).
"""

from __future__ import annotations

import re
import sys
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from types import MappingProxyType
from typing import Any

from .diagnostics import Diagnostic, Severity, did_you_mean, listing
from .errors import ConfigError

__all__ = ["CONFIG_FILES", "Config", "find_config", "load_config"]

CONFIG_FILES = ("fishbot.toml", "pyproject.toml")
"""The files searched for in each folder, in this order (pyproject.toml only counts when it
has a ``[tool.fishbot]`` table)."""

_KEYS = ("select", "extend-select", "ignore", "severity", "strict", "ground-tolerance")
_ALL = "ALL"


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
        path: The file the configuration was read from, if any.
    """

    select: tuple[str, ...] | None = None
    extend_select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    severity: Mapping[str, Severity] = field(default_factory=lambda: MappingProxyType({}))
    strict: bool = False
    ground_tolerance: float | None = None
    path: str | None = None
    enabled: frozenset[str] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        from .rules import all_rules

        rules = all_rules()
        for key, names in (
            ("select", self.select or ()),
            ("extend-select", self.extend_select),
            ("ignore", self.ignore),
            ("severity", tuple(self.severity)),
        ):
            for name in names:
                _known(name, key, self.path, allow_groups=key != "severity")
        fatal = {r.id for r in rules if r.fatal}
        for key, names in (("ignore", self.ignore), ("severity", tuple(self.severity))):
            for name in names:
                if name in fatal:
                    raise ConfigError(
                        f"{key}: rule {name!r} cannot be changed: it stops the file from "
                        "being read",
                        path=self.path,
                        line=_line_of(self.path, name),
                    )
        chosen = _expand(self.select if self.select is not None else (_ALL,))
        chosen |= _expand(self.extend_select)
        chosen -= _expand(self.ignore) - fatal
        object.__setattr__(self, "enabled", frozenset(chosen | fatal))
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
    ) -> Config:
        """This configuration with options on top, as the command line gives them:
        ``select`` replaces the selection, the others add to it."""
        return Config(
            select=tuple(select) if select is not None else self.select,
            extend_select=(*self.extend_select, *extend_select),
            ignore=(*self.ignore, *ignore),
            severity={**self.severity, **(severity or {})},
            strict=self.strict if strict is None else strict,
            ground_tolerance=(
                self.ground_tolerance if ground_tolerance is None else ground_tolerance
            ),
            path=self.path,
        )


def find_config(start: str | Path) -> Path | None:
    """The nearest fishbot.toml, or pyproject.toml with a ``[tool.fishbot]`` table, in the
    folder ``start`` (or the folder of the file ``start``) and the folders above it."""
    here = Path(start).absolute()
    if not here.is_dir():
        here = here.parent
    for folder in (here, *here.parents):
        for name in CONFIG_FILES:
            candidate = folder / name
            if candidate.is_file() and (name != "pyproject.toml" or _has_table(candidate)):
                return candidate
    return None


def load_config(path: str | Path) -> Config:
    """Read a fishbot.toml (keys at the top) or a pyproject.toml (keys under
    ``[tool.fishbot]``).

    Raises:
        ConfigError: The file cannot be read, is not TOML, or has an unknown key, rule or
            severity, or a value of the wrong type.
    """
    name = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) else "not UTF-8 text"
        raise ConfigError(f"cannot read the configuration: {reason}", path=name) from exc
    try:
        document = _toml().loads(text)
    except ValueError as exc:  # tomllib.TOMLDecodeError
        line = re.search(r"line (\d+)", str(exc))
        raise ConfigError(
            f"not valid TOML: {str(exc).split(' (at ')[0]}",
            path=name,
            line=int(line[1]) if line else None,
        ) from exc
    table: Any = document
    if Path(path).name == "pyproject.toml":
        table = document.get("tool", {}).get("fishbot", {})
    if not isinstance(table, dict):
        raise ConfigError("[tool.fishbot] must be a table", path=name)
    return _from_table(table, name)


def _from_table(table: dict[str, Any], path: str) -> Config:
    for key in table:
        if key not in _KEYS:
            raise ConfigError(
                f"unknown key {key!r} ({did_you_mean(key, _KEYS)}keys: {', '.join(_KEYS)})",
                path=path,
                line=_line_of(path, key),
            )
    lists = {key: _names(table, key, path) for key in ("select", "extend-select", "ignore")}
    severity: dict[str, Severity] = {}
    given = table.get("severity", {})
    if not isinstance(given, dict):
        raise _wrong(path, "severity", 'a table of rule = "error|warning|note"')
    for rule, level in given.items():
        if level not in {s.value for s in Severity}:
            raise ConfigError(
                f"severity of {rule!r} is {level!r}: it must be error, warning or note",
                path=path,
                line=_line_of(path, rule),
            )
        severity[rule] = Severity(level)
    strict = table.get("strict", False)
    if not isinstance(strict, bool):
        raise _wrong(path, "strict", "true or false")
    tolerance = table.get("ground-tolerance")
    if tolerance is not None and (
        isinstance(tolerance, bool) or not isinstance(tolerance, int | float) or tolerance < 0
    ):
        raise _wrong(path, "ground-tolerance", "a number of millimetres, >= 0")
    return Config(
        select=lists["select"] if "select" in table else None,
        extend_select=lists["extend-select"],
        ignore=lists["ignore"],
        severity=severity,
        strict=strict,
        ground_tolerance=None if tolerance is None else float(tolerance),
        path=path,
    )


def _names(table: dict[str, Any], key: str, path: str) -> tuple[str, ...]:
    value = table.get(key, [])
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise _wrong(path, key, "a list of rule ids or family names")
    return tuple(value)


def _wrong(path: str, key: str, wanted: str) -> ConfigError:
    return ConfigError(f"{key} must be {wanted}", path=path, line=_line_of(path, key))


def _known(name: str, key: str, path: str | None, *, allow_groups: bool) -> None:
    from .rules import Family, ids

    known = set(ids())
    if allow_groups:
        known |= {f.value for f in Family} | {_ALL}
    if name not in known:
        what = "rule or family" if allow_groups else "rule"
        raise ConfigError(
            f"{key}: no {what} {name!r} ({did_you_mean(name, known)}rules: "
            f"{listing(ids(), 6)}; `fishbot rules` lists them all)",
            path=path,
            line=_line_of(path, name),
        )


def _expand(names: Iterable[str]) -> set[str]:
    from .rules import Family, all_rules

    families = {f.value for f in Family}
    chosen: set[str] = set()
    for name in names:
        if name == _ALL:
            chosen.update(r.id for r in all_rules())
        elif name in families:
            chosen.update(r.id for r in all_rules() if r.family.value == name)
        else:
            chosen.add(name)
    return chosen


def _line_of(path: str | None, word: str) -> int | None:
    """The first line of ``path`` that names ``word`` (for the error's location)."""
    if path is None:
        return None
    try:
        lines = Path(path).read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return None
    pattern = re.compile(rf"(^|[\s\"'\[,{{]){re.escape(word)}([\s\"'\],=}}]|$)")
    start = 0
    if Path(path).name == "pyproject.toml":
        start = next((i for i, t in enumerate(lines) if t.strip().startswith("[tool.fishbot")), 0)
    for number in range(start, len(lines)):
        if pattern.search(lines[number]):
            return number + 1
    return None


def _has_table(pyproject: Path) -> bool:
    try:
        text = pyproject.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return False
    return re.search(r"^\s*\[\s*tool\s*\.\s*fishbot\s*[\].]", text, re.M) is not None


def _toml() -> Any:
    if sys.version_info >= (3, 11):
        import tomllib

        return tomllib
    import tomli  # the same module, from PyPI, for Python 3.10

    return tomli
