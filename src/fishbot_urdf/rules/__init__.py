"""The checks: one module per family of rules, each reporting the rules of the catalogue
(`fishbot_urdf.catalog`) that it lists in its ``REPORTS``.

The rule's data (``Rule``, ``all_rules``, ``get``, ``ids``) is the catalogue's, and kept here
under its former names.
"""

from __future__ import annotations

from ..catalog import Consumer, Family, Rule, all_rules, get, ids

__all__ = ["Consumer", "Family", "Rule", "all_rules", "get", "ids"]
