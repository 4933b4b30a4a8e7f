"""One budget for the whole document: each way to spend it stops within the limits.

Every case runs ``fishbot expand`` as a user would, with ``--timeout`` and ``--max-size``,
and is measured from outside: it must end within the time limit (plus 10%, plus the time
the same command takes on a small robot), its peak memory must stay within the size limit
(over what the command takes on a small robot), and it must say so in one ``limit`` line,
with exit status 2.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def _robot(body: str) -> str:
    return f'<robot name="r" {NS}>\n{body}\n</robot>\n'


def _run(robot: Path, *options: str) -> tuple[int, str, float, int]:
    """Exit status, standard error, wall time (s) and peak memory (KiB) of one expand."""
    started = time.monotonic()
    process = subprocess.Popen(
        [sys.executable, "-m", "fishbot_urdf", "expand", robot.name, *options],
        cwd=robot.parent,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    assert process.stderr is not None
    with process.stderr:
        said = process.stderr.read()
    _, status, usage = os.wait4(process.pid, 0)
    process.returncode = os.waitstatus_to_exitcode(status)
    elapsed = time.monotonic() - started
    return process.returncode, said.decode(), elapsed, usage.ru_maxrss


@pytest.fixture(scope="module")
def small(tmp_path_factory: pytest.TempPathFactory) -> tuple[float, int]:
    """What expand takes on a small robot: its wall time and peak memory (the most of 3)."""
    robot = tmp_path_factory.mktemp("small") / "robot.xacro"
    robot.write_text(_robot('<xacro:property name="w" value="0.1"/><link name="a_${w}"/>'))
    runs = [_run(robot) for _ in range(3)]
    assert all(status == 0 for status, *_ in runs)
    return max(r[2] for r in runs), max(r[3] for r in runs)


CASES = {
    # Functions that go through what they are given, in C, over and over.
    "callbacks": _robot(
        "".join(
            f'<link name="l{i}_${{python.sum(python.range(900000))}}'
            f'_${{python.any(python.map(python.abs, python.range(900000)))}}"/>'
            for i in range(200)
        )
    ),
    # Whole numbers of a million bits, each made anew.
    "integers": _robot('<link name="${python.len([2**999999 + i for i in python.range(9000)])}"/>'),
    # A hundred properties of nine million characters each.
    "properties": _robot(
        "".join(f'<xacro:property name="p{i}" value="${{\'x\' * 9000000}}"/>' for i in range(100))
        + "".join(f'<link name="${{p{i}[:1]}}{i}"/>' for i in range(100))
    ),
    # A format width taken from an argument.
    "format": _robot(
        '<xacro:property name="t" value="{0:>{1}}"/><link name="${t.format(\'x\', 10**9)}"/>'
    ),
    # Divisions of big numbers, each taking a quarter of a second.
    "division": _robot(
        "".join(
            f'<link name="l{i}_${{python.len(python.str((3**630000 + {i}) // 7**178000 % 10))}}"/>'
            for i in range(60)
        )
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_each_way_to_spend_the_budget_stops_within_the_limits(
    case: str, tmp_path: Path, small: tuple[float, int]
) -> None:
    start_up, baseline = small
    robot = tmp_path / "robot.xacro"
    robot.write_text(CASES[case])
    status, said, elapsed, peak = _run(robot, "--timeout", "2", "--max-size", "16")
    assert status == 2, said
    lines = said.splitlines()
    assert len(lines) == 1, said
    assert lines[0].startswith("robot.xacro:") and lines[0].endswith("[limit]")
    assert elapsed <= 2 * 1.1 + start_up, (elapsed, said)
    assert peak - baseline <= 16 * 1024, (peak, baseline, said)


def test_an_include_made_fifty_times_fifty_times_stops_within_the_limits(
    tmp_path: Path, small: tuple[float, int]
) -> None:
    start_up, baseline = small
    (tmp_path / "c.xacro").write_text(_robot(f"<link name='c'>{'x' * 200_000}</link>"))
    inner = "".join('<xacro:include filename="c.xacro"/>' for _ in range(50))
    (tmp_path / "b.xacro").write_text(_robot(inner))
    outer = "".join('<xacro:include filename="b.xacro"/>' for _ in range(50))
    robot = tmp_path / "robot.xacro"
    robot.write_text(_robot(outer))
    status, said, elapsed, peak = _run(robot, "--timeout", "2", "--max-size", "16")
    assert status == 2, said
    assert said.count("\n") == 1 and said.rstrip().endswith("[limit]"), said
    assert "the expansion would make more than 16.0 MiB in all, the size limit" in said
    assert elapsed <= 2 * 1.1 + start_up, (elapsed, said)
    assert peak - baseline <= 16 * 1024, (peak, baseline)


def test_the_budget_is_shared_by_every_expression(tmp_path: Path) -> None:
    # Each expression alone is well within the bounds of one; together they are not.
    from fishbot_urdf.expansion import ExpansionLimitError, expand
    from fishbot_urdf.inputs import size_limit

    robot = tmp_path / "robot.xacro"
    robot.write_text(_robot("".join(f"<link name=\"${{'x' * 1000000}}{i}\"/>" for i in range(20))))
    with size_limit(8 * 1024 * 1024), pytest.raises(ExpansionLimitError) as caught:
        expand(robot)
    assert caught.value.rule == "limit"
    assert caught.value.message.startswith("the expansion would make more than 8.0 MiB in all")
    with size_limit(64 * 1024 * 1024):
        assert expand(robot).text.count("x" * 1000000) == 20


def test_a_probes_calls_spend_the_expansions_budget(tmp_path: Path) -> None:
    # A macro that makes a million-character name is fine called once; a probe that calls
    # it twenty times spends the same budget as the document and is stopped with it.
    from fishbot_urdf.expansion import ExpansionLimitError, probe_macros
    from fishbot_urdf.inputs import size_limit

    robot = tmp_path / "robot.xacro"
    robot.write_text(
        _robot(
            '<xacro:macro name="big" params="i"><link name="${\'x\' * 1000000}${i}"/>'
            '</xacro:macro><xacro:big i="0"/>'
        )
    )

    def probe(table: Any) -> list[str | None]:
        return [table.call("big", {"i": str(i)}) for i in range(1, 20)]

    with size_limit(8 * 1024 * 1024), pytest.raises(ExpansionLimitError) as caught:
        probe_macros(robot, probe)
    assert caught.value.message.startswith("the expansion would make more than 8.0 MiB in all")
    with size_limit(64 * 1024 * 1024):
        made = probe_macros(robot, probe)
    assert all(text is not None and "x" * 1000000 in text for text in made)
