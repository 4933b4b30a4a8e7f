"""Shared test helpers: fixture paths, the real ROS tools and their golden outputs, and the
real-robot corpus."""

from __future__ import annotations

import functools
import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parent.parent
DATA = Path(__file__).resolve().parent / "data"
VALID = sorted((DATA / "valid").glob("*.urdf"))
INVALID = sorted((DATA / "invalid").glob("*.urdf"))
ROBOTS = ROOT / "robots"
FISHBOT = ROBOTS / "fishbot"
STUB = Path(__file__).resolve().parent / "ament_stub"

# Set in CI: a missing tool is then a failure, never a skip.
REQUIRE_TOOLS = os.environ.get("FISHBOT_REQUIRE_TOOLS") == "1"

# In CI the property tests draw the same examples every run (a run's verdict is the code's,
# not the draw's); on a developer's machine they explore, and remember what failed.
if os.environ.get("CI"):
    from hypothesis import settings

    settings.register_profile("ci", derandomize=True, database=None)
    settings.load_profile("ci")


# The ROS tools come from the system (liburdfdom-tools) or a ROS install. pin, a test
# dependency, brings cmeel-urdfdom, whose own check_urdf and urdf_to_graphviz (another
# urdfdom, built on TinyXML2) land in a Python environment's bin folder: they are not what
# the golden files record, so no Python environment's folder (this one or another on PATH)
# is searched for them.
SYSTEM_TOOLS = ("check_urdf", "urdf_to_graphviz")


def _python_environment(folder: str) -> bool:
    parent = Path(folder).resolve().parent
    return (parent / "pyvenv.cfg").exists() or (parent / "conda-meta").is_dir()


def find_tool(name: str) -> str | None:
    """The path of tool ``name`` on PATH (for the ROS tools, outside Python environments)."""
    if name not in SYSTEM_TOOLS:
        return shutil.which(name)
    folders = os.environ.get("PATH", "").split(os.pathsep)
    kept = [f for f in folders if f and not _python_environment(f)]
    return shutil.which(name, path=os.pathsep.join(kept))


def require_tool(name: str, package: str) -> str:
    """The path of tool ``name``; skip (or, with FISHBOT_REQUIRE_TOOLS=1, fail) when missing."""
    found = find_tool(name)
    if found is None:
        message = f"{name} is not installed (Debian/Ubuntu: apt-get install {package})"
        if REQUIRE_TOOLS:
            pytest.fail(message + "; FISHBOT_REQUIRE_TOOLS=1 forbids skipping")
        pytest.skip(message)
    return found


def live_tool(name: str, package: str) -> str | None:
    """The path of tool ``name`` to run live beside its golden output: None when it is missing
    (the golden output stands alone), a failure when FISHBOT_REQUIRE_TOOLS=1."""
    found = find_tool(name)
    if found is None and REQUIRE_TOOLS:
        pytest.fail(
            f"{name} is not installed (Debian/Ubuntu: apt-get install {package}); "
            "FISHBOT_REQUIRE_TOOLS=1 forbids skipping"
        )
    return found


def run_check_urdf(path: Path) -> subprocess.CompletedProcess[bytes]:
    """Run the real check_urdf on ``path``."""
    tool = require_tool("check_urdf", "liburdfdom-tools")
    return subprocess.run([tool, str(path)], capture_output=True, timeout=120, check=False)


