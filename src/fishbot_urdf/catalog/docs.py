"""The rules as text: a table, one rule explained, and the same in Markdown (the
documentation site's rule list and rule pages are made here as the site builds, so that
they always say what the registry says).

`with_rule_table` fills a page's rule list, between its two markers, from the registry;
`with_consumer_table` the table of which programs each rule matters to.
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Sequence

from ..errors import ArgumentError
from . import Consumer, Rule

__all__ = [
    "CONSUMERS_BEGIN",
    "CONSUMERS_END",
    "README_BEGIN",
    "README_END",
    "explanation",
    "markdown_consumers",
    "markdown_explanation",
    "markdown_table",
    "table",
    "with_consumer_table",
    "with_rule_table",
]

README_BEGIN = "<!-- rules: begin -->"
"""The line after which a page's rule list starts."""
README_END = "<!-- rules: end -->"
"""The line before which a page's rule list ends."""
CONSUMERS_BEGIN = "<!-- consumers: begin -->"
"""The line after which a page's table of rules and programs starts."""
CONSUMERS_END = "<!-- consumers: end -->"
"""The line before which a page's table of rules and programs ends."""


def _flags(rule: Rule) -> str:
    return rule.severity.value + (", always on" if rule.fatal else "")


def _fill(text: str) -> str:
    # Rule ids, options and numbers with a hyphen (inertia-mismatch, 0-255) stay whole.
    return textwrap.fill(text, 88, break_on_hyphens=False, break_long_words=False)


def _markdown(text: str) -> str:
    """A summary in Markdown: tags as code (a bare <robot> is an HTML tag there, which
    renderers drop), and a table's | escaped."""
    return re.sub(r"(<[^<>`]+>)", r"`\1`", text).replace("|", "\\|")


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
        parts += ["", _fill(rule.explanation)]
    if rule.consumers:
        parts += ["", _fill(_matters(rule))]
    for title, snippet in (("Fails:", rule.bad), ("Passes:", rule.good)):
        if snippet:
            parts += ["", title, textwrap.indent(snippet.rstrip("\n"), "    ")]
    return "\n".join(parts) + "\n"


def _matters(rule: Rule) -> str:
    """The programs a rule matters to, and, for an error, that it is one only for them."""
    text = "Matters to: " + ", ".join(c.label for c in rule.consumers) + "."
    if rule.severity.value == "error" and not rule.fatal:
        text += " An error where the robot is for one of them (its targets), a warning elsewhere."
    return text


def markdown_table(rules: Sequence[Rule]) -> str:
    """The rules as a Markdown table: id, default severity, family, summary."""
    lines = ["| rule | severity | family | what it finds |", "| --- | --- | --- | --- |"]
    for rule in rules:
        severity = f"{rule.severity.value}" + (" (always on)" if rule.fatal else "")
        summary = _markdown(rule.summary)
        lines.append(f"| `{rule.id}` | {severity} | {rule.family.value} | {summary} |")
    return "\n".join(lines) + "\n"


def markdown_consumers(rules: Sequence[Rule]) -> str:
    """The rules that name the programs they matter to, as a Markdown table: id, default
    severity, and a column per program, ticked where the rule matters to it."""
    columns = list(Consumer)
    lines = [
        "| rule | severity | " + " | ".join(c.value for c in columns) + " |",
        "| --- | --- |" + " :-: |" * len(columns),
    ]
    for rule in rules:
        if not rule.consumers:
            continue
        ticks = " | ".join("✓" if c in rule.consumers else "" for c in columns)
        severity = f"{rule.severity.value}" + (" (always on)" if rule.fatal else "")
        lines.append(f"| `{rule.id}` | {severity} | {ticks} |")
    return "\n".join(lines) + "\n"


def markdown_explanation(rule: Rule) -> str:
    """One rule, explained in Markdown."""
    parts = [
        f"## `{rule.id}`",
        "",
        f"{_markdown(rule.summary)} *{_flags(rule)}; family {rule.family.value}*",
    ]
    if rule.explanation:
        parts += ["", rule.explanation]
    if rule.consumers:
        parts += ["", _matters(rule)]
    fence = "bash" if rule.language == "shell" else "toml" if rule.language == "toml" else "xml"
    for title, snippet in (("Fails:", rule.bad), ("Passes:", rule.good)):
        if snippet:
            parts += ["", title, "", f"```{fence}", snippet.rstrip("\n"), "```"]
    return "\n".join(parts) + "\n"


def with_rule_table(readme: str, rules: Sequence[Rule]) -> str:
    """``readme`` with the text between `README_BEGIN` and `README_END` replaced by the
    `markdown_table` of ``rules`` (a blank line on either side).

    Raises:
        ArgumentError: The text lacks a marker, or has the end before the beginning.
    """
    table = markdown_table(rules)
    return _between(readme, README_BEGIN, README_END, table, "README", "the rule list")


def with_consumer_table(page: str, rules: Sequence[Rule]) -> str:
    """``page`` with the text between `CONSUMERS_BEGIN` and `CONSUMERS_END` replaced by the
    `markdown_consumers` table of ``rules`` (a blank line on either side).

    Raises:
        ArgumentError: The text lacks a marker, or has the end before the beginning.
    """
    table = markdown_consumers(rules)
    return _between(page, CONSUMERS_BEGIN, CONSUMERS_END, table, "page", "the rules' programs")


def _between(
    text: str, begin_marker: str, end_marker: str, body: str, owner: str, what: str
) -> str:
    begin = text.find(begin_marker)
    end = text.find(end_marker)
    if begin < 0 or end < begin:
        raise ArgumentError(
            f"the {owner} has no {begin_marker} ... {end_marker} section for {what}",
            name=owner.lower(),
        )
    start = begin + len(begin_marker)
    return text[:start] + "\n\n" + body + "\n" + text[end:]
