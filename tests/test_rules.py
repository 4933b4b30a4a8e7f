"""The rule registry: every rule documented, its examples checked, every rule id the code can
report registered, `fishbot rules`, and the documentation's rule list made from the registry."""

from __future__ import annotations

import dataclasses
import importlib
import json
import pkgutil
import re
import shlex
from collections.abc import Iterator
from pathlib import Path

import pytest
from click.testing import CliRunner, Result
from conftest import ARM, ROOT, box_stl, fine_stl, require_tool, run_check_urdf

import fishbot_urdf
from fishbot_urdf.catalog import Family, Rule, all_rules, get, ids
from fishbot_urdf.catalog.docs import (
    README_BEGIN,
    README_END,
    explanation,
    markdown_table,
    table,
    with_rule_table,
)
from fishbot_urdf.cli import cli
from fishbot_urdf.diagnostics import Severity
from fishbot_urdf.errors import ArgumentError, FishbotUrdfError

RULES = all_rules()
ROBOT_RULES = [r for r in RULES if r.language in ("urdf", "xacro")]
SETUP_RULES = [r for r in RULES if r.language in ("shell", "toml")]

# Error classes for a caller of the library: a wrong argument or question. The commands turn
# them into usage errors or never meet them, so they are no finding and need no rule.
LIBRARY_ONLY = {
    "error",
    "invalid-robot",
    "structure",
    "unknown-name",
    "argument",
    "shape",
    "field-type",
}

# Beside every xacro example: the file xacro-include's fixed example includes.
WHEEL_XACRO = """\
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="side">
    <link name="${side}_wheel_link"/>
    <joint name="${side}_wheel_joint" type="continuous">
      <parent link="base_link"/><child link="${side}_wheel_link"/><axis xyz="0 1 0"/>
    </joint>
  </xacro:macro>
</robot>
"""

# The folder the setup rules' shell examples run in: a valid robot whose wheels have
# collision shapes and no inertial (for fishbot inertia --fill; they are welded to the base,
# so that the robot is valid without them: a moving link without one is an error), a xacro
# file that includes a file of the ROS package in src/, a robot with a box too far to draw
# (and one drawn).
WORKSPACE = {
    "fishbot.urdf": """\
<robot name="fishbot">
  <link name="base_link">
    <visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.0042" ixy="0" ixz="0" iyy="0.0042" iyz="0" izz="0.0067"/>
    </inertial>
  </link>
  <link name="left_wheel_link">
    <collision><geometry><cylinder radius="0.032" length="0.04"/></geometry></collision>
  </link>
  <link name="right_wheel_link">
    <collision><geometry><cylinder radius="0.032" length="0.04"/></geometry></collision>
  </link>
  <joint name="left_wheel_joint" type="fixed">
    <parent link="base_link"/><child link="left_wheel_link"/>
  </joint>
  <joint name="right_wheel_joint" type="fixed">
    <parent link="base_link"/><child link="right_wheel_link"/>
  </joint>
</robot>
""",
    "fishbot.urdf.xacro": """\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="use_sim" default="false"/>
  <xacro:include filename="$(find fishbot_description)/urdf/wheel.urdf.xacro"/>
  <link name="base_link"/>
  <xacro:wheel side="left"/>
</robot>
""",
    "src/fishbot_description/package.xml": (
        '<package format="3"><name>fishbot_description</name></package>\n'
    ),
    "src/fishbot_description/urdf/wheel.urdf.xacro": WHEEL_XACRO,
    "far.urdf": """\
<robot name="far">
  <link name="base_link">
    <visual><origin xyz="1e10 0 0"/><geometry><box size="0.2 0.2 0.1"/></geometry></visual>
    <visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>
  </link>
</robot>
""",
}
# The same robot as fishbot.urdf, with no <visual>.
WORKSPACE["frames.urdf"] = WORKSPACE["fishbot.urdf"].replace(
    '    <visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>\n', ""
)