def xacro_command(
    path: str | Path,
    *args: str,
    cwd: Path | None = None,
    packages: dict[str, Path] | None = None,
) -> subprocess.CompletedProcess[str]:
    """Run the real xacro command (the PyPI package's), with $(find) answered by the stand-in."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(STUB), env.get("PYTHONPATH", "")])
    env["FISHBOT_TEST_PACKAGES"] = os.pathsep.join(
        f"{name}={folder}" for name, folder in (packages or {}).items()
    )
    code = "import sys, xacro; sys.exit(xacro.main())"
    return subprocess.run(
        [sys.executable, "-c", code, str(path), *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
        timeout=300,
        check=False,
    )


def _site_packages() -> set[Path]:
    import sysconfig

    return {Path(sysconfig.get_paths()[key]) for key in ("purelib", "platlib")}


def _corpus_folders() -> list[Path]:
    found = (
        root / "cmeel.prefix" / "share" / "example-robot-data" / "robots"
        for root in _site_packages()
    )
    return sorted(folder for folder in found if folder.is_dir())


def corpus() -> list[Path]:
    """Every URDF shipped by example-robot-data (a test dependency)."""
    return [path for folder in _corpus_folders() for path in sorted(folder.rglob("*.urdf"))]


def xacro_corpus() -> list[Path]:
    """Every xacro file of the real robot packages in the test dependencies
    (example-robot-data, hpp-environments, cookie-description)."""
    found: list[Path] = []
    for root in _site_packages():
        found.extend(sorted((root / "cmeel.prefix" / "share").rglob("*.xacro")))
        found.extend(sorted((root / "cookie_description").rglob("*.xacro")))
    return found


CORPUS = corpus()

# A 1 m arm of 5 kg, its mass at its middle, on a joint whose effort limit is {effort} N*m:
# fishbot sim holds it level against 5 * 9.81 * 0.5 N*m of gravity, or it sags.
ARM = """\
<robot name="arm">
  <link name="base"/>
  <link name="arm">
    <collision><origin xyz="0.5 0 0"/><geometry><box size="1 0.05 0.05"/></geometry></collision>
    <inertial><origin xyz="0.5 0 0"/><mass value="5"/>
      <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.418" iyz="0" izz="0.418"/></inertial>
  </link>
  <joint name="shoulder" type="revolute"><axis xyz="0 1 0"/>
    <parent link="base"/><child link="arm"/>
    <limit lower="-1.57" upper="1.57" effort="{effort}" velocity="1"/></joint>
