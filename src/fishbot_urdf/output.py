"""Writing output files safely: whole or not at all, never over an input."""

from __future__ import annotations

import os
import secrets
from collections.abc import Iterable
from pathlib import Path

from .errors import InputError

__all__ = ["write_atomic"]


def write_atomic(path: str | Path, data: bytes | str, *, inputs: Iterable[str | Path] = ()) -> Path:
    """Write ``data`` to ``path`` through a temporary file and a rename, making parent folders.

    A reader never sees half a file, and an existing file is only replaced by a complete new
    one; an interrupt leaves no temporary file behind. A link is written through (its target
    is replaced; a link whose target's folder does not exist is refused, not made); a
    device or a pipe (``/dev/null``, a FIFO) is written to directly. Text is written as
    UTF-8 (a file name that is no UTF-8, as its own bytes).

    Raises:
        InputError: ``path`` is one of ``inputs``, a folder, read-only, or cannot be
            written.
    """
    if not str(path):
        raise InputError("the output file name is empty", path="<output>")
    if str(path).endswith(("/", os.sep)):
        raise InputError(f"{path} names a folder (name a file in it)", path=str(path))
    payload = data.encode("utf-8", "surrogateescape") if isinstance(data, str) else data
    try:
        target = Path(os.path.realpath(path))
        for source in inputs:
            if _same_file(target, Path(source)):
                raise InputError(f"refusing to write over the input {source}", path=str(path))
        if target.is_dir():
            raise InputError(f"{path} is a folder (name a file in it)", path=str(path))
        if os.path.islink(path) and not target.parent.is_dir():
            raise InputError(
                f"{path} is a link to {target}, whose folder does not exist", path=str(path)
            )
        special = target.exists() and not target.is_file()
        if target.is_file() and (not target.stat().st_mode & 0o222 or not _writable(target)):
            # As a shell's > refuses it (root included: the mode says "keep").
            raise InputError(
                f"{path} is read-only (make it writable to replace it)", path=str(path)
            )
    except OSError as exc:  # a name too long, a loop of links, ...
        raise InputError(f"cannot write {path}: {exc.strerror}", path=str(path)) from exc
    if special:
        try:  # a device or a pipe: there is nothing to replace
            with open(target, "wb") as stream:
                stream.write(payload)
        except OSError as exc:
            raise InputError(f"cannot write {path}: {exc.strerror}", path=str(path)) from exc
        return target
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        # A new file gets the mode any new file gets: 0o666 less the umask, which the system
        # applies by itself. A file replaced keeps its own mode, given once the data is in
        # (until then only its owner may read it, as the file may be private).
        mode = target.stat().st_mode & 0o7777 if target.exists() else None
        handle, temporary = _create_temporary(target, 0o666 if mode is None else 0o600)
    except OSError as exc:
        raise InputError(f"cannot write {path}: {exc.strerror}", path=str(path)) from exc
    try:
        with os.fdopen(handle, "wb") as stream:
            stream.write(payload)
        if mode is not None:
            os.chmod(temporary, mode)
        os.replace(temporary, target)
    except BaseException as exc:  # a full disk, or an interrupt: no half file is left
        temporary.unlink(missing_ok=True)
        if isinstance(exc, OSError):
            raise InputError(f"cannot write {path}: {exc.strerror}", path=str(path)) from exc
        raise
    return target


def _create_temporary(target: Path, mode: int) -> tuple[int, Path]:
    """A new, empty file beside ``target``, open for writing, with a name no other has."""
    # Short enough that a file name near the 255-byte limit still has room for it.
    prefix = f".{target.name[:40]}."
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    tries = 100
    while True:
        temporary = target.parent / f"{prefix}{secrets.token_hex(4)}"
        try:
            return os.open(temporary, flags, mode), temporary
        except FileExistsError:
            tries -= 1
            if not tries:  # the caller says it cannot write there
                raise


def _writable(path: Path) -> bool:
    return os.access(path, os.W_OK)


def _same_file(a: Path, b: Path) -> bool:
    try:
        return a.exists() and b.exists() and a.samefile(b)
    except OSError:
        return False
