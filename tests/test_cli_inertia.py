"""`fishbot inertia`: shape blocks, the mass table, and --fill."""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner, Result
from conftest import DATA, FISHBOT, xacro_command
from lxml import etree

import fishbot_urdf
from fishbot_urdf.cli import cli
from fishbot_urdf.inertia import box_inertia, cylinder_inertia, sphere_inertia

PHYSICS = DATA / "physics"
XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"
COMMON = FISHBOT / "urdf" / "fishbot" / "common_inertia.xacro"


def run(*args: str, stdin: bytes | None = None) -> Result:
    return CliRunner().invoke(cli, ["inertia", *args], input=stdin)


def _macro_attributes(tmp_path: Path, call: str) -> dict[str, str]:
    """The <inertia> attributes the real xacro command writes for a common_inertia call."""
    source = tmp_path / "one.urdf.xacro"
    source.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        f'<xacro:include filename="{COMMON}"/><link name="a">{call}</link></robot>'
    )
    done = xacro_command(source)
    assert done.returncode == 0, done.stderr
    element = etree.fromstring(done.stdout.encode()).find("link/inertial/inertia")
    assert element is not None
    return dict(element.attrib)


@pytest.mark.parametrize(
    ("args", "call"),
    [
        (
            ["box", "--mass", "0.01", "--size", "0.02", "0.1", "0.02"],
            '<xacro:box_inertia m="0.01" w="0.02" h="0.1" d="0.02"/>',
        ),
        (
            ["cylinder", "--mass", "1.0", "--radius", "0.10", "--length", "0.12"],
            '<xacro:cylinder_inertia m="1.0" r="0.10" h="0.12"/>',
        ),
        (
            ["sphere", "--mass", "0.02", "--radius", "0.016"],
            '<xacro:sphere_inertia m="0.02" r="0.016"/>',
        ),
    ],
    ids=["box", "cylinder", "sphere"],
)
def test_shape_blocks_have_the_macros_numbers(tmp_path: Path, args: list[str], call: str) -> None:
    result = run(*args)
    assert result.exit_code == 0, result.output
    printed = etree.fromstring(result.stdout.encode())
    assert printed.tag == "inertial"
    inertia = printed.find("inertia")
    assert inertia is not None
    real = _macro_attributes(tmp_path, call)
    for name in ("ixx", "iyy", "izz"):
        # The macro's number to 12 significant digits, as short as it reads back.
        assert float(inertia.get(name, "nan")) == float(f"{float(real[name]):.12g}")
        assert inertia.get(name) == repr(float(f"{float(real[name]):.12g}"))


def test_cylinder_block_exactly() -> None:
    result = run(
        "cylinder",
        "--mass",
        "0.1",
        "--radius",
        "0.032",
        "--length",
        "0.04",
        "--rpy",
        "1.57079",
        "0",
        "0",
    )
    made = cylinder_inertia(0.1, 0.032, 0.04).inertia
    assert result.exit_code == 0
    # To 12 significant digits: 0.1 / 2 * 0.032^2 is 5.1200000000000004e-05 in floats.
    assert (made.izz, made.ixx) == (5.1200000000000004e-05, 3.8933333333333336e-05)
    assert result.stdout == (
        "<inertial>\n"
        '  <origin xyz="0 0 0" rpy="1.57079 0 0"/>\n'
        '  <mass value="0.1"/>\n'
        '  <inertia ixx="3.89333333333e-05" ixy="0" ixz="0" iyy="3.89333333333e-05" iyz="0" '
        'izz="5.12e-05"/>\n'
        "</inertial>\n"
    )


def test_a_shapes_numbers_carry_no_float_noise() -> None:
    # 1/12 * (3 * 0.1^2 + 0.12^2) is 0.0037000000000000006 and 1/2 * 0.1^2 is
    # 0.005000000000000001 in floats: what the user pastes is the number meant.
    args = ("cylinder", "--mass", "1", "--radius", "0.1", "--length", "0.12")
    assert run(*args).stdout == (
        "<inertial>\n"
        '  <origin xyz="0 0 0" rpy="0 0 0"/>\n'
        '  <mass value="1"/>\n'
        '  <inertia ixx="0.0037" ixy="0" ixz="0" iyy="0.0037" iyz="0" izz="0.005"/>\n'
        "</inertial>\n"
    )
    data = json.loads(run(*args, "--format", "json").stdout)
    assert data["inertia"] == {
        "ixx": 0.0037,
        "ixy": 0.0,
        "ixz": 0.0,
        "iyy": 0.0037,
        "iyz": 0.0,
        "izz": 0.005,
    }


def test_a_fill_notes_numbers_carry_no_float_noise(tmp_path: Path) -> None:
    source = tmp_path / "body.urdf"
    source.write_text(
        '<robot name="b"><link name="a"/>\n<link name="b">\n<collision><geometry>'
        '<cylinder radius="0.1" length="0.12"/></geometry></collision></link>'
        '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>\n'
    )
    result = run(str(source), "--fill", "--mass", "b=1")
    assert result.exit_code == 0, result.output
    assert result.stdout == (
        f"{source}:2:1: note: link 'b' has no <inertial>; for 1 kg, write at line 3, inside "
        "the <link>:\n"
        "  <inertial>\n"
        '    <origin xyz="0 0 0" rpy="0 0 0"/>\n'
        '    <mass value="1"/>\n'
        '    <inertia ixx="0.0037" ixy="0" ixz="0" iyy="0.0037" iyz="0" izz="0.005"/>\n'
        "  </inertial>\n"
    )
    data = json.loads(run(str(source), "--fill", "--mass", "b=1", "--format", "json").stdout)
    (made,) = data["suggestions"]
    assert made["inertial"]["inertia"]["izz"] == 0.005
    assert made["inertial"]["inertia"]["ixx"] == 0.0037


