"""Reading the files a robot names: regular files only, and no bigger than a limit; and
how long the work on a robot may take.

Every file the library reads on a robot's behalf (the robot itself, its includes, YAML
files, package manifests, meshes) goes through :func:`read_input`, so a FIFO, a device such
as ``/dev/zero`` or a file of many gigabytes is refused with one clear error instead of
hanging or filling the memory. Inside :func:`recording_inputs`, every file read so is
noted, so that an output is never written over a file the work was made from.

The limits belong to the caller's context (a :class:`contextvars.ContextVar`), not to the
process: :func:`size_limit` and :func:`time_limit` change them for the code inside a
``with``, in that thread only. The time limit is one deadline for the whole ``with``:
every long piece of work (expanding, globbing an include, loading YAML, reading,
matching suppression comments, analysing, rendering, Graphviz's `dot`) asks
:func:`deadline` and stops with a :class:`TimeLimitError` once it has passed. Outside a
``with``, each piece of work gets :data:`DEFAULT_MAX_SECONDS` from when it starts. The
folders a xacro expansion may read beyond the robot's own (:func:`allowing_reads`) and
whether it runs expressions as Python (:func:`trusting_expressions`) are the context's too.

So are the two things a workspace (:mod:`fishbot_urdf.workspace`) lays over the disk: the
unsaved texts of files open in an editor (:func:`reading_through`: :func:`read_input` gives
a file's text from there when it has one), and a :class:`Cancellation` (:func:`cancellable`)
that stops the work at its next look at the deadline, with :class:`Cancelled`, when newer
work makes it moot.
"""

from __future__ import annotations

import errno
import os
import stat
import time
from collections.abc import Iterable, Iterator
from contextlib import AbstractContextManager, contextmanager
from contextvars import ContextVar
from pathlib import Path
from typing import Any, Protocol

from .errors import ArgumentError, InputError, LimitError

__all__ = [
    "DEFAULT_MAX_BYTES",
    "DEFAULT_MAX_SECONDS",
    "Cancellation",
    "Cancelled",
    "Deadline",
    "InputTooLargeError",
    "Overlay",
    "TimeLimitError",
    "allowing_reads",
    "cancellable",
    "deadline",
    "is_input_file",
    "looking_for",
    "max_bytes",
    "max_seconds",
    "note_inputs",
    "note_looked",
    "read_input",
    "reading_through",
    "reads_allowed",
    "recording_inputs",
    "size_limit",
    "time_limit",
    "trusting_expressions",
    "trusts_expressions",
]

DEFAULT_MAX_BYTES = 256 * 1024 * 1024
"""The largest file read by default: 256 MiB, about fifteen times a 100,000-link URDF."""

DEFAULT_MAX_SECONDS = 60.0
"""How long the work on one robot may take by default, in seconds."""

_LIMIT: ContextVar[int] = ContextVar("fishbot_urdf_max_bytes", default=DEFAULT_MAX_BYTES)
_SECONDS: ContextVar[float] = ContextVar("fishbot_urdf_max_seconds", default=DEFAULT_MAX_SECONDS)
_END: ContextVar[float | None] = ContextVar("fishbot_urdf_deadline", default=None)
_TRUST: ContextVar[bool] = ContextVar("fishbot_urdf_trust_expressions", default=False)
_READ: ContextVar[list[str] | None] = ContextVar("fishbot_urdf_inputs_read", default=None)
_READS: ContextVar[tuple[str, ...]] = ContextVar("fishbot_urdf_allowed_reads", default=())


class Overlay(Protocol):
    """Texts laid over the files on disk (an editor's unsaved buffers)."""

    def buffer(self, path: str) -> bytes | None:
        """The text held for the file ``path`` (as given: relative to the current folder or
        absolute), or None to read the disk."""


class Cancellation:
    """A flag another thread raises to stop work it no longer needs (a newer edit came).

    The work stops at its next look at the deadline (:meth:`Deadline.check`) with
    :class:`Cancelled`."""

    __slots__ = ("_set",)

    def __init__(self) -> None:
        self._set = False

    def cancel(self) -> None:
        """Stop the work (callable from any thread)."""
        self._set = True

    @property
    def cancelled(self) -> bool:
        """Whether :meth:`cancel` was called."""
        return self._set


class Cancelled(BaseException):
    """The work was cancelled (see :class:`Cancellation`), or its caller stopped waiting for
    it. A BaseException, so that no handler of ordinary errors goes on with the work."""


_OVERLAY: ContextVar[Overlay | None] = ContextVar("fishbot_urdf_overlay", default=None)
_LOOKED: ContextVar[list[str] | None] = ContextVar("fishbot_urdf_looked_for", default=None)
_CANCEL: ContextVar[Cancellation | None] = ContextVar("fishbot_urdf_cancellation", default=None)