# mjcf-left-out's example: a robot whose visual mesh is a COLLADA file, found.
WORKSPACE["mixed.urdf"] = WORKSPACE["fishbot.urdf"].replace(
    '<visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>',
    '<visual><geometry><mesh filename="meshes/base_link.dae"/></geometry></visual>',
)
WORKSPACE["meshes/base_link.dae"] = ""
# mjcf-mesh-converted's: a visual mesh in ASCII STL, which MuJoCo refuses and mjcf converts.
WORKSPACE["ascii.urdf"] = WORKSPACE["fishbot.urdf"].replace(
    '<visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>',
    '<visual><geometry><mesh filename="meshes/base_link_ascii.stl"/></geometry></visual>',
)
WORKSPACE["meshes/base_link_ascii.stl"] = """\
solid base_link
facet normal 0 0 0
outer loop
vertex 0 0 0
vertex 0.2 0 0
vertex 0 0.2 0
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 0 0 0
vertex 0 0.2 0
vertex 0 0 0.1
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 0 0 0
vertex 0 0 0.1
vertex 0.2 0 0
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 0.2 0 0
vertex 0 0.2 0
vertex 0 0 0.1
endloop
endfacet
endsolid base_link
"""
# mjcf-refused's: a massless link between the two joints of a hip.
WORKSPACE["hip.urdf"] = WORKSPACE["fishbot.urdf"].replace(
    "</robot>",
    """  <link name="hip_virtual"/>
  <link name="thigh"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="hip_roll" type="continuous"><axis xyz="1 0 0"/>
    <parent link="base_link"/><child link="hip_virtual"/></joint>
  <joint name="hip_pitch" type="continuous"><axis xyz="0 1 0"/>
    <parent link="hip_virtual"/><child link="thigh"/></joint>
</robot>""",
)
# mjcf-empty-shape's: a frame drawn as a box of size 0.
WORKSPACE["frame.urdf"] = WORKSPACE["fishbot.urdf"].replace(
    '<visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>',
    '<visual><geometry><box size="0 0 0"/></geometry></visual>',
)
# mjcf-joined-inertial's: a link fixed to the base whose inertia no solid has.
WORKSPACE["antenna.urdf"] = WORKSPACE["fishbot.urdf"].replace(
    '  <link name="left_wheel_link">\n',
    '  <link name="left_wheel_link">\n    <inertial><mass value="0.01"/>'
    '<inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-5"/></inertial>\n',
)

# The conversion's example: an arm whose <gazebo> block has a number, and the same with a
# xacro expression left where the converter reads a number.
_ARM = """\
<robot name="arm">
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="upper_arm">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="upper_arm"/><axis xyz="0 1 0"/>
    <limit lower="-1.57" upper="1.57" effort="10" velocity="1"/>
  </joint>{gazebo}
</robot>
"""
WORKSPACE["arm.urdf"] = _ARM.format(
    gazebo='\n  <gazebo reference="upper_arm"><mu1>0.8</mu1></gazebo>'
)
WORKSPACE["gazebo.urdf"] = _ARM.format(
    gazebo='\n  <gazebo reference="upper_arm"><mu1>${mu}</mu1></gazebo>'
)