def test_shape_json() -> None:
    result = run(
        "sphere", "--mass", "2", "--radius", "0.5", "--xyz", "0", "0", "0.1", "--format", "json"
    )
    assert result.exit_code == 0
    data = json.loads(result.stdout)
    made = sphere_inertia(2.0, 0.5).inertia
    assert data == {
        "mass": 2.0,
        "origin": {"xyz": [0.0, 0.0, 0.1], "rpy": [0.0, 0.0, 0.0]},
        "inertia": {
            "ixx": made.ixx,
            "ixy": 0.0,
            "ixz": 0.0,
            "iyy": made.iyy,
            "iyz": 0.0,
            "izz": made.izz,
        },
    }


@pytest.mark.parametrize(
    "args",
    [
        ["box", "--mass", "0", "--size", "1", "1", "1"],
        ["box", "--mass", "1", "--size", "1", "1"],
        ["cylinder", "--mass", "1", "--radius", "-0.1", "--length", "1"],
        ["sphere", "--radius", "0.1"],
        ["sphere", "--mass", "nan", "--radius", "0.1"],
    ],
)
def test_bad_shape_arguments_are_usage_errors(args: list[str]) -> None:
    result = run(*args)
    assert result.exit_code == 2
    assert "Traceback" not in result.output


def test_help_lists_the_shapes_and_the_robot_form() -> None:
    result = run("--help")
    assert result.exit_code == 0
    for word in ("box", "cylinder", "sphere", "--fill -o OUT", "--density", "Examples:"):
        assert word in result.stdout
    for shape in ("box", "cylinder", "sphere"):
        assert "Example:" in run(shape, "--help").stdout


def test_the_fishbot_mass_table() -> None:
    result = run(str(XACRO))
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert lines[0].split() == [
        "link",
        "mass",
        "kg",
        "com",
        "x",
        "y",
        "z",
        "(m,",
        "link",
        "frame)",
        "principal",
        "moments",
        "(kg*m^2)",
        "checks",
    ]
    rows = {line.split()[0]: line.split() for line in lines[1:-1]}
    assert rows["base_footprint"] == ["base_footprint", "-", "-", "-", "ok"]
    # cylinder_inertia(1, 0.1, 0.12): 1/12 (3 0.01 + 0.0144) = 0.0037, 1/2 0.01 = 0.005
    assert rows["base_link"] == ["base_link", "1", "0", "0", "0", "0.0037", "0.0037", "0.005", "ok"]
    # 1.41 kg; z = 0.13422 / 1.41 = 0.09519 (tests/test_inertia.py works it out)
    assert lines[-1].startswith(
        "total: 1.41 kg; centre of mass 0.0007092 0 0.09519 m in base_footprint"
    )
    assert result.stderr == ""


def test_the_mass_table_as_json() -> None:
    result = run(str(XACRO), "--format", "json")
    assert result.exit_code == 0
    data = json.loads(result.stdout)
    assert data["robot"] == "fishbot"
    assert len(data["links"]) == 11
    assert data["total"]["mass"] == pytest.approx(1.41)
    assert data["total"]["frame"] == "base_footprint"
    # One vocabulary with `fishbot check --format json`: findings are "diagnostics".
    assert data["ok"] is True and data["diagnostics"] == []
    assert all(row["rules"] == [] for row in data["links"])


def test_json_is_asked_for_one_way() -> None:
    result = run(str(XACRO), "--json")
    assert result.exit_code == 2
    assert "No such option '--json'" in result.stderr


def test_a_robot_with_errors_is_tabled_with_its_findings() -> None:
    result = run(str(PHYSICS / "massless_wheel.urdf"))
    assert result.exit_code == 1
    row = next(line for line in result.stdout.splitlines() if line.startswith("left_wheel_link"))
    assert row.endswith("massless-link")
    assert "[massless-link]" in result.stderr


def _inertial_of(path: Path, link: str) -> fishbot_urdf.Inertial | None:
    return fishbot_urdf.load(path).link(link).inertial


def test_fill_adds_the_missing_inertial_and_keeps_the_input(tmp_path: Path) -> None:
    source = tmp_path / "robot.urdf"
    shutil.copy(PHYSICS / "missing_inertial.urdf", source)
    before = source.read_bytes()
    out = tmp_path / "filled.urdf"
    result = run(str(source), "--fill", "--mass", "left_wheel_link=0.1", "-o", str(out))
    assert result.exit_code == 0, result.output
    assert result.stderr == f"Wrote {out}: <inertial> added to 1 link: left_wheel_link (0.1 kg)\n"
    assert source.read_bytes() == before
    expected = cylinder_inertia(0.1, 0.032, 0.04, fishbot_urdf.Origin(rpy=(1.57079, 0.0, 0.0)))
    assert _inertial_of(out, "left_wheel_link") == expected
    text = out.read_text()
    assert "<!-- The left wheel has a collision shape" in text  # comments kept
    checked = CliRunner().invoke(cli, ["check", str(out)])
    assert (checked.exit_code, checked.stderr) == (0, "")


def test_fill_by_density(tmp_path: Path) -> None:
    out = tmp_path / "filled.urdf"
    result = run(
        str(PHYSICS / "missing_inertial.urdf"), "--fill", "--density", "1000", "-o", str(out)
    )
    assert result.exit_code == 0, result.output
    made = _inertial_of(out, "left_wheel_link")
    assert made is not None
    assert made.mass == pytest.approx(1000 * math.pi * 0.032**2 * 0.04)


def test_fill_to_stdout_from_stdin() -> None:
    data = (PHYSICS / "missing_inertial.urdf").read_bytes()
    result = run("-", "--fill", "--density", "1000", "-o", "-", stdin=data)
    assert result.exit_code == 0, result.output
    robot = fishbot_urdf.parse(result.stdout_bytes)
    assert robot.link("left_wheel_link").inertial is not None
    assert "standard output" in result.stderr


def test_fill_never_writes_over_the_input_nor_its_includes(tmp_path: Path) -> None:
    source = tmp_path / "robot.urdf"
    shutil.copy(PHYSICS / "missing_inertial.urdf", source)
    before = source.read_bytes()
    result = run(str(source), "--fill", "--density", "1000", "-o", str(source))
    assert result.exit_code == 2
    assert "refusing to write over the input" in result.stderr
    assert source.read_bytes() == before
    copy = tmp_path / "fishbot"
    shutil.copytree(FISHBOT / "urdf" / "fishbot", copy)
    include = copy / "base.urdf.xacro"
    before = include.read_bytes()
    result = run(
        str(copy / "fishbot.urdf.xacro"), "--fill", "--density", "1000", "-o", str(include)
    )
    assert result.exit_code == 2
    assert include.read_bytes() == before


