"""The files of one `fishbot check`: each file's outcome, in the order given, checked by
several processes when there are many files."""

from __future__ import annotations

import os
import sys
import threading
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from ..errors import FishbotUrdfError
from ._common import EXIT_INVALID, EXIT_OK, check_input, fail, mesh_files, status_of

if TYPE_CHECKING:
    from ..check import CheckResult
    from ..config import Config
    from ..diagnostics import Diagnostic
    from ..report import FileReport

SHARED_FROM = 8
"""Files: fewer are checked one after another, as starting processes would cost more."""

_LARGEST = 4 * 2**20
"""Bytes: a bigger file is checked by the main process, its tree streamed (a deep chain's
tree is hundreds of megabytes, too much to hand from one process to another)."""


@dataclass(frozen=True, slots=True)
class Run:
    """What every file of one command shares.

    Attributes:
        args: xacro arguments.
        packages: ``--package`` folders.
        fmt: The output format.
        skip_includes: Pass over xacro files that define no robot.
        meshes: The mesh files a robot names are inputs too (``-o FILE``: never written).
        tree: check_urdf's tree is printed (text format, not quiet).
    """

    args: dict[str, str]
    packages: dict[str, str]
    fmt: str
    skip_includes: bool
    meshes: bool
    tree: bool


@dataclass(frozen=True, slots=True)
class Outcome:
    """What checking one file gives the command.

    Attributes:
        status: Its exit status (0, 1 or 2).
        findings: The lines to print (text format).
        report: Its report (other formats).
        result: The check, for its tree to be streamed (checked in this process).
        tree: Its tree as text (checked in another process).
        inputs: The files it was read from, never to be written over.
    """

    status: int
    findings: tuple[Diagnostic, ...] = ()
    report: FileReport | None = None
    result: CheckResult | None = None
    tree: str | None = None
    inputs: tuple[str, ...] = ()


def outcomes(
    names: Sequence[str], configs: Sequence[Config], run: Run, jobs: int
) -> Iterator[Outcome]:
    """Each file's outcome, in order. With ``jobs`` above 1 and at least `SHARED_FROM`
    files, that many forked processes check them (Linux only, where a fork imports nothing
    again); standard input and big files are checked here, in their turn."""
    jobs = min(jobs, len(names))
    if jobs < 2 or len(names) < SHARED_FROM or not _can_fork():
        for name, config in zip(names, configs, strict=True):
            yield outcome(name, config, run)
        return
    import multiprocessing

    from ..inputs import max_bytes, max_seconds

    work = (names, configs, run, max_bytes(), max_seconds())
    sys.stdout.flush()
    sys.stderr.flush()
    chunk = max(1, len(names) // (jobs * 8))
    with multiprocessing.get_context("fork").Pool(jobs, _start, work) as pool:
        for index, done in enumerate(pool.imap(_elsewhere, range(len(names)), chunk)):
            yield outcome(names[index], configs[index], run) if done is None else done


def outcome(name: str, config: Config, run: Run) -> Outcome:
    """Check one file (``-``: standard input)."""
    try:
        result = check_input(name, run.args, run.packages, config)
    except FishbotUrdfError as exc:
        if run.fmt == "text":
            return Outcome(status_of(exc), findings=(fail(exc),))
        return Outcome(status_of(exc), report=_failure(exc, config))
    inputs = list(result.files)
    if run.meshes:
        inputs.extend(mesh_files(result.robot, result.path, run.packages))
    if run.skip_includes and _is_include(result):
        skipped = None if run.fmt == "text" else _skipped(result, config)
        return Outcome(EXIT_OK, report=skipped, inputs=tuple(inputs))
    failed = _failed(result, config)
    status = EXIT_INVALID if failed else EXIT_OK
    if run.fmt != "text":
        return Outcome(status, report=_report(result, config, failed), inputs=tuple(inputs))
    shown = result if run.tree else None
    return Outcome(status, findings=result.diagnostics, result=shown, inputs=tuple(inputs))


def tree_chunks(result: CheckResult) -> Iterable[str]:
    """check_urdf's output, whenever the tree can be printed (errors or not: a script
    reading it keeps working, and the exit status tells the rest)."""
    from ..graph import tree_text

    topo = result.topology
    if result.analysis is None or topo is None or topo.root is None or topo.loop_from_root:
        return ()
    return tree_text(result.analysis)


def _can_fork() -> bool:
    # Forking copies one thread only: never with others running (a program embedding us).
    return sys.platform == "linux" and threading.active_count() == 1


_work: tuple[Sequence[str], Sequence[Config], Run, int, float] | None = None


def _start(
    names: Sequence[str], configs: Sequence[Config], run: Run, size: int, seconds: float
) -> None:
    """Set up a checking process: Ctrl-C and SIGTERM are the main process's to handle."""
    import signal

    global _work
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    _work = (names, configs, run, size, seconds)


def _elsewhere(index: int) -> Outcome | None:
    """File ``index``'s outcome, with its tree as text; None for one the main process
    checks."""
    from ..inputs import size_limit, time_limit

    assert _work is not None
    names, configs, run, size, seconds = _work
    name = names[index]
    try:
        if name == "-" or os.path.getsize(name) > _LARGEST:
            return None
    except OSError:
        return None  # (the main process reports it)
    with size_limit(size), time_limit(seconds):
        done = outcome(name, configs[index], run)
        if done.result is None:
            return done
        return replace(done, result=None, tree="".join(tree_chunks(done.result)))


def _report(result: CheckResult, config: Config, failed: bool) -> FileReport:
    from ..report import FileReport

    robot, topo = result.robot, result.topology
    return FileReport(
        path=result.path,
        ok=not failed,
        diagnostics=result.diagnostics,
        suppressed=result.suppressed,
        robot=None if robot is None else robot.name,
        root=None if topo is None else topo.root,
        links=None if robot is None else len(robot.links),
        joints=None if robot is None else len(robot.joints),
        config=config.path,
    )


def _failure(exc: FishbotUrdfError, config: Config) -> FileReport:
    from ..report import FileReport

    finding = fail(exc)
    return FileReport(path=finding.path, ok=False, diagnostics=(finding,), config=config.path)


def _skipped(result: CheckResult, config: Config) -> FileReport:
    from ..report import FileReport

    return FileReport(
        path=result.path,
        ok=True,
        diagnostics=(),
        config=config.path,
        skipped="defines no robot (macros for other files to include)",
    )


def _is_include(result: CheckResult) -> bool:
    """A xacro file that defines no robot: macros, properties, materials for others."""
    from ..parse import is_xacro_path

    robot = result.robot
    return (
        robot is not None
        and is_xacro_path(result.path)
        and not robot.name
        and not robot.links
        and not robot.joints
    )


def _failed(result: CheckResult, config: Config) -> bool:
    """Whether the file fails the check: no robot, or errors (warnings too, when strict)."""
    from ..diagnostics import has_errors

    return result.robot is None or has_errors(result.diagnostics, strict=config.strict)