# The simulation's examples: a box on two wheels and two frictionless ball casters, driven by
# Gazebo Classic's plugin, that drives as it is told; each copy below has one fault.
_WHEEL = (
    '<inertial><mass value="0.2"/><inertia ixx="0.00014" ixy="0" ixz="0" iyy="0.00025" '
    'iyz="0" izz="0.00014"/></inertial>'
)
_BALL = (
    '<collision><geometry><sphere radius="0.025"/></geometry></collision>\n    <inertial>'
    '<mass value="0.05"/><inertia ixx="1.25e-5" ixy="0" ixz="0" iyy="1.25e-5" iyz="0" '
    'izz="1.25e-5"/></inertial>'
)
_TYRE = '<collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.03"/>'
CART = f"""\
<robot name="cart">
  <link name="base_link">
    <collision><origin xyz="0 0 0.08"/><geometry><box size="0.3 0.2 0.1"/></geometry></collision>
    <inertial><origin xyz="0 0 0.08"/><mass value="2"/>
      <inertia ixx="0.00833" ixy="0" ixz="0" iyy="0.01667" iyz="0" izz="0.02167"/></inertial>
  </link>
  <link name="left_wheel">
    {_TYRE}</geometry></collision>
    {_WHEEL}
  </link>
  <link name="right_wheel">
    {_TYRE}</geometry></collision>
    {_WHEEL}
  </link>
  <link name="caster">
    {_BALL}
  </link>
  <link name="back_caster">
    {_BALL}
  </link>
  <joint name="left_wheel_joint" type="continuous"><origin xyz="0 0.13 0.05"/><axis xyz="0 1 0"/>
    <parent link="base_link"/><child link="left_wheel"/></joint>
  <joint name="right_wheel_joint" type="continuous"><origin xyz="0 -0.13 0.05"/><axis xyz="0 1 0"/>
    <parent link="base_link"/><child link="right_wheel"/></joint>
  <joint name="caster_joint" type="fixed"><origin xyz="0.12 0 0.025"/>
    <parent link="base_link"/><child link="caster"/></joint>
  <joint name="back_caster_joint" type="fixed"><origin xyz="-0.12 0 0.025"/>
    <parent link="base_link"/><child link="back_caster"/></joint>
  <gazebo reference="caster"><mu1>0</mu1><mu2>0</mu2></gazebo>
  <gazebo reference="back_caster"><mu1>0</mu1><mu2>0</mu2></gazebo>
  <gazebo><plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
    <left_joint>left_wheel_joint</left_joint><right_joint>right_wheel_joint</right_joint>
    <wheel_separation>0.26</wheel_separation><wheel_diameter>0.1</wheel_diameter>
  </plugin></gazebo>
</robot>
"""
_FAULTS = {
    "coins.urdf": [(_TYRE, _TYRE.replace('<origin rpy="1.5708 0 0"/>', ""))] * 2,
    "spinner.urdf": [(_WHEEL, _WHEEL.replace("0.00014", "1e-11").replace("0.00025", "1e-11"))] * 2,
    "anvil.urdf": [('<mass value="2"/>', '<mass value="100000"/>')],
    "tall.urdf": [
        (
            '  <gazebo reference="caster">',
            '  <link name="mast"><inertial><origin xyz="0 0 1"/><mass value="10"/>'
            '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.01"/></inertial>'
            '</link>\n  <joint name="mast_joint" type="fixed"><origin xyz="0.1 0 0.13"/>'
            '<parent link="base_link"/><child link="mast"/></joint>\n'
            '  <gazebo reference="caster">',
        )
    ],
    "stilts.urdf": [('<origin xyz="0.12 0 0.025"/>', '<origin xyz="0.12 0 0.015"/>')],
    "sledge.urdf": [
        (
            '<origin xyz="0 0 0.08"/><geometry><box size="0.3 0.2 0.1"/>',
            '<origin xyz="0 0 0.06"/><geometry><box size="0.3 0.2 0.14"/>',
        )
    ],
    "braked.urdf": [
        ('  <gazebo reference="caster"><mu1>0</mu1><mu2>0</mu2></gazebo>\n', ""),
        ('  <gazebo reference="back_caster"><mu1>0</mu1><mu2>0</mu2></gazebo>\n', ""),
    ],
    "slow.urdf": [("<wheel_diameter>0.1</", "<wheel_diameter>0.05</")],
    "mirrored.urdf": [
        (
            "<left_joint>left_wheel_joint</left_joint><right_joint>right_wheel_joint",
            "<left_joint>right_wheel_joint</left_joint><right_joint>left_wheel_joint",
        )
    ],
    "crowded.urdf": [
        ('<origin xyz="0 0.13 0.05"/>', '<origin xyz="0 0.01 0.05"/>'),
        ('<origin xyz="0 -0.13 0.05"/>', '<origin xyz="0 -0.01 0.05"/>'),
        ("<wheel_separation>0.26</", "<wheel_separation>0.02</"),
    ],
}
WORKSPACE["cart.urdf"] = CART
for _name, _edits in _FAULTS.items():
    _text = CART
    for _old, _new in _edits:
        assert _old in _text, (_name, _old)
        _text = _text.replace(_old, _new, 1)
    WORKSPACE[_name] = _text
