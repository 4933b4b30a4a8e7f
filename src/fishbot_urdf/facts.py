"""The facts behind a finding, for programs: typed fields that also read as a mapping."""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, fields
from typing import Any

__all__ = ["Facts"]


@dataclass(frozen=True, slots=True, kw_only=True)
class Facts(Mapping[str, Any]):
    """The facts behind a finding, for programs: each rule that has some reports them as a
    subclass with typed fields (`catalog.physics.GroundFacts`, ...).

    A finding's facts are also a read-only mapping of the fields that are set (not None),
    so ``finding.data["mass"]`` and ``json.dumps(dict(finding.data))`` work as they did
    when the facts were a dict.
    """

    def __getitem__(self, key: str) -> Any:
        value = getattr(self, key, None) if key in self._names() else None
        if value is None:
            raise KeyError(key)
        return value

    def __iter__(self) -> Iterator[str]:
        return (name for name in self._names() if getattr(self, name) is not None)

    def __len__(self) -> int:
        return sum(1 for _ in self)

    @classmethod
    def _names(cls) -> tuple[str, ...]:
        return tuple(f.name for f in fields(cls))

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of the fields that are set (tuples as lists)."""
        return {name: _plain(getattr(self, name)) for name in self}


def _plain(value: Any) -> Any:
    return [_plain(v) for v in value] if isinstance(value, tuple) else value
