"""The `fishbot` command: exit codes and exact output, through click's CliRunner."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import IO

import pytest
from click.testing import CliRunner
from conftest import DATA, FISHBOT, GoldenInput, check_urdf

import fishbot_urdf
from fishbot_urdf.cli import cli

FIRST = FISHBOT / "urdf" / "first_robot.urdf"
FIRST_TREE = (
    "robot name is: first_robot\n"
    "---------- Successfully Parsed XML ---------------\n"
    "root Link: base_link has 1 child(ren)\n"
    "    child(1):  imu_link\n"
)


def run(*args: str, stdin: bytes | None = None) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, list(args), input=stdin)
    return result.exit_code, result.stdout, result.stderr


def test_check_first_robot() -> None:
    assert run("check", str(FIRST)) == (0, FIRST_TREE, "")


def test_check_reads_stdin() -> None:
    assert run("check", "-", stdin=FIRST.read_bytes()) == (0, FIRST_TREE, "")


UNUSED_ARG = (
    f"{FIRST}: warning: argument 'use_sim' is given, but a URDF file takes no arguments "
    "(name:=value is for a .xacro file: it was not used) [xacro-unknown-arg]\n"
)


@pytest.mark.parametrize(
    "command",
    [
        ["check", "-q", "FILE", "use_sim:=true"],
        ["graph", "FILE", "use_sim:=true", "-o", "-"],
        ["inertia", "FILE", "use_sim:=true"],
        ["tf", "FILE", "base_link", "imu_link", "use_sim:=true"],
        ["render", "FILE", "use_sim:=true", "-o", "robot.png"],
    ],
    ids=lambda c: c[0],
)
def test_an_argument_given_with_a_urdf_file_is_a_warning_that_it_was_not_used(
    command: list[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(cli, [str(FIRST) if a == "FILE" else a for a in command])
    assert (result.exit_code, result.stderr) == (0, UNUSED_ARG)


def test_arguments_go_to_the_xacro_files_checked_with_a_urdf_file() -> None:
    xacro = FISHBOT / "urdf" / "first_robot.urdf.xacro"
    status, _, err = run("check", "-q", str(FIRST), str(xacro), "use_sim:=true")
    assert (status, err) == (
        0,
        f"{xacro}: warning: argument 'use_sim' is given, but no <xacro:arg> declares it and "
        "nothing reads it (the files declare no arguments) [xacro-unknown-arg]\n",
    )
    piped = run("check", "-q", "-", "use_sim:=true", stdin=FIRST.read_bytes())
    assert piped == (0, "", UNUSED_ARG.replace(str(FIRST), "<stdin>"))
    assert run("check", "-q", "--strict", str(FIRST), "use_sim:=true") == (1, "", UNUSED_ARG)


def test_a_xacro_substitution_left_in_a_urdf_says_to_expand_its_source(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"/><link name="b"/>\n'
        '<joint name="j" type="$(arg joint_type)"><parent link="a"/><child link="b"/>\n'
        '<origin xyz="0 ${wheel_y} 0"/></joint></robot>\n',
        encoding="utf-8",
    )
    expand = (
        "(this is a xacro substitution left unexpanded: run xacro or `fishbot expand` on the "
        ".xacro file it came from, or give that file instead)"
    )
    assert run("check", "-q", str(robot)) == (
        1,
        "",
        f"{robot}:2:17: error: joint 'j': type '$(arg joint_type)' is not a URDF joint type "
        f"{expand} [joint-type]\n"
        f"{robot}:3:9: error: joint 'j': <origin xyz=\"0 ${{wheel_y}} 0\">: '${{wheel_y}}' is "
        f"not a number {expand} [bad-number]\n",
    )


FISHBOT_LINKS = ["back_caster_link", "base_footprint", "base_link", "camera_link"]
FISHBOT_LINKS += ["front_caster_link", "imu_link", "laser_cylinder_link", "laser_link"]
FISHBOT_LINKS += ["left_wheel_link", "right_wheel_link"]


def test_an_undefined_link_lists_the_links_like_it_first_and_counts_the_others(
    tmp_path: Path,
) -> None:
    # A child named without its ROS suffix: the link is offered, and the links like it come
    # first in the listing (alphabetically, the wheels would be cut off).
    robot = tmp_path / "fishbot.urdf"
    links = "".join(f'<link name="{name}"/>' for name in FISHBOT_LINKS)
    joints = '<joint name="left_wheel_joint" type="continuous"><parent link="base_link"/>'
    joints += '<child link="left_wheel"/></joint>'
    joints += '<joint name="imu_joint" type="fixed"><parent link="base_link"/>'
    joints += '<child link="imu"/></joint>'
    robot.write_text(f'<robot name="fishbot">\n{links}\n{joints}\n</robot>\n')
    status, out, err = run("check", "-q", "--select", "undefined-link", str(robot))
    assert (status, out) == (1, "")
    assert err == (
        f"{robot}:3:76: error: joint 'left_wheel_joint': child link 'left_wheel' is not "
        "defined (did you mean 'left_wheel_link'? links: left_wheel_link, right_wheel_link, "
        "back_caster_link, base_footprint, base_link, camera_link, front_caster_link, "
        "imu_link, ... (2 more)) [undefined-link]\n"
        f"{robot}:3:173: error: joint 'imu_joint': child link 'imu' is not defined (did you "
        "mean 'imu_link'? links: imu_link, back_caster_link, base_footprint, base_link, "
        "camera_link, front_caster_link, laser_cylinder_link, laser_link, ... (2 more)) "
        "[undefined-link]\n"
    )


def test_a_property_that_shares_only_a_word_with_the_misspelt_one_is_not_offered(
    tmp_path: Path,
) -> None:
    robot = tmp_path / "wheel.urdf.xacro"
    robot.write_text(
        '<robot name="w" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<xacro:property name="wheel_name" value="left"/>\n'
        '<xacro:property name="wheel_length" value="0.04"/>\n'
        '<link name="${wheel_name}_wheel_link"><visual><geometry>\n'
        '<cylinder radius="${wheel_radius}" length="${wheel_length}"/>\n'
        "</geometry></visual></link></robot>\n"
    )
    status, _, err = run("expand", str(robot))
    assert (status, err) == (
        1,
        f"{robot}:5:1: error: 'wheel_radius' is not defined in ${{wheel_radius}} (defined "
        "properties: wheel_length, wheel_name) [xacro-undefined]\n",
    )
    # A misspelling of a property defined is offered.
    robot.write_text(robot.read_text().replace("${wheel_radius}", "${wheel_lenght}"))
    status, _, err = run("expand", str(robot))
    assert (status, err) == (
        1,
        f"{robot}:5:1: error: 'wheel_lenght' is not defined in ${{wheel_lenght}} (did you "
        "mean 'wheel_length'?) [xacro-undefined]\n",
    )


def test_findings_go_to_stderr_and_exit_1() -> None:
    path = DATA / "invalid" / "undefined_parent.urdf"
    status, out, err = run("check", str(path))
    assert status == 1
    assert out == ""
    assert err == (
        f"{path}:6:5: error: joint 'left_wheel_joint': parent link 'base' is not defined "
        "(did you mean 'base_link'? links: base_link, left_wheel_link) [undefined-link]\n"
    )


def test_a_thousand_findings_are_written_whole_and_in_order(tmp_path: Path) -> None:
    # More findings than are written at once: every line, once, in the library's order.
    links = "".join(f'<link name="l{i}"><visual/></link>' for i in range(1201))
    robot = tmp_path / "many.urdf"
    robot.write_text(f'<robot name="r">{links}</robot>')
    status, _, err = run("check", str(robot))
    expected = fishbot_urdf.check_file(robot).diagnostics
    assert len(expected) > 1201
    assert status == (1 if any(d.is_error for d in expected) else 0)
    assert err == "".join(f"{d.format()}\n" for d in expected)


def test_warnings_pass_unless_strict() -> None:
    path = str(DATA / "invalid" / "collision_material.urdf")
    status, out, err = run("check", path)
    assert status == 0
    assert out.startswith("robot name is: classic_mistake\n")
    assert err.count("warning:") == 1
    status, strict_out, err = run("check", "--strict", path)
    # The tree is check_urdf's output all the same; the status says the robot fails.
    assert (status, strict_out) == (1, out)
    assert err.count("warning:") == 1


def test_missing_file_is_exit_2() -> None:
    assert run("check", "does/not/exist.urdf") == (
        2,
        "",
        "does/not/exist.urdf: error: no such file [io]\n",
    )


def test_a_folder_is_exit_2(tmp_path: Path) -> None:
    assert run("check", str(tmp_path)) == (
        2,
        "",
        f"{tmp_path}: error: is a directory, not a file [io]\n",
    )


def test_bad_option_is_exit_2() -> None:
    status, _, err = run("check", "--colour", str(FIRST))
    assert status == 2
    assert "Error: No such option '--colour'" in err
    assert err.startswith("Usage: fishbot check ")


def test_no_file_is_exit_2() -> None:
    status, _, err = run("check")
    assert status == 2
    assert "Missing argument 'FILE...'" in err


def test_check_a_xacro_file_points_at_the_xacro_source(tmp_path: Path) -> None:
    ns = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    (tmp_path / "wheel.xacro").write_text(
        f"""<robot {ns}>
  <xacro:macro name="wheel" params="side">
    <link name="${{side}}_wheel"/>
    <joint name="${{side}}_joint" type="continuous">
      <parent link="base"/>
      <child link="${{side}}_wheel"/>
    </joint>
  </xacro:macro>
