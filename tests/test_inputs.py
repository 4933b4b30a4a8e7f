"""Reading the files a robot names: regular files only, within a size limit."""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest

from fishbot_urdf.errors import ArgumentError, InputError
from fishbot_urdf.inputs import (
    DEFAULT_MAX_BYTES,
    InputTooLargeError,
    max_bytes,
    note_inputs,
    read_input,
    recording_inputs,
    size_limit,
)


def test_a_regular_file_is_read_whole(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_bytes(b"<robot/>" * 1000)
    assert read_input(path) == b"<robot/>" * 1000


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="this system has no FIFOs")
def test_a_fifo_is_refused_at_once_not_waited_on(tmp_path: Path) -> None:
    fifo = tmp_path / "pipe.urdf"
    os.mkfifo(fifo)
    with pytest.raises(InputError) as caught:
        read_input(fifo)  # nothing writes to it: a blocking read would never return
    assert caught.value.message == "is a FIFO (named pipe), not a regular file"
    assert caught.value.path == str(fifo)


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="this system has no /dev/zero")
def test_a_device_is_refused_not_read_without_end() -> None:
    with pytest.raises(InputError) as caught:
        read_input("/dev/zero")
    assert caught.value.message == "is a device, not a regular file"


def test_a_folder_and_a_missing_file_are_named(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="is a directory, not a file"):
        read_input(tmp_path)
    with pytest.raises(InputError, match="no such file"):
        read_input(tmp_path / "missing.urdf")


def test_a_file_over_the_limit_is_refused_with_its_size_and_the_limit(tmp_path: Path) -> None:
    path = tmp_path / "big.urdf"
    path.write_bytes(b" " * 3000)
    with size_limit(2048), pytest.raises(InputTooLargeError) as caught:
        read_input(path)
    assert (caught.value.size, caught.value.limit) == (3000, 2048)
    assert caught.value.message == "is 3,000 bytes, more than the limit of 2,048 bytes"
    assert caught.value.rule == "io"
    with size_limit(3000):
        assert len(read_input(path)) == 3000


def test_the_files_read_are_recorded_in_the_context_that_reads_them(tmp_path: Path) -> None:
    first, second, missing = tmp_path / "a.urdf", tmp_path / "b.yaml", tmp_path / "no.urdf"
    first.write_bytes(b"<robot/>")
    second.write_bytes(b"mass: 1\n")
    elsewhere: list[list[str]] = []

    def in_another_thread() -> None:
        with recording_inputs() as other:
            read_input(second)
        elsewhere.append(other)

    read_input(first)  # outside a recording: nothing noted, nothing kept
    with recording_inputs() as outer:
        read_input(first)
        with recording_inputs() as inner:
            read_input(second)
            with pytest.raises(InputError):
                read_input(missing)  # not read: no input
            note_inputs(["kept.xml"])
            thread = threading.Thread(target=in_another_thread)
            thread.start()
            thread.join()
        assert inner == [str(second), "kept.xml"]
    assert outer == [str(first), str(second), "kept.xml"]  # the inner one's too
    assert elsewhere == [[str(second)]]  # another thread's recording is its own


def test_the_limit_belongs_to_the_context_not_the_process() -> None:
    seen: list[int] = []
    with size_limit(10):
        thread = threading.Thread(target=lambda: seen.append(max_bytes()))
        thread.start()
        thread.join()
        assert max_bytes() == 10
    assert seen == [DEFAULT_MAX_BYTES]
    assert max_bytes() == DEFAULT_MAX_BYTES


def test_a_limit_must_be_positive() -> None:
    with pytest.raises(ArgumentError), size_limit(0):
        pass


def test_every_command_refuses_a_file_over_max_size_and_says_how_to_raise_it(
    tmp_path: Path,
) -> None:
    from click.testing import CliRunner

    from fishbot_urdf.cli import cli

    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>' + " " * 2000)
    size = robot.stat().st_size
    line = (
        f"{robot}: error: is {size:,} bytes, more than the limit of 1,048 bytes "
        "(raise the limit with --max-size MIB) [io]\n"
    )
    for command in (["check"], ["graph", "-o", "-"], ["expand"], ["inertia"]):
        result = CliRunner().invoke(cli, [*command, str(robot), "--max-size", "0.001"])
        assert result.exit_code == 2, command
        assert line in result.stderr, command
        assert "Traceback" not in result.output
        roomy = CliRunner().invoke(cli, [*command, str(robot), "--max-size", "1"])
        assert "more than the limit" not in roomy.stderr, command


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="this system has no FIFOs")
def test_every_command_says_a_fifo_is_a_fifo(tmp_path: Path) -> None:
    from click.testing import CliRunner

    from fishbot_urdf.cli import cli

    for name in ("r.urdf", "r.urdf.xacro"):
        fifo = tmp_path / name
        os.mkfifo(fifo)
        for command in (["check"], ["graph", "-o", "-"], ["expand"], ["inertia"]):
            result = CliRunner().invoke(cli, [*command, str(fifo)])
            assert result.exit_code == 2, (name, command)
            assert result.stderr == (
                f"{fifo}: error: is a FIFO (named pipe), not a regular file [io]\n"
            ), (name, command)


