"""`fishbot graph` and `fishbot_urdf.to_dot` against the real urdf_to_graphviz.

What urdf_to_graphviz writes for every fixture, the fishbot robot and a corpus is kept in
tests/golden/ (see regenerate.py there), so this runs on any machine; where the tool is
installed it also runs live and must write exactly what is kept. Where urdfdom accepts a
robot, the DOT must be urdf_to_graphviz's byte for byte, except for the bugs we fix on
purpose: a joint named like a link gets its own node, and links the root does not reach are
drawn too. ``_undo_fixes`` takes exactly those out of our DOT, and what is left must still be
identical.
"""

from __future__ import annotations

import os
import re
import subprocess
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import (
    DATA,
    FISHBOT,
    INVALID,
    VALID,
    GoldenInput,
    golden_inputs,
    require_tool,
    sha256,
    urdf_to_graphviz,
    urdf_to_graphviz_form,
)

import fishbot_urdf
from fishbot_urdf.cli import cli
from fishbot_urdf.drawing.dot import drawing

FIRST = FISHBOT / "urdf" / "first_robot.urdf"
FISHBOT_XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"
ESCAPE = DATA / "valid" / "names_to_escape.urdf"


def _golden_gv(id: str) -> bytes:
    """The .gv urdf_to_graphviz wrote for input ``id``, kept in tests/golden/."""
    gv = urdf_to_graphviz(GoldenInput.from_id(id)).gv
    assert gv is not None, f"urdf_to_graphviz refused {id}"
    return gv


def ours(path: Path, *args: str) -> tuple[int, bytes, str]:
    result = CliRunner().invoke(cli, ["graph", str(path), "-o", "-", *args])
    return result.exit_code, result.stdout_bytes, result.stderr


def _undo_fixes(text: str, robot: fishbot_urdf.Robot) -> str:
    """Our DOT with the deliberate fixes taken out, as urdf_to_graphviz would write it."""
    plan = drawing(robot)
    renamed = {f'"{e.node}"': f'"{e.name}"' for e in plan.edges if e.node != e.name}
    hidden = {f'"{n}"' for n in plan.unreachable}
    hidden |= {f'"{e.node}"' for e in plan.edges if e.parent in plan.unreachable}
    kept = []
    for line in text.splitlines(keepends=True):
        quoted = re.findall(r'"[^"]*"', line.split(" [label=")[0])
        if any(q in hidden for q in quoted):
            continue
        if quoted and quoted[0] in renamed and " [label=" in line and " -> " not in line:
            continue  # the declaration of a joint's own node
        for new, old in renamed.items():
            line = line.replace(new, old)
        kept.append(line)
    return "".join(kept)


def _compare(item: GoldenInput) -> None:
    real = urdf_to_graphviz(item)
    status, out, err = ours(item.path)
    if real.gv is None:
        # urdfdom refuses the robot, or never finishes: so do we (and still draw what could
        # be read).
        assert status == 1, err
        return
    if out == real.gv:
        return
    result = fishbot_urdf.check_file(item.path)
    assert result.robot is not None
    fixed = _undo_fixes(out.decode("utf-8"), result.robot)
    assert fixed.encode("utf-8") == real.gv
    assert status == (0 if result.ok else 1), err


# These two show urdf_to_graphviz's bugs, each in its own test below.
OWN_TESTS = ("data/invalid/multiple_parents.urdf", "data/valid/names_to_escape.urdf")
INPUTS = golden_inputs()
FIXTURES = [item for item in INPUTS if not item.in_corpus and item.id not in OWN_TESTS]
CORPUS_INPUTS = [item for item in INPUTS if item.in_corpus]


@pytest.mark.parametrize("item", FIXTURES, ids=[item.id for item in FIXTURES])
def test_fixture_parity(item: GoldenInput) -> None:
    _compare(item)


@pytest.mark.parametrize("item", CORPUS_INPUTS, ids=[item.id for item in CORPUS_INPUTS])
def test_corpus_parity(item: GoldenInput) -> None:
    _compare(item)


