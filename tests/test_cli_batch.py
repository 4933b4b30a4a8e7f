"""`fishbot check` over many files: the same output and exit status in one process or in
several, in the order the files were given."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import DATA, FISHBOT

from fishbot_urdf.cli import _batch
from fishbot_urdf.config import Config
from fishbot_urdf.lint import check_file
from fishbot_urdf.packages import PackageFinder

# Valid and faulty robots, a xacro file, one that is no XML and one that is not there.
FILES = [
    *sorted(str(p) for p in (DATA / "invalid").glob("*.urdf")),
    str(FISHBOT / "urdf" / "first_robot.urdf"),
    str(FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"),
    str(DATA / "no_such_robot.urdf"),
]

linux_only = pytest.mark.skipif(sys.platform != "linux", reason="forked processes: Linux only")


def _check(*args: str) -> tuple[int, bytes, bytes]:
    done = subprocess.run(
        [sys.executable, "-m", "fishbot_urdf", "check", *args], capture_output=True, check=False
    )
    return done.returncode, done.stdout, done.stderr


@linux_only
@pytest.mark.parametrize(
    "options",
    [
        ("--format", "text"),
        ("--format", "json"),
        ("--format", "sarif"),
        ("--format", "github"),
        ("--quiet", "--strict"),
        ("--max-size", "0.001"),  # the limit holds in every process
    ],
)
def test_several_processes_print_what_one_prints(options: tuple[str, ...]) -> None:
    one = _check(*options, "--jobs", "1", *FILES)
    assert one[0] == 2  # the missing file
    assert _check(*options, "--jobs", "3", *FILES) == one


@linux_only
def test_files_are_checked_elsewhere_and_come_back_in_order(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # A file bigger than this is checked here, its tree streamed from the check itself.
    monkeypatch.setattr(_batch, "_LARGEST", 1000)
    run = _batch.Run({}, PackageFinder(), "text", skip_includes=False, meshes=False, tree=True)
    configs = [Config()] * len(FILES)
    assert _batch._can_fork()
    shared = list(_batch.outcomes(FILES, configs, run, 2))
    alone = [_batch.outcome(name, Config(), run) for name in FILES]
    assert any(o.tree is not None for o in shared)  # checked elsewhere
    assert any(o.result is not None for o in shared)  # checked here, in its turn
    assert [o.findings for o in shared] == [o.findings for o in alone]
    assert [o.status for o in shared] == [o.status for o in alone]
    for name, there, here in zip(FILES, shared, alone, strict=True):
        small = Path(name).is_file() and Path(name).stat().st_size <= 1000
        if small and here.result is not None:  # checked by another process: its tree as text
            assert there.result is None
            assert there.tree == "".join(_batch.tree_chunks(here.result))
        else:
            assert there.tree is None
            assert (there.result is None) == (here.result is None)


def test_few_files_are_checked_here() -> None:
    run = _batch.Run({}, PackageFinder(), "text", skip_includes=False, meshes=False, tree=True)
    names = FILES[: _batch.SHARED_FROM - 1]
    found = list(_batch.outcomes(names, [Config()] * len(names), run, 4))
    assert all(o.tree is None for o in found)
    assert [o.result is not None for o in found] == [
        _batch.outcome(name, Config(), run).result is not None for name in names
    ]


@linux_only
def test_a_process_that_dies_leaves_its_files_to_the_main_one(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    def die(name: str, config: Config, run: _batch.Run) -> _batch.Outcome | None:
        os._exit(1)

    monkeypatch.setattr(_batch, "_away", die)
    run = _batch.Run({}, PackageFinder(), "json", skip_includes=False, meshes=False, tree=False)
    configs = [Config()] * len(FILES)
    assert list(_batch.outcomes(FILES, configs, run, 2)) == [
        _batch.outcome(name, Config(), run) for name in FILES
    ]


@linux_only
def test_no_process_to_be_had_checks_the_files_here(monkeypatch: pytest.MonkeyPatch) -> None:
    real_fork, forked = os.fork, []

    def fork_once() -> int:
        if forked:
            raise BlockingIOError(11, "Resource temporarily unavailable")
        forked.append(real_fork())
        return forked[-1]

    monkeypatch.setattr(os, "fork", fork_once)
    run = _batch.Run({}, PackageFinder(), "json", False, False, False)
    configs = [Config()] * len(FILES)
    assert list(_batch.outcomes(FILES, configs, run, 2)) == [
        _batch.outcome(name, Config(), run) for name in FILES
    ]
    assert forked and forked[0] > 0
    with pytest.raises(ChildProcessError):  # the one made was stopped and reaped
        os.waitpid(forked[0], 0)


def test_findings_pickle_with_their_facts() -> None:
    readable = [name for name in FILES[:-3] if not name.endswith("xml_syntax.urdf")]
    findings = [d for name in readable for d in check_file(name).diagnostics]
    assert any(d.data for d in findings)
    copies = pickle.loads(pickle.dumps(findings))
    assert copies == findings
    assert [dict(d.data) for d in copies] == [dict(d.data) for d in findings]
    assert all(type(c.data) is type(d.data) for c, d in zip(copies, findings, strict=True))
    # A finding made in a worker process keeps its rule: the same object as here.
    assert any(d.definition is not None for d in findings)
    assert all(c.definition is d.definition for c, d in zip(copies, findings, strict=True))
    assert [c.follows for c in copies] == [d.follows for d in findings]


def _slow_check(monkeypatch: pytest.MonkeyPatch, seconds: float) -> None:
    """Every file's check takes ``seconds`` more, and then asks the deadline in force."""
    import importlib
    import time

    from fishbot_urdf.inputs import deadline

    checking = importlib.import_module("fishbot_urdf.lint")
    commands = importlib.import_module("fishbot_urdf.cli._checking")  # where the CLI calls it

    real = checking.check_file

    def slow(*args: object, **options: object) -> object:
        time.sleep(seconds)
        deadline().check("checking")
        return real(*args, **options)  # type: ignore[arg-type]

    monkeypatch.setattr(checking, "check_file", slow)
    monkeypatch.setattr(commands, "check_file", slow)


def test_each_file_has_the_whole_time_limit(monkeypatch: pytest.MonkeyPatch) -> None:
    from click.testing import CliRunner

    from fishbot_urdf.cli import cli

    _slow_check(monkeypatch, 0.6)
    first = str(FISHBOT / "urdf" / "first_robot.urdf")
    # Two files of 0.6 s each, 1.2 s in all: within a 1-second limit each.
    result = CliRunner().invoke(cli, ["check", "-q", "--timeout", "1", first, first])
    assert (result.exit_code, result.stdout, result.stderr) == (0, "", "")
    # One file that takes longer than the limit is stopped, and the next is checked.
    _slow_check(monkeypatch, 0.6)  # (now 1.2 s a file)
    result = CliRunner().invoke(cli, ["check", "-q", "--timeout", "1", first])
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr == (
        f"{first}: error: checking takes longer than the time limit of 1 s (allow it longer "
        "with --timeout SECONDS) [limit]\n"
    )


@linux_only
def test_each_file_has_the_whole_time_limit_in_every_process(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from click.testing import CliRunner

    from fishbot_urdf.cli import cli

    _slow_check(monkeypatch, 0.3)
    first = str(FISHBOT / "urdf" / "first_robot.urdf")
    files = [first] * _batch.SHARED_FROM  # 4 files of 0.3 s in each of 2 processes
    result = CliRunner().invoke(cli, ["check", "-q", "--jobs", "2", "--timeout", "0.5", *files])
    assert (result.exit_code, result.stdout, result.stderr) == (0, "", "")