class TimeLimitError(LimitError):
    """Work went on past the time limit; ``seconds`` is the limit, ``what`` the work."""

    def __init__(self, what: str, seconds: float) -> None:
        super().__init__(f"{what} takes longer than the time limit of {seconds:g} s")
        self.what = what
        self.seconds = seconds


class Deadline:
    """When the work in hand must stop: :meth:`check` raises once it has passed.

    A check costs one clock read; loops call it every few hundred steps.
    """

    __slots__ = ("cancellation", "end", "seconds")

    def __init__(
        self, end: float, seconds: float, cancellation: Cancellation | None = None
    ) -> None:
        self.end = end
        self.seconds = seconds
        self.cancellation = cancellation

    def passed(self) -> bool:
        """Whether the deadline has passed (raises :class:`Cancelled` if the work was
        cancelled)."""
        if self.cancellation is not None and self.cancellation.cancelled:
            raise Cancelled
        return time.monotonic() > self.end

    def left(self) -> float:
        """Seconds left before the deadline (0 once it has passed)."""
        return max(0.0, self.end - time.monotonic())

    def check(self, what: str) -> None:
        """Raise :class:`TimeLimitError` naming ``what`` if the deadline has passed, and
        :class:`Cancelled` if the work was cancelled."""
        if self.passed():
            raise TimeLimitError(what, self.seconds)


def deadline() -> Deadline:
    """The deadline in force: that of the enclosing :func:`time_limit`, or, outside one,
    :func:`max_seconds` from now."""
    seconds = _SECONDS.get()
    end = _END.get()
    return Deadline(time.monotonic() + seconds if end is None else end, seconds, _CANCEL.get())


def cancellable(cancellation: Cancellation) -> AbstractContextManager[None]:
    """Inside the ``with`` (this thread or task only, and the threads it runs work in with
    its context), the work stops with :class:`Cancelled` at its next look at the deadline
    once ``cancellation`` is cancelled."""
    return _holding(_CANCEL, cancellation)


def reading_through(overlay: Overlay | None) -> AbstractContextManager[None]:
    """Inside the ``with`` (this thread or task only, and the threads it runs work in with
    its context), :func:`read_input` gives the text ``overlay`` holds for a file, where it
    holds one, instead of the disk's."""
    return _holding(_OVERLAY, overlay)


def is_input_file(path: str | Path) -> bool:
    """Whether ``path`` is a file :func:`read_input` may give: a text the overlay in force
    holds, or a regular file on disk."""
    overlay = _OVERLAY.get()
    if overlay is not None and overlay.buffer(str(path)) is not None:
        return True
    return os.path.isfile(path)


class InputTooLargeError(InputError):
    """A file is bigger than the limit; ``size`` (None: not known, a stream) and ``limit``
    are in bytes."""

    rule = "io"

    def __init__(self, path: str, size: int | None, limit: int) -> None:
        bigger = "is more" if size is None else f"is {_megabytes(size)}, more"
        super().__init__(f"{bigger} than the limit of {_megabytes(limit)}", path=path)
        self.size = size
        self.limit = limit


def max_bytes() -> int:
    """The size limit in force here, in bytes."""
    return _LIMIT.get()


def size_limit(limit: int) -> AbstractContextManager[None]:
    """Read files of up to ``limit`` bytes inside the ``with`` (this thread or task only)."""
    if limit <= 0:
        raise ArgumentError("the size limit must be a positive number of bytes")
    return _holding(_LIMIT, limit)


def max_seconds() -> float:
    """The time limit in force here, in seconds."""
    return _SECONDS.get()


def time_limit(seconds: float) -> AbstractContextManager[None]:
    """Let the work inside the ``with`` take up to ``seconds`` in all, from now (this thread
    or task only): one deadline for everything it does."""
    if not seconds > 0:
        raise ArgumentError("the time limit must be a positive number of seconds")
    return _timing(seconds)


@contextmanager
def _timing(seconds: float) -> Iterator[None]:
    with _holding(_SECONDS, seconds), _holding(_END, time.monotonic() + seconds):
        yield


def trusting_expressions(trust: bool = True) -> AbstractContextManager[None]:
    """Inside the ``with`` (this thread or task only), xacro expansions evaluate ``${...}``
    and ``$(eval ...)`` with Python's ``eval``, as ROS's xacro does: the file's code runs
    with the rights of the process. Outside, expressions are interpreted by an allowlist
    that cannot reach past the symbol table (see :mod:`fishbot_urdf.expansion`)."""
    return _holding(_TRUST, trust)


def trusts_expressions() -> bool:
    """Whether expansions here run expressions as Python (see :func:`trusting_expressions`)."""
    return _TRUST.get()