# sim-sag's: a 1 m arm of 5 kg, its mass at its middle, on a joint of 1 N*m.
WORKSPACE["weak_arm.urdf"] = ARM.format(effort=1)

# Rules of what render and view cannot draw, and of what mjcf leaves out or converts: the
# picture or the model is made without it, exit status 0.
DRAWING_RULES = {
    "shape-not-drawn",
    "mjcf-left-out",
    "mjcf-joined-inertial",
    "mjcf-mesh-converted",
    "mjcf-empty-shape",
}


def _modules() -> Iterator[object]:
    """Every module of the package (``__main__`` runs the command when imported)."""
    yield fishbot_urdf
    for info in pkgutil.walk_packages(fishbot_urdf.__path__, "fishbot_urdf."):
        if not info.name.endswith("__main__"):
            yield importlib.import_module(info.name)


def _subclasses(cls: type) -> Iterator[type]:
    for sub in cls.__subclasses__():
        yield sub
        yield from _subclasses(sub)


def _findings(result: Result) -> list[tuple[str, str]]:
    """(rule, severity) of every finding in a `fishbot check --format json` report."""
    report = json.loads(result.stdout)
    return [(d["rule"], d["severity"]) for f in report["files"] for d in f["diagnostics"]]


def _check(tmp_path: Path, rule: Rule, text: str) -> Result:
    """`fishbot check --format json` on ``text``, written as a .urdf or a .urdf.xacro file."""
    name = write_example(tmp_path, rule, text)
    # For every program (--target all): each finding at its rule's severity; but what MuJoCo
    # refuses of the MJCF of a sketch that weighs nothing (mjcf-refused's own example)
    command = ["check", "--isolated", "--target", "all", "--format", "json", str(name)]
    command += ["--ignore", "mjcf-refused", "--ignore", "mjcf-joined-inertial"]
    return CliRunner().invoke(cli, command)


def write_example(tmp_path: Path, rule: Rule, text: str) -> Path:
    """``text``, an example of ``rule``, written as a .urdf or a .urdf.xacro file in
    ``tmp_path``, with the files the examples name beside it."""
    (tmp_path / "wheel.urdf.xacro").write_text(WHEEL_XACRO, encoding="utf-8")
    (tmp_path / "meshes").mkdir(exist_ok=True)
    # found, as the mesh rules' examples say: a box in metres, a .step file, a box in
    # millimetres, a binary STL cut short, a flat box
    (tmp_path / "meshes" / "base_link.stl").write_bytes(box_stl(0.2, 0.2, 0.1))
    (tmp_path / "meshes" / "base_link.step").write_bytes(b"")
    (tmp_path / "meshes" / "base_link_mm.stl").write_bytes(box_stl(200, 200, 100))
    (tmp_path / "meshes" / "base_link_cut.stl").write_bytes(box_stl(0.2, 0.2, 0.1)[:-20])
    (tmp_path / "meshes" / "base_link_flat.stl").write_bytes(box_stl(0.2, 0.2, 0.0))
    if "base_link_fine" in text:
        (tmp_path / "meshes" / "base_link_fine.stl").write_bytes(fine_stl(30_000))
    if "package://fishbot_description/" in text:  # the package the examples name
        (tmp_path / "package.xml").write_text(
            "<package><name>fishbot_description</name></package>\n", encoding="utf-8"
        )
    name = tmp_path / ("robot.urdf.xacro" if rule.language == "xacro" else "robot.urdf")
    name.write_text(text, encoding="utf-8")
    return name


def _sentences(text: str) -> list[str]:
    return re.split(r"(?<=[.!?])\s+", text.strip())


def _words(text: str) -> str:
    return " ".join(text.split())


# -- the registry --------------------------------------------------------------------------