def test_fill_from_xacro_writes_the_expanded_urdf(tmp_path: Path) -> None:
    out = tmp_path / "fishbot.urdf"
    result = run(str(XACRO), "--fill", "--density", "1000", "-o", str(out))
    assert result.exit_code == 0, result.output
    assert result.stderr == f"Wrote {out}: no link needed an <inertial>\n"
    assert fishbot_urdf.load(out) == fishbot_urdf.load(XACRO)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--fill", "-o", "x.urdf"], "--density"),
        (["--density", "1"], "go with --fill"),
        (["--fill", "--density", "1", "-o", "x.urdf", "--format", "json"], "no --format"),
        (["--fill", "--mass", "left_wheel=1", "-o", "x.urdf"], "did you mean 'left_wheel_link'"),
        (["--fill", "--mass", "base_link=1", "-o", "x.urdf"], "already has an <inertial>"),
        (["--fill", "--mass", "base_footprint=1", "-o", "x.urdf"], "no <collision> shape"),
        (["--fill", "--mass", "left_wheel_link=-1", "-o", "x.urdf"], "LINK=KG with KG > 0"),
    ],
)
def test_fill_usage_errors(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, args: list[str], words: str
) -> None:
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(cli, ["inertia", str(PHYSICS / "missing_inertial.urdf"), *args])
    assert result.exit_code == 2
    assert words in result.output
    assert not (tmp_path / "x.urdf").exists()


def test_a_usage_error_of_the_robot_form_hints_at_a_command_that_works() -> None:
    # The user typed a file, not the form's internal name `robot`.
    result = run(str(PHYSICS / "missing_inertial.urdf"), "--fill")
    assert result.exit_code == 2
    assert result.stderr == (
        "Usage: fishbot inertia ROBOT [name:=value]... [OPTIONS]\n"
        "Try 'fishbot inertia --help' for help.\n\n"
        "Error: --fill needs --density KG_PER_M3 or --mass LINK=KG\n"
    )


def test_fill_skips_a_mesh_and_says_so(tmp_path: Path) -> None:
    source = tmp_path / "mesh.urdf"
    source.write_text(
        '<robot name="m"><link name="a"/><link name="b"><collision><geometry>'
        '<mesh filename="package://demo/b.stl"/></geometry></collision></link>'
        '<joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>'
    )
    out = tmp_path / "out.urdf"
    result = run(str(source), "--fill", "--density", "1000", "-o", str(out))
    assert result.exit_code == 1
    assert f"{source}:1:" in result.stderr
    # package://demo is found nowhere: the mesh cannot be read.
    assert "link 'b': no <inertial> added (package 'demo' not found" in result.stderr
    assert "error: link 'b': no <inertial> added (" in result.stderr
    assert "[fill-skipped]" in result.stderr
    assert "nothing written: no link could be filled" in result.stderr
    assert not out.exists()


def _fishbot_without(tmp_path: Path, name: str, call: str) -> tuple[Path, Path]:
    """A copy of the fishbot package with ``call`` taken out of its file ``name``: the
    robot, and the file."""
    copy = tmp_path / "fishbot"
    shutil.copytree(FISHBOT, copy)
    edited = copy / "urdf" / "fishbot" / name
    text = edited.read_text()
    assert call in text
    edited.write_text(text.replace(call, ""))
    return copy / "urdf" / "fishbot" / "fishbot.urdf.xacro", edited


def _pasted(path: Path, line: int, text: str) -> None:
    """``text`` written into ``path`` at ``line`` (the line there and those below move down)."""
    lines = path.read_text().splitlines(keepends=True)
    lines.insert(line - 1, text)
    path.write_text("".join(lines))


def _same_inertial(made: fishbot_urdf.Inertial | None, wanted: fishbot_urdf.Inertial) -> None:
    assert made is not None
    assert made.origin.xyz == pytest.approx(wanted.origin.xyz)
    assert made.origin.rpy == pytest.approx(wanted.origin.rpy)
    assert made.mass == pytest.approx(wanted.mass, rel=1e-5)
    for moment in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
        got, expected = getattr(made.inertia, moment), getattr(wanted.inertia, moment)
        assert got == pytest.approx(expected, rel=1e-5, abs=1e-15)


