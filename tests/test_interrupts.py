"""An untrusted expansion can never be walked with Python's eval, however it is stopped.

Each hostile file holds, in every element, an escape that only Python's ``eval`` takes:
the branch of a conditional that the allowlist interpreter never chooses (a lambda's
``repr`` differs between the two), which writes a canary file through a lambda's class's
subclasses. Expansions of it are interrupted at random points -- a library caller's
SIGALRM, an exception put into the caller's thread from another, SIGINT and SIGTERM to
the command -- and the canary is never written. A trusted expansion of the same file does
write it: the escape is real.
"""

from __future__ import annotations

import contextlib
import ctypes
import random
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from fishbot_urdf import FishbotUrdfError
from fishbot_urdf.expansion import expand
from fishbot_urdf.inputs import time_limit

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def _escape(canary: Path) -> str:
    """Writes ``canary`` when Python's eval runs it; the allowlist chooses the harmless
    branch. The names with two underscores sit inside a lambda, where xacro's own check of
    an expression's names does not look."""
    writes = (
        "(lambda: [c for c in ().__class__.__base__.__subclasses__() "
        "if c.__name__ == '_wrap_close'][0].__init__.__globals__['system']"
        f"('touch {canary}'))()"
    )
    return f"({writes}) if python.repr(lambda: 0) != '&lt;lambda&gt;' else 'safe'"


def _hostile(folder: Path, canary: Path, depth: int = 9) -> Path:
    """A robot of 2**depth macro calls, each element holding the escape."""
    escape = _escape(canary)
    text = (
        f'<robot name="r" {NS}>\n'
        '<xacro:macro name="m" params="n"><xacro:if value="${n > 0}">'
        '<xacro:m n="${n-1}"/><xacro:m n="${n-1}"/></xacro:if>'
        f'<link name="l_${{{escape}}}_${{python.len([x for x in python.range(200)])}}"/>'
        "</xacro:macro>\n"
        f'<xacro:m n="{depth}"/>\n'
        "</robot>\n"
    )
    robot = folder / "robot.xacro"
    robot.write_text(text)
    return robot


def _wait_for_walks() -> None:
    """Every expansion's walk ended (a cancelled one ends at its next step)."""
    for thread in threading.enumerate():
        if thread.name == "fishbot-xacro":
            _join(thread)
            assert not thread.is_alive(), "a cancelled expansion went on walking"


def _join(thread: threading.Thread) -> None:
    """Join a thread that may be listed before it has said it started (join refuses one
    until then: seen once in a full run, under load). One whose start an alarm broke off
    inside threading's own wait may never say so: after 30 s, it is taken as never run
    (it is not alive then)."""
    give_up = time.monotonic() + 30
    while True:
        try:
            thread.join(timeout=30)
            return
        except RuntimeError:
            if time.monotonic() > give_up:
                return
            time.sleep(0.001)


def _duration(robot: Path) -> float:
    """How long one expansion of ``robot`` takes (the median of five)."""
    times = []
    for _ in range(5):
        started = time.perf_counter()
        expand(robot)
        times.append(time.perf_counter() - started)
    return sorted(times)[2]


def test_the_escape_is_real_when_trusted(tmp_path: Path) -> None:
    canary = tmp_path / "trusted.canary"
    robot = _hostile(tmp_path, canary, depth=1)
    expand(robot, trust_expressions=True)
    assert canary.exists()


def test_an_untrusted_expansion_to_its_end_takes_the_safe_branch(tmp_path: Path) -> None:
    canary = tmp_path / "untrusted.canary"
    robot = _hostile(tmp_path, canary, depth=3)
    text = expand(robot).text
    assert "l_safe_200" in text
    assert not canary.exists()


class _Alarm(Exception):
    pass


def _raise_alarm(signum: int, frame: object) -> None:
    raise _Alarm


# An alarm or an exception put into a thread may also land in a weak reference's callback
# of Python's own, where Python drops it with a warning: that is not the expansion's doing.
@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
def test_a_callers_alarm_at_any_point_never_runs_the_escape(tmp_path: Path) -> None:
    canary = tmp_path / "alarm.canary"
    robot = _hostile(tmp_path, canary, depth=5)
    whole = _duration(robot)  # to spread the alarms over
    rng = random.Random(34)
    previous = signal.signal(signal.SIGALRM, _raise_alarm)
    stopped = 0
    try:
        for _ in range(1000):
            try:
                signal.setitimer(signal.ITIMER_REAL, rng.uniform(0.0, whole) or 1e-6)
                try:
                    expand(robot)
                finally:
                    signal.setitimer(signal.ITIMER_REAL, 0)
            except _Alarm:
                stopped += 1
            except RuntimeError as exc:
                # An alarm that lands inside threading's own Condition.wait (as the walk's
                # thread starts) can leave its lock released twice: Python's doing, and the
                # walk is stopped all the same.
                if str(exc) != "release unlocked lock":
                    raise
                stopped += 1
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    _wait_for_walks()
    assert stopped > 300  # many alarms came while the walk was going on
    assert not canary.exists()


