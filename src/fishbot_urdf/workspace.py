"""The inputs of a session and what is derived from them, kept until an input changes.

A :class:`Workspace` owns two things:

- **the inputs**: the files on disk, with the unsaved texts of an editor's open files laid
  over them (:meth:`Workspace.open`). Every file the library reads on a robot's behalf goes
  through :func:`fishbot_urdf.inputs.read_input`, which, inside :meth:`Workspace.reading`,
  gives a held text instead of the disk's: the robot, its includes and YAML files, the
  suppression comments, package manifests;
- **the caches**: the packages found (one :class:`~fishbot_urdf.packages.PackageFinder`), and
  every answer :meth:`Workspace.memo` keeps (an expansion, a whole check with its analysis),
  each with what it was made from: the fingerprint of every file it read or looked for.
  An answer is given again only while every one of those is unchanged (a held text is the
  same text; a file on disk has the same size, time and inode; a file that was missing is
  still missing), so an edit, a save or a new mesh file invalidates exactly the answers
  that read it, and :meth:`Workspace.readers` names them.

The layers above ask it: ``parsing.read`` keeps each expansion here, ``lint.check_file`` each
check; the command line makes one workspace per run, the language server one per session.
Safe to share between threads: two threads asking for the same answer may both make it, and
the last one made is kept.
"""

from __future__ import annotations

import os
import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable, Iterable, Iterator, Mapping
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from .inputs import looking_for, note_looked, read_input, reading_through, recording_inputs
from .packages import PackageFinder

__all__ = ["Workspace", "package_key"]

T = TypeVar("T")

Fingerprint = tuple[Any, ...] | None
"""What a file was when an answer read it: ``("text", hash, length)`` for a held text,
``(mtime_ns, ctime_ns, size, inode)`` for a file on disk, None for a file that was not there."""

# The fingerprints of the files read from disk by the answer being made, each taken just
# before the file was read (see Workspace.buffer).
_SEEN: ContextVar[dict[str, Fingerprint] | None] = ContextVar("fishbot_urdf_seen", default=None)

MAX_ANSWERS = 256
"""How many answers a workspace keeps; the one used longest ago goes first."""


@dataclass(frozen=True, slots=True)
class _Answer:
    value: Any
    inputs: tuple[tuple[str, Fingerprint], ...]