def test_fill_without_output_says_which_macro_call_to_write_and_where(tmp_path: Path) -> None:
    call = '<xacro:cylinder_inertia m="${mass}" r="${radius}" h="${length}"/>'
    robot, base = _fishbot_without(tmp_path, "base.urdf.xacro", call)
    before = base.read_bytes()
    result = run(str(robot), "--fill", "--mass", "base_link=1.5")
    assert result.exit_code == 0, result.output
    assert result.stderr == ""
    assert base.read_bytes() == before  # nothing is written
    # base.urdf.xacro: <link name="base_link"> is line 24 of the macro base_xacro, which
    # fishbot.urdf.xacro calls on its line 56.
    assert result.stdout == (
        f"{base}:24:5: note: link 'base_link' has no <inertial>; for 1.5 kg, write at line 25, "
        f"inside the <link>, in the body of macro base_xacro (called at {robot}:56:3):\n"
        '  <xacro:cylinder_inertia m="1.5" r="0.1" h="0.12"/>\n'
        "  or, with the sizes as the macro's body writes them, to fit every call:\n"
        '  <xacro:cylinder_inertia m="1.5" r="${radius}" h="${length}"/>\n'
    )
    # The numbers by hand: a solid cylinder of radius 0.1 m and height 0.12 m about its
    # centre, 1/12 m (3 r^2 + h^2) across its axis and 1/2 m r^2 along it.
    data = json.loads(
        run(str(robot), "--fill", "--mass", "base_link=1.5", "--format", "json").stdout
    )
    (made,) = data["suggestions"]
    assert made["macro"]["name"] == "cylinder_inertia"
    assert made["arguments"] == {"m": "1.5", "r": "0.1", "h": "0.12"}
    assert (made["source"]["path"], made["source"]["line"], made["line"]) == (str(base), 24, 25)
    assert made["made_by"] == [
        {"macro": "base_xacro", "call": {"path": str(robot), "line": 56, "column": 3}}
    ]
    moments = made["inertial"]["inertia"]
    assert moments["ixx"] == pytest.approx(1.5 / 12 * (3 * 0.1**2 + 0.12**2))
    assert moments["iyy"] == pytest.approx(1.5 / 12 * (3 * 0.1**2 + 0.12**2))
    assert moments["izz"] == pytest.approx(1.5 / 2 * 0.1**2)
    assert made["inertial"]["mass"] == 1.5
    # Pasted there, the call gives what -o writes.
    out = tmp_path / "filled.urdf"
    assert run(str(robot), "--fill", "--mass", "base_link=1.5", "-o", str(out)).exit_code == 0
    wanted = _inertial_of(out, "base_link")
    assert wanted is not None
    _pasted(base, made["line"], "      " + made["text"])
    _same_inertial(_inertial_of(robot, "base_link"), wanted)
    again = run(str(robot), "--fill", "--mass", "base_link=1.5")
    assert again.exit_code == 2  # base_link has its inertial now
    assert "already has an <inertial>" in again.output


def test_fill_without_output_turns_a_wheels_inertia_with_it(tmp_path: Path) -> None:
    call = """<xacro:cylinder_inertia m="${mass}" r="${radius}" h="${length}"
                              xyz="0.0 0.0 0.0" rpy="1.57079 0.0 0.0"/>"""
    robot, wheel = _fishbot_without(tmp_path, "actuator/wheel.urdf.xacro", call)
    result = run(str(robot), "--fill", "--density", "1000")
    assert result.exit_code == 0, result.output
    mass = 1000 * math.pi * 0.032**2 * 0.04  # kg: 0.128680 to six digits
    assert f"{mass:.6g}" == "0.12868"
    # One line of wheel_xacro's body makes both wheels: one note, one call for both.
    assert result.stdout == (
        f"{wheel}:11:5: note: links 'left_wheel_link', 'right_wheel_link' have no "
        "<inertial>; the body of macro wheel_xacro makes each of them (called at "
        f"{robot}:63:3, {robot}:65:3): write at line 12, inside the <link>, once, to fit "
        "every call:\n"
        '  <xacro:cylinder_inertia m="${mass}" r="${radius}" h="${length}" '
        'rpy="1.57079 0.0 0.0"/>\n'
        "  its mass is wheel_xacro's parameter mass, as each call gives it:\n"
        f"    left_wheel_link (0.12868 kg): the call at {robot}:63:3 gives "
        'mass="${wheel_mass}" (0.1); write mass="0.12868" there\n'
        f"    right_wheel_link (0.12868 kg): the call at {robot}:65:3 gives "
        'mass="${wheel_mass}" (0.1); write mass="0.12868" there\n'
    )
    out = tmp_path / "filled.urdf"
    assert run(str(robot), "--fill", "--density", "1000", "-o", str(out)).exit_code == 0
    _pasted(
        wheel,
        12,
        '      <xacro:cylinder_inertia m="${mass}" r="${radius}" h="${length}" '
        'rpy="1.57079 0.0 0.0"/>\n',
    )
    robot.write_text(robot.read_text().replace('mass="${wheel_mass}"', 'mass="0.12868"'))
    for side in ("left", "right"):
        wanted = _inertial_of(out, f"{side}_wheel_link")
        assert wanted is not None
        assert wanted.mass == pytest.approx(mass)
        _same_inertial(_inertial_of(robot, f"{side}_wheel_link"), wanted)
    # The real xacro command reads the pasted call as this expansion does.
    done = xacro_command(robot, packages={"fishbot_description": tmp_path / "fishbot"})
    assert done.returncode == 0, done.stderr
    expanded = fishbot_urdf.parse(done.stdout)
    _same_inertial(expanded.link("left_wheel_link").inertial, wanted)


WHEEL_CALL = """<xacro:cylinder_inertia m="${mass}" r="${radius}" h="${length}"
                              xyz="0.0 0.0 0.0" rpy="1.57079 0.0 0.0"/>"""


