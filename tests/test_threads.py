"""Checking and expanding from many threads at once gives the serial results, and the library
changes nothing the whole process shares (the cycle collector, sys.stderr, the umask)."""

from __future__ import annotations

import dataclasses
import gc
import os
import random
import stat
import sys
import threading
import uuid
from pathlib import Path
from typing import Any

import pytest
from conftest import DATA, FISHBOT

import fishbot_urdf
from fishbot_urdf import FishbotUrdfError
from fishbot_urdf.output import write_atomic

THREADS = 8
ROUNDS = 3

URDFS = [*sorted(DATA.glob("*/*.urdf")), FISHBOT / "urdf" / "first_robot.urdf"]
XACROS = [
    *sorted((DATA / "xacro").glob("*/robot.urdf.xacro")),
    FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro",
]


def _everything(value: object) -> object:
    """``value`` as nested tuples of every field, locations included (equality skips them)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        parts = [(f.name, _everything(getattr(value, f.name))) for f in dataclasses.fields(value)]
        return (type(value).__name__, *parts)
    if isinstance(value, tuple | list):
        return tuple(_everything(item) for item in value)
    if isinstance(value, float):
        return repr(value)  # tells 0.0 from -0.0
    return value


def _check(path: Path) -> object:
    try:
        result = fishbot_urdf.check_file(path, packages={"demo": DATA / "valid" / "demo"})
    except FishbotUrdfError as exc:
        return ("raised", type(exc).__name__, str(exc))
    return (
        tuple(d.format() for d in result.diagnostics),
        _everything(result.robot),
        result.files,
        result.data,
    )


def _expand(path: Path) -> object:
    try:
        expansion = fishbot_urdf.expand(path)
    except FishbotUrdfError as exc:
        return ("raised", type(exc).__name__, str(exc))
    return _everything(expansion)


def _write(path: Path, folder: Path) -> object:
    """Expand ``path`` into a new file of ``folder``; its text and mode."""
    target = folder / f"{uuid.uuid4().hex}.urdf"
    try:
        write_atomic(target, fishbot_urdf.expand(path).text)
    except FishbotUrdfError as exc:
        return ("raised", type(exc).__name__, str(exc))
    return target.read_text(), stat.S_IMODE(target.stat().st_mode)


TASKS = [
    *(("check", path) for path in URDFS + XACROS),
    *(("expand", path) for path in XACROS),
    *(("write", path) for path in XACROS),
]


def _run(kind: str, path: Path, folder: Path) -> object:
    if kind == "check":
        return _check(path)
    return _expand(path) if kind == "expand" else _write(path, folder)


def _umask() -> int:
    """The process umask, read without setting it (os.umask would change it to read it)."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("Umask:"):
            return int(line.split()[1], 8)
    raise AssertionError("no Umask line in /proc/self/status")


def _shared_state() -> tuple[object, ...]:
    return (gc.isenabled(), sys.stderr, sys.stdout, _umask())


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("written")


@pytest.fixture(scope="module")
def serial(folder: Path) -> dict[tuple[str, Path], object]:
    """Every task's outcome, run one after the other."""
    return {(kind, path): _run(kind, path, folder) for kind, path in TASKS}


def test_the_tasks_pass_fail_and_warn(serial: dict[tuple[str, Path], object]) -> None:
    def outcome(kind: str, *parts: str) -> Any:
        return serial[(kind, DATA.joinpath(*parts))]

    assert outcome("check", "valid", "all_elements.urdf")[0] == ()
    assert outcome("check", "invalid", "cycle.urdf")[0] != ()
    assert outcome("check", "invalid", "xml_syntax.urdf")[:2] == ("raised", "XmlSyntaxError")
    assert outcome("expand", "xacro", "missing_include", "robot.urdf.xacro")[0] == "raised"
    assert len(outcome("expand", "xacro", "warnings", "robot.urdf.xacro")[-1][1]) == 10
    assert outcome("write", "xacro", "warnings", "robot.urdf.xacro")[1] == 0o666 & ~_umask()
    assert len(TASKS) > 50


# Functions that change what every thread sees; none may be called while the tasks run.
PROCESS_WIDE = [
    (os, "umask"),
    (os, "chdir"),
    (gc, "disable"),
    (gc, "freeze"),
    (gc, "set_threshold"),
    (sys, "setrecursionlimit"),
]


def _spy(calls: list[str], name: str, real: Any) -> Any:
    def spy(*args: Any) -> Any:
        calls.append(name)
        return real(*args)

    return spy


def test_threads_give_the_serial_results(
    serial: dict[tuple[str, Path], object], folder: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    calls: list[str] = []
    for module, name in PROCESS_WIDE:
        monkeypatch.setattr(module, name, _spy(calls, name, getattr(module, name)))
    before = _shared_state()
    results: list[tuple[str, Path, object]] = []
    seen: set[tuple[object, ...]] = set()
    errors: list[BaseException] = []
    lock = threading.Lock()
    start = threading.Barrier(THREADS + 1)
    done = threading.Event()

    def work(index: int) -> None:
        # Each thread takes its own share, a quarter of the tasks, in its own order: every
        # task runs in about two threads at a time, each round.
        order = random.Random(index).sample(TASKS, len(TASKS))
        mine = order[: len(TASKS) // 4]
        try:
            start.wait()
            for _ in range(ROUNDS):
                for kind, path in mine:
                    outcome = _run(kind, path, folder)
                    with lock:
                        results.append((kind, path, outcome))
        except BaseException as exc:  # reported below, in the test's own thread
            with lock:
                errors.append(exc)

    def watch() -> None:
        start.wait()
        while not done.is_set():
            seen.add(_shared_state())

    threads = [threading.Thread(target=work, args=(i,)) for i in range(THREADS)]
    watcher = threading.Thread(target=watch)
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-4)  # the test's own choice: threads take turns 50 times as often
    try:
        watcher.start()
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join(timeout=120)
    finally:
        done.set()
        watcher.join(timeout=10)
        sys.setswitchinterval(interval)
    assert not any(thread.is_alive() for thread in threads)
    assert errors == []
    assert len(results) == THREADS * ROUNDS * (len(TASKS) // 4)
    for kind, path, outcome in results:
        assert outcome == serial[(kind, path)], f"{kind} {path.name}"
    assert calls == []
    assert seen == {before}  # the whole time the threads ran
    assert _shared_state() == before