</robot>
"""
    )
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(
        f"""<robot name="r" {ns}>
  <xacro:include filename="wheel.xacro"/>
  <link name="base_link"/>
  <xacro:wheel side="left"/>
</robot>
"""
    )
    status, out, err = run("check", str(path))
    assert (status, out) == (1, "")
    wheel = os.path.relpath(tmp_path / "wheel.xacro")
    shown = wheel if not wheel.startswith("..") else str(tmp_path / "wheel.xacro")
    assert err == (
        f"{shown}:5:7: error: joint 'left_joint': parent link 'base' is not defined "
        "(did you mean 'base_link'? links: base_link, left_wheel) [undefined-link]\n"
    )


def test_check_a_xacro_file_with_arguments(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(
        '<robot name="$(arg name)" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="name" default="x"/><link name="only"/></robot>'
    )
    status, out, err = run("check", str(path), "name:=given")
    assert (status, err) == (0, "")
    assert out.startswith("robot name is: given\n")


def test_many_files_worst_status_wins() -> None:
    bad = str(DATA / "invalid" / "cycle.urdf")
    status, out, err = run("check", str(FIRST), bad, "missing.urdf")
    assert status == 2
    # The loop misses the root, so the tree is printed as check_urdf prints it.
    cycle = check_urdf(GoldenInput.from_id("data/invalid/cycle.urdf"))
    assert out == FIRST_TREE + cycle.stdout.decode()
    assert "[cycle]" in err
    assert "missing.urdf: error: no such file [io]" in err


def test_json_report() -> None:
    bad = DATA / "invalid" / "limit_range.urdf"  # an error for the simulators
    status, out, err = run("check", "--target", "gazebo", "--format", "json", str(FIRST), str(bad))
    assert status == 1
    assert err == ""
    report = json.loads(out)
    assert report["ok"] is False
    first, second = report["files"]
    assert first == {
        "path": str(FIRST),
        "ok": True,
        "robot": "first_robot",
        "root": "base_link",
        "links": 2,
        "joints": 1,
        "config": None,
        "targets": ["gazebo"],
        "skipped": None,
        "diagnostics": [],
        "suppressed": {"count": 0, "rules": {}},
    }
    assert second["ok"] is False
    assert second["targets"] == ["gazebo"]
    assert [d["rule"] for d in second["diagnostics"]] == ["limit-range"]
    assert second["diagnostics"][0]["line"] == 7


def test_json_report_for_unreadable_file() -> None:
    status, out, _ = run("check", "--format", "json", "nope.urdf")
    assert status == 2
    assert json.loads(out)["files"][0]["diagnostics"][0]["rule"] == "io"


def test_help_has_an_example() -> None:
    for args in (["--help"], ["check", "--help"]):
        status, out, _ = run(*args)
        assert status == 0
        assert "fishbot check robots/fishbot/urdf/first_robot.urdf" in out


def test_python_dash_m_and_no_color(tmp_path: Path) -> None:
    bad = DATA / "invalid" / "cycle.urdf"
    proc = subprocess.run(
        [sys.executable, "-m", "fishbot_urdf", "check", str(bad)],
        capture_output=True,
        text=True,
        check=False,
        env={"NO_COLOR": "1", "PATH": ""},
    )
    assert proc.returncode == 1
    assert proc.stdout.startswith("robot name is: loop_off_root\n")
    assert proc.stderr.startswith(f"{bad}:7:3: error: joints 'a_to_b'")
    assert "\x1b[" not in proc.stderr


def test_colour_only_on_a_terminal() -> None:
    bad = str(DATA / "invalid" / "cycle.urdf")
    _, _, err = run("check", bad)  # CliRunner's stderr is no terminal
    assert "\x1b[" not in err


def test_version() -> None:
    status, out, _ = run("--version")
    assert status == 0
    assert out.startswith("fishbot, version ")


def _slow_dot(folder: Path) -> dict[str, str]:
    """An environment whose `dot` says it has started (a file), then waits for ever."""
    bin_folder = folder / "bin"
    bin_folder.mkdir()
    script = bin_folder / "dot"
    script.write_text(f"#!/bin/sh\ntouch {folder / 'dot-started'}\nexec sleep 600\n")
    script.chmod(0o755)
    return {**os.environ, "PATH": f"{bin_folder}{os.pathsep}{os.environ['PATH']}"}


def _stopped_while_drawing(tmp_path: Path, signum: int) -> subprocess.CompletedProcess[bytes]:
    import signal
    import time

    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    process = subprocess.Popen(
        [sys.executable, "-m", "fishbot_urdf", "graph", str(robot), "-o", str(tmp_path / "r.png")],
        env=_slow_dot(tmp_path),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    for _ in range(600):  # until dot runs (at most a minute on a slow machine)
        if (tmp_path / "dot-started").exists() or process.poll() is not None:
            break
        time.sleep(0.1)
    process.send_signal(signal.SIGINT if signum == 2 else signal.SIGTERM)
    out, err = process.communicate(timeout=60)
    return subprocess.CompletedProcess(process.args, process.returncode, out, err)


@pytest.mark.skipif(os.name != "posix", reason="signals and the stand-in dot are POSIX")
@pytest.mark.parametrize(("signum", "status"), [(2, 130), (15, 143)])
def test_an_interrupt_or_a_termination_exits_quietly_with_the_shells_status(
    tmp_path: Path, signum: int, status: int
) -> None:
    done = _stopped_while_drawing(tmp_path, signum)
    assert done.returncode == status
    assert b"Traceback" not in done.stderr and b"Aborted" not in done.stderr
    assert done.stderr.strip() == b""
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bin", "dot-started", "r.urdf"]


@pytest.mark.skipif(os.name != "posix", reason="closing a standard stream is POSIX shell work")
def test_closed_standard_streams_are_no_traceback(tmp_path: Path) -> None:
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/><link name="b"/></robot>')
    command = [sys.executable, "-m", "fishbot_urdf", "check", str(robot)]
    closed_out = subprocess.run(
        command,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        close_fds=True,
        pass_fds=(),
        check=False,
        preexec_fn=lambda: os.close(1),
    )
    assert closed_out.returncode == 1
    assert b"Traceback" not in closed_out.stderr
    assert b"has 2 root links" in closed_out.stderr
    closed_err = subprocess.run(
        command, capture_output=True, check=False, preexec_fn=lambda: os.close(2)
    )
    assert closed_err.returncode == 1
    assert closed_err.stdout == b""  # two roots: no tree to print


_XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"
_CLOSED_OUT = b"<stdout>: error: cannot write: Bad file descriptor [io]\n"


def _with_stdout_closed(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[bytes]:
    """``fishbot ARGS >&-``, as a shell runs it."""
    command = " ".join(f"'{a}'" for a in (sys.executable, "-m", "fishbot_urdf", *args))
    return subprocess.run(
        ["sh", "-c", f"exec {command} >&-"], capture_output=True, check=False, cwd=cwd
    )


@pytest.mark.skipif(os.name != "posix", reason="closing a standard stream is POSIX shell work")
@pytest.mark.parametrize(
    "args",
    [
        ["check", str(FIRST)],
        ["check", "--format", "json", str(FIRST)],
        ["expand", str(_XACRO)],
        ["graph", str(FIRST), "-o", "-"],
        ["tf", str(FIRST), "base_link", "base_link"],
        ["inertia", str(FIRST)],
        ["inertia", "sphere", "--mass", "1", "--radius", "1"],
        ["render", str(FIRST), "-o", "-", "--size", "32x32"],
        ["rules"],
        ["--help"],
        ["--version"],
    ],
)
def test_a_closed_standard_output_is_an_error_for_a_command_that_writes_there(
    args: list[str],
) -> None:
    done = _with_stdout_closed(*args)
    assert (done.returncode, done.stderr) == (2, _CLOSED_OUT)


@pytest.mark.skipif(os.name != "posix", reason="closing a standard stream is POSIX shell work")
def test_a_closed_standard_output_is_no_error_for_a_command_that_writes_nothing_there(
    tmp_path: Path,
) -> None:
    assert _with_stdout_closed("check", "-q", str(FIRST)).returncode == 0
    # The output file opened while standard output is closed does not take its place: it
    # holds the report, and nothing else.
    report = tmp_path / "report.json"
    done = _with_stdout_closed("check", "--format", "json", str(FIRST), "-o", str(report))
    assert (done.returncode, done.stderr) == (0, b"")
    assert json.loads(report.read_text())["files"][0]["ok"] is True


@pytest.mark.skipif(os.name != "posix", reason="a pipe closed by its reader")
def test_a_reader_that_has_gone_ends_nothing_but_the_output(tmp_path: Path) -> None:
    # `fishbot check robot.urdf | head -0`: no line, no traceback, and the robot's own
    # status (its findings still go to stderr). A mass urdfdom cannot read: an error for
    # every program (a negative mass harms only simulators).
    robot = tmp_path / "r.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"/><link name="b"><inertial><mass value="1kg"/>'
        '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>'
        '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>'
    )
    for args, status in (
        (["check", str(robot)], 1),
        (["check", str(FIRST), str(robot)], 1),
        (["graph", str(robot), "-o", "-"], 1),
        (["expand", str(_XACRO)], 0),
    ):
        process = subprocess.Popen(
            [sys.executable, "-m", "fishbot_urdf", *args],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )
        assert process.stdout is not None and process.stderr is not None
        process.stdout.close()  # the reader is gone before anything is written
        with process.stderr:
            assert process.wait(timeout=60) == status, args
            said = process.stderr.read()
        assert b"Traceback" not in said and b"stdout" not in said, args
        assert said.count(b"\n") == (1 if status else 0), args


def test_file_names_that_are_no_utf8_are_written_as_their_bytes(tmp_path: Path) -> None:
    if sys.platform == "darwin" or os.name != "posix":
        pytest.skip("this file system takes names that are not UTF-8 only on Linux")
    name = os.fsdecode(b"\xff.urdf.xacro")
    robot = tmp_path / name
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"/>'
        '<link name="b"/></robot>'
    )
    raw = os.fsencode(str(robot))
    for command in (["check"], ["expand"], ["inertia"], ["graph", "-o", "-"]):
        result = CliRunner().invoke(cli, [*command, str(robot)])
        assert result.exception is None or isinstance(result.exception, SystemExit), command
        assert result.exit_code in (0, 1), command
        assert raw in result.stderr_bytes + result.stdout_bytes, command
    report = CliRunner().invoke(cli, ["check", "--format", "sarif", str(robot)])
    uri = json.loads(report.stdout)["runs"][0]["results"][0]["locations"][0]["physicalLocation"]
    assert "%FF.urdf.xacro" in uri["artifactLocation"]["uri"]
    out = os.fsdecode(b"\xfe.gv")
    drawn = CliRunner().invoke(cli, ["graph", str(robot), "-o", str(tmp_path / out)])
    assert (tmp_path / out).exists()
    assert drawn.stdout_bytes == b"Created file " + os.fsencode(str(tmp_path / out)) + b"\n"


def test_no_output_is_written_over_a_mesh_the_robot_names(tmp_path: Path) -> None:
    package = tmp_path / "pkg"
    (package / "urdf").mkdir(parents=True)
    (package / "meshes").mkdir()
    (package / "package.xml").write_text('<package format="3"><name>pkg</name></package>')
    trimesh = pytest.importorskip("trimesh", reason="--fill reads meshes with trimesh")
    mesh = package / "meshes" / "box.stl"
    trimesh.creation.box(extents=(0.1, 0.1, 0.1)).export(mesh)  # closed: --fill reads it
    before = mesh.read_bytes()
    robot = package / "urdf" / "robot.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"><collision>'
        '<geometry><mesh filename="package://pkg/meshes/box.stl"/></geometry></collision></link>'
        "</robot>"
    )
    for command in (
        ["graph", str(robot), "--format", "gv"],
        ["expand", str(robot)],
        ["sdf", str(robot)],
        ["check", str(robot), "--format", "json"],
        ["inertia", str(robot), "--fill", "--mass", "a=1"],
    ):
        result = CliRunner().invoke(cli, [*command, "-o", str(mesh)])
        assert result.exit_code == 2, command
        assert f"refusing to write over the input {mesh}" in result.stderr, command
        assert mesh.read_bytes() == before, command


def test_the_listed_summaries_are_the_commands_own() -> None:
    # `fishbot --help` lists the subcommands without importing them: what it shows must be
    # what click shows from each command's own help, at every width.
    import importlib

    import fishbot_urdf.cli
    from fishbot_urdf.cli import COMMANDS, summary

    modules = {p.stem for p in Path(fishbot_urdf.cli.__file__).parent.glob("*.py")}
    assert set(COMMANDS) == {m for m in modules if not m.startswith("_")}
    for name in COMMANDS:
        command = getattr(importlib.import_module(f"fishbot_urdf.cli.{name}"), name)
        assert command.name == name
        for limit in range(20, 200, 7):
            shown = summary(name).get_short_help_str(limit)
            assert shown == command.get_short_help_str(limit), (name, limit)


def _modules_after(*args: str) -> set[str]:
    code = (
        "import sys\nfrom fishbot_urdf.cli import main\ntry:\n    main(sys.argv[1:])\n"
        "except SystemExit:\n    pass\n"
        "sys.stderr.write(' '.join(m for m in sys.modules if m.startswith('fishbot_urdf')))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code, *args], capture_output=True, text=True, check=True
    )
    return set(out.stderr.split("\n")[-1].split())


def test_help_and_check_import_only_what_they_use() -> None:
    assert not {m for m in _modules_after("--help") if m.startswith("fishbot_urdf.cli.")}
    loaded = _modules_after("check", str(FIRST), "-q")
    drawn = {"fishbot_urdf.cli.graph", "fishbot_urdf.drawing.dot", "fishbot_urdf.cli.render"}
    assert "fishbot_urdf.cli.check" in loaded
    assert not loaded & drawn
    # a URDF file needs no xacro: neither the PyPI package nor the engine that runs it
    assert not loaded & {"xacro", "fishbot_urdf.expansion._engine"}


def _python(
    code: str, stdout: int | IO[bytes] = subprocess.PIPE
) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", code], stdout=stdout, stderr=subprocess.PIPE, text=True, check=False
    )


@pytest.mark.parametrize(("argv", "status"), [(FIRST, 0), (DATA / "invalid" / "cycle.urdf", 1)])
def test_the_command_ends_its_process_with_its_output_and_status_and_nothing_taken_apart(
    argv: Path, status: int
) -> None:
    ending = "import atexit\natexit.register(lambda: print('taken apart'))\n"
    own = f"import sys\nsys.argv = ['fishbot', 'check', {str(argv)!r}]\n"
    ended = _python(f"{ending}{own}from fishbot_urdf.cli import main\nmain()\n")
    assert ended.returncode == status
    assert ended.stdout == run("check", str(argv))[1]  # the tree, all of it
    assert "taken apart" not in ended.stdout
    given = _python(f"{ending}from fishbot_urdf.cli import main\nmain(['check', {str(argv)!r}])\n")
    assert given.returncode == status
    assert given.stdout.endswith("taken apart\n")  # an argv given: SystemExit as usual


@pytest.mark.parametrize(
    ("code", "status", "said"),
    [("None", 0, ""), ("1", 1, ""), ("'stopped'", 1, "stopped\n")],
)
def test_the_process_ends_as_python_would_on_system_exit(code: str, status: int, said: str) -> None:
    ended = _python(
        f"from fishbot_urdf.cli import _end_process\nprint('out')\n_end_process({code})\n"
    )
    assert (ended.returncode, ended.stdout, ended.stderr) == (status, "out\n", said)


def test_output_that_cannot_be_written_at_the_end_is_one_line_and_status_2() -> None:
    if not Path("/dev/full").exists():
        pytest.skip("this system has no /dev/full to fill")
    code = (  # stdout buffered, as for a file (Python writes through to a device)
        "import io, sys\nfrom fishbot_urdf.cli import _end_process\n"
        "sys.stdout = io.TextIOWrapper(io.BufferedWriter(io.FileIO(1, 'w'), 1 << 16))\n"
        "sys.stdout.write('x')\n"
    )
    with open("/dev/full", "wb") as full:
        ended = _python(f"{code}_end_process(0)\n", stdout=full)
    assert ended.returncode == 2
    assert ended.stderr == "<stdout>: error: cannot write: No space left on device [io]\n"


def _package_robot(root: Path) -> dict[str, Path]:
    """A xacro robot in a package: it includes a file and loads YAML through $(find), names
    a mesh by package://, and has a configuration file. Every file it reads, by role."""
    from conftest import box_stl

    package = root / "pkg"
    for folder in ("urdf", "meshes", "config"):
        (package / folder).mkdir(parents=True)
    files = {
        "manifest": package / "package.xml",
        "config": package / "fishbot.toml",
        # no [tool.fishbot] table: read on the way to fishbot.toml, and passed over
        "pyproject": package / "urdf" / "pyproject.toml",
        "robot": package / "urdf" / "robot.urdf.xacro",
        "include": package / "urdf" / "parts.xacro",
        "yaml": package / "config" / "params.yaml",
        "mesh": package / "meshes" / "body.stl",
    }
    files["manifest"].write_text('<package format="3"><name>pkg</name></package>')
    files["config"].write_text('ignore = ["mesh-faces"]\n')
    files["pyproject"].write_text('[project]\nname = "fishbot-parts"\n')
    files["yaml"].write_text("mass: 1.5\n")
    files["mesh"].write_bytes(box_stl(0.1, 0.1, 0.1))
    files["include"].write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:property name="params" '
        "value=\"${xacro.load_yaml('$(find pkg)/config/params.yaml')}\"/>"
        "</robot>"
    )
    files["robot"].write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find pkg)/urdf/parts.xacro"/>'
        '<link name="base_link"><visual><geometry>'
        '<mesh filename="package://pkg/meshes/body.stl"/></geometry></visual>'
        '<collision><geometry><mesh filename="package://pkg/meshes/body.stl"/></geometry>'
        "</collision></link>"
        '<link name="arm"><inertial><mass value="${params[\'mass\']}"/>'
        '<inertia ixx="0.0025" iyy="0.0025" izz="0.0025" ixy="0" ixz="0" iyz="0"/></inertial>'
        '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>'
        '<joint name="j" type="fixed"><parent link="base_link"/><child link="arm"/></joint>'
        "</robot>"
    )
    return files