def test_fill_gives_the_links_of_one_macro_one_call_through_its_mass_parameter(
    tmp_path: Path,
) -> None:
    # wheel_xacro makes both wheels on one line of its body: one line cannot hold two
    # masses, so the call writes its parameter mass, and the right wheel's call changes.
    robot, wheel = _fishbot_without(tmp_path, "actuator/wheel.urdf.xacro", WHEEL_CALL)
    args = ("--fill", "--mass", "left_wheel_link=0.1", "--mass", "right_wheel_link=0.2")
    result = run(str(robot), *args)
    assert result.exit_code == 0, result.output
    assert result.stdout == (
        f"{wheel}:11:5: note: links 'left_wheel_link', 'right_wheel_link' have no "
        "<inertial>; the body of macro wheel_xacro makes each of them (called at "
        f"{robot}:63:3, {robot}:65:3): write at line 12, inside the <link>, once, to fit "
        "every call:\n"
        '  <xacro:cylinder_inertia m="${mass}" r="${radius}" h="${length}" '
        'rpy="1.57079 0.0 0.0"/>\n'
        "  its mass is wheel_xacro's parameter mass, as each call gives it:\n"
        f"    left_wheel_link (0.1 kg): the call at {robot}:63:3 gives "
        'mass="${wheel_mass}" (0.1), as it should\n'
        f"    right_wheel_link (0.2 kg): the call at {robot}:65:3 gives "
        'mass="${wheel_mass}" (0.1); write mass="0.2" there\n'
    )
    data = json.loads(run(str(robot), *args, "--format", "json").stdout)
    assert [s["link"] for s in data["suggestions"]] == ["left_wheel_link", "right_wheel_link"]
    (shared,) = data["shared"]
    assert shared == {
        "links": ["left_wheel_link", "right_wheel_link"],
        "source": {"path": str(wheel), "line": 11, "column": 5},
        "line": 12,
        "macro": "wheel_xacro",
        "text": '<xacro:cylinder_inertia m="${mass}" r="${radius}" h="${length}" '
        'rpy="1.57079 0.0 0.0"/>\n',
        "arguments": {"m": "${mass}", "r": "${radius}", "h": "${length}", "rpy": "1.57079 0.0 0.0"},
        "mass_parameter": "mass",
        "add_parameter": None,
        "fits_every_call": True,
        "one_site": False,
        "calls": [
            {
                "link": "left_wheel_link",
                "call": {"path": str(robot), "line": 63, "column": 3},
                "mass": 0.1,
                "argument": "${wheel_mass}",
                "value": 0.1,
                "write": None,
                "outer": None,
            },
            {
                "link": "right_wheel_link",
                "call": {"path": str(robot), "line": 65, "column": 3},
                "mass": 0.2,
                "argument": "${wheel_mass}",
                "value": 0.1,
                "write": 'mass="0.2"',
                "outer": None,
            },
        ],
    }
    # Done as said, each wheel has the mass asked for, and one <inertial>.
    out = tmp_path / "filled.urdf"
    assert run(str(robot), *args, "-o", str(out)).exit_code == 0
    _pasted(wheel, 12, "      " + shared["text"])
    right = '<xacro:wheel_xacro name="right"'
    text = robot.read_text()
    at = text.index(right)
    robot.write_text(text[:at] + text[at:].replace('mass="${wheel_mass}"', 'mass="0.2"', 1))
    for side in ("left", "right"):
        wanted = _inertial_of(out, f"{side}_wheel_link")
        assert wanted is not None
        assert wanted.mass == {"left": 0.1, "right": 0.2}[side]
        _same_inertial(_inertial_of(robot, f"{side}_wheel_link"), wanted)
    checked = CliRunner().invoke(cli, ["check", str(robot)])
    assert checked.exit_code == 0, checked.output


def test_fill_asks_for_a_mass_parameter_when_a_macro_has_none(tmp_path: Path) -> None:
    (tmp_path / "inertias.xacro").write_text(COMMON.read_text())
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="inertias.xacro"/>\n'
        '  <link name="base"/>\n'
        '  <xacro:macro name="leg" params="name">\n'
        '    <link name="${name}">\n'
        "      <collision>\n"
        '        <geometry><box size="0.1 0.2 0.3"/></geometry>\n'
        "      </collision>\n"
        "    </link>\n"
        '    <joint name="${name}_j" type="fixed"><parent link="base"/>'
        '<child link="${name}"/></joint>\n'
        "  </xacro:macro>\n"
        '  <xacro:leg name="a"/>\n'
        '  <xacro:leg name="b"/>\n'
        "</robot>\n"
    )
    result = run(str(robot), "--fill", "--mass", "a=1", "--mass", "b=2")
    assert result.exit_code == 0, result.output
    assert result.stdout == (
        f"{robot}:5:5: note: links 'a', 'b' have no <inertial>; the body of macro leg makes "
        f"each of them (called at {robot}:12:3, {robot}:13:3): write at line 6, inside the "
        "<link>, once, to fit every call:\n"
        '  <xacro:box_inertia m="${mass}" w="0.1" h="0.2" d="0.3"/>\n'
        "  leg has no parameter for the mass, and the links' masses differ (1 kg, 2 kg): add "
        f'mass to its params (at {robot}:4:3: params="name mass"), and give it in each '
        "call:\n"
        f'    a (1 kg): the call at {robot}:12:3 gives none; write mass="1" there\n'
        f'    b (2 kg): the call at {robot}:13:3 gives none; write mass="2" there\n'
    )
    # The same mass for both needs no parameter.
    same = run(str(robot), "--fill", "--mass", "a=1", "--mass", "b=1")
    assert same.stdout.endswith(
        '  <xacro:box_inertia m="1" w="0.1" h="0.2" d="0.3"/>\n  (every link is 1 kg)\n'
    )
    # Done as said, each link has its own mass.
    out = tmp_path / "filled.urdf"
    assert (
        run(str(robot), "--fill", "--mass", "a=1", "--mass", "b=2", "-o", str(out)).exit_code == 0
    )
    text = robot.read_text().replace('params="name"', 'params="name mass"')
    text = text.replace('name="a"/>', 'name="a" mass="1"/>')
    text = text.replace('name="b"/>', 'name="b" mass="2"/>')
    robot.write_text(text)
    _pasted(robot, 6, '      <xacro:box_inertia m="${mass}" w="0.1" h="0.2" d="0.3"/>\n')
    for name, kg in (("a", 1.0), ("b", 2.0)):
        wanted = _inertial_of(out, name)
        assert wanted is not None
        assert wanted.mass == kg
        _same_inertial(_inertial_of(robot, name), wanted)


def test_fill_without_output_on_a_urdf_gives_the_inertial_block() -> None:
    robot = PHYSICS / "missing_inertial.urdf"
    result = run(str(robot), "--fill", "--mass", "left_wheel_link=0.1")
    assert result.exit_code == 0, result.output
    expected = cylinder_inertia(0.1, 0.032, 0.04, fishbot_urdf.Origin(rpy=(1.57079, 0.0, 0.0)))
    assert result.stdout == (
        f"{robot}:19:3: note: link 'left_wheel_link' has no <inertial>; for 0.1 kg, write at "
        "line 20, inside the <link>:\n"
        + "".join(f"  {line}\n" for line in fishbot_urdf.inertial_xml(expected).splitlines())
    )
    data = json.loads(
        run(str(robot), "--fill", "--mass", "left_wheel_link=0.1", "--format", "json").stdout
    )
    (made,) = data["suggestions"]
    assert (made["macro"], made["arguments"], made["line"]) == (None, None, 20)
    assert made["text"] == fishbot_urdf.inertial_xml(expected)


