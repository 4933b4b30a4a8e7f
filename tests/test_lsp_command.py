"""`fishbot lsp` as a command: its help, and the one line it says when pygls is missing."""

from __future__ import annotations

import os
import subprocess
import sys

from click.testing import CliRunner
from conftest import ROOT

from fishbot_urdf.cli import cli

# pygls made impossible to import, as in an environment without the lsp extra
WITHOUT_PYGLS = """
import sys
class Refuse:
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("pygls", "lsprotocol"):
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
sys.meta_path.insert(0, Refuse())
from fishbot_urdf.cli import main
main(["lsp"])
"""


def test_without_pygls_it_says_how_to_install_it() -> None:
    run = subprocess.run(
        [sys.executable, "-c", WITHOUT_PYGLS],
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT / "src"), "NO_COLOR": "1"},
        stdin=subprocess.DEVNULL,
        check=False,
    )
    assert run.returncode == 2
    assert run.stdout == ""
    assert run.stderr == (
        "fishbot lsp: error: setup: the pygls package, an optional part of fishbot-urdf that "
        "the language server needs, is not installed (install it: pip install "
        "'fishbot-urdf[lsp]') [tool-missing]\n"
    )


def test_the_help_gives_examples() -> None:
    run = CliRunner().invoke(cli, ["lsp", "--help"])
    assert run.exit_code == 0
    examples = "  Examples:\n    fishbot lsp\n    python -m fishbot_urdf lsp --debounce 150\n"
    assert examples in run.output


def test_an_end_of_input_without_exit_is_status_1() -> None:
    run = subprocess.run(
        [sys.executable, "-m", "fishbot_urdf", "lsp"],
        input=b"",
        capture_output=True,
        env={**os.environ, "PYTHONPATH": str(ROOT / "src")},
        timeout=60,
        check=False,
    )
    assert (run.returncode, run.stdout) == (1, b"")
