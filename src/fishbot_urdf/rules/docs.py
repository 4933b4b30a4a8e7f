"""The rules as text: a table, one rule explained, and the same in Markdown (the README's
rule list is made here, so that it always says what the registry says)."""

from __future__ import annotations

import textwrap
from collections.abc import Sequence

from . import Rule

__all__ = ["explanation", "markdown_explanation", "markdown_table", "table"]


def _flags(rule: Rule) -> str:
    return rule.severity.value + (", always on" if rule.fatal else "")


def table(rules: Sequence[Rule]) -> str:
    """One line per rule: id, default severity, family, summary."""
    widths = [max((len(r.id) for r in rules), default=2), 7, 9]
    lines = [f"{'rule':<{widths[0]}}  {'severity':<8} {'family':<9}  summary"]
    for rule in rules:
        lines.append(
            f"{rule.id:<{widths[0]}}  {rule.severity.value:<8} {rule.family.value:<9}  "
            f"{rule.summary}"
        )
    return "\n".join(lines) + "\n"


def explanation(rule: Rule) -> str:
    """One rule, explained for a terminal."""
    parts = [
        f"{rule.id} ({_flags(rule)}; family {rule.family.value})",
        "",
        rule.summary,
    ]
    if rule.explanation:
        parts += ["", textwrap.fill(rule.explanation, 88)]
    if rule.consumers:
        parts += ["", "Matters to: " + ", ".join(c.label for c in rule.consumers) + "."]
    for title, snippet in (("Fails:", rule.bad), ("Passes:", rule.good)):
        if snippet:
            parts += ["", title, textwrap.indent(snippet.rstrip("\n"), "    ")]
    return "\n".join(parts) + "\n"


def markdown_table(rules: Sequence[Rule]) -> str:
    """The rules as a Markdown table: id, default severity, family, summary."""
    lines = ["| rule | severity | family | what it finds |", "| --- | --- | --- | --- |"]
    for rule in rules:
        severity = f"{rule.severity.value}" + (" (always on)" if rule.fatal else "")
        summary = rule.summary.replace("|", "\\|")
        lines.append(f"| `{rule.id}` | {severity} | {rule.family.value} | {summary} |")
    return "\n".join(lines) + "\n"


def markdown_explanation(rule: Rule) -> str:
    """One rule, explained in Markdown."""
    parts = [f"## `{rule.id}`", "", f"{rule.summary} *{_flags(rule)}; family {rule.family.value}*"]
    if rule.explanation:
        parts += ["", rule.explanation]
    if rule.consumers:
        parts += ["", "Matters to: " + ", ".join(c.label for c in rule.consumers) + "."]
    fence = "bash" if rule.language == "shell" else "toml" if rule.language == "toml" else "xml"
    for title, snippet in (("Fails:", rule.bad), ("Passes:", rule.good)):
        if snippet:
            parts += ["", title, "", f"```{fence}", snippet.rstrip("\n"), "```"]
    return "\n".join(parts) + "\n"
