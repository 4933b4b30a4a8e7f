"""Options more than one command takes."""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

import click

Wrapped = TypeVar("Wrapped", bound=Callable[..., object])


def text_or_json(text: str) -> Callable[[Wrapped], Wrapped]:
    """``--format text|json`` (default text), stored as ``fmt``."""
    return click.option(
        "--format",
        "fmt",
        type=click.Choice(["text", "json"]),
        default="text",
        show_default=True,
        help=text,
    )