def test_fishbot_parity_urdf_and_xacro() -> None:
    real = _golden_gv("robots/fishbot/urdf/first_robot.urdf")
    assert ours(FIRST) == (0, real, "")
    # The xacro: the real xacro command expanded it, urdf_to_graphviz drew the result; we
    # read the .xacro ourselves.
    real = _golden_gv("robots/fishbot/urdf/fishbot/fishbot.urdf.xacro")
    assert ours(FISHBOT_XACRO) == (0, real, "")
    assert fishbot_urdf.to_dot(fishbot_urdf.load(FISHBOT_XACRO)).encode() == real


def test_the_numbers_are_printed_as_urdf_to_graphviz_prints_them() -> None:
    """Gimbal lock, angles near pi, negative zeros, exponents, 7 significant digits."""
    real = _golden_gv("data/valid/rotations.urdf")
    status, out, _ = ours(DATA / "valid" / "rotations.urdf")
    assert status == 0
    assert out == real
    text = out.decode()
    assert '"base" -> "pitch_up_joint" [label="xyz: 0 0 0 \\nrpy: 0 1.5708 -0"]' in text
    assert "xyz: 0.123457 -1e-07 1e+300 \\nrpy: 0 -0 0" in text


def test_default_output_is_urdf_to_graphviz_s_pair_of_files(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    require_tool("dot", "graphviz")  # for our PDF
    real = urdf_to_graphviz_form("default-form")  # urdf_to_graphviz first_robot.urdf
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(cli, ["graph", str(FIRST)])
    assert result.exit_code == 0, result.stderr
    assert result.stdout == real["stdout"]
    assert result.stdout == "Created file first_robot.gv\nCreated file first_robot.pdf\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(real["files"])
    gv = tmp_path / "first_robot.gv"
    assert gv.read_bytes() == _golden_gv("robots/fishbot/urdf/first_robot.urdf")
    assert sha256(gv.read_bytes()) == real["files"]["first_robot.gv"]
    assert _pdf_pages(tmp_path / "first_robot.pdf") >= 1


def _pdf_pages(path: Path) -> int:
    from pypdf import PdfReader

    return len(PdfReader(path).pages)


# ----------------------------------------------------------------------------- rendering


@pytest.fixture()
def in_tmp(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.fixture()
def fishbot_robot() -> fishbot_urdf.Robot:
    return fishbot_urdf.load(FISHBOT_XACRO)


LINKS = [
    "base_footprint",
    "base_link",
    "imu_link",
    "camera_link",
    "camera_optical_link",
    "laser_cylinder_link",
    "laser_link",
    "left_wheel_link",
    "right_wheel_link",
    "front_caster_link",
    "back_caster_link",
]


def test_pdf_opens(in_tmp: Path) -> None:
    require_tool("dot", "graphviz")
    result = CliRunner().invoke(cli, ["graph", str(FISHBOT_XACRO), "-o", "tree.pdf"])
    assert result.exit_code == 0, result.stderr
    assert result.stdout == "Created file tree.pdf\n"
    assert _pdf_pages(in_tmp / "tree.pdf") == 1


def test_svg_parses_and_names_every_link(in_tmp: Path) -> None:
    require_tool("dot", "graphviz")
    result = CliRunner().invoke(cli, ["graph", str(FISHBOT_XACRO), "-o", "tree.svg"])
    assert result.exit_code == 0, result.stderr
    from lxml import etree

    svg = etree.parse(str(in_tmp / "tree.svg"), etree.XMLParser(resolve_entities=False))
    ns = {"svg": "http://www.w3.org/2000/svg"}
    titles = {t.text for t in svg.iterfind(".//svg:g[@class='node']/svg:title", ns)}
    assert titles == {*LINKS, *(j.name for j in fishbot_urdf.load(FISHBOT_XACRO).joints)}
    texts = {t.text for t in svg.iterfind(".//svg:text", ns)}
    assert set(LINKS) <= texts


def test_png_decodes(in_tmp: Path) -> None:
    require_tool("dot", "graphviz")
    result = CliRunner().invoke(cli, ["graph", str(FISHBOT_XACRO), "-o", "tree.png"])
    assert result.exit_code == 0, result.stderr
    from PIL import Image

    with Image.open(in_tmp / "tree.png") as image:
        image.load()
        width, height = image.size
    assert width > 500 and height > 300  # eleven links and ten joints, four levels deep


def test_render_and_draw_in_the_library(tmp_path: Path, fishbot_robot: fishbot_urdf.Robot) -> None:
    require_tool("dot", "graphviz")
    written = fishbot_urdf.render_graph(fishbot_robot, tmp_path / "tree.svg")
    assert written == tmp_path / "tree.svg"
    assert written.read_bytes().lstrip().startswith(b"<?xml")
    gv = fishbot_urdf.render_graph(fishbot_robot, tmp_path / "tree.txt", format="gv")
    assert gv.read_text() == fishbot_urdf.to_dot(fishbot_robot)
    assert fishbot_urdf.draw(fishbot_robot, "png").startswith(b"\x89PNG\r\n\x1a\n")
    with pytest.raises(ValueError, match="unknown format 'jpg'"):
        fishbot_urdf.draw(fishbot_robot, "jpg")


def test_render_is_render_graph_under_its_old_name(tmp_path: Path) -> None:
    robot = fishbot_urdf.load(FIRST)
    with pytest.deprecated_call(match="render_graph"):
        written = fishbot_urdf.render(robot, tmp_path / "tree.gv")
    assert written.read_text() == fishbot_urdf.to_dot(robot)


def test_render_never_writes_over_the_robot_s_own_file(tmp_path: Path) -> None:
    source = tmp_path / "robot.gv"
    source.write_bytes(FIRST.read_bytes())
    robot = fishbot_urdf.load(source)
    with pytest.raises(fishbot_urdf.InputError, match="refusing to write over the input"):
        fishbot_urdf.render_graph(robot, source)
    assert source.read_bytes() == FIRST.read_bytes()


# ---------------------------------------------------------------- urdf_to_graphviz's bugs


def _dot_nodes(dot_text: bytes) -> tuple[int, list[str]] | None:
    """Run `dot -Tplain`: the node count and labels, or None when dot refuses the text."""
    tool = require_tool("dot", "graphviz")
    run = subprocess.run([tool, "-Tplain"], input=dot_text, capture_output=True, check=False)
    if run.returncode != 0:
        return None
    nodes = [line for line in run.stdout.decode().splitlines() if line.startswith("node ")]
    return len(nodes), nodes


def test_names_are_escaped() -> None:
    real = _golden_gv("data/valid/names_to_escape.urdf")
    # urdf_to_graphviz writes names as they are: the quote ends the DOT string early.
    assert b'"say "hi"" [label="say "hi""];' in real
    status, out, _ = ours(ESCAPE)
    assert status == 0
    assert '"say \\"hi\\"" [label="say \\"hi\\""];' in out.decode()
    assert '"back\\\\slash\\\\" [label="back\\\\slash\\\\"];' in out.decode()


def test_escaped_names_are_what_dot_reads_and_draws() -> None:
    real = _golden_gv("data/valid/names_to_escape.urdf")
    assert _dot_nodes(real) is None  # dot: syntax error
    parsed = _dot_nodes(ours(ESCAPE)[1])
    assert parsed is not None
    # 4 links and 3 joints, each its own node.
    assert parsed[0] == 7
    # And the picture shows the names as they are.
    from lxml import etree

    svg = etree.fromstring(fishbot_urdf.draw(fishbot_urdf.load(ESCAPE), "svg"))
    texts = {t.text for t in svg.iter("{http://www.w3.org/2000/svg}text")}
    assert {'say "hi"', "back\\slash\\", "slash\\joint", "arm", "base"} <= texts


SO100 = "example-robot-data/so_arm_description/urdf/so100.urdf"


def test_a_joint_named_like_a_link_gets_its_own_node() -> None:
    real = _golden_gv(SO100)
    # urdf_to_graphviz: the joint "gripper" and the link "gripper" are one node.
    assert b'"gripper" -> "gripper" [label=' in real
    status, out, _ = ours(GoldenInput.from_id(SO100).path)
    assert status == 0
    text = out.decode()
    assert '"gripper (joint)" [label="gripper"];' in text
    # The joint "gripper" goes from the link "gripper" to the jaw.
    assert '"gripper" -> "gripper (joint)" [label=' in text
    assert '"gripper (joint)" -> "jaw"\n' in text


def test_dot_sees_one_node_fewer_in_urdf_to_graphviz_s_drawing() -> None:
    so100 = GoldenInput.from_id(SO100).path
    robot = fishbot_urdf.load(so100)
    size = len(robot.links) + len(robot.joints)
    real_nodes = _dot_nodes(_golden_gv(SO100))
    assert real_nodes is not None and real_nodes[0] == size - 1  # merged
    our_nodes = _dot_nodes(ours(so100)[1])
    assert our_nodes is not None and our_nodes[0] == size


def test_a_link_with_two_parents_keeps_both_joints() -> None:
    path = DATA / "invalid" / "multiple_parents.urdf"
    real_text = _golden_gv("data/invalid/multiple_parents.urdf").decode()
    # urdf_to_graphviz draws the link twice and one of its two joints twice.
    assert real_text.count('"bar" [label="bar"];') == 2
    assert "bar_left" not in real_text
    status, out, err = ours(path)
    assert status == 1 and "[multiple-parents]" in err
    text = out.decode()
    assert text.count('"bar" [label="bar"];') == 1
    assert '"left" -> "bar_left" [label=' in text and '"right" -> "bar_right" [label=' in text


def test_links_behind_a_loop_are_drawn_and_marked() -> None:
    path = DATA / "invalid" / "cycle.urdf"
    assert b'"a"' not in _golden_gv("data/invalid/cycle.urdf")
    status, out, err = ours(path)
    assert status == 1 and "[cycle]" in err
    text = out.decode()
    for name in "abc":
        assert f'"{name}" [label="{name}\\n(not reached from the root)", style=dashed' in text
    assert '"c" -> "c_to_a" [label=' in text and '"c_to_a" -> "a"' in text


def test_a_missing_link_is_drawn_and_marked() -> None:
    status, out, err = ours(DATA / "invalid" / "undefined_parent.urdf")
    assert status == 1 and "[undefined-link]" in err
    assert '[label="base\\n(not defined)", style=dotted, color=red, fontcolor=red];' in (
        out.decode()
    )


def test_every_fixture_draws_as_valid_dot() -> None:
    require_tool("dot", "graphviz")
    for path in [*VALID, *INVALID]:
        _, out, _ = ours(path)
        if not out:
            continue  # not even a <robot> to draw
        assert _dot_nodes(out) is not None, path
        assert _dot_nodes(ours(path, "--detail")[1]) is not None, path


# ----------------------------------------------------------------------- the command line


def test_dot_missing_still_writes_the_gv_and_claims_nothing_else(
    in_tmp: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    empty = in_tmp / "bin"
    empty.mkdir()
    # The real tool says it made a PDF it did not make.
    real = urdf_to_graphviz_form("without-dot")  # urdf_to_graphviz first_robot.urdf tree
    assert real["stdout"] == "Created file tree.gv\nCreated file tree.pdf\n"
    assert list(real["files"]) == ["tree.gv"]
    monkeypatch.setenv("PATH", str(empty))
    result = CliRunner().invoke(cli, ["graph", str(FIRST)])
    assert result.exit_code == 2
    assert result.stdout == "Created file first_robot.gv\n"
    assert (in_tmp / "first_robot.gv").exists() and not (in_tmp / "first_robot.pdf").exists()
    (line,) = result.stderr.splitlines()
    assert line == (
        "first_robot.pdf: error: Graphviz's dot program is needed for PDF output and was not "
        "found (install Graphviz: apt install graphviz, brew install graphviz, winget install "
        "graphviz, or conda install -c conda-forge graphviz) [tool-missing]"
    )
    # An existing picture is left as it was.
    (in_tmp / "old.svg").write_text("old")
    result = CliRunner().invoke(cli, ["graph", str(FIRST), "-o", "old.svg"])
    assert result.exit_code == 2 and result.stdout == ""
    assert (in_tmp / "old.svg").read_text() == "old"
    assert [p.name for p in in_tmp.iterdir() if p.name.startswith(".")] == []
    # DOT and Mermaid need no Graphviz.
    assert CliRunner().invoke(cli, ["graph", str(FIRST), "-o", "t.gv"]).exit_code == 0
    assert CliRunner().invoke(cli, ["graph", str(FIRST), "-o", "t.mmd"]).exit_code == 0
    with pytest.raises(fishbot_urdf.ToolNotFoundError) as caught:
        fishbot_urdf.draw(fishbot_urdf.load(FIRST), "png")
    assert caught.value.rule == "tool-missing" and caught.value.tool == "dot"


def test_unwritable_output_folder(in_tmp: Path) -> None:
    (in_tmp / "taken").write_text("a file, not a folder")
    result = CliRunner().invoke(cli, ["graph", str(FIRST), "-o", "taken/tree.gv"])
    assert result.exit_code == 2
    assert result.stdout == ""
    (line,) = result.stderr.splitlines()
    assert line.startswith("taken/tree.gv: error: cannot write taken/tree.gv: ")
    assert line.endswith("[io]")


def test_stdout_and_format(in_tmp: Path, fishbot_robot: fishbot_urdf.Robot) -> None:
    runner = CliRunner()
    result = runner.invoke(cli, ["graph", str(FISHBOT_XACRO), "-o", "-"])
    assert result.exit_code == 0 and result.stderr == ""
    assert result.stdout == fishbot_urdf.to_dot(fishbot_robot)
    result = runner.invoke(cli, ["graph", str(FISHBOT_XACRO), "-o", "-", "--format", "mmd"])
    assert result.stdout == fishbot_urdf.to_mermaid(fishbot_robot)
    result = runner.invoke(cli, ["graph", str(FISHBOT_XACRO), "-o", "tree.txt", "--format", "dot"])
    assert result.exit_code == 0
    assert (in_tmp / "tree.txt").read_text() == fishbot_urdf.to_dot(fishbot_robot)
    result = runner.invoke(cli, ["graph", str(FISHBOT_XACRO), "--format", "mmd"])
    assert result.stdout == "Created file fishbot.mmd\n"
    result = runner.invoke(cli, ["graph", str(FISHBOT_XACRO), "-o", "tree.jpg"])
    assert result.exit_code == 2
    assert "cannot tell the format of 'tree.jpg' (extensions: gv, dot, pdf, svg, png, mmd" in (
        result.stderr
    )
    assert not (in_tmp / "tree.jpg").exists()


def test_xacro_arguments_and_stdin(in_tmp: Path) -> None:
    (in_tmp / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="second" default="b"/>'
        '<link name="a"/><link name="$(arg second)"/>'
        '<joint name="j" type="fixed"><parent link="a"/><child link="$(arg second)"/></joint>'
        "</robot>"
    )
    result = CliRunner().invoke(cli, ["graph", "r.urdf.xacro", "second:=wheel", "-o", "-"])
    assert result.exit_code == 0, result.stderr
    assert '"j" -> "wheel"' in result.stdout
    piped = CliRunner().invoke(cli, ["graph", "-", "-o", "-"], input=FIRST.read_bytes())
    assert piped.exit_code == 0
    assert piped.stdout == fishbot_urdf.to_dot(fishbot_urdf.load(FIRST))


def test_never_writes_over_the_input(in_tmp: Path) -> None:
    robot = in_tmp / "robot.gv"
    robot.write_bytes(FIRST.read_bytes())
    result = CliRunner().invoke(cli, ["graph", "robot.gv", "-o", "robot.gv"])
    assert result.exit_code == 2
    assert "refusing to write over the input robot.gv" in result.stderr
    assert robot.read_bytes() == FIRST.read_bytes()


@pytest.mark.parametrize(
    ("name", "path"),
    [("../up", "../up.gv"), ("/tmp/up", "/tmp/up.gv"), ("a/b", "a/b.gv"), ("..", "<output>")],
)
def test_a_robot_name_that_is_no_file_name_here_needs_o(in_tmp: Path, name: str, path: str) -> None:
    (in_tmp / "r.urdf").write_text(f'<robot name="{name}"><link name="a"/></robot>')
    result = CliRunner().invoke(cli, ["graph", "r.urdf"])
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr == (
        f"{path}: error: the robot's name {name!r} is no file name in the current folder "
        "(name the output: give OUT or -o FILE) [io]\n"
    )
    assert sorted(p.name for p in in_tmp.iterdir()) == ["r.urdf"]
    svg = CliRunner().invoke(cli, ["graph", "r.urdf", "--format", "svg"])
    assert svg.exit_code == 2
    assert svg.stderr.startswith(f"{path.replace('.gv', '.svg')}: error: the robot's name ")


@pytest.mark.skipif(os.name != "posix", reason="symbolic links")
@pytest.mark.parametrize("fmt", [None, "gv", "mmd"])
def test_a_name_made_from_the_robot_is_never_written_through_a_link(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, fmt: str | None
) -> None:
    # A robot named "evil" beside evil.gv -> ../victim.txt: the victim stays as it is.
    here = tmp_path / "here"
    here.mkdir()
    monkeypatch.chdir(here)
    victim = tmp_path / "victim.txt"
    victim.write_bytes(b"kept\n")
    (here / "r.urdf").write_text('<robot name="evil"><link name="a"/></robot>')
    link = f"evil.{fmt or 'gv'}"
    (here / link).symlink_to("../victim.txt")
    extra = [] if fmt is None else ["--format", fmt]
    result = CliRunner().invoke(cli, ["graph", "r.urdf", *extra])
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr == (
        f"{link}: error: {link} is a link: this output is not written through one "
        "(name the output: give OUT or -o FILE) [io]\n"
    )
    assert victim.read_bytes() == b"kept\n"
    assert sorted(p.name for p in here.iterdir()) == sorted(["r.urdf", link])  # no .pdf
    # A name the user gives is written as a shell's > writes it: through the link.
    given = CliRunner().invoke(cli, ["graph", "r.urdf", "-o", link])
    assert given.exit_code == 0, given.stderr
    assert victim.read_bytes() != b"kept\n"


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="this system has no FIFOs")
def test_a_name_made_from_the_robot_is_no_fifo(in_tmp: Path) -> None:
    (in_tmp / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>')
    os.mkfifo(in_tmp / "r.gv")  # written to directly, it would wait for a reader for ever
    result = CliRunner().invoke(cli, ["graph", "r.urdf"])
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr == (
        "r.gv: error: r.gv is no regular file: this output replaces only one "
        "(name the output: give OUT or -o FILE) [io]\n"
    )


def test_unreadable_robot(in_tmp: Path) -> None:
    result = CliRunner().invoke(cli, ["graph", "missing.urdf"])
    assert result.exit_code == 2 and result.stdout == ""
    assert result.stderr.count("\n") == 1
    result = CliRunner().invoke(cli, ["graph", str(DATA / "invalid" / "xml_syntax.urdf")])
    assert result.exit_code == 1 and result.stdout == ""
    assert sorted(in_tmp.iterdir()) == []


def test_detail() -> None:
    """What all_elements.urdf declares, shown: types, axes, limits, counts, masses."""
    status, out, _ = ours(DATA / "valid" / "all_elements.urdf", "--detail")
    assert status == 0
    lines = out.decode().splitlines()
    assert '"arm" [label="arm\\n1 visual, 0 collisions\\nno inertial"];' in lines
    assert '"base_link" [label="base_link\\n2 visuals, 2 collisions\\nmass 2.5 kg"];' in lines
    assert (
        '"shoulder" [label="shoulder\\nrevolute\\naxis 0 1 0\\nlimit -1.57 .. 1.57, effort 30, '
        'velocity 2", color=blue, fontcolor=blue];'
    ) in lines
    assert any(line.endswith("color=dimgray, fontcolor=dimgray];") for line in lines)
    assert any("\\nmimic finger_a_joint x1 +0" in line for line in lines)
    # The edges are the same as without --detail.
    plain = ours(DATA / "valid" / "all_elements.urdf")[1].decode().splitlines()
    assert [line for line in lines if " -> " in line] == [line for line in plain if " -> " in line]
    assert "revolute" not in "".join(plain)


def test_help_has_an_example() -> None:
    result = CliRunner().invoke(cli, ["graph", "--help"])
    assert result.exit_code == 0
    assert "fishbot graph robots/fishbot/urdf/fishbot/fishbot.urdf.xacro" in result.stdout


# ------------------------------------------------------------- found in a new-user review


def test_the_out_form_of_urdf_to_graphviz(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """`urdf_to_graphviz ROBOT OUT` (its form that is not deprecated) writes OUT.gv, OUT.pdf."""
    require_tool("dot", "graphviz")  # for our PDF
    # The golden runs are `urdf_to_graphviz ROBOT tree`.
    real = urdf_to_graphviz(GoldenInput.from_id("robots/fishbot/urdf/first_robot.urdf"))
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(cli, ["graph", str(FIRST), "ours/tree"])
    assert result.exit_code == 0, result.stderr
    assert result.stdout == real.stdout.decode().replace("tree", "ours/tree")
    assert (tmp_path / "ours" / "tree.gv").read_bytes() == real.gv
    assert _pdf_pages(tmp_path / "ours" / "tree.pdf") >= 1
    both = CliRunner().invoke(cli, ["graph", str(FIRST), "tree", "-o", "x.gv"])
    assert both.exit_code == 2 and "give one OUT" in both.stderr


def test_never_writes_over_a_file_the_xacro_includes(in_tmp: Path) -> None:
    (in_tmp / "inc.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"/></robot>'
    )
    (in_tmp / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="inc.xacro"/></robot>'
    )
    before = (in_tmp / "inc.xacro").read_bytes()
    result = CliRunner().invoke(cli, ["graph", "r.urdf.xacro", "-o", "inc.xacro", "--format", "gv"])
    assert result.exit_code == 2 and result.stdout == ""
    assert "refusing to write over the input" in result.stderr
    robot = fishbot_urdf.load(in_tmp / "r.urdf.xacro")
    with pytest.raises(fishbot_urdf.InputError, match="refusing to write over the input"):
        fishbot_urdf.render_graph(robot, in_tmp / "inc.xacro", format="gv")
    assert (in_tmp / "inc.xacro").read_bytes() == before


def test_long_names(in_tmp: Path) -> None:
    # 250 bytes is a legal file name once ".gv" is added: the temporary file must fit too.
    (in_tmp / "long.urdf").write_text(f'<robot name="{"y" * 250}"><link name="a"/></robot>')
    result = CliRunner().invoke(cli, ["graph", "long.urdf", "--format", "gv"])
    assert result.exit_code == 0, result.stderr
    assert (in_tmp / f"{'y' * 250}.gv").exists()
    # Too long for any file system: one line, no traceback.
    result = CliRunner().invoke(cli, ["graph", "long.urdf", "-o", "z" * 260 + ".gv"])
    assert result.exit_code == 2, result.output
    (line,) = result.stderr.splitlines()
    assert line.endswith("File name too long [io]")


def test_dot_failing_is_a_tool_problem(in_tmp: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    fake = in_tmp / "bin" / "dot"
    fake.parent.mkdir()
    fake.write_text("#!/bin/sh\necho 'Format: \"pdf\" not recognized' >&2\nexit 1\n")
    fake.chmod(0o755)
    monkeypatch.setenv("PATH", f"{fake.parent}{os.pathsep}{os.environ['PATH']}")
    result = CliRunner().invoke(cli, ["graph", str(FIRST), "-o", "x.pdf"])
    assert result.exit_code == 2
    (line,) = result.stderr.splitlines()
    assert (
        line == 'x.pdf: error: dot could not render PDF: Format: "pdf" not recognized [tool-failed]'
    )
    assert not (in_tmp / "x.pdf").exists()


def test_an_output_naming_a_folder(in_tmp: Path) -> None:
    result = CliRunner().invoke(cli, ["graph", str(FIRST), "-o", "newdir/", "--format", "gv"])
    assert result.exit_code == 2
    assert "newdir/ names a folder (name a file in it) [io]" in result.stderr
    assert not (in_tmp / "newdir").exists()


def test_a_closed_pipe_stops_quietly(tmp_path: Path) -> None:
    import sys

    for command in (["graph", str(FISHBOT_XACRO), "-o", "-"], ["check", str(FISHBOT_XACRO)]):
        process = subprocess.Popen(
            [sys.executable, "-m", "fishbot_urdf", *command],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )
        assert process.stdout is not None and process.stderr is not None
        process.stdout.close()  # the reader is gone before anything is written
        with process.stderr:
            assert process.wait(timeout=60) == 0
            assert process.stderr.read() == b""


def test_stdin_takes_no_xacro_arguments() -> None:
    result = CliRunner().invoke(cli, ["graph", "-", "a:=b", "-o", "-"], input=FIRST.read_bytes())
    assert result.exit_code == 2
    assert "name:=value arguments are for a .xacro file, not standard input" in result.stderr


def test_devnull_and_upper_case_formats(fishbot_robot: fishbot_urdf.Robot) -> None:
    assert CliRunner().invoke(cli, ["graph", str(FIRST), "-o", os.devnull]).exit_code == 0
    assert fishbot_urdf.draw(fishbot_robot, "GV") == fishbot_urdf.to_dot(fishbot_robot).encode()


def _fake_dot(folder: Path, body: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """A `dot` on PATH that runs ``body`` (a shell script) instead of Graphviz."""
    folder.mkdir()
    script = folder / "dot"
    script.write_text("#!/bin/sh\n" + body + "\n")
    script.chmod(0o755)
    monkeypatch.setenv("PATH", f"{folder}{os.pathsep}{os.environ['PATH']}")


@pytest.mark.skipif(os.name != "posix", reason="the stand-in dot is a shell script")
def test_a_dot_that_never_ends_is_stopped_with_what_it_started(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The stand-in starts a child that would hold the pipe open, then waits for ever.
    pid_file = tmp_path / "child.pid"
    _fake_dot(tmp_path / "bin", f"sleep 600 & echo $! > {pid_file}\nwait", monkeypatch)
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    result = CliRunner().invoke(
        cli, ["graph", str(robot), "-o", str(tmp_path / "r.png"), "--timeout", "0.5"]
    )
    assert result.exit_code == 2
    assert result.stderr == (
        f"{tmp_path / 'r.png'}: error: dot did not finish drawing the PNG within 0.5 s "
        "(allow it longer with --timeout SECONDS) [tool-failed]\n"
    )
    assert not (tmp_path / "r.png").exists()
    child = int(pid_file.read_text())
    assert not _alive(child)  # killed with dot's process group


@pytest.mark.skipif(os.name != "posix", reason="the stand-in dot is a shell script")
@pytest.mark.parametrize("seconds", ["2200000", "1e300"])
def test_a_timeout_beyond_what_a_wait_can_count_still_draws(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, seconds: str
) -> None:
    # The system's wait counts milliseconds in a C int: 2,200,000 s is past its 24.8 days.
    _fake_dot(tmp_path / "bin", "cat", monkeypatch)
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    out = tmp_path / "r.svg"
    result = CliRunner().invoke(cli, ["graph", str(robot), "-o", str(out), "--timeout", seconds])
    assert (result.exit_code, result.stderr) == (0, "")
    assert out.read_text() == fishbot_urdf.to_dot(fishbot_urdf.load(robot))


@pytest.mark.skipif(os.name != "posix", reason="the stand-in dot is a shell script")
def test_dot_is_waited_for_in_parts_up_to_the_timeout(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from fishbot_urdf import ToolError
    from fishbot_urdf.drawing import dot

    _fake_dot(tmp_path / "bin", "cat > /dev/null; sleep 0.4; echo drawn", monkeypatch)
    monkeypatch.setattr(dot, "_LONGEST_WAIT", 0.05)
    assert dot.pipe_dot("digraph G {}", "svg", timeout=30) == b"drawn\n"
    started = time.monotonic()
    with pytest.raises(ToolError, match=r"within 0\.2 s"):
        dot.pipe_dot("digraph G {}", "svg", timeout=0.2)
    assert time.monotonic() - started < 5


def _alive(pid: int) -> bool:
    """Whether a process runs, waiting a little for a kill to land (a zombie does not run)."""
    for _ in range(100):
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return False
        stat = Path(f"/proc/{pid}/stat")
        if stat.exists() and stat.read_text().rsplit(")", 1)[1].split()[0] == "Z":
            return False
        time.sleep(0.05)
    return True


@pytest.mark.skipif(os.name != "posix", reason="the stand-in dot is a shell script")
def test_a_dot_that_fails_says_its_first_line(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    _fake_dot(tmp_path / "bin", 'echo "Format: \\"png\\" not recognized." >&2; exit 1', monkeypatch)
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    result = CliRunner().invoke(cli, ["graph", str(robot), "-o", str(tmp_path / "r.png")])
    assert result.exit_code == 2
    assert 'dot could not render PNG: Format: "png" not recognized.' in result.stderr


def test_the_graph_command_offers_every_format_the_drawing_writes() -> None:
    from fishbot_urdf.cli.graph import _GRAPH_FORMATS
    from fishbot_urdf.drawing.dot import FORMATS

    assert tuple(FORMATS) == _GRAPH_FORMATS
