"""What one expansion may spend, counted across all it does: one budget per document.

Every expression, include, YAML file and macro call of one expansion draws on the same
:class:`Budget`:

- **steps**: nodes an expression walks, items a function goes through, and the work of one
  operation on big numbers by its size (a step is about a microsecond of work);
- **bytes made**: the values expressions make (strings by their characters, containers by
  their items, whole numbers by their bits), the text of the files read, and the elements
  parsed or cloned by macro calls, at what each takes in memory;
- **wall time**: the deadline of :mod:`fishbot_urdf.inputs`, looked at every
  :data:`CHECK_EVERY` steps and before any one operation that would take longer than the
  time left.

Sizes are charged before the value is made wherever they can be known first. A budget that
has run out stays out: every later charge raises again, so code that catches an error and
goes on (xacro does, in places) is stopped at its next charge. :meth:`Budget.cancel` ends
the walk from another thread: the caller of an expansion that is interrupted cancels it,
and the walk stops at its next step with :class:`Cancelled`, which no ``except Exception``
catches.
"""

from __future__ import annotations

from typing import Any

from ..errors import LimitError
from ..inputs import Cancelled, Deadline, TimeLimitError, deadline, max_bytes

__all__ = [
    "CHECK_EVERY",
    "ELEMENT_BYTES",
    "MAX_DOCUMENT_STEPS",
    "STEP_SECONDS",
    "Budget",
    "Cancelled",
    "size_of",
]

MAX_DOCUMENT_STEPS = 50_000_000
"""The most steps one expansion's expressions may take in all (about a minute of work)."""
CHECK_EVERY = 1024
"""How many steps go by between two looks at the deadline."""
STEP_SECONDS = 1e-6
"""About how long one step takes: what an operation charged ``n`` steps is expected to take
is ``n`` times this, and one that would pass the deadline is not begun."""
ELEMENT_BYTES = 640
"""What one parsed or cloned XML element takes in memory, with its attributes and where it
was written (measured: about 680 bytes for a URDF element in Python's DOM)."""


class Budget:
    """The steps, bytes and time left to one expansion (see the module's docstring).

    Attributes:
        deadline: When the expansion must stop.
        steps: Steps taken so far.
        made: Bytes made so far.
        max_made: The most bytes the expansion may make: the size limit in force.
    """

    __slots__ = ("_cancelled", "_next_look", "_spent", "deadline", "made", "max_made", "steps")

    def __init__(self, until: Deadline | None = None, max_made: int | None = None) -> None:
        self.deadline = until or deadline()
        self.max_made = max_bytes() if max_made is None else max_made
        self.steps = 0
        self.made = 0
        self._next_look = CHECK_EVERY
        self._spent: LimitError | None = None  # what ran out first; raised again each time
        self._cancelled = False  # set from the caller's thread, read by the walk's

    # -- steps and time ------------------------------------------------------------------
    def tick(self, count: int = 1) -> None:
        """Take ``count`` steps; look at the deadline every :data:`CHECK_EVERY` steps."""
        self.steps += count
        if self.steps >= self._next_look:
            self._look()

    def afford(self, count: int, what: str) -> None:
        """Take ``count`` steps for one operation that cannot be stopped once begun (``what``
        names it): refused first if its time would pass the deadline."""
        if count * STEP_SECONDS > self.deadline.left():
            self._spend_out(_timed_out(self.deadline, what))
        self.tick(count)

    def check(self) -> None:
        """Look at the deadline and at a cancellation now."""
        self._look()

    def _look(self) -> None:
        self._next_look = self.steps + CHECK_EVERY
        if self._cancelled:
            raise Cancelled
        if self._spent is not None:
            raise self._spent
        if self.steps > MAX_DOCUMENT_STEPS:
            self._spend_out(
                LimitError(
                    f"the expansion's expressions take more than {MAX_DOCUMENT_STEPS:,} steps "
                    "in all"
                )
            )
        if self.deadline.passed():
            self._spend_out(_timed_out(self.deadline, "the expansion"))

    # -- bytes -----------------------------------------------------------------------------
    def spend(self, size: int, what: str = "values") -> None:
        """Charge ``size`` bytes made (before they are made, where that can be known)."""
        self.made += size
        if self.made > self.max_made:
            self._spend_out(
                LimitError(
                    f"the expansion would make more than {_mebibytes(self.max_made)} in all, "
                    f"the size limit (reached making {what})"
                )
            )
        if size >= 1 << 16:  # a big value: the time it took is looked at too
            self._look()

    def _spend_out(self, error: LimitError) -> None:
        if self._spent is None:
            self._spent = error
        raise self._spent

    # -- from another thread --------------------------------------------------------------
    def cancel(self) -> None:
        """Stop the expansion at its next step (callable from any thread)."""
        self._cancelled = True
        self._next_look = 0

    @property
    def cancelled(self) -> bool:
        """Whether :meth:`cancel` was called."""
        return self._cancelled


def size_of(value: Any) -> int:
    """About how many bytes ``value`` takes, itself and not what it holds: a string by its
    characters, a container by its slots, a whole number by its bits."""
    if isinstance(value, str | bytes | bytearray):
        return len(value) + 48
    if isinstance(value, bool) or value is None:
        return 0
    if isinstance(value, int):
        return value.bit_length() // 8 + 28
    if isinstance(value, list | tuple):
        return 8 * len(value) + 56
    if isinstance(value, dict | set | frozenset):
        return 48 * len(value) + 64
    return 32


def _timed_out(until: Deadline, what: str) -> LimitError:
    return TimeLimitError(what, until.seconds)


def _mebibytes(size: int) -> str:
    if size < 1 << 20:
        return f"{size:,} bytes"
    return f"{size / (1 << 20):,.1f} MiB"
