"""One editor session: its workspace (the open files' texts over the disk), the checks it
runs in a worker thread a moment after the last change, and the findings it has published."""

from __future__ import annotations

import asyncio
import logging
import os
from collections.abc import Callable, Collection, Iterable, Mapping
from concurrent.futures import ThreadPoolExecutor
from typing import TypeVar

from lsprotocol import types
from pygls.lsp.server import LanguageServer

from ..inputs import Cancellation, Cancelled, cancellable
from ..workspace import Workspace
from ._checking import Checked, Round, check_round, lines_reader, merged
from ._convert import Lines, Shown, Units, uri_of

__all__ = ["DEBOUNCE", "Session"]

DEBOUNCE = 0.075
"""Seconds from the last change to the check (a burst of keystrokes is checked once)."""

logger = logging.getLogger(__name__)

T = TypeVar("T")


class Session:
    """The state of one session, changed on the server's event loop only; the checks run in
    one worker thread, and a change cancels the check under way (its results, for texts
    that are no longer the editor's, are never published). The editor's texts are laid
    over the disk in the worker, before a round: never while a check reads them, so that
    what a check keeps is what it read.

    Args:
        server: The language server that publishes the findings.
        debounce: Seconds from the last change to the check.
    """

    def __init__(self, server: LanguageServer, debounce: float = DEBOUNCE) -> None:
        self.server = server
        self.debounce = debounce
        self.workspace = Workspace()
        self.versions: dict[str, int | None] = {}  # the open files, by absolute path
        self.unheard: set[str] = set()  # open files changed since their last publication
        self.tops_of: dict[str, tuple[str, ...]] = {}  # each open file's robots, last round
        self.checked: dict[str, Checked] = {}  # each robot's findings, by its top file
        self.shown: dict[str, list[Shown]] = {}  # what each file shows now
        self.generation = 0  # one more at each change: a round of an older one is stale
        self._timer: asyncio.TimerHandle | None = None
        self._cancellation: Cancellation | None = None
        self._tasks: set[asyncio.Future[None]] = set()
        self._worker = ThreadPoolExecutor(1, thread_name_prefix="fishbot-check")
        self._texts: dict[str, str | None] = {}  # to hold (None: to let go) before a round
        self._forget = False  # every answer and package found, before a round
        self._asked: set[Cancellation] = set()  # the questions under way, cancelled by a change

    # -- the editor's changes ------------------------------------------------------------
    def opened(self, path: str, text: str, version: int | None, *, robot: bool = True) -> None:
        """The editor holds ``text`` for ``path`` (opened, or changed): a robot file is
        checked; any other (a YAML file a robot loads) is read as held."""
        self._texts[path] = text
        if robot:
            self.versions[path] = version
        self.change([path])

    def closed(self, path: str) -> None:
        """The editor closed ``path``: the disk's text is read again."""
        self._texts[path] = None
        self.versions.pop(path, None)
        self.tops_of.pop(path, None)
        self.change([path])

    def disk_changed(self, paths: Iterable[str]) -> None:
        """Files changed on disk (saved, made, deleted by another program): the answers
        made from them are told by their fingerprints, but for a package made or taken
        away (a package.xml), which changes where every ``$(find)`` leads."""
        paths = list(paths)
        if any(os.path.basename(p) == "package.xml" for p in paths):
            self._forget = True
        self.change([*paths, *self.versions])

    def change(self, paths: Iterable[str]) -> None:
        """Check the robots of the open files a moment from now (those of ``paths`` are
        among them, or are no longer wanted), cancelling the check under way."""
        self.unheard.update(p for p in paths if p in self.versions)
        self.generation += 1
        self._cancel_questions()
        if self._cancellation is not None:
            self._cancellation.cancel()
        if self._timer is not None:
            self._timer.cancel()
        loop = asyncio.get_running_loop()
        self._timer = loop.call_later(self.debounce, self._start)

    def stop(self) -> None:
        """Cancel the work under way and let the worker go."""
        if self._timer is not None:
            self._timer.cancel()
        if self._cancellation is not None:
            self._cancellation.cancel()
        self._cancel_questions()
        self._worker.shutdown(wait=False, cancel_futures=True)

    def _cancel_questions(self) -> None:
        for cancellation in self._asked:
            cancellation.cancel()
        self._asked.clear()

    # -- the rounds ----------------------------------------------------------------------
    def _start(self) -> None:
        self._timer = None
        cancellation = self._cancellation = Cancellation()
        task = asyncio.ensure_future(self._run(self.generation, cancellation))
        self._tasks.add(task)  # (the loop holds tasks weakly)
        task.add_done_callback(self._tasks.discard)

    async def _run(self, generation: int, cancellation: Cancellation) -> None:
        texts, forget = self._texts, self._forget
        self._texts, self._forget = {}, False
        opened = tuple(self.versions)
        known = dict(self.checked)
        units = self.units()
        loop = asyncio.get_running_loop()
        try:
            found = await loop.run_in_executor(
                self._worker, self._work, texts, forget, opened, known, units, cancellation
            )
        except RuntimeError:  # the worker has stopped: the session is ending
            return
        if found is None or generation != self.generation:
            return  # cancelled, or a newer change came: a newer round will say
        self._publish(found)

    def _work(
        self,
        texts: Mapping[str, str | None],
        forget: bool,
        opened: Collection[str],
        known: Mapping[str, Checked],
        units: Units,
        cancellation: Cancellation,
    ) -> Round | None:
        self._lay(texts, forget)
        with cancellable(cancellation):
            try:
                return check_round(self.workspace, opened, known, units)
            except Cancelled:
                return None
            except Exception:  # a fault of the server's own: said, and the session goes on
                logger.exception("checking %s", ", ".join(sorted(opened)))
                return None

    def _lay(self, texts: Mapping[str, str | None], forget: bool) -> None:
        """Lay the editor's texts over the disk (None: let go of one), in the worker."""
        for path, text in texts.items():
            if text is None:
                self.workspace.close(path)
            else:
                self.workspace.open(path, text)
        if forget:
            self.workspace.forget(None)

    def _answer(
        self,
        texts: Mapping[str, str | None],
        forget: bool,
        question: Callable[[], T],
        cancellation: Cancellation,
    ) -> T | None:
        self._lay(texts, forget)
        with cancellable(cancellation):
            try:
                return question()
            except Cancelled:
                return None

    def _publish(self, found: Round) -> None:
        self.tops_of = dict(found.tops_of)
        # an open file hears of its robots' check, even of no findings, once a change
        affected = {path for path in self.unheard if path in found.tops_of}
        self.unheard -= affected
        for top, checked in found.checked.items():
            before = self.checked.get(top)
            if before is not checked:
                affected.update(before.shown if before is not None else (), checked.shown)
        for top in [t for t in self.checked if t not in found.checked]:
            affected.update(self.checked.pop(top).shown)
        self.checked.update(found.checked)
        for path in sorted(affected):
            shown = merged(c.shown[path] for c in self.checked.values() if path in c.shown)
            if shown:
                self.shown[path] = shown
            else:
                self.shown.pop(path, None)
            self.server.text_document_publish_diagnostics(
                types.PublishDiagnosticsParams(
                    uri=uri_of(path),
                    diagnostics=[s.diagnostic for s in shown],
                    version=self.versions.get(path),
                )
            )

    # -- what the requests ask -----------------------------------------------------------
    async def ask(self, question: Callable[[], T]) -> T | None:
        """The answer of ``question`` (which reads through the workspace), asked in the
        worker after the check under way, once the editor's latest texts are laid over the
        disk (the round to come finds them there); None when a change came first (the
        question is cancelled, as a check is) or the session has ended."""
        texts, forget = self._texts, self._forget
        self._texts, self._forget = {}, False
        cancellation = Cancellation()
        self._asked.add(cancellation)
        loop = asyncio.get_running_loop()
        try:
            return await loop.run_in_executor(
                self._worker, self._answer, texts, forget, question, cancellation
            )
        except RuntimeError:  # the worker has stopped: the session is ending
            return None
        finally:
            self._asked.discard(cancellation)

    def units(self) -> Units:
        """How the client counts the characters of a position."""
        return self.server.workspace.position_codec.client_num_units

    def lines(self, path: str) -> Lines:
        """The lines of ``path`` as the session reads it (the editor's text first)."""
        return lines_reader(self.workspace, self.units())(path)

    def findings_at(self, path: str, position: types.Position) -> list[Shown]:
        """The findings shown in ``path`` whose range holds ``position``."""
        return [s for s in self.shown.get(path, ()) if _holds(s.diagnostic.range, position)]

    def findings_in(self, path: str, where: types.Range) -> list[Shown]:
        """The findings shown in ``path`` whose range meets ``where``."""
        return [s for s in self.shown.get(path, ()) if _meets(s.diagnostic.range, where)]


def _key(position: types.Position) -> tuple[int, int]:
    return (position.line, position.character)


def _holds(where: types.Range, position: types.Position) -> bool:
    return _key(where.start) <= _key(position) <= _key(where.end)


def _meets(where: types.Range, other: types.Range) -> bool:
    return _key(where.start) <= _key(other.end) and _key(other.start) <= _key(where.end)