def test_fill_without_output_on_a_xacro_without_inertia_macros(tmp_path: Path) -> None:
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="side" value="0.2"/>\n'
        '  <link name="a"/>\n'
        '  <link name="b">\n'
        "    <collision>\n"
        '      <geometry><box size="${side} 0.1 0.1"/></geometry>\n'
        "    </collision>\n"
        "  </link>\n"
        '  <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint>\n'
        "</robot>\n"
    )
    result = run(str(robot), "--fill", "--mass", "b=2")
    assert result.exit_code == 0, result.output
    expected = box_inertia(2.0, 0.2, 0.1, 0.1)
    assert result.stdout == (
        f"{robot}:4:3: note: link 'b' has no <inertial>; for 2 kg, write at line 5, inside the "
        "<link>:\n"
        + "".join(f"  {line}\n" for line in fishbot_urdf.inertial_xml(expected).splitlines())
        + "  (written out: no inertia macros)\n"
    )


def test_fill_without_output_on_a_full_robot_and_on_standard_input() -> None:
    full = run(str(XACRO), "--fill", "--density", "1000")
    assert (full.exit_code, full.stdout, full.stderr) == (0, "", "no link needs an <inertial>\n")
    data = (PHYSICS / "missing_inertial.urdf").read_bytes()
    piped = run("-", "--fill", "--mass", "left_wheel_link=0.1", stdin=data)
    assert piped.exit_code == 0, piped.output
    assert piped.stdout.startswith(
        "<stdin>:19:3: note: link 'left_wheel_link' has no <inertial>; for 0.1 kg, write at "
        "line 20, inside the <link>:\n  <inertial>\n"
    )


def test_the_missing_inertial_hint_names_fill() -> None:
    command = ["check", "--target", "gazebo", str(PHYSICS / "missing_inertial.urdf")]
    result = CliRunner().invoke(cli, command)
    assert result.exit_code == 1
    assert (
        "`fishbot inertia ROBOT --fill --mass LINK=KG` says what to write and where, and with "
        "-o OUT writes a filled copy) [missing-inertial]" in result.stderr
    )


def test_fill_without_output_skips_as_fill_does() -> None:
    result = run(str(PHYSICS / "missing_inertial.urdf"), "--fill", "--mass", "base_link=1")
    assert result.exit_code == 2
    assert "already has an <inertial>" in result.output
    mesh = run(str(PHYSICS / "triangle.urdf"), "--fill", "--density", "1000")
    assert mesh.exit_code == 1
    assert "nothing to suggest: fix the errors above first" in mesh.stderr
    assert mesh.stdout == ""


def test_box_inertia_is_the_one_fill_uses_for_a_box(tmp_path: Path) -> None:
    source = tmp_path / "box.urdf"
    source.write_text(
        '<robot name="b"><link name="a"/><link name="b"><collision><geometry>'
        '<box size="0.3 0.2 0.1"/></geometry></collision></link>'
        '<joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>'
    )
    out = tmp_path / "out.urdf"
    assert run(str(source), "--fill", "--mass", "b=2", "-o", str(out)).exit_code == 0
    assert _inertial_of(out, "b") == box_inertia(2.0, 0.3, 0.2, 0.1)


def test_options_may_come_before_the_robot() -> None:
    result = run("--format", "json", str(XACRO))
    assert result.exit_code == 0
    assert json.loads(result.stdout)["robot"] == "fishbot"


@pytest.mark.parametrize(
    ("word", "guess"), [("cube", ""), ("cylnder", "did you mean 'cylinder'? ")]
)
def test_a_mistyped_shape_is_named(word: str, guess: str) -> None:
    result = run(word, "--mass", "1")
    assert result.exit_code == 2
    assert f"no shape or file {word!r} ({guess}shapes: box, cylinder, sphere)" in result.stderr


@pytest.mark.parametrize(
    "args",
    [
        ["sphere", "--mass", "1", "--radius", "0"],
        ["cylinder", "--mass", "1", "--radius", "0.1", "--length", "0"],
        ["sphere", "--mass", "1", "--radius", "1e200"],
        ["sphere", "--mass", "1", "--radius", "0.1", "--xyz", "nan", "0", "0"],
        ["sphere", "--mass", "1", "--radius", "0.1", "--rpy", "inf", "0", "0"],
    ],
)
def test_shapes_take_real_sizes_only(args: list[str]) -> None:
    result = run(*args)
    assert result.exit_code == 2
    assert result.stdout == ""


@pytest.mark.parametrize(
    ("args", "said"),
    [
        (
            ["sphere", "--mass", "1", "--radius", "1e-200"],
            "the sphere's inertia underflows to 0 kg*m^2 (radius 1e-200 m, mass 1 kg)",
        ),
        (
            ["box", "--mass", "1", "--size", "1e-200", "1e-200", "1"],
            "the box's inertia underflows to 0 kg*m^2 (x 1e-200 m, y 1e-200 m, z 1 m, mass 1 kg)",
        ),
        (
            ["cylinder", "--mass", "1e-300", "--radius", "1e-5", "--length", "1e-5"],
            "the cylinder's inertia underflows to 3.33333e-311 kg*m^2 (radius 1e-05 m, "
            "length 1e-05 m, mass 1e-300 kg)",
        ),
    ],
)
def test_a_shape_whose_inertia_underflows_is_a_usage_error(args: list[str], said: str) -> None:
    # As a size of 0 is: a value given on the command line that has no inertia to print.
    result = run(*args)
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr.endswith(
        f"Error: {said}: too small for a float; give a larger size or mass\n"
    )


def test_fill_leaves_out_a_link_whose_inertia_underflows(tmp_path: Path) -> None:
    robot = tmp_path / "dust.urdf"
    robot.write_text(
        '<robot name="r">\n  <link name="dust"><collision><geometry><sphere radius="1e-100"/>'
        "</geometry></collision></link>\n</robot>\n"
    )
    out = tmp_path / "filled.urdf"
    result = run(str(robot), "--fill", "--density", "1000", "-o", str(out))
    assert (result.exit_code, result.stdout) == (1, "")
    assert result.stderr == (
        f"{robot}:2:3: error: link 'dust': no <inertial> added (the sphere's inertia underflows "
        "to 0 kg*m^2 (radius 1e-100 m, mass 4.18879e-297 kg): too small for a float; give a "
        "larger size or mass) [fill-skipped]\nnothing written: no link could be filled\n"
    )
    assert not out.exists()