def allowing_reads(
    folders: str | os.PathLike[str] | Iterable[str | os.PathLike[str]],
) -> AbstractContextManager[None]:
    """Inside the ``with`` (this thread or task only), xacro expansions that do not run
    expressions as Python may also read the files in ``folders`` (one, or several) and below
    them, besides the robot's own tree, the packages ``$(find)`` finds and the folders of an
    enclosing ``with`` (see :mod:`fishbot_urdf.expansion`). A relative folder is taken from
    the current folder now, and links in it are resolved now."""
    given = [folders] if isinstance(folders, str | os.PathLike) else folders
    added = tuple(os.path.realpath(folder) for folder in given)
    return _holding(_READS, tuple(dict.fromkeys((*_READS.get(), *added))))


def reads_allowed() -> tuple[str, ...]:
    """The folders :func:`allowing_reads` allows here, links resolved."""
    return _READS.get()


@contextmanager
def recording_inputs() -> Iterator[list[str]]:
    """Note, in the list it gives, the name of every regular file :func:`read_input` opens
    inside the ``with`` (this thread or task only, and the threads it runs work in with its
    context), in the order opened, with those :func:`note_inputs` adds. Recordings may nest:
    an inner one's names are the outer one's too, once it ends.

    An output written with these names as its ``inputs`` (see :mod:`fishbot_urdf.output`)
    is never written over a file the work read: the robot, its includes and YAML files,
    the ``package.xml`` files read to find packages, the configuration, the meshes."""
    with _noting(_READ) as read:
        yield read


def note_inputs(paths: Iterable[str]) -> None:
    """Add files to the recording in force (if any), as if read: those an answer depends on
    without reading them again (an answer kept from an earlier search, a package's
    manifest found by its place)."""
    recording = _READ.get()
    if recording is not None:
        recording.extend(paths)


@contextmanager
def looking_for() -> Iterator[list[str]]:
    """Note, in the list it gives, every file :func:`note_looked` says was looked for inside
    the ``with`` (this thread or task only, and the threads it runs work in with its
    context): files an answer depends on being there or not (a mesh file), unread."""
    with _noting(_LOOKED) as looked:
        yield looked


@contextmanager
def _noting(variable: ContextVar[list[str] | None]) -> Iterator[list[str]]:
    """A list of names ``variable`` holds inside the ``with``; an enclosing one's gets them
    too, once it ends."""
    outer = variable.get()
    noted: list[str] = []
    token = variable.set(noted)
    try:
        yield noted
    finally:
        variable.reset(token)
        if outer is not None:
            outer.extend(noted)


def note_looked(path: str) -> None:
    """Note that the answer in hand depends on whether ``path`` is there (see
    :func:`looking_for`)."""
    looked = _LOOKED.get()
    if looked is not None:
        looked.append(path)


@contextmanager
def _holding(variable: ContextVar[Any], value: Any) -> Iterator[None]:
    token = variable.set(value)
    try:
        yield
    finally:
        variable.reset(token)


def read_input(path: str | Path) -> bytes:
    """Read a whole regular file of at most :func:`max_bytes` bytes (or the text the overlay
    in force holds for it: see :func:`reading_through`).

    The file is opened without blocking, so a FIFO is refused at once rather than waited on.

    Raises:
        InputError: The file does not exist, is a folder, a FIFO, a device or a socket, or
            cannot be read (the message says which).
        InputTooLargeError: The file is bigger than the limit.
    """
    name = str(path)
    limit = _LIMIT.get()
    overlay = _OVERLAY.get()
    held = None if overlay is None else overlay.buffer(name)
    if held is not None:
        recording = _READ.get()
        if recording is not None:
            recording.append(name)
        if len(held) > limit:
            raise InputTooLargeError(name, len(held), limit)
        return held
    try:
        handle = os.open(name, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | _BINARY)
    except FileNotFoundError as exc:
        raise InputError("no such file", path=name) from exc
    except IsADirectoryError as exc:
        raise InputError("is a directory, not a file", path=name) from exc
    except PermissionError as exc:
        raise InputError("permission denied", path=name) from exc
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", path=name) from exc
    try:
        mode = os.fstat(handle).st_mode
        if stat.S_ISDIR(mode):
            cause = IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), name)
            raise InputError("is a directory, not a file", path=name) from cause
        if not stat.S_ISREG(mode):
            raise InputError(f"is {_kind(mode)}, not a regular file", path=name)
        recording = _READ.get()
        if recording is not None:
            recording.append(name)
        size = os.fstat(handle).st_size
        if size > limit:
            raise InputTooLargeError(name, size, limit)
        chunks = []
        left = limit + 1  # a file that grows while it is read is caught too
        while left > 0:
            chunk = os.read(handle, min(left, 1 << 20))
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
        data = b"".join(chunks)
        if len(data) > limit:
            raise InputTooLargeError(name, len(data), limit)
        return data
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", path=name) from exc
    finally:
        os.close(handle)


_BINARY = getattr(os, "O_BINARY", 0)


def _kind(mode: int) -> str:
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def _megabytes(size: int) -> str:
    if size < 1024 * 1024:
        return f"{size:,} bytes"
    return f"{size / (1024 * 1024):,.1f} MiB"