def test_ids_are_unique_and_every_rule_is_registered() -> None:
    assert len({r.id for r in RULES}) == len(RULES) == len(ids())
    defined = [v for module in _modules() for v in vars(module).values() if isinstance(v, Rule)]
    assert {r.id for r in defined} == ids()
    for rule in defined:
        assert get(rule.id) is rule, f"{rule.id} is defined twice, or not collected"


def test_every_error_rule_that_reaches_a_command_is_registered() -> None:
    list(_modules())  # every error class is defined
    from fishbot_urdf.errors import ConfigError, InputError, ToolError, ToolNotFoundError
    from fishbot_urdf.errors import XmlSyntaxError as Xml
    from fishbot_urdf.packages import PackageNotFoundError

    reported = (InputError, Xml, PackageNotFoundError, ToolNotFoundError, ToolError, ConfigError)
    assert {c.rule for c in reported} <= ids()
    for cls in _subclasses(FishbotUrdfError):
        assert cls.rule in ids() | LIBRARY_ONLY, f"{cls.__name__}.rule {cls.rule!r}"
    # Rule ids the code names as text: only the errors of the layers below the catalogue
    # (a finding made of one is given its rule by id); above it, code names the Rule.
    package = Path(fishbot_urdf.__file__).parent
    written = re.compile(r'\brule(?::\s*str)?\s*=\s*"([a-z0-9-]+)"|diagnostic\(\s*"([a-z0-9-]+)"')
    named = {
        (path.relative_to(package).as_posix(), a or b)
        for path in package.rglob("*.py")
        if "catalog" not in path.parts
        for a, b in written.findall(path.read_text(encoding="utf-8"))
    }
    assert {where for where, _ in named} == {"errors.py", "inputs.py"}
    assert {"io", "xml-syntax", "tool-missing"} <= {rule for _, rule in named}
    assert {rule for _, rule in named} - LIBRARY_ONLY <= ids()


@pytest.mark.parametrize("rule", RULES, ids=[r.id for r in RULES])
def test_rule_is_explained_with_a_failing_and_a_fixed_example(rule: Rule) -> None:
    assert rule.summary.strip()
    assert 2 <= len(_sentences(rule.explanation)) <= 5, rule.explanation
    assert rule.bad.strip() and rule.good.strip() and rule.bad != rule.good
    assert rule.bad.endswith("\n") and rule.good.endswith("\n")
    assert max(len(rule.bad.splitlines()), len(rule.good.splitlines())) <= 13  # short
    assert rule.language in ("urdf", "xacro", "shell", "toml")


# -- the examples --------------------------------------------------------------------------


@pytest.mark.parametrize("rule", ROBOT_RULES, ids=[r.id for r in ROBOT_RULES])
def test_failing_example_is_found(tmp_path: Path, rule: Rule) -> None:
    result = _check(tmp_path, rule, rule.bad)
    assert rule.id in [found for found, _ in _findings(result)], result.output
    assert result.exit_code == (1 if rule.severity.value == "error" else 0)


@pytest.mark.parametrize("rule", ROBOT_RULES, ids=[r.id for r in ROBOT_RULES])
def test_fixed_example_is_clean(tmp_path: Path, rule: Rule) -> None:
    result = _check(tmp_path, rule, rule.good)
    assert (result.exit_code, _findings(result)) == (0, []), result.output


URDF_RULES = [r for r in ROBOT_RULES if r.language == "urdf"]


@pytest.mark.parametrize("rule", URDF_RULES, ids=[r.id for r in URDF_RULES])
def test_fixed_example_passes_check_urdf(tmp_path: Path, rule: Rule) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(rule.good, encoding="utf-8")
    proc = run_check_urdf(path)
    assert proc.returncode == 0, proc.stderr
    assert b"Error" not in proc.stderr + proc.stdout


def _commands(snippet: str) -> list[list[str]]:
    """The `fishbot` commands of a shell example, as argument lists (other lines, such as
    an install command, are what a person does)."""
    found = []
    for line in snippet.replace("\\\n", " ").splitlines():
        words = shlex.split(line, comments=True)
        if words[:1] == ["fishbot"]:
            found.append(words[1:])
    return found