_WRITING = {
    "check": ["check", "{robot}", "-q"],
    "check-json": ["check", "{robot}", "--format", "json"],
    "expand": ["expand", "{robot}"],
    "graph": ["graph", "{robot}", "--format", "gv"],
    "inertia": ["inertia", "{robot}", "--fill", "--density", "1000"],
    "render": ["render", "{robot}", "--size", "32x32"],
}


_ROLES = ["robot", "include", "yaml", "mesh", "manifest", "config", "pyproject"]


@pytest.mark.parametrize(
    ("command", "role"),
    # expand reads no configuration
    [
        (c, r)
        for c in sorted(_WRITING)
        for r in _ROLES
        if c != "expand" or r not in ("config", "pyproject")
    ],
)
def test_no_file_read_is_written_over(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, command: str, role: str
) -> None:
    files = _package_robot(tmp_path)
    monkeypatch.chdir(tmp_path)
    before = {path: path.read_bytes() for path in files.values()}
    target = files[role]
    args = [a.format(robot=files["robot"]) for a in _WRITING[command]]
    result = CliRunner().invoke(cli, [*args, "-o", str(target)])
    assert result.exit_code == 2, result.stderr
    assert result.stderr.startswith(f"{target}: error: refusing to write over the input ")
    assert result.stderr.endswith(" [io]\n")
    assert result.stderr.count("\n") == 1, result.stderr
    assert {path: path.read_bytes() for path in files.values()} == before
    assert not [p for p in tmp_path.rglob(".*") if p.is_file()]  # no temporary file left