</robot>
"""
XACRO_CORPUS = xacro_corpus()


# ------------------------------------------------------------------ golden outputs
#
# What the real check_urdf and urdf_to_graphviz print for every input, kept in tests/golden/
# so that parity is checked on any machine; where a tool is installed, it also runs live and
# must still print exactly that (which proves the golden files current). Written only by:
REGENERATE = "python tests/golden/regenerate.py"
GOLDEN = Path(__file__).resolve().parent / "golden"
CORPUS_PACKAGE = "example-robot-data"
# urdf_to_graphviz ROBOT OUT writes OUT.gv (and OUT.pdf with Graphviz's dot).
OUT = "tree"
# A run is stopped after this long or this much output (check_urdf prints a joint loop from
# the root without end); the golden entry then says "timeout". A run killed by a signal
# (urdf_to_graphviz overflows its stack on the same loops) says "crashed"; what either wrote
# is not kept (it is partial, and not the same from one run to the next).
SECONDS = 10.0
OUTPUT_BYTES = 16 * 2**20
# A live run that the golden entry says never finishes is given this long to prove it again.
LIVE_ENDLESS_SECONDS = 1.0


@dataclass(frozen=True)
class GoldenInput:
    """One robot the real tools are run on, named by a stable id:
    ``data/<path under tests/data>``, ``robots/<path under robots>`` or
    ``example-robot-data/<path under its robots folder>``."""

    id: str
    path: Path  # what fishbot reads: a .urdf, or a .xacro the real xacro expands for the tools

    @property
    def is_xacro(self) -> bool:
        return self.path.suffix == ".xacro"

    @property
    def in_corpus(self) -> bool:
        return self.id.startswith(CORPUS_PACKAGE + "/")

    @classmethod
    def from_id(cls, id: str) -> GoldenInput:
        collection, _, rest = id.partition("/")
        if collection == "data":
            return cls(id, DATA / rest)
        if collection == "robots":
            return cls(id, ROBOTS / rest)
        if collection == CORPUS_PACKAGE:
            folders = _corpus_folders()
            if not folders:
                pytest.fail(f"{CORPUS_PACKAGE} is not installed: pip install -e '.[test]'")
            return cls(id, folders[0] / rest)
        raise ValueError(f"unknown golden input collection in {id!r}")


def repo_id(path: Path) -> str:
    """The id of a file in the repository (also the key of an xacro's included files)."""
    path = path.resolve()
    if path.is_relative_to(DATA):
        return "data/" + path.relative_to(DATA).as_posix()
    return "robots/" + path.relative_to(ROBOTS).as_posix()


def golden_inputs(included: set[str] | None = None) -> list[GoldenInput]:
    """Every input: each .urdf under tests/data (recursively) and robots/, each xacro robot
    under robots/ (a .xacro no other one includes), and each URDF of example-robot-data.

    ``included`` names (by id) the .xacro files that others include; by default, as the
    golden index recorded them (a new include makes its robot's golden entry stale anyway)."""
    if included is None:
        recorded = _read_index() or {"inputs": {}}
        included = {
            name for entry in recorded["inputs"].values() for name in entry.get("includes", {})
        }
    found = [GoldenInput(repo_id(p), p) for p in sorted(DATA.rglob("*.urdf"))]
    found += [GoldenInput(repo_id(p), p) for p in sorted(ROBOTS.rglob("*.urdf"))]
    xacros = [GoldenInput(repo_id(p), p) for p in sorted(ROBOTS.rglob("*.xacro"))]
    found += [x for x in xacros if x.id not in included]
    for folder in _corpus_folders()[:1]:
        found += [
            GoldenInput(f"{CORPUS_PACKAGE}/{p.relative_to(folder).as_posix()}", p)
            for p in sorted(folder.rglob("*.urdf"))
        ]
    return found


def robot_packages() -> dict[str, Path]:
    """The ROS packages under robots/, by name: what ``$(find pkg)`` means in their xacro."""
    from fishbot_urdf.packages import package_name

    found: dict[str, Path] = {}
    for manifest in sorted(ROBOTS.rglob("package.xml")):
        name = package_name(manifest)
        if name:
            found[name] = manifest.parent
    return found


@functools.cache
def expand(path: Path) -> bytes:
    """The URDF that the real xacro command makes of ``path``."""
    expanded = xacro_command(path, packages=robot_packages())
    if expanded.returncode != 0:
        raise RuntimeError(f"xacro could not expand {path}: {expanded.stderr}")
    return expanded.stdout.encode("utf-8")


def xacro_includes(path: Path) -> list[Path]:
    """The files ``path`` includes, as the real xacro command lists them (``--deps``)."""
    listed = xacro_command(path, "--deps", packages=robot_packages())
    if listed.returncode != 0:
        raise RuntimeError(f"xacro could not list what {path} includes: {listed.stderr}")
    return sorted(Path(name).resolve() for name in listed.stdout.split())


@dataclass(frozen=True)
class ToolRun:
    """One run of a real tool: its exit status (None: stopped, it never finished; negative:
    killed by that signal), its stdout and, for urdf_to_graphviz, the OUT.gv it wrote (None:
    none)."""

    status: int | None
    stdout: bytes
    gv: bytes | None = None


def _limit_output() -> None:  # pragma: no cover - runs in the child
    import resource

    resource.setrlimit(resource.RLIMIT_FSIZE, (OUTPUT_BYTES, OUTPUT_BYTES))


def _run(
    argv: list[str], cwd: Path, seconds: float, env: Mapping[str, str] | None = None
) -> ToolRun:
    """Run a tool with its stdout in a file; stop it after ``seconds`` or OUTPUT_BYTES."""
    with tempfile.TemporaryFile() as out:
        try:
            done = subprocess.run(
                argv,
                stdin=subprocess.DEVNULL,
                stdout=out,
                stderr=subprocess.DEVNULL,  # log lines naming urdfdom's own source lines
                cwd=cwd,
                env=env,
                timeout=seconds,
                preexec_fn=_limit_output,
                check=False,
            )
        except subprocess.TimeoutExpired:
            return ToolRun(None, b"")
        if done.returncode == -signal.SIGXFSZ:
            return ToolRun(None, b"")
        if done.returncode < 0:
            return ToolRun(done.returncode, b"")
        out.seek(0)
        return ToolRun(done.returncode, out.read())


def _tool_input(item: GoldenInput, folder: Path) -> Path:
    """The URDF file the real tools read for ``item``."""
    if not item.is_xacro:
        return item.path
    urdf = folder / "expanded.urdf"
    urdf.write_bytes(expand(item.path))
    return urdf


def run_check_urdf_on(tool: str, item: GoldenInput, seconds: float = SECONDS) -> ToolRun:
    """What the real check_urdf prints for ``item``."""
    with tempfile.TemporaryDirectory() as folder:
        return _run([tool, str(_tool_input(item, Path(folder)))], Path(folder), seconds)


def run_urdf_to_graphviz_on(tool: str, item: GoldenInput, seconds: float = SECONDS) -> ToolRun:
    """What the real ``urdf_to_graphviz ROBOT tree`` prints and writes to tree.gv for ``item``."""
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        run = _run([tool, str(_tool_input(item, folder)), OUT], folder, seconds)
        gv = folder / f"{OUT}.gv"
        if run.status is None or run.status < 0 or not gv.exists():
            return run
        return ToolRun(run.status, run.stdout, gv.read_bytes())


# Runs of urdf_to_graphviz that show how it behaves as a command, each on one input:
# (arguments after the input, whether Graphviz's dot is on its PATH).
RUNS: dict[str, tuple[str, tuple[str, ...], bool]] = {
    # The older form, ROBOT alone: OUT is the robot's name.
    "default-form": ("robots/fishbot/urdf/first_robot.urdf", (), True),
    # Without dot it still says it made a PDF.
    "without-dot": ("robots/fishbot/urdf/first_robot.urdf", (OUT,), False),
}


def run_urdf_to_graphviz_form(tool: str, name: str) -> dict[str, Any]:
    """One of RUNS: its status, stdout and the files it wrote (each .gv with its sha256)."""
    id, args, with_dot = RUNS[name]
    item = GoldenInput.from_id(id)
    with tempfile.TemporaryDirectory() as folder_name:
        folder = Path(folder_name)
        env = None
        if not with_dot:
            empty = folder / "empty-path"
            empty.mkdir()
            env = {"PATH": str(empty)}
        work = folder / "work"
        work.mkdir()
        run = _run([tool, str(item.path), *args], work, SECONDS, env)
        files = {
            p.name: sha256(p.read_bytes()) if p.suffix == ".gv" else None
            for p in sorted(work.iterdir())
        }
    return {
        "input": id,
        "arguments": list(args),
        "dot": with_dot,
        "status": run.status,
        "stdout": run.stdout.decode("utf-8"),
        "files": files,
    }


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def installed_corpus_version() -> str | None:
    try:
        return metadata.version(CORPUS_PACKAGE)
    except metadata.PackageNotFoundError:
        return None


@functools.cache
def _read_index() -> dict[str, Any] | None:
    index = GOLDEN / "index.json"
    if not index.exists():
        return None
    loaded: dict[str, Any] = json.loads(index.read_text(encoding="utf-8"))
    return loaded


def golden_index() -> dict[str, Any]:
    """tests/golden/index.json: the inputs, their sha256, and what the tools did with each."""
    index = _read_index()
    if index is None:
        _stale(f"{GOLDEN / 'index.json'} is missing")
    assert index is not None
    return index


def _stale(message: str) -> None:
    pytest.fail(f"{message}: regenerate the golden files with {REGENERATE}")


def _told(run: ToolRun) -> str:
    if run.status is None:
        return "stopped"
    gv = "" if run.gv is None else f", a .gv of {len(run.gv)} bytes"
    return f"status {run.status}, {len(run.stdout)} bytes of stdout{gv}"


def golden_entry(item: GoldenInput) -> dict[str, Any]:
    """The golden entry of ``item``; a failure naming the command if it is missing or stale."""
    index = golden_index()
    if item.in_corpus:
        recorded = index["versions"][CORPUS_PACKAGE]
        installed = installed_corpus_version()
        if installed != recorded:
            _stale(
                f"the golden outputs are of {CORPUS_PACKAGE} {recorded}, but {installed} is "
                f"installed: install {recorded} (pip install -e '.[test]' pins it) or"
            )
    entry: dict[str, Any] | None = index["inputs"].get(item.id)
    if entry is None:
        _stale(f"{item.id} has no golden entry")
    assert entry is not None
    sources = {item.path: entry["sha256"]}
    for included, digest in entry.get("includes", {}).items():
        sources[GoldenInput.from_id(included).path] = digest
    changed = [
        _shown(path)
        for path, digest in sources.items()
        if not path.exists() or sha256(path.read_bytes()) != digest
    ]
    if changed:
        _stale(f"the golden outputs of {item.id} are stale ({', '.join(changed)} changed)")
    return entry


def _shown(path: Path) -> str:
    """``path`` as the repository names it, where it is in the repository."""
    return path.relative_to(ROOT).as_posix() if path.is_relative_to(ROOT) else str(path)


def _golden_bytes(name: str | None) -> bytes:
    return b"" if name is None else (GOLDEN / name).read_bytes()


def _no_answer(record: dict[str, Any]) -> ToolRun:
    """A run that gave no answer: stopped ("timeout") or killed by a signal ("crashed")."""
    if "crashed" in record:
        return ToolRun(-signal.Signals[record["crashed"]].value, b"")
    assert record["timeout"] is True
    return ToolRun(None, b"")


def golden_check_urdf(item: GoldenInput) -> ToolRun:
    """check_urdf's run on ``item``, as its golden entry recorded it."""
    record = golden_entry(item)["check_urdf"]
    if "status" not in record:
        return _no_answer(record)
    return ToolRun(record["status"], _golden_bytes(record["stdout"]))


def golden_urdf_to_graphviz(item: GoldenInput) -> ToolRun:
    """urdf_to_graphviz's run on ``item``, as its golden entry recorded it."""
    record = golden_entry(item)["urdf_to_graphviz"]
    if "status" not in record:
        return _no_answer(record)
    gv = None if record["gv"] is None else _golden_bytes(record["gv"])
    return ToolRun(record["status"], record["stdout"].encode("utf-8"), gv)


def _live_seconds(golden: ToolRun) -> float:
    return LIVE_ENDLESS_SECONDS if golden.status is None else 120.0


def check_urdf(item: GoldenInput) -> ToolRun:
    """check_urdf's run on ``item``: the golden one, which the real tool, where it is
    installed, must reproduce live."""
    golden = golden_check_urdf(item)
    tool = live_tool("check_urdf", "liburdfdom-tools")
    if tool is not None:
        live = run_check_urdf_on(tool, item, _live_seconds(golden))
        if live != golden:
            _stale(
                f"check_urdf no longer prints the golden output for {item.id} "
                f"(golden: {_told(golden)}; live: {_told(live)})"
            )
    return golden


def urdf_to_graphviz(item: GoldenInput) -> ToolRun:
    """urdf_to_graphviz's run on ``item``: the golden one, which the real tool, where it is
    installed, must reproduce live."""
    golden = golden_urdf_to_graphviz(item)
    tool = live_tool("urdf_to_graphviz", "liburdfdom-tools")
    if tool is not None:
        live = run_urdf_to_graphviz_on(tool, item, _live_seconds(golden))
        if live != golden:
            _stale(
                f"urdf_to_graphviz no longer writes the golden output for {item.id} "
                f"(golden: {_told(golden)}; live: {_told(live)})"
            )
    return golden


def urdf_to_graphviz_form(name: str) -> dict[str, Any]:
    """One of RUNS, as recorded; where urdf_to_graphviz is installed it must still do that."""
    golden = golden_index()["runs"].get(name)
    id, args, with_dot = RUNS[name]
    if golden is None or (golden["input"], golden["arguments"], golden["dot"]) != (
        id,
        list(args),
        with_dot,
    ):
        _stale(f"the urdf_to_graphviz run {name!r} has no golden entry")
    golden_entry(GoldenInput.from_id(id))  # its input is unchanged
    tool = live_tool("urdf_to_graphviz", "liburdfdom-tools")
    if tool is not None and run_urdf_to_graphviz_form(tool, name) != golden:
        _stale(f"urdf_to_graphviz no longer behaves as recorded in the run {name!r}")
    assert golden is not None
    return golden


def binary_stl(triangles: list[tuple[float, ...]]) -> bytes:
    """A binary STL file of ``triangles``, each nine numbers (three corners)."""
    import struct

    body = b"".join(struct.pack("<12fH", 0.0, 0.0, 0.0, *t, 0) for t in triangles)
    return b"\0" * 80 + struct.pack("<I", len(triangles)) + body


def box_stl(x: float, y: float, z: float) -> bytes:
    """A closed box from (0, 0, 0) to (x, y, z), as twelve triangles."""
    c = [(i * x, j * y, k * z) for i in (0, 1) for j in (0, 1) for k in (0, 1)]
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1)]
    faces += [(2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    return binary_stl([(*c[a], *c[b], *c[d]) for a, b, d in faces])


def fine_stl(count: int, size: float = 0.1) -> bytes:
    """``count`` small triangles spread over a cube of side ``size``."""
    step = size / count
    return binary_stl(
        [(i * step, 0.0, 0.0, i * step, size, 0.0, 0.0, 0.0, size) for i in range(count)]
    )