def _environment(rule: Rule, fixed: bool, tmp_path: Path) -> dict[str, str | None]:
    """The machine a setup rule's example describes (in its comment)."""
    env: dict[str, str | None] = {"ROS_PACKAGE_PATH": None, "AMENT_PREFIX_PATH": None}
    if rule.id in ("tool-missing", "tool-failed"):
        require_tool("dot", "graphviz")
        empty = tmp_path / "empty"
        empty.mkdir(exist_ok=True)
        if not fixed and rule.id == "tool-missing":
            env["PATH"] = str(empty)  # no Graphviz
        if not fixed and rule.id == "tool-failed":
            env["GVBINDIR"] = str(empty)  # Graphviz with no plugins registered
    return env


def _run_setup(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, rule: Rule, fixed: bool) -> Result:
    for name, text in WORKSPACE.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    snippet = rule.good if fixed else rule.bad
    if rule.language == "toml":  # a configuration beside the robot, then the check
        Path("pyproject.toml").write_text(snippet, encoding="utf-8")
        commands = [["check", "fishbot.urdf"]]
    else:
        commands = _commands(snippet)
    assert commands, snippet
    env = _environment(rule, fixed, tmp_path)
    results = [CliRunner().invoke(cli, args, env=env) for args in commands]
    failed = [r for r in results if r.exit_code != 0]
    return failed[0] if failed else results[-1]


@pytest.mark.parametrize("rule", SETUP_RULES, ids=[r.id for r in SETUP_RULES])
def test_failing_setup_example_reports_its_rule(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, rule: Rule
) -> None:
    result = _run_setup(tmp_path, monkeypatch, rule, fixed=False)
    assert f"[{rule.id}]" in result.output, result.output
    if rule.family is Family.SIMULATION and rule.severity is not Severity.ERROR:
        # a warning of what went wrong: exit 1 only for the errors it came with
        assert result.exit_code == (1 if ": error: " in result.output else 0), result.output
        return
    assert result.exit_code == (2 if rule.fatal else 0 if rule.id in DRAWING_RULES else 1)


@pytest.mark.parametrize("rule", SETUP_RULES, ids=[r.id for r in SETUP_RULES])
def test_fixed_setup_example_runs(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, rule: Rule
) -> None:
    result = _run_setup(tmp_path, monkeypatch, rule, fixed=True)
    assert result.exit_code == 0, result.output
    assert f"[{rule.id}]" not in result.output


# -- fishbot rules -------------------------------------------------------------------------


def _rules(*args: str) -> Result:
    return CliRunner().invoke(cli, ["rules", *args])


def test_rules_lists_every_rule_once() -> None:
    result = _rules()
    assert (result.exit_code, result.stderr) == (0, "")
    assert result.stdout == table(RULES)
    lines = result.stdout.splitlines()
    assert lines[0].split() == ["rule", "severity", "family", "summary"]
    assert [line.split()[0] for line in lines[1:]] == [r.id for r in RULES]


@pytest.mark.parametrize("rule", RULES, ids=[r.id for r in RULES])
def test_rules_explains_one(rule: Rule) -> None:
    result = _rules(rule.id)
    assert (result.exit_code, result.stderr) == (0, "")
    text = result.stdout
    assert text == explanation(rule)
    assert text.startswith(f"{rule.id} ({rule.severity.value}")
    assert rule.summary in text
    assert _words(rule.explanation) in _words(text)
    for snippet in (rule.bad, rule.good):
        assert "\n".join("    " + line for line in snippet.splitlines()) in text
    for consumer in rule.consumers:
        assert _words(consumer.label) in _words(text)
    assert text.index("Fails:") < text.index("Passes:")


@pytest.mark.parametrize("family", list(Family), ids=[f.value for f in Family])
def test_rules_lists_a_family(family: Family) -> None:
    result = _rules(family.value)
    assert result.exit_code == 0
    listed = [line.split()[0] for line in result.stdout.splitlines()[1:]]
    assert listed == [r.id for r in RULES if r.family is family]
    assert listed  # every family has rules


