"""The findings an expansion gives besides its errors: arguments nobody reads (or given to a
URDF file, which reads none), and xacro's own warnings."""

from __future__ import annotations

from collections.abc import Collection, Iterable, Iterator

from ..catalog.xacro import XACRO_UNKNOWN_ARG, XACRO_WARNING, UnknownArgFacts
from ..diagnostics import Diagnostic, Kind, Subject
from ..wording import closest, listing

__all__ = ["unknown_args", "unused_args", "xacro_warning"]


def unknown_args(
    given: Iterable[str], declared: Collection[str], path: str
) -> Iterator[Diagnostic]:
    """A finding for each argument given that no file declares, with the closest name."""
    for name in given:
        if name in declared:
            continue
        close = closest(name, declared)
        if close:
            hint = f"did you mean {close!r}?"
        elif declared:
            hint = f"declared: {listing(declared, near=name)}"
        else:
            hint = "the files declare no arguments"
        yield XACRO_UNKNOWN_ARG.report(
            f"argument {name!r} is given, but no <xacro:arg> declares it and nothing reads it",
            None,
            path=path,
            subject=Subject(Kind.FILE, path),
            hint=hint,
            data=UnknownArgFacts(argument=name),
        )


def unused_args(given: Iterable[str], path: str) -> Iterator[Diagnostic]:
    """A finding for each argument given with a URDF file: only a xacro file reads them."""
    for name in given:
        yield XACRO_UNKNOWN_ARG.report(
            f"argument {name!r} is given, but a URDF file takes no arguments",
            None,
            path=path,
            subject=Subject(Kind.FILE, path),
            hint="name:=value is for a .xacro file: it was not used",
            data=UnknownArgFacts(argument=name),
        )


def xacro_warning(message: str, path: str) -> Diagnostic:
    """A warning xacro gave while expanding ``path``, as a finding about the file."""
    return XACRO_WARNING.report(
        message.removeprefix("warning: ").strip(), None, path=path, subject=Subject(Kind.FILE, path)
    )
