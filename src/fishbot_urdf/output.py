"""Writing output files safely: whole or not at all, never over an input."""

from __future__ import annotations

import contextlib
import os
import stat
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from .errors import InputError

__all__ = ["AtomicFile", "Source", "refuse_inputs", "write_atomic"]

Source = str | Path | int
"""A file an output must never replace: its name, or a file descriptor open on it (``0``
for standard input, when that is a file)."""


def write_atomic(
    path: str | Path,
    data: bytes | str,
    *,
    inputs: Iterable[Source] = (),
    through_links: bool = True,
) -> Path:
    """Write ``data`` to ``path`` through a temporary file and a rename, making parent folders.

    A reader never sees half a file, and an existing file is only replaced by a complete new
    one; an interrupt leaves no temporary file behind. A link is written through (its target
    is replaced; a link whose target's folder does not exist is refused, not made); a
    device or a pipe (``/dev/null``, a FIFO) is written to directly. Text is written as
    UTF-8 (a file name that is no UTF-8, as its own bytes).

    ``inputs`` are the files the output was made from: ``path`` is refused when it is one
    of them, compared as files (device and inode, links followed), not as names.

    With ``through_links`` False (for a name the caller made, not one a user gave), ``path``
    must be a new file or a regular one: a link, a device or a pipe there is refused, and a
    link made there while the file is written is replaced, never written through.

    Raises:
        InputError: ``path`` is one of ``inputs``, a folder, read-only, or cannot be
            written; without ``through_links``, a link or no regular file.
    """
    inputs = tuple(inputs)
    with AtomicFile(path, inputs=inputs, through_links=through_links) as out:
        out.write(data)
        return out.commit(inputs)


class AtomicFile:
    """An output file written piece by piece and put in place whole, or not at all.

    Use it in a ``with``: :meth:`commit` puts the file in place; leaving the ``with``
    without it (an error, an interrupt) removes what was written. The checks of
    :func:`write_atomic` are made when it opens (against the ``inputs`` known then) and
    again at :meth:`commit` (against all of them); ``through_links`` is as there.
    """

    def __init__(
        self, path: str | Path, *, inputs: Iterable[Source] = (), through_links: bool = True
    ) -> None:
        self.path = str(path)
        self.target = _target(path, inputs, through_links)
        self._temporary: Path | None = None
        self._mode: int | None = None
        self._stream: Any = None
        try:
            if self.target.exists() and not self.target.is_file():
                # a device or a pipe: there is nothing to replace
                self._stream = open(self.target, "wb")  # noqa: SIM115
                return
            self.target.parent.mkdir(parents=True, exist_ok=True)
            # A new file gets the mode any new file gets: 0o666 less the umask, which the
            # system applies by itself. A file replaced keeps its own mode, given once the
            # data is in (until then only its owner may read it, as the file may be private).
            if self.target.exists():
                self._mode = self.target.stat().st_mode & 0o7777
            handle, self._temporary = _create_temporary(
                self.target, 0o666 if self._mode is None else 0o600
            )
            self._stream = os.fdopen(handle, "wb")
        except OSError as exc:
            raise self._cannot(exc) from exc

    def __enter__(self) -> AtomicFile:
        return self

    def __exit__(self, *exc: object) -> None:
        self.discard()

    def write(self, data: bytes | str) -> None:
        """Add ``data`` (text as UTF-8) to the file."""
        payload = data.encode("utf-8", "surrogateescape") if isinstance(data, str) else data
        try:
            self._stream.write(payload)
        except OSError as exc:
            raise self._cannot(exc) from exc

    def commit(self, inputs: Iterable[Source] = ()) -> Path:
        """Put the file in place, unless it is one of ``inputs``; the path written."""
        try:
            refuse_inputs(self.path, inputs)
        except InputError:
            self.discard()
            raise
        try:
            self._stream.close()
            if self._temporary is not None:
                if self._mode is not None:
                    os.chmod(self._temporary, self._mode)
                os.replace(self._temporary, self.target)
                self._temporary = None
        except OSError as exc:
            raise self._cannot(exc) from exc
        return self.target

    def discard(self) -> None:
        """Remove what was written, if it was not put in place."""
        if self._stream is not None and not self._stream.closed:
            with contextlib.suppress(OSError):  # the file goes anyway
                self._stream.close()
        if self._temporary is not None:
            self._temporary.unlink(missing_ok=True)
            self._temporary = None

    def _cannot(self, exc: OSError) -> InputError:
        self.discard()
        return InputError(f"cannot write {self.path}: {exc.strerror}", path=self.path)