@pytest.mark.parametrize("fmt", ["text", "json", "sarif", "github"])
@pytest.mark.parametrize("role", ["include", "yaml", "manifest", "config", "pyproject"])
def test_what_a_robot_that_cannot_be_read_read_is_not_written_over_either(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, fmt: str, role: str
) -> None:
    # check writes its report for a file it could not read: what that file read before it
    # stopped (its includes, YAML files, the package.xml of $(find)) is an input all the same.
    files = _package_robot(tmp_path)
    monkeypatch.chdir(tmp_path)
    files["robot"].write_text(
        files["robot"].read_text().replace("</robot>", '<link name="${no_such}"/></robot>')
    )
    before = {path: path.read_bytes() for path in files.values()}
    target = files[role]
    result = CliRunner().invoke(
        cli, ["check", str(files["robot"]), "--format", fmt, "-o", str(target)]
    )
    assert result.exit_code == 2, result.stderr
    refusal = result.stderr.splitlines()[-1]  # after the finding that stopped the reading
    assert refusal.startswith(f"{target}: error: refusing to write over the input ")
    assert refusal.endswith(f"{target.relative_to(tmp_path)} [io]")
    assert {path: path.read_bytes() for path in files.values()} == before


@pytest.mark.parametrize("command", sorted(_WRITING))
def test_the_manifest_of_an_installed_package_is_not_written_over(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, command: str
) -> None:
    # A package under AMENT_PREFIX_PATH is found by its place, its package.xml unread.
    share = tmp_path / "install" / "share" / "parts"
    (share / "urdf").mkdir(parents=True)
    manifest = share / "package.xml"
    manifest.write_text('<package format="3"><name>parts</name></package>')
    (share / "urdf" / "base.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base_link">'
        '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
        '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link></robot>'
    )
    robot = tmp_path / "robot" / "robot.urdf.xacro"
    robot.parent.mkdir()
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find parts)/urdf/base.xacro"/></robot>'
    )
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(tmp_path / "install"))
    before = manifest.read_bytes()
    args = [a.format(robot=robot) for a in _WRITING[command]]
    result = CliRunner().invoke(cli, [*args, "-o", str(manifest)])
    assert result.exit_code == 2, result.stderr
    # (check and inertia say first that the base link has no <inertial>)
    assert result.stderr.splitlines()[-1] == (
        f"{manifest}: error: refusing to write over the input {manifest} [io]"
    )
    assert manifest.read_bytes() == before


