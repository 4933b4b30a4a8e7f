"""`fishbot rules`: every rule, or one explained."""

from __future__ import annotations

import json
import sys

import click

from ..catalog import Family, Rule, all_rules, get
from ..catalog.docs import explanation, markdown_explanation, markdown_table, table
from ..errors import UnknownNameError
from ..wording import did_you_mean
from ._common import EXIT_USAGE, to_stdout


@click.command()
@click.argument("name", required=False, metavar="[RULE|FAMILY]")
@click.option(
    "--format",
    "fmt",
    type=click.Choice(["text", "json", "markdown"]),
    default="text",
    show_default=True,
    help="text: a table, or one rule explained; json: every field; markdown: for documents.",
)
def rules(name: str | None, fmt: str) -> None:
    """List the rules of `fishbot check`, or explain one (as `ruff rule` does).

    Each rule has an id (shown in brackets after each finding), a default severity, a
    family (selectable as a whole: --select physics), the programs it matters to, and an
    explanation with a failing and a fixed example. A family name lists its rules.

    \b
    Examples:
      fishbot rules
      fishbot rules massless-link
      fishbot rules physics
      fishbot rules --format json
    """
    families = {f.value for f in Family}
    if name is not None and name not in families:
        try:
            rule = get(name)
        except UnknownNameError:
            known = [r.id for r in all_rules()] + sorted(families)
            click.echo(
                f"fishbot rules: error: no rule or family {name!r} "
                f"({did_you_mean(name, known)}`fishbot rules` lists them)",
                err=True,
            )
            sys.exit(EXIT_USAGE)
        chosen: tuple[Rule, ...] = (rule,)
        one = True
    else:
        chosen = tuple(r for r in all_rules() if name is None or r.family.value == name)
        one = False
    if fmt == "json":
        data = [r.to_dict() for r in chosen]
        text = json.dumps(data[0] if one else data, indent=2) + "\n"
    elif fmt == "markdown":
        text = markdown_explanation(chosen[0]) if one else markdown_table(chosen)
    else:
        text = explanation(chosen[0]) if one else table(chosen)
    to_stdout(text.encode("utf-8", "surrogateescape"))