def refuse_inputs(path: str | Path, inputs: Iterable[Source]) -> None:
    """Refuse ``path`` as an output when it is one of ``inputs``: the same regular file
    (device and inode, links followed), whatever its name. A path that does not exist yet,
    a device or a pipe is no input.

    Raises:
        InputError: ``path`` is one of ``inputs``.
    """
    mine = _identity(path)
    if mine is None:
        return
    for source in inputs:
        if _identity(source) == mine:
            named = source if not isinstance(source, int) else _descriptor(source)
            raise InputError(f"refusing to write over the input {named}", path=str(path))


def _descriptor(fd: int) -> str:
    return "<stdin>" if fd == 0 else f"<fd {fd}>"


def _identity(source: Source) -> tuple[int, int] | None:
    """The device and inode of the regular file ``source`` names (or is open on); None for
    anything else, which no input is (a device, a pipe: every input is read as a regular
    file) or a name with no file."""
    try:
        found = os.fstat(source) if isinstance(source, int) else os.stat(source)
    except (OSError, ValueError):  # not there, a loop of links, a name with a NUL
        return None
    if not stat.S_ISREG(found.st_mode):
        return None
    return found.st_dev, found.st_ino


def _target(path: str | Path, inputs: Iterable[Source], through_links: bool = True) -> Path:
    """The file ``path`` names, once it is known to be one that may be written."""
    if not str(path):
        raise InputError("the output file name is empty", path="<output>")
    if str(path).endswith(("/", os.sep)):
        raise InputError(f"{path} names a folder (name a file in it)", path=str(path))
    refuse_inputs(path, inputs)
    if not through_links:
        _refuse_other_than_a_file(path)
    try:
        # Without links followed, the rename puts the file in place of whatever the name
        # is by then: a link made there meanwhile is replaced, not written through.
        target = Path(os.path.realpath(path) if through_links else os.path.abspath(path))
        if target.is_dir():
            raise InputError(f"{path} is a folder (name a file in it)", path=str(path))
        if os.path.islink(path) and not target.parent.is_dir():
            raise InputError(
                f"{path} is a link to {target}, whose folder does not exist", path=str(path)
            )
        if target.is_file() and (not target.stat().st_mode & 0o222 or not _writable(target)):
            # As a shell's > refuses it (root included: the mode says "keep").
            raise InputError(
                f"{path} is read-only (make it writable to replace it)", path=str(path)
            )
    except OSError as exc:  # a name too long, a loop of links, ...
        raise InputError(f"cannot write {path}: {exc.strerror}", path=str(path)) from exc
    return target


def _refuse_other_than_a_file(path: str | Path) -> None:
    """Refuse a link, a device, a pipe or a socket at ``path`` (a folder is refused later)."""
    try:
        found = os.lstat(path)
    except FileNotFoundError:
        return
    except OSError as exc:  # a name too long, a folder on the way that is no folder, ...
        raise InputError(f"cannot write {path}: {exc.strerror}", path=str(path)) from exc
    if stat.S_ISLNK(found.st_mode):
        raise InputError(
            f"{path} is a link: this output is not written through one", path=str(path)
        )
    if not stat.S_ISREG(found.st_mode) and not stat.S_ISDIR(found.st_mode):
        raise InputError(
            f"{path} is no regular file: this output replaces only one", path=str(path)
        )


def _create_temporary(target: Path, mode: int) -> tuple[int, Path]:
    """A new, empty file beside ``target``, open for writing, with a name no other has."""
    # Short enough that a file name near the 255-byte limit still has room for it.
    prefix = f".{target.name[:40]}."
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    tries = 100
    while True:
        temporary = target.parent / f"{prefix}{_token()}"
        try:
            return os.open(temporary, flags, mode), temporary
        except FileExistsError:
            tries -= 1
            if not tries:  # the caller says it cannot write there
                raise


def _writable(path: Path) -> bool:
    return os.access(path, os.W_OK)


def _token() -> str:
    """Eight random hex digits for a temporary file's name."""
    return os.urandom(4).hex()