def test_a_link_to_a_file_read_is_refused_too(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    files = _package_robot(tmp_path)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "link.stl").symlink_to(files["mesh"])
    (tmp_path / "hard.stl").hardlink_to(files["mesh"])
    before = files["mesh"].read_bytes()
    for name in ("link.stl", "hard.stl"):
        result = CliRunner().invoke(
            cli, ["render", str(files["robot"]), "--size", "32x32", "-o", name]
        )
        assert (result.exit_code, result.stdout) == (2, "")
        assert result.stderr == (
            f"{name}: error: refusing to write over the input {files['mesh']} [io]\n"
        )
    assert files["mesh"].read_bytes() == before
    # Elsewhere, it is written.
    result = CliRunner().invoke(
        cli, ["render", str(files["robot"]), "--size", "32x32", "-o", "picture.png"]
    )
    assert result.exit_code == 0, result.stderr
    assert (tmp_path / "picture.png").read_bytes().startswith(b"\x89PNG")


@pytest.mark.parametrize(
    "command",
    [
        ["check", "-", "-q"],
        ["check", "--format", "json", "-"],
        ["graph", "-", "--format", "gv"],
        ["inertia", "-", "--fill", "--density", "1000"],
        ["render", "-", "--size", "32x32"],
    ],
)
def test_standard_input_from_the_output_file_is_refused(tmp_path: Path, command: list[str]) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_bytes(FIRST.read_bytes())
    with open(robot, "rb") as stdin:
        done = subprocess.run(
            [sys.executable, "-m", "fishbot_urdf", *command, "-o", str(robot)],
            stdin=stdin,
            capture_output=True,
            cwd=tmp_path,
            check=False,
        )
    assert (done.returncode, done.stdout) == (2, b"")
    assert done.stderr == (
        f"{robot}: error: refusing to write over the input <stdin> [io]\n".encode()
    )
    assert robot.read_bytes() == FIRST.read_bytes()


