"""`fishbot lsp`: the language server, over standard input and output."""

from __future__ import annotations

import gc
import sys

import click

from ..errors import ToolNotFoundError
from ..lsp import serve
from ._common import emit_findings, not_installed, status_of

_COLLECT_EVERY = 100_000  # new container objects between two young collections (Python: 700)


@click.command()
@click.option(
    "--stdio",
    is_flag=True,
    help="Talk over standard input and output (the default and only way; editors' clients "
    "pass it).",
)
@click.option(
    "--debounce",
    default=75,
    show_default=True,
    type=click.IntRange(0, 10_000),
    metavar="MS",
    help="Milliseconds from the last change to the check.",
)
def lsp(stdio: bool, debounce: int) -> None:
    """The language server for URDF and xacro files, over standard input and output: the
    findings of `fishbot check` as you type, in the file each is in (and at the macro call
    that made it), quick fixes, and each rule explained on hover; go to definition,
    references, rename, completion and the outline of the robot's names across its
    files. An included file is checked through the robots of its package that include
    it. Needs `pip install 'fishbot-urdf[lsp]'`; docs/editors.md says how to set up VS
    Code, Neovim, Helix and Emacs.

    \b
    Examples:
      fishbot lsp
      python -m fishbot_urdf lsp --debounce 150
    """
    del stdio
    # Off for the commands that end (see main); on, rarely, for a session that goes on.
    gc.set_threshold(_COLLECT_EVERY, *gc.get_threshold()[1:])
    try:
        clean = serve(debounce=debounce / 1000)
    except ToolNotFoundError as exc:  # pygls: the setup's fault
        emit_findings([not_installed(exc, "fishbot lsp", "the language server")])
        sys.exit(status_of(exc))  # 2, as view without viser
    sys.exit(0 if clean else 1)  # 1: an exit the client sent without a shutdown first
