"""The files of one `fishbot check`: each file's outcome, in the order given, checked by
several processes when there are many files."""

from __future__ import annotations

import contextlib
import os
import pickle
import selectors
import signal
import struct
import sys
import threading
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, NoReturn

from ..diagnostics import escape_line_controls as shown
from ..diagnostics import has_errors
from ..errors import FishbotUrdfError
from ..graph import tree_text
from ..inputs import max_seconds, recording_inputs, time_limit
from ..parsing import is_xacro_path
from ..report import FileReport
from ._checking import check_input, read_files
from ._common import EXIT_INVALID, EXIT_OK, fail, status_of

if TYPE_CHECKING:
    from ..config import Config
    from ..diagnostics import Diagnostic
    from ..lint import CheckResult
    from ..output import Source
    from ..packages import PackageFinder
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
        finder: The ``--package`` folders, and where mesh packages were found, for the next
            files.
        fmt: The output format.
        skip_includes: Pass over xacro files that define no robot.
        meshes: An output file is written (``-o FILE``): everything a file's check reads
            (its meshes too) is an input, never to be written over.
        tree: check_urdf's tree is printed (text format, not quiet).
        urdf_args: A URDF file is given ``args`` too (to be warned that it reads none):
            no xacro file in the run takes them.
    """

    args: dict[str, str]
    finder: PackageFinder
    fmt: str
    skip_includes: bool
    meshes: bool
    tree: bool
    urdf_args: bool = True


@dataclass(frozen=True, slots=True)
class Outcome:
    """What checking one file gives the command.

    Attributes:
        status: Its exit status (0, 1 or 2).
        findings: The lines to print (text format).
        report: Its report (other formats).
        result: The check, for its tree to be streamed (checked in this process).
        tree: Its tree as text (checked in another process).
        inputs: The files it was read from, never to be written over (with ``-o FILE``:
            the file, what it includes, its meshes, the package.xml files read to find
            its packages; for a file that could not be read, what was read before).
    """

    status: int
    findings: tuple[Diagnostic, ...] = ()
    report: FileReport | None = None
    result: CheckResult | None = None
    tree: str | None = None
    inputs: tuple[Source, ...] = ()


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

    sys.stdout.flush()  # (nothing buffered is copied into the processes)
    sys.stderr.flush()
    try:
        workers = _Workers(names, configs, run, jobs)
    except OSError:  # no more processes or pipes to be had: one after another, here
        for name, config in zip(names, configs, strict=True):
            yield outcome(name, config, run)
        return
    with workers:
        for index, (name, config) in enumerate(zip(names, configs, strict=True)):
            done = workers.outcome(index)
            yield outcome(name, config, run) if done is None else done


_INDEX = struct.Struct("<i")  # a file's index (-1: no more files)
_HEAD = struct.Struct("<iQ")  # a file's index, and the size of its pickled outcome
_AHEAD = 2  # files given to each process before it reports on one


class _Workers:
    """Processes forked to check files, each given the next file as it reports one done,
    over a pair of pipes. Forked by hand: `concurrent.futures.ProcessPoolExecutor` with a
    fork context took 1.15x the time over the 1,747 URDF files of the PyPI corpus (wall,
    median of 5 pairs; a forkserver cannot pickle a configuration's mapping proxies)."""

    def __init__(
        self, names: Sequence[str], configs: Sequence[Config], run: Run, jobs: int
    ) -> None:
        self._count = len(names)
        self._next = 0  # the next file to give out
        self._done: dict[int, Outcome | None] = {}
        self._selector = selectors.DefaultSelector()
        self._children: dict[int, _Child] = {}  # by the pipe their outcomes come through
        try:
            for _ in range(jobs):
                self._fork(names, configs, run)
        except BaseException:
            self.__exit__()
            raise

    def _fork(self, names: Sequence[str], configs: Sequence[Config], run: Run) -> None:
        tasks_read, tasks = os.pipe()
        try:
            results, results_write = os.pipe()
        except OSError:
            os.close(tasks_read)
            os.close(tasks)
            raise
        try:
            pid = os.fork()
        except OSError:
            for fd in (tasks_read, tasks, results, results_write):
                os.close(fd)
            raise
        if pid == 0:  # pragma: no cover - the checking process (coverage sees the parent)
            os.close(tasks)
            os.close(results)
            _serve(names, configs, run, tasks_read, results_write)
        os.close(tasks_read)
        os.close(results_write)
        child = self._children[results] = _Child(pid, tasks)
        self._selector.register(results, 1)
        for _ in range(_AHEAD):
            self._give(child)

    def __enter__(self) -> _Workers:
        return self

    def __exit__(self, *exc: object) -> None:
        """Stop every process (also on Ctrl-C, or when the output's reader has gone)."""
        self._selector.close()
        for results, child in self._children.items():
            for fd in (results, child.tasks):
                with contextlib.suppress(OSError):
                    os.close(fd)
            with contextlib.suppress(OSError):
                os.kill(child.pid, signal.SIGKILL)
            os.waitpid(child.pid, 0)
        self._children.clear()

    def outcome(self, index: int) -> Outcome | None:
        """File ``index``'s outcome, once a process has sent it; None for a file to check
        here."""
        while index not in self._done:
            if not self._selector.get_map():  # every process has died
                return None
            for key, _ in self._selector.select():
                self._receive(key.fd)
        return self._done.pop(index)

    def _give(self, child: _Child) -> None:
        index = -1 if self._next >= self._count else self._next
        self._next += index >= 0
        if index >= 0:
            child.given.append(index)
        with contextlib.suppress(OSError):  # it has died: its files are checked here
            os.write(child.tasks, _INDEX.pack(index))

    def _receive(self, results: int) -> None:
        child = self._children[results]
        data = os.read(results, 1 << 16)
        if not data:  # it has ended or died: what it was given and did not send, here
            self._selector.unregister(results)
            for index in child.given:
                self._done[index] = None
            child.given.clear()
            return
        child.buffer += data
        while len(child.buffer) >= _HEAD.size:
            index, size = _HEAD.unpack_from(child.buffer)
            if len(child.buffer) < _HEAD.size + size:
                break
            body = bytes(child.buffer[_HEAD.size : _HEAD.size + size])
            del child.buffer[: _HEAD.size + size]
            self._done[index] = pickle.loads(body)
            child.given.remove(index)
            self._give(child)


class _Child:
    """A checking process: its id, the pipe its files go to, the files it has been given and
    not reported, and what it has sent of the next outcome. (A plain class: a dataclass
    would cost every `fishbot check` its definition at start-up.)"""

    __slots__ = ("buffer", "given", "pid", "tasks")

    def __init__(self, pid: int, tasks: int) -> None:
        self.pid = pid
        self.tasks = tasks
        self.given: list[int] = []
        self.buffer = bytearray()


def _serve(
    names: Sequence[str], configs: Sequence[Config], run: Run, tasks: int, results: int
) -> NoReturn:
    """Check the files whose indexes come through ``tasks`` and send each outcome through
    ``results``, with its tree as text; None for a file the main process checks (standard
    input, a big file, or one that raised)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the main process's to handle
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    status = 0
    try:
        with os.fdopen(tasks, "rb") as given, os.fdopen(results, "wb") as out:
            while (head := given.read(_INDEX.size)) and len(head) == _INDEX.size:
                (index,) = _INDEX.unpack(head)
                if index < 0:
                    break
                done: Outcome | None = None
                with contextlib.suppress(Exception):  # checked again there, to report it
                    done = _away(names[index], configs[index], run)
                body = pickle.dumps(done, pickle.HIGHEST_PROTOCOL)
                out.write(_HEAD.pack(index, len(body)))
                out.write(body)
                out.flush()
    except BaseException:  # the main process has gone: nothing to tell it
        status = 1
    # A forked copy of the main process: its clean-up and its output's buffers are the main
    # process's, not this one's to run or flush.
    os._exit(status)


def _away(name: str, config: Config, run: Run) -> Outcome | None:
    """A file's outcome as a checking process sends it: its tree as text; None for a file
    the main process checks."""
    if name == "-" or os.path.getsize(name) > _LARGEST:
        return None
    done = outcome(name, config, run)
    if done.result is None:
        return done
    return replace(done, result=None, tree="".join(tree_chunks(done.result)))


def outcome(name: str, config: Config, run: Run) -> Outcome:
    """Check one file (``-``: standard input), within a time limit of its own: as long as
    the command's (``--timeout``), from now."""
    with time_limit(max_seconds()), recording_inputs() as read:
        try:
            args = run.args if run.urdf_args or is_xacro_path(name) else {}
            result = check_input(name, args, run.finder, config)
        except FishbotUrdfError as exc:
            if exc.path is None:  # a time limit: about the file all the same
                exc.path = "<stdin>" if name == "-" else name
            # What was read before it stopped (includes, package.xml files) is an input too.
            partial = (*read_files(name, None), *read) if run.meshes else ()
            if run.fmt == "text":
                return Outcome(status_of(exc), findings=(fail(exc),), inputs=partial)
            return Outcome(status_of(exc), report=_failure(exc, config), inputs=partial)
        inputs: list[Source] = []
        if run.meshes:  # -o FILE: nothing read may be written over
            inputs = [*read_files(name, result), *read]
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
    """check_urdf's output: the tree wherever urdfdom builds the robot, our errors or not (a
    script reading it keeps working, and the exit status tells the rest), nothing where it
    refuses the file (`CheckResult.refused_by_urdfdom`). A joint loop reached from the root, which
    check_urdf prints without end, is not printed either."""
    topo = result.topology
    if result.analysis is None or topo is None or topo.root is None or topo.loop_from_root:
        return ()
    if result.refused_by_urdfdom:
        return ()
    robot = result.analysis.robot

    if all(shown(name) == name for name in (robot.name, *(k.name for k in robot.links))):
        return tree_text(result.analysis)
    # A name that holds a line end or a terminal control: written visibly, as in the
    # findings (check_urdf prints them raw, escape sequences and all); a tab and DEL are
    # kept as check_urdf prints them. Each piece is one line and its newline.
    return (
        shown(chunk[:-1]) + "\n" if chunk.endswith("\n") else shown(chunk)
        for chunk in tree_text(result.analysis)
    )


def _can_fork() -> bool:
    # Forking copies one thread only: never with others running (a program embedding us).
    return sys.platform == "linux" and threading.active_count() == 1


def _report(result: CheckResult, config: Config, failed: bool) -> FileReport:
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
        targets=result.targets,
    )


def _failure(exc: FishbotUrdfError, config: Config) -> FileReport:
    finding = fail(exc)
    return FileReport(path=finding.path, ok=False, diagnostics=(finding,), config=config.path)


def _skipped(result: CheckResult, config: Config) -> FileReport:
    return FileReport(
        path=result.path,
        ok=True,
        diagnostics=(),
        config=config.path,
        skipped="defines no robot (macros for other files to include)",
    )


def _is_include(result: CheckResult) -> bool:
    """A xacro file that defines no robot: macros, properties, materials for others."""
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
    return result.robot is None or has_errors(result.diagnostics, strict=config.strict)