@pytest.mark.parametrize(
    "command",
    [
        ["check"],
        ["check", "-"],
        ["expand"],
        ["graph", "-o", "-"],
        ["inertia"],
        ["render", "-o", "-", "--size", "32x32"],
        ["tf", "a", "a"],
    ],
)
def test_limits_beyond_any_need_are_no_limits_not_a_crash(
    tmp_path: Path, command: list[str]
) -> None:
    from click.testing import CliRunner

    from fishbot_urdf.cli import cli

    robot = tmp_path / "r.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><visual><geometry><box size="1 1 1"/></geometry>'
        '</visual><inertial><mass value="1"/>'
        '<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'
        "</link></robot>"
    )
    where = [] if command[1:2] == ["-"] else [str(robot)]  # "-": standard input
    for limits in (["--max-size", "1e308"], ["--max-size", "1e13"], ["--timeout", "1e300"]):
        result = CliRunner().invoke(
            cli, [*command[:1], *where, *command[1:], *limits], input=robot.read_bytes()
        )
        assert result.exit_code == 0, (limits, result.output, result.exception)


def test_standard_input_is_read_in_parts_whatever_the_limit() -> None:
    # Read at once, a limit of 1e12 MiB asked the memory for that many bytes.
    import subprocess
    import sys

    robot = b'<robot name="r"><link name="a"/></robot>'
    done = subprocess.run(
        [sys.executable, "-m", "fishbot_urdf", "check", "-", "--max-size", "1e12"],
        input=robot,
        capture_output=True,
        check=False,
    )
    assert (done.returncode, done.stderr) == (0, b"")
    assert done.stdout.startswith(b"robot name is: r\n")


def test_standard_input_is_read_within_the_limit_too() -> None:
    from click.testing import CliRunner

    from fishbot_urdf.cli import cli

    robot = '<robot name="r"><link name="a"/></robot>' + " " * 2000
    result = CliRunner().invoke(cli, ["check", "-", "--max-size", "0.001"], input=robot)
    assert result.exit_code == 2
    assert result.stderr == (
        "<stdin>: error: is more than the limit of 1,048 bytes "
        "(raise the limit with --max-size MIB) [io]\n"
    )


def test_one_deadline_holds_for_the_whole_with_and_reports_the_work() -> None:
    import time

    from fishbot_urdf.inputs import TimeLimitError, deadline, time_limit

    with time_limit(0.05):
        first = deadline()
        time.sleep(0.06)
        second = deadline()
        assert first.end == second.end  # one deadline, not one per piece of work
        with pytest.raises(TimeLimitError) as caught:
            second.check("reading the robot")
    assert caught.value.rule == "limit"
    assert caught.value.message == "reading the robot takes longer than the time limit of 0.05 s"
    assert not deadline().passed()  # outside, each piece of work gets its own


def test_reading_a_robot_stops_at_the_deadline(tmp_path: Path) -> None:
    from click.testing import CliRunner

    import fishbot_urdf
    from fishbot_urdf.cli import cli
    from fishbot_urdf.inputs import TimeLimitError, time_limit

    links = "".join(f'<link name="l{i}"/>' for i in range(5000))
    robot = tmp_path / "many.urdf"
    robot.write_text(f'<robot name="r">{links}</robot>')
    with time_limit(1e-9), pytest.raises(TimeLimitError) as caught:
        fishbot_urdf.check_file(robot)
    assert caught.value.what == "reading the robot"
    result = CliRunner().invoke(cli, ["check", str(robot), "--timeout", "0.000000001"])
    assert result.exit_code == 2
    assert result.stderr.endswith(
        "reading the robot takes longer than the time limit of 1e-09 s "
        "(allow it longer with --timeout SECONDS) [limit]\n"
    )
    assert result.stderr.count("\n") == 1