def test_closed_standard_input_is_one_line() -> None:
    done = subprocess.run(
        ["sh", "-c", f'exec "{sys.executable}" -m fishbot_urdf check - <&-'],
        capture_output=True,
        check=False,
    )
    assert (done.returncode, done.stdout) == (2, b"")
    assert done.stderr == (
        b"<stdin>: error: standard input is closed (give a FILE, or pipe the robot in) [io]\n"
    )


_PWNED = "a\n::error file=x::pwned\x1b[2J.urdf"
_PWNED_SHOWN = "a\\n::error file=x::pwned\\x1b[2J.urdf"


@pytest.mark.skipif(sys.platform == "win32", reason="a newline in a file name: POSIX only")
def test_control_characters_in_a_file_name_are_written_visibly(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    robot = tmp_path / _PWNED
    robot.write_text(
        '<robot name="r"><link name="a"/>'
        '<joint name="j" type="fixed"><parent link="b"/><child link="a"/></joint></robot>'
    )
    status, out, err = run("check", "-q", _PWNED)
    assert (status, out) == (1, "")
    lines = err.splitlines()
    assert len(lines) == len(fishbot_urdf.check_file(robot).diagnostics) > 0
    assert all(line.startswith(f"{_PWNED_SHOWN}:1:") for line in lines)
    assert "\x1b" not in err
    status, out, err = run("check", "--format", "github", _PWNED)
    assert (status, err) == (1, "")
    assert len(out.splitlines()) == len(lines)
    assert all(
        line.startswith("::error file=a%0A%3A%3Aerror file=x%3A%3Apwned\\x1b[2J.urdf,line=1,")
        for line in out.splitlines()
    )
    for fmt in ("json", "sarif"):
        status, out, err = run("check", "--format", fmt, _PWNED)
        assert (status, err) == (1, "")
        assert "\x1b" not in out and _PWNED not in out
        assert _PWNED in out.encode().decode("unicode_escape") or json.loads(out)
    assert json.loads(run("check", "--format", "json", _PWNED)[1])["files"][0]["path"] == _PWNED
    # A file that is not there: the one line of the error.
    status, out, err = run("check", "missing\r\n" + _PWNED)
    assert (status, out, err) == (2, "", f"missing\\r\\n{_PWNED_SHOWN}: error: no such file [io]\n")


@pytest.mark.skipif(sys.platform == "win32", reason="control characters in a file name")
def test_control_characters_in_a_file_name_are_written_visibly_in_the_banner(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A terminal escape and a character XML refuses, in the name expand writes at the top.
    import re

    from fishbot_urdf.escaping import escape_controls

    monkeypatch.chdir(tmp_path)
    body = '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"/></robot>'
    plain, odd = "plain--name.xacro", "a\x1b[31mred\x01--name.xacro"
    for name in (plain, odd):
        (tmp_path / name).write_text(body)
    shown = re.sub(r"-+", "-", escape_controls(odd))  # as xacro shortens dashes
    status, out, err = run("expand", odd)
    assert (status, err) == (0, "")
    assert "\x1b" not in out and "\x01" not in out
    banner = f"<!-- |    This document was autogenerated by xacro from {shown:<30} | -->"
    assert banner in out.splitlines()
    # Only the name differs from the file of an ordinary name.
    ordinary = run("expand", plain)[1]
    assert out == ordinary.replace(f"{re.sub(r'-+', '-', plain):<30}", f"{shown:<30}")


def test_control_characters_in_a_link_name_are_written_visibly() -> None:
    text = (
        '<robot name="r&#10;x"><link name="a&#10;::error::b&#x9b;2J&#13;"/>'
        '<joint name="j&#10;k" type="fixed"><parent link="zz&#10;"/>'
        '<child link="a&#10;::error::b&#x9b;2J&#13;"/></joint></robot>'
    )
    status, out, err = run("check", "-", stdin=text.encode())
    assert status == 1
    lines = err.splitlines()
    assert len(lines) == len(fishbot_urdf.check_file(text.encode(), path="<stdin>").diagnostics)
    assert all(line.startswith("<stdin>:1:") and line.endswith("]") for line in lines)
    assert "\x9b" not in err and "\r" not in err
    status, out, err = run("check", "--format", "github", "-", stdin=text.encode())
    assert len(out.splitlines()) == len(lines) and "\x9b" not in out and "\r" not in out
    for fmt in ("json", "sarif"):
        status, out, err = run("check", "--format", fmt, "-", stdin=text.encode())
        assert json.loads(out)  # valid, its strings escaped by JSON's rules
    # The tree: no control character but the line ends.
    status, out, err = run(
        "check", "-", stdin=text.replace('"zz&#10;"', '"a&#10;::error::b&#x9b;2J&#13;"').encode()
    )
    assert "\x9b" not in out and "\r" not in out


def test_a_newline_in_a_link_name_leaves_one_line_per_link_in_tree_and_table() -> None:
    text = (
        '<robot name="r"><link name="base&#10;::error file=x::pwned">'
        '<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
        '</inertial></link><link name="w&#13;"><inertial><mass value="1"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>'
        '<joint name="j" type="fixed"><parent link="base&#10;::error file=x::pwned"/>'
        '<child link="w&#13;"/></joint></robot>'
    )
    status, out, _ = run("check", "-", stdin=text.encode())
    assert (status, out) == (
        0,
        "robot name is: r\n"
        "---------- Successfully Parsed XML ---------------\n"
        "root Link: base\\n::error file=x::pwned has 1 child(ren)\n"
        "    child(1):  w\\r\n",
    )
    status, out, _ = run("inertia", "-", stdin=text.encode())
    assert status == 0
    rows = out.splitlines()
    assert [row.split()[0] for row in rows[1:3]] == ["base\\n::error", "w\\r"]
    assert len(rows) == 4 and "\r" not in out


def test_a_workspace_with_links_that_cannot_be_followed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    (tmp_path / "ws" / "build").mkdir(parents=True)
    urdf = tmp_path / "ws" / "src" / "pkg" / "urdf"
    urdf.mkdir(parents=True)
    (tmp_path / "ws" / "src" / "loop").symlink_to("loop")
    (tmp_path / "ws" / "src" / "dangling").symlink_to(tmp_path / "nowhere")
    robot = urdf / "r.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><visual><geometry>'
        '<mesh filename="package://nopkg/m.stl"/></geometry></visual>'
        '<visual><geometry><box size="1 1 1"/></geometry></visual></link></robot>'
    )
    status, out, err = run("check", "-q", "ws/src/pkg/urdf/r.urdf")
    assert (status, out) == (0, "")
    assert err.count("\n") == 1 and "[mesh-not-found]" in err
    status, out, err = run("graph", "ws/src/pkg/urdf/r.urdf", "-o", "tree.gv")
    assert (status, out) == (0, "Created file tree.gv\n")
    status, out, err = run("render", "ws/src/pkg/urdf/r.urdf", "--size", "32x32", "-o", "r.png")
    assert (status, out) == (0, "")
    assert "Traceback" not in err


SDF_GOLDEN = Path(__file__).parent / "golden" / "sdf"


def test_sdf_prints_what_ign_sdf_prints() -> None:
    xacro = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"
    result = CliRunner().invoke(cli, ["sdf", str(xacro)])
    assert (result.exit_code, result.stderr) == (0, "")
    assert result.stdout == (SDF_GOLDEN / "fishbot.sdf").read_text(encoding="utf-8")


def test_sdf_writes_a_file(tmp_path: Path) -> None:
    out = tmp_path / "build" / "first_robot.sdf"
    result = CliRunner().invoke(cli, ["sdf", str(FIRST), "-o", str(out)])
    assert (result.exit_code, result.stdout, result.stderr) == (0, "", "")
    assert out.read_text(encoding="utf-8") == (SDF_GOLDEN / "first_robot.sdf").read_text()


def test_sdf_converts_gazebo_blocks() -> None:
    xacro = Path(__file__).parent / "data" / "gazebo" / "fishbot_description" / "urdf"
    result = CliRunner().invoke(cli, ["sdf", str(xacro / "fishbot.urdf.xacro")])
    assert (result.exit_code, result.stderr) == (0, "")
    golden = (SDF_GOLDEN / "gazebo_fishbot_ament.sdf").read_text(encoding="utf-8")
    assert result.stdout == golden


def test_sdf_refuses_a_gazebo_setting_the_converter_stops_on(tmp_path: Path) -> None:
    robot = tmp_path / "r.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"/><gazebo reference="a"><kp>x</kp></gazebo></robot>'
    )
    result = CliRunner().invoke(cli, ["sdf", str(robot)])
    assert (result.exit_code, result.stdout) == (1, "")
    assert result.stderr == (
        f"{robot}:1:55: error: <gazebo reference='a'>: <kp> is 'x', not a number: sdformat's "
        "converter stops on it [conversion]\n"
    )