def test_degrees_for_rpy_draw_a_warning() -> None:
    result = run("sphere", "--mass", "1", "--radius", "0.1", "--rpy", "90", "0", "0")
    assert result.exit_code == 0
    assert "if 90 0 0 are degrees, write --rpy 1.5708 0 0" in result.stderr


def test_xacro_on_standard_input_is_refused_with_the_way_out() -> None:
    result = run("-", stdin=XACRO.read_bytes())
    assert result.exit_code == 2
    assert "standard input is read as URDF, and this is xacro" in result.stderr
    assert result.stdout == ""


def test_a_robot_without_mass() -> None:
    result = run(str(FISHBOT / "urdf" / "first_robot.urdf"))
    assert result.exit_code == 0
    assert result.stdout.splitlines()[-1] == "total: 0 kg (no link has a mass)"
    data = json.loads(run(str(FISHBOT / "urdf" / "first_robot.urdf"), "--format", "json").stdout)
    assert data["total"]["com"] is None
    assert data["ok"] is True
    assert data["diagnostics"] == []


def test_the_table_names_the_link_the_robot_floats_on() -> None:
    result = run(str(PHYSICS / "floating.urdf"))
    row = next(line for line in result.stdout.splitlines() if line.startswith("left_wheel_link"))
    assert row.endswith("above-ground")


def test_links_in_a_loop_are_said_to_be_left_out(tmp_path: Path) -> None:
    path = tmp_path / "loop.urdf"
    path.write_text(
        '<robot name="l"><link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" '
        'ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link><link name="b"/><link name="c"/>'
        '<joint name="j1" type="fixed"><parent link="b"/><child link="c"/></joint>'
        '<joint name="j2" type="fixed"><parent link="c"/><child link="b"/></joint></robot>'
    )
    result = run(str(path))
    assert result.exit_code == 1
    assert (
        result.stdout.splitlines()[-1] == "left out of the total, not reached from the root: b, c"
    )


def test_fill_stops_on_a_robot_with_errors(tmp_path: Path) -> None:
    out = tmp_path / "t.urdf"
    result = run(str(PHYSICS / "triangle.urdf"), "--fill", "--density", "1000", "-o", str(out))
    assert result.exit_code == 1
    assert "[inertia-triangle]" in result.stderr
    assert "nothing written: fix the errors above first" in result.stderr
    assert not out.exists()


def test_fill_refuses_json_and_a_link_given_twice(tmp_path: Path) -> None:
    robot = str(PHYSICS / "missing_inertial.urdf")
    out = str(tmp_path / "o.urdf")
    assert run(robot, "--fill", "--density", "1", "-o", out, "--format", "json").exit_code == 2
    twice = run(
        robot, "--fill", "--mass", "left_wheel_link=1", "--mass", "left_wheel_link=2", "-o", out
    )
    assert twice.exit_code == 2
    assert "link 'left_wheel_link' is given twice" in twice.output


def test_a_full_disk_is_one_line_and_status_2() -> None:
    import subprocess
    import sys

    if not Path("/dev/full").exists():
        pytest.skip("this system has no /dev/full to fill")
    for args in (["inertia", "box", "--mass", "1", "--size", "1", "1", "1"], ["check", str(XACRO)]):
        with open("/dev/full", "wb") as full:
            proc = subprocess.run(
                [sys.executable, "-m", "fishbot_urdf", *args],
                stdout=full,
                stderr=subprocess.PIPE,
                text=True,
                check=False,
            )
        assert proc.returncode == 2, proc.stderr
        assert proc.stderr == "<stdout>: error: cannot write: No space left on device [io]\n"


ARM_WITH_MASS = """\
<robot name="arm">
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm"><inertial><origin xyz="1 0 0"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
</robot>
"""


def test_joint_positions_move_the_total_centre_of_mass(tmp_path: Path) -> None:
    # Two 1 kg masses, one at the base's origin, one 1 m out along the arm: the centre of
    # mass is halfway, at (0.5, 0, 0); with the shoulder turned 90 degrees about z the arm's
    # mass is at (0, 1, 0), so the centre is at (0, 0.5, 0).
    path = tmp_path / "arm.urdf"
    path.write_text(ARM_WITH_MASS, encoding="utf-8")
    zero = CliRunner().invoke(cli, ["inertia", str(path), "--format", "json"])
    assert json.loads(zero.stdout)["total"]["com"] == [0.5, 0.0, 0.0]
    for given in ("shoulder=90deg", f"shoulder={math.pi / 2}"):
        turned = CliRunner().invoke(cli, ["inertia", str(path), "-j", given, "--format", "json"])
        report = json.loads(turned.stdout)
        assert report["total"]["com"] == pytest.approx([0.0, 0.5, 0.0], abs=1e-12)
        assert report["positions"] == {"shoulder": pytest.approx(math.pi / 2)}
    text = CliRunner().invoke(cli, ["inertia", str(path), "-j", "shoulder=90deg"]).stdout
    assert "com x y z (m, link frame)" in text.splitlines()[0]
    assert text.rstrip().endswith("(joints at shoulder=1.571, the rest at zero)")


@pytest.mark.parametrize(
    ("given", "said"),
    [
        ("shoulder=3", "joint 'shoulder': position 3 is outside its limits -2 .. 2"),
        ("shouldr=1", "no joint 'shouldr' (did you mean 'shoulder'?"),
        ("shoulder", "'shoulder' is not NAME=VALUE with a number VALUE"),
    ],
)
def test_a_wrong_joint_position_is_a_usage_error(tmp_path: Path, given: str, said: str) -> None:
    path = tmp_path / "arm.urdf"
    path.write_text(ARM_WITH_MASS, encoding="utf-8")
    result = CliRunner().invoke(cli, ["inertia", str(path), "-j", given])
    assert result.exit_code == 2
    assert said in result.stderr


