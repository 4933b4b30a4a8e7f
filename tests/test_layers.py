"""The layers written in pyproject.toml's import-linter contracts hold, and every import made
inside a function loads a heavy or optional dependency lazily, with its reason beside it."""

from __future__ import annotations

import ast
import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "src" / "fishbot_urdf"


def _lint(config: Path, cwd: Path, path: Path) -> subprocess.CompletedProcess[str]:
    # in a process of its own: import-linter sets up logging as it likes
    return subprocess.run(
        [sys.executable, "-c", _LINT, str(config)],
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(path)},
        cwd=cwd,
        check=False,
    )


def test_the_import_contracts_hold() -> None:
    # layers (each imports only from below), no cycles in any package, xacro only in the
    # expansion, pygls only in the language server, click only in the command line, mujoco
    # only in the simulation
    run = _lint(ROOT / "pyproject.toml", ROOT, ROOT / "src")
    assert run.returncode == 0, run.stdout + run.stderr
    assert "Contracts: 6 kept, 0 broken." in run.stdout


def test_a_broken_layer_is_caught(tmp_path: Path) -> None:
    # the same contracts over a copy whose model imports the command line
    config = tmp_path / "contracts.toml"
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    config.write_text(text[text.index("\n[tool.importlinter]\n") :], encoding="utf-8")
    shutil.copytree(PACKAGE, tmp_path / "src" / "fishbot_urdf")
    model = tmp_path / "src" / "fishbot_urdf" / "model.py"
    model.write_text(model.read_text(encoding="utf-8") + "\nfrom . import cli\n", encoding="utf-8")
    run = _lint(config, tmp_path, tmp_path / "src")
    assert run.returncode == 1, run.stdout + run.stderr
    assert "fishbot_urdf.model is not allowed to import fishbot_urdf.cli" in run.stdout


_LINT = """
import sys
from importlinter.cli import lint_imports

sys.exit(lint_imports(config_filename=sys.argv[1], no_cache=True, no_logo=True))
"""


# What may be imported inside a function: what costs a command that does not use it (numpy,
# networkx, the viewer's and the mesh extra's packages, xacro and YAML) or may be missing.
LAZY = {
    "numpy",
    "networkx",
    "trimesh",
    "viser",
    "mujoco",
    "websockets",
    "rich",
    "xacro",
    "yaml",
    "importlib.metadata",
    "ament_index_python",
    "PIL",
}
# Parts of this package loaded on first use, each costing a command that does not need it
# milliseconds at start-up (measured by `python -X importtime -m fishbot_urdf check ...`).
LAZY_HERE = {
    "src/fishbot_urdf/xml/recover/__init__.py": {
        "._messages",
        "._rewrite",
        "._strict",
        "._tinyxml",
    },
    "src/fishbot_urdf/expansion/__init__.py": {"._engine"},
    "src/fishbot_urdf/inertia/__init__.py": {"."},
    "src/fishbot_urdf/cli/__init__.py": {"._common"},
    "src/fishbot_urdf/lsp/__init__.py": {"._server"},
    "src/fishbot_urdf/cli/expand.py": {"..analysis", "..parsing"},
    "src/fishbot_urdf/cli/check.py": {"._fixing"},
    "src/fishbot_urdf/fixes.py": {".inertia"},
    "src/fishbot_urdf/simulation/__init__.py": {"."},
}


def _function_imports() -> list[tuple[str, int, str, str]]:
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        lines = text.splitlines()
        for node in ast.walk(ast.parse(text)):
            if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                continue
            for inner in ast.walk(node):
                if isinstance(inner, ast.Import):
                    names = [alias.name for alias in inner.names]
                elif isinstance(inner, ast.ImportFrom):
                    names = ["." * inner.level + (inner.module or "")]
                else:
                    continue
                line = lines[inner.lineno - 1]
                above = inner.lineno - 2
                while above >= 0 and lines[above].strip().startswith(("from ", "import ")):
                    above -= 1
                if above >= 0 and lines[above].strip().startswith("#"):
                    line += "  " + lines[above].strip()  # the reason, above the imports
                found.extend(
                    (str(path.relative_to(ROOT)), inner.lineno, name, line) for name in names
                )
    return found


def test_imports_inside_functions_load_heavy_or_optional_packages_only() -> None:
    wrong = [
        f"{where}:{line}: {name}"
        for where, line, name, _ in _function_imports()
        if not any(name == lazy or name.startswith(lazy + ".") for lazy in LAZY)
        and name not in LAZY_HERE.get(where, ())
    ]
    assert wrong == []


def test_each_lazy_import_says_why() -> None:
    silent = [
        f"{where}:{number}: {line.strip()}"
        for where, number, _, line in _function_imports()
        if "#" not in line
    ]
    assert silent == []


def test_the_architecture_page_names_every_layer() -> None:
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    layers = text.split("layers = [", 1)[1].split("]", 1)[0]
    names = {
        name.strip().strip('",').removeprefix("fishbot_urdf.")
        for line in layers.splitlines()
        for name in line.split("|")
        if name.strip().strip('",')
    }
    page = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    assert sorted(n for n in names if f"`{n}" not in page) == []
