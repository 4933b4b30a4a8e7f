"""The rule catalogue: every finding fishbot can make, as data.

Each rule has a stable id, a default severity, a family, a one-line summary, an explanation
with a failing and a fixed snippet, and the programs it matters to. The catalogue imports
nothing above the findings, so the XML reader, the parser and the xacro expansion report
its rules without climbing; the checks that report the tree's rules are in
`fishbot_urdf.rules`, each registered against the rules it reports.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import cache
from types import MappingProxyType, ModuleType

from ..diagnostics import Consumer, Family, Rule
from ..errors import UnknownNameError
from . import (
    conversion,
    gazebo,
    joints,
    meshes,
    physics,
    reading,
    references,
    setup,
    simulation,
    structure,
    xacro,
    xml,
)

__all__ = ["Consumer", "Family", "Rule", "all_rules", "get", "ids", "rules_in"]


def all_rules() -> tuple[Rule, ...]:
    """Every rule, by family then id."""
    return tuple(_registry().values())


def get(rule_id: str) -> Rule:
    """The rule ``rule_id``.

    Raises:
        UnknownNameError: No rule has that id (the error names the closest ones).
    """
    registry = _registry()
    try:
        return registry[rule_id]
    except KeyError:
        raise UnknownNameError("rule", rule_id, registry) from None


def ids() -> frozenset[str]:
    """Every rule id."""
    return frozenset(_registry())


@cache
def _registry() -> Mapping[str, Rule]:
    """Every rule by id, collected once (read-only, so threads may share it)."""
    return MappingProxyType(_collect())


def rules_in(module: ModuleType) -> tuple[Rule, ...]:
    """The rules a module of the catalogue defines (``rules_in(catalog.meshes)``), in the
    order it defines them."""
    return tuple(r for r in vars(module).values() if isinstance(r, Rule))


def _collect() -> dict[str, Rule]:
    found: dict[str, Rule] = {}
    order = list(Family)
    modules = (
        xml,
        reading,
        structure,
        joints,
        references,
        meshes,
        physics,
        gazebo,
        simulation,
        conversion,
        xacro,
        setup,
    )
    rules = [r for module in modules for r in rules_in(module)]
    for rule in sorted(rules, key=lambda r: (order.index(r.family), r.id)):
        if rule.id in found and found[rule.id] is not rule:
            raise AssertionError(f"two rules are named {rule.id!r}")
        found[rule.id] = rule
    return found