def test_a_fixed_joint_is_said_to_be_fixed() -> None:
    result = CliRunner().invoke(cli, ["inertia", str(XACRO), "-j", "imu_joint=1"])
    assert result.exit_code == 2
    assert "joint 'imu_joint' is fixed: it takes no position" in result.stderr


def test_fill_says_when_no_one_call_fits_the_links_of_a_macro(tmp_path: Path) -> None:
    # arm's <link> holds a collision tube's body writes: arm's body writes no size that
    # one call could take, and the two arms differ in length.
    (tmp_path / "inertias.xacro").write_text(COMMON.read_text())
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="inertias.xacro"/>\n'
        '  <link name="base"/>\n'
        '  <xacro:macro name="arm" params="name len">\n'
        '    <link name="${name}">\n'
        '      <xacro:tube r="0.02" h="${len}"/>\n'
        "    </link>\n"
        '    <joint name="${name}_j" type="fixed"><parent link="base"/>'
        '<child link="${name}"/></joint>\n'
        "  </xacro:macro>\n"
        '  <xacro:macro name="tube" params="r h">\n'
        "    <collision>\n"
        '      <geometry><cylinder radius="${r}" length="${h}"/></geometry>\n'
        "    </collision>\n"
        "  </xacro:macro>\n"
        '  <xacro:arm name="a" len="0.3"/>\n'
        '  <xacro:arm name="b" len="0.4"/>\n'
        "</robot>\n"
    )
    result = run(str(robot), "--fill", "--mass", "a=1", "--mass", "b=2")
    assert result.exit_code == 0, result.output
    assert result.stdout == (
        f"{robot}:5:5: note: links 'a', 'b' have no <inertial>; the body of macro arm makes "
        f"each of them (called at {robot}:15:3, {robot}:16:3): write inside the <link>:\n"
        "  no one call fits every call: the sizes differ from call to call, and the macro's "
        "body does not write them; each link's own call fits its call only:\n"
        '  a: <xacro:cylinder_inertia m="1" r="0.02" h="0.3"/>\n'
        '  b: <xacro:cylinder_inertia m="2" r="0.02" h="0.4"/>\n'
    )
    data = json.loads(
        run(str(robot), "--fill", "--mass", "a=1", "--mass", "b=2", "--format", "json").stdout
    )
    (shared,) = data["shared"]
    assert (shared["links"], shared["fits_every_call"], shared["line"]) == (["a", "b"], False, None)


def test_a_second_inertial_a_macro_call_made_names_the_calls(tmp_path: Path) -> None:
    # Two masses pasted on one line of wheel_xacro's body: the second <inertial> is written
    # in common_inertia.xacro, and the warning names the pasted call that made it.
    robot, wheel = _fishbot_without(tmp_path, "actuator/wheel.urdf.xacro", WHEEL_CALL)
    _pasted(
        wheel,
        12,
        '      <xacro:cylinder_inertia m="0.1" r="${radius}" h="${length}"/>\n'
        '      <xacro:cylinder_inertia m="0.2" r="${radius}" h="${length}"/>\n',
    )
    result = CliRunner().invoke(cli, ["check", "-q", str(robot)])
    common = tmp_path / "fishbot" / "urdf" / "fishbot" / "common_inertia.xacro"
    warnings = [line for line in result.stderr.splitlines() if "[duplicate-element]" in line]
    assert warnings == [
        f"{common}:23:5: warning: link '{side}_wheel_link': a second <inertial> is ignored; "
        f"it is made by macro cylinder_inertia called at {wheel}:13, in macro wheel_xacro "
        f"called at {robot}:{line} (a link has at most one <inertial>) [duplicate-element]"
        for side, line in (("left", 63), ("right", 65))
    ]


def test_fill_sends_each_mass_through_the_outer_calls_of_a_call_written_once(
    tmp_path: Path,
) -> None:
    # leg is called on one line of side's body: the argument there is the same text for
    # both legs, so each leg's mass comes in through side's calls.
    (tmp_path / "inertias.xacro").write_text(COMMON.read_text())
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="inertias.xacro"/>\n'
        '  <link name="base"/>\n'
        '  <xacro:macro name="leg" params="name mass">\n'
        '    <link name="${name}">\n'
        "      <collision>\n"
        '        <geometry><box size="0.1 0.2 0.3"/></geometry>\n'
        "      </collision>\n"
        "    </link>\n"
        '    <joint name="${name}_j" type="fixed"><parent link="base"/>'
        '<child link="${name}"/></joint>\n'
        "  </xacro:macro>\n"
        '  <xacro:macro name="side" params="name m">\n'
        '    <xacro:leg name="${name}_leg" mass="${m}"/>\n'
        "  </xacro:macro>\n"
        '  <xacro:side name="a" m="1"/>\n'
        '  <xacro:side name="b" m="1"/>\n'
        "</robot>\n"
    )
    args = ("--fill", "--mass", "a_leg=1", "--mass", "b_leg=2")
    result = run(str(robot), *args)
    assert result.exit_code == 0, result.output
    assert result.stdout == (
        f"{robot}:5:5: note: links 'a_leg', 'b_leg' have no <inertial>; the body of macro leg "
        f"makes each of them (called at {robot}:13:5): write at line 6, inside the <link>, "
        "once, to fit every call:\n"
        '  <xacro:box_inertia m="${mass}" w="0.1" h="0.2" d="0.3"/>\n'
        f"  its mass is leg's parameter mass; the call at {robot}:13:5 that gives it is "
        "written once in the body of macro side, for all of its calls: give each link its "
        f"mass through them (a_leg 1 kg at {robot}:15:3; b_leg 2 kg at {robot}:16:3)\n"
    )
    (shared,) = json.loads(run(str(robot), *args, "--format", "json").stdout)["shared"]
    assert shared["one_site"] is True
    assert [c["write"] for c in shared["calls"]] == [None, None]
    assert [c["outer"]["call"]["line"] for c in shared["calls"]] == [15, 16]