def test_rules_json_has_every_field() -> None:
    result = _rules("--format", "json")
    assert result.exit_code == 0
    data = json.loads(result.stdout)
    assert data == [r.to_dict() for r in RULES]
    fields = {f.name for f in dataclasses.fields(Rule)}
    assert all(set(item) == fields for item in data)
    one = json.loads(_rules("massless-link", "--format", "json").stdout)
    assert one == get("massless-link").to_dict()
    assert one["consumers"] == ["gazebo", "mujoco", "drake", "pybullet"]
    assert one["bad"].startswith("<robot name=")


def test_rules_markdown() -> None:
    assert _rules("--format", "markdown").stdout == markdown_table(RULES)
    # a tag is code in Markdown: bare, it is HTML, which a renderer drops
    assert "| `robot-name` | error | urdf | `<robot>` has no name. |" in markdown_table(RULES)
    one = _rules("config", "--format", "markdown").stdout
    assert one.startswith("## `config`\n")
    assert f"Fails:\n\n```toml\n{get('config').bad}```\n" in one


def test_unknown_rule_is_one_line_with_the_closest() -> None:
    result = _rules("massles-link")
    assert result.exit_code == 2
    assert result.stdout == ""
    assert result.stderr == (
        "fishbot rules: error: no rule or family 'massles-link' "
        "(did you mean 'massless-link'? `fishbot rules` lists them)\n"
    )


# -- the rule list of the documentation ----------------------------------------------------


def test_the_rules_page_keeps_no_copy_of_the_rule_list() -> None:
    # docs/hooks.py fills the list between the markers as the site is built
    # (tests/test_docs.py checks the built page), so the page's source holds none.
    page = (ROOT / "docs" / "rules" / "index.md").read_text(encoding="utf-8")
    assert page.count(README_BEGIN) == page.count(README_END) == 1
    assert page.split(README_BEGIN, 1)[1].split(README_END, 1)[0].strip() == ""
    filled = with_rule_table(page, RULES)
    assert f"{README_BEGIN}\n\n{markdown_table(RULES)}\n{README_END}" in filled


def test_a_page_without_markers_is_refused() -> None:
    with pytest.raises(ArgumentError, match="rules: begin"):
        with_rule_table("# robot\n", RULES)


def test_each_check_reports_only_the_rules_it_lists(tmp_path: Path) -> None:
    # check() runs a family's check only when one of the rules it lists is selected: a rule
    # it reports but does not list would be lost when the others are turned off. Every
    # rule's failing and passing example, read and analysed, goes through each check.
    from fishbot_urdf.analysis import analyse
    from fishbot_urdf.parsing import read
    from fishbot_urdf.rules import gazebo, joints, meshes, physics, references

    seen: dict[str, set[str]] = {}
    for rule in all_rules():
        for index, text in enumerate((rule.bad, rule.good)):
            if rule.language not in ("urdf", "xacro") or not text:
                continue
            folder = tmp_path / f"{rule.id}-{index}"
            folder.mkdir()
            _check(folder, rule, text)  # lays out the examples' files
            name = folder / ("robot.urdf.xacro" if rule.language == "xacro" else "robot.urdf")
            try:
                parsed = read(name)
            except FishbotUrdfError:
                continue
            if parsed.robot is None:
                continue
            analysis = analyse(parsed.robot, parsed.path, parsed.references)
            for module, found in (
                (joints, joints.joints(analysis)),
                (references, references.references(analysis)),
                (meshes, meshes.meshes(analysis, None)),
                (physics, physics.physics(analysis)),
                (gazebo, gazebo.gazebo(analysis)),
            ):
                rules = {d.rule for d in found}
                assert rules <= {r.id for r in module.REPORTS}, (rule.id, rules)
                seen.setdefault(module.__name__, set()).update(rules)
    for module in (joints, references, meshes, physics, gazebo):  # each listed rule is met
        listed = {r.id for r in module.REPORTS} - {"bad-number", "negative-mass"}
        assert listed <= seen[module.__name__], listed - seen[module.__name__]
