"""Options more than one command takes."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, TypeVar

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


PACKAGE_HELP = "Where ROS package NAME is, for $(find NAME) and package:// (repeatable)."


class Number(click.ParamType):  # type: ignore[type-arg]
    """A finite number (click's float lets nan and inf through), > 0 with ``positive``,
    >= 0 with ``zero``."""

    name = "float"

    def __init__(self, *, positive: bool = False, zero: bool = False) -> None:
        self.positive = positive
        self.zero = zero

    def convert(
        self, value: Any, param: click.Parameter | None, ctx: click.Context | None
    ) -> float:
        try:
            number = float(value)
        except (TypeError, ValueError):
            self.fail(f"{value!r} is not a number", param, ctx)
        if not math.isfinite(number):
            self.fail(f"{value!r} is not a finite number", param, ctx)
        if self.positive and not number > 0:
            self.fail(f"{value!r} must be > 0", param, ctx)
        if self.zero and number < 0:
            self.fail(f"{value!r} must be >= 0", param, ctx)
        return number