class Workspace:
    """Files on disk with unsaved texts laid over them, and the answers made from them.

    Args:
        packages: Package folders for ``$(find NAME)`` and ``package://``, searched first
            (see :mod:`fishbot_urdf.packages`), or a finder to share.
        environ: The environment the package search reads (default: the process's).
        keep: How many answers to keep (0: none, for a run that reads each robot once and
            had better free it once done).
    """

    def __init__(
        self,
        packages: Mapping[str, str | Path] | PackageFinder | None = None,
        environ: Mapping[str, str] | None = None,
        *,
        keep: int = MAX_ANSWERS,
    ) -> None:
        self.keep = keep
        if isinstance(packages, PackageFinder):
            self.packages = packages
        else:
            self.packages = PackageFinder(packages, environ)
        self._texts: dict[str, bytes] = {}
        self._answers: OrderedDict[Hashable, _Answer] = OrderedDict()
        self._lock = threading.Lock()
        self.made = 0  # answers made, not given again (for tests and benchmarks)

    # -- the inputs ----------------------------------------------------------------------
    def open(self, path: str | Path, text: str | bytes) -> None:
        """Hold ``text`` as the content of the file ``path`` (an editor's unsaved buffer),
        whether the disk has the file or not, until :meth:`close`."""
        data = text.encode("utf-8") if isinstance(text, str) else bytes(text)
        with self._lock:
            self._texts[_key(path)] = data

    def close(self, path: str | Path) -> None:
        """Read the file ``path`` from the disk again."""
        with self._lock:
            self._texts.pop(_key(path), None)

    def text(self, path: str | Path) -> bytes | None:
        """The text held for ``path``, or None when the disk's is read."""
        return self._texts.get(_key(path))

    def buffer(self, path: str) -> bytes | None:
        """The text held for ``path`` (the overlay `fishbot_urdf.inputs.read_input` asks);
        inside `memo`, the fingerprint of what is given is taken now (a file on disk before
        it is read), so that a change while the answer is made makes the answer stale."""
        held = self._texts.get(_key(path)) if self._texts else None
        seen = _SEEN.get()
        if seen is not None and path not in seen:
            seen[path] = self.fingerprint(path) if held is None else _text_print(held)
        return held

    def held(self) -> tuple[str, ...]:
        """The files whose texts are held, as absolute paths."""
        with self._lock:
            return tuple(self._texts)

    def read(self, path: str | Path) -> bytes:
        """The content of ``path``: the text held for it, else the file on disk.

        Raises:
            InputError: There is no such file, or it cannot be read (see
                `fishbot_urdf.inputs.read_input`).
        """
        with self.reading():
            return read_input(path)

    @contextmanager
    def reading(self) -> Iterator[None]:
        """Inside the ``with`` (this thread and the work it hands to threads with its
        context), every input is read through this workspace: held texts first."""
        with reading_through(self):
            yield

    def fingerprint(self, path: str) -> Fingerprint:
        """What ``path`` is now (see `Fingerprint`)."""
        held = self._texts.get(_key(path))
        if held is not None:
            return _text_print(held)
        try:
            status = os.stat(path)
        except (OSError, ValueError):
            return None
        return (status.st_mtime_ns, status.st_ctime_ns, status.st_size, status.st_ino)

    # -- the answers ---------------------------------------------------------------------
    def memo(self, key: Hashable, make: Callable[[], T]) -> T:
        """The answer kept for ``key``, if nothing it was made from has changed since; else
        ``make()``, run reading through this workspace, kept with the fingerprints of every
        file it read or looked for. An error ``make`` raises is raised, and not kept."""
        with self._lock:
            known = self._answers.get(key)
            if known is not None:
                self._answers.move_to_end(key)
        if known is not None and all(self.fingerprint(p) == f for p, f in known.inputs):
            # An answer made from this one (a memo inside a memo) depends on its files too.
            for path, _ in known.inputs:
                note_looked(path)
            return known.value  # type: ignore[no-any-return]
        outer = _SEEN.get()
        seen: dict[str, Fingerprint] = {}
        token = _SEEN.set(seen)
        try:
            with self.reading(), recording_inputs() as read, looking_for() as looked:
                value = make()
        finally:
            _SEEN.reset(token)
            if outer is not None:
                outer.update((p, f) for p, f in seen.items() if p not in outer)
        with self._lock:
            self.made += 1
        if not self.keep:
            return value
        inputs = tuple(
            (p, seen[p] if p in seen else self.fingerprint(p))
            for p in dict.fromkeys((*read, *looked))
        )
        with self._lock:
            self._answers[key] = _Answer(value, inputs)
            self._answers.move_to_end(key)
            while len(self._answers) > self.keep:
                self._answers.popitem(last=False)
        return value

    def readers(self, paths: Iterable[str | Path]) -> list[Hashable]:
        """The keys of the answers made from any of ``paths`` (read, or looked for)."""
        wanted = {_key(p) for p in paths}
        with self._lock:
            answers = list(self._answers.items())
        return [key for key, answer in answers if any(_key(p) in wanted for p, _ in answer.inputs)]

    def forget(self, paths: Iterable[str | Path] | None = None) -> None:
        """Drop the answers made from any of ``paths``; for None, every answer and the
        packages found (for a change no fingerprint sees: a package added somewhere)."""
        if paths is None:
            with self._lock:
                self._answers.clear()
            self.packages = PackageFinder(self.packages.packages, self.packages.environ)
            return
        for key in self.readers(paths):
            with self._lock:
                self._answers.pop(key, None)


def _text_print(text: bytes) -> Fingerprint:
    return ("text", hash(text), len(text))


def _key(path: str | Path) -> str:
    return os.path.normpath(os.path.abspath(path))


def package_key(packages: Mapping[str, str | Path] | PackageFinder) -> Hashable:
    """How an answer's key names the packages it was made with: a finder by itself (its
    answers are its own), folders by their names and paths."""
    if isinstance(packages, PackageFinder):
        return ("finder", id(packages), tuple(sorted(map(str, packages.packages.items()))))
    return tuple(sorted(map(str, packages.items())))