class _Interrupted(Exception):
    pass


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
def test_an_exception_put_into_the_caller_by_another_thread_never_runs_the_escape(
    tmp_path: Path,
) -> None:
    canary = tmp_path / "async.canary"
    robot = _hostile(tmp_path, canary, depth=5)
    whole = _duration(robot)
    rng = random.Random(35)
    caller = threading.get_ident()
    inside = threading.Event()  # the caller is in expand()

    def interrupt(after: float) -> None:
        # Put in while the caller waits for the walk: Python's threading itself is not safe
        # from an exception put in anywhere (one landing while it holds a lock of its own
        # deadlocks the next thread started).
        time.sleep(after)
        frame = sys._current_frames().get(caller)
        if (
            inside.is_set()
            and frame is not None
            and frame.f_code.co_name == "_wait_for_tstate_lock"
        ):
            ctypes.pythonapi.PyThreadState_SetAsyncExc(
                ctypes.c_ulong(caller), ctypes.py_object(_Interrupted)
            )

    stopped = 0
    for _ in range(1000):
        other = threading.Thread(target=interrupt, args=(rng.uniform(0.0, whole),))
        other.start()
        try:
            inside.set()
            try:
                expand(robot)
            finally:
                inside.clear()
            while other.is_alive():  # one put in just as expand() returned lands here
                other.join(0.01)
        except _Interrupted:
            stopped += 1
        while other.is_alive():
            with contextlib.suppress(_Interrupted):
                other.join(0.01)
    _wait_for_walks()
    assert stopped > 300
    assert not canary.exists()


def test_a_thread_of_the_caller_running_out_of_time_never_runs_the_escape(
    tmp_path: Path,
) -> None:
    # A library caller's own time limit, as short as can be: the walk stops at a bound.
    canary = tmp_path / "deadline.canary"
    robot = _hostile(tmp_path, canary)
    rng = random.Random(36)
    stopped = 0
    for _ in range(300):
        with time_limit(rng.uniform(0.001, 0.05)):
            try:
                expand(robot)
            except FishbotUrdfError as exc:
                assert exc.rule == "limit"
                stopped += 1
    _wait_for_walks()
    assert stopped > 100
    assert not canary.exists()


@pytest.mark.parametrize("signal_name", ["SIGINT", "SIGTERM"])
def test_the_command_interrupted_at_any_point_never_runs_the_escape(
    signal_name: str, tmp_path: Path
) -> None:
    canary = tmp_path / f"{signal_name}.canary"
    robot = _hostile(tmp_path, canary, depth=11)
    rng = random.Random(signal_name)
    for _ in range(25):
        process = subprocess.Popen(
            [sys.executable, "-m", "fishbot_urdf", "expand", str(robot)],
            cwd=tmp_path,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )
        try:
            time.sleep(rng.uniform(0.1, 0.8))  # from start-up to well into the walk
            process.send_signal(getattr(signal, signal_name))
            _, said = process.communicate(timeout=20)
        finally:
            process.kill()
            process.wait()
        assert b"Traceback" not in said
    assert not canary.exists()


def test_a_trusted_and_an_untrusted_expansion_side_by_side(tmp_path: Path) -> None:
    trusted_canary = tmp_path / "t" / "trusted.canary"
    untrusted_canary = tmp_path / "u" / "untrusted.canary"
    trusted_canary.parent.mkdir()
    untrusted_canary.parent.mkdir()
    trusted = _hostile(trusted_canary.parent, trusted_canary, depth=6)
    untrusted = _hostile(untrusted_canary.parent, untrusted_canary, depth=6)
    texts: dict[str, str] = {}
    failures: list[BaseException] = []
    start = threading.Barrier(2)

    def run(name: str, robot: Path, trust: bool) -> None:
        try:
            start.wait()
            for _ in range(10):
                texts[name] = expand(robot, trust_expressions=trust).text
        except BaseException as exc:  # handed to the test's thread
            failures.append(exc)

    threads = [
        threading.Thread(target=run, args=("trusted", trusted, True)),
        threading.Thread(target=run, args=("untrusted", untrusted, False)),
    ]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not failures
    assert trusted_canary.exists()  # Python's eval ran the trusted file's code
    assert not untrusted_canary.exists()
    assert "l_safe_200" in texts["untrusted"]
    assert "l_0_200" in texts["trusted"]  # os.system's status, written out


def test_the_imported_xacro_is_never_changed_and_an_untrusted_copy_has_no_eval(
    tmp_path: Path,
) -> None:
    import xacro  # type: ignore[import-untyped]
    import xacro.substitution_args  # type: ignore[import-untyped]

    from fishbot_urdf.expansion._instance import EvaluatorRefused, load_xacro

    before = (xacro.safe_eval, xacro.substitution_args._eval, xacro._global_symbols)
    robot = _hostile(tmp_path, tmp_path / "never.canary", depth=2)
    expand(robot)
    expand(robot, trust_expressions=True)
    assert (xacro.safe_eval, xacro.substitution_args._eval, xacro._global_symbols) == before

    def nothing(*args: object) -> str:
        return ""

    own = load_xacro(trust=False, message=nothing, evaluate=nothing, substitution_eval=nothing)
    assert own.xacro.safe_eval is nothing and own.subst._eval is nothing
    names = vars(own.xacro)["__builtins__"]
    for name in ("eval", "exec", "compile"):
        with pytest.raises(EvaluatorRefused):
            names[name]("1")
    assert own.xacro is not xacro and own.subst is not xacro.substitution_args
