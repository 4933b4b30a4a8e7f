"""Regenerate the golden outputs of the real ROS tools: ``python tests/golden/regenerate.py``.

The parity tests compare fishbot with what the real ``check_urdf`` and ``urdf_to_graphviz``
print; this command runs them and keeps what they print here, so the tests run on any
machine. It needs the tools (Debian/Ubuntu: ``apt-get install liburdfdom-tools graphviz``)
and refuses to run without them; run it after changing, adding or removing an input, or
after a new version of example-robot-data, and commit what it changed.

The inputs: every ``.urdf`` under tests/data (recursively) and robots/, every xacro robot
under robots/ (expanded by the real xacro first: the tools read URDF only) and every URDF
of example-robot-data. It writes, under tests/golden/:

- ``index.json``: each input by id, with the sha256 of its files and each tool's exit
  status; the versions of example-robot-data, xacro and the tools;
- ``check_urdf/<id>.txt``: check_urdf's stdout, where it printed any (its stderr is log
  noise and is not kept);
- ``urdf_to_graphviz/<id>.gv``: the ``tree.gv`` that ``urdf_to_graphviz ROBOT tree``
  wrote (its stdout is in the index).

A run that prints a joint loop without end is stopped (after 10 s or 16 MiB) and recorded
as a timeout; one killed by a signal (a stack overflow on such a loop) as crashed, with the
signal's name. What they wrote before is not kept. Files are written atomically, and only
when their content changed; golden files no input needs any more are removed.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import tempfile
from importlib import metadata
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from conftest import (
    CORPUS_PACKAGE,
    GOLDEN,
    ROBOTS,
    RUNS,
    GoldenInput,
    ToolRun,
    expand,
    find_tool,
    golden_inputs,
    installed_corpus_version,
    repo_id,
    run_check_urdf_on,
    run_urdf_to_graphviz_form,
    run_urdf_to_graphviz_on,
    sha256,
    xacro_includes,
)

TOOLS = {
    "check_urdf": "liburdfdom-tools",
    "urdf_to_graphviz": "liburdfdom-tools",
    "dot": "graphviz",
}
OUTPUTS = ("check_urdf", "urdf_to_graphviz")


def _tool_versions() -> dict[str, str]:
    """The Debian versions of the tools' packages, where dpkg can tell."""
    found: dict[str, str] = {}
    for package in sorted(set(TOOLS.values())):
        try:
            asked = subprocess.run(
                ["dpkg-query", "-W", "-f", "${Version}", package],
                capture_output=True,
                text=True,
                check=False,
            )
        except OSError:
            continue
        if asked.returncode == 0 and asked.stdout:
            found[package] = asked.stdout
    return found


def _includes() -> dict[str, dict[str, str]]:
    """Each .xacro under robots/: the files it includes, with their sha256."""
    found: dict[str, dict[str, str]] = {}
    for path in sorted(ROBOTS.rglob("*.xacro")):
        found[repo_id(path)] = {
            repo_id(included): sha256(included.read_bytes()) for included in xacro_includes(path)
        }
    return found


def _record(item: GoldenInput, tool: str, run: ToolRun, files: dict[str, bytes]) -> dict[str, Any]:
    """The index record of one run; its outputs go into ``files``."""
    if run.status is None:
        return {"timeout": True}
    if run.status < 0:
        return {"crashed": signal.Signals(-run.status).name}
    if tool == "check_urdf":
        name = None
        if run.stdout:
            name = f"check_urdf/{item.id}.txt"
            files[name] = run.stdout
        return {"status": run.status, "stdout": name}
    gv = None
    if run.gv is not None:
        gv = f"urdf_to_graphviz/{item.id}.gv"
        files[gv] = run.gv
    return {"status": run.status, "stdout": run.stdout.decode("utf-8"), "gv": gv}


def generate(tools: dict[str, str]) -> dict[str, bytes]:
    """Every golden file, by its path under tests/golden."""
    includes = _includes()
    included = {name for listed in includes.values() for name in listed}
    files: dict[str, bytes] = {}
    inputs: dict[str, Any] = {}
    for item in golden_inputs(included):
        entry: dict[str, Any] = {"sha256": sha256(item.path.read_bytes())}
        if item.is_xacro:
            expand(item.path)  # fails here, with xacro's message, if it cannot be expanded
            entry["includes"] = includes[item.id]
        check = run_check_urdf_on(tools["check_urdf"], item)
        entry["check_urdf"] = _record(item, "check_urdf", check, files)
        graph = run_urdf_to_graphviz_on(tools["urdf_to_graphviz"], item)
        entry["urdf_to_graphviz"] = _record(item, "urdf_to_graphviz", graph, files)
        inputs[item.id] = entry
        print(f"{item.id}: check_urdf {_said(check)}, urdf_to_graphviz {_said(graph)}")
    runs = {name: run_urdf_to_graphviz_form(tools["urdf_to_graphviz"], name) for name in RUNS}
    index = {
        "about": (
            "What the real check_urdf and urdf_to_graphviz print for each input. Written by "
            "python tests/golden/regenerate.py (see its docstring); never edit by hand."
        ),
        "versions": {
            CORPUS_PACKAGE: installed_corpus_version(),
            "xacro": metadata.version("xacro"),
            **_tool_versions(),
        },
        "inputs": inputs,
        "runs": runs,
    }
    files["index.json"] = (json.dumps(index, indent=1, sort_keys=True) + "\n").encode("utf-8")
    return files


def _said(run: ToolRun) -> str:
    return "timeout" if run.status is None else f"status {run.status}"


def _write(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically: a reader sees the old file or the new one."""
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    try:
        os.fchmod(handle, 0o644)  # mkstemp's files are private; these are for everyone
        with os.fdopen(handle, "wb") as out:
            out.write(data)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def store(files: dict[str, bytes]) -> tuple[list[str], list[str]]:
    """Write the files that changed and remove golden outputs no input has any more:
    (the changed paths, the removed paths)."""
    changed = []
    for name, data in sorted(files.items()):
        path = GOLDEN / name
        if not path.exists() or path.read_bytes() != data:
            _write(path, data)
            changed.append(name)
    removed = []
    for folder in OUTPUTS:
        for path in sorted((GOLDEN / folder).rglob("*")):
            name = path.relative_to(GOLDEN).as_posix()
            if path.is_file() and name not in files:
                path.unlink()
                removed.append(name)
        for path in sorted((GOLDEN / folder).rglob("*"), reverse=True):
            if path.is_dir() and not any(path.iterdir()):
                path.rmdir()
    return changed, removed


def main() -> int:
    tools = {name: find_tool(name) for name in TOOLS}
    missing = sorted(name for name, path in tools.items() if path is None)
    if missing:
        packages = " ".join(sorted({TOOLS[name] for name in missing}))
        print(
            f"regenerate.py: {', '.join(missing)} not found: the golden files are what the real "
            f"tools print (Debian/Ubuntu: apt-get install {packages})",
            file=sys.stderr,
        )
        return 2
    if installed_corpus_version() is None:
        print(
            f"regenerate.py: {CORPUS_PACKAGE} is not installed: pip install -e '.[test]'",
            file=sys.stderr,
        )
        return 2
    found = {name: path for name, path in tools.items() if path is not None}
    changed, removed = store(generate(found))
    total = sum(
        p.stat().st_size for p in GOLDEN.rglob("*") if p.is_file() and p.name != Path(__file__).name
    )
    for name in changed:
        print(f"written: {name}")
    for name in removed:
        print(f"removed: {name}")
    print(f"{len(changed)} written, {len(removed)} removed; tests/golden holds {total} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
