"""`fishbot_urdf.inertia.inertia_macros` and the suggestions: a robot's own inertia macros
are found by what they make, whatever their names, and a link gets their call."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from conftest import FISHBOT

import fishbot_urdf
from fishbot_urdf.diagnostics import shown_path
from fishbot_urdf.inertia import (
    InertiaMacro,
    cylinder_inertia,
    fill_inertials,
    inertia_macros,
    shared_inertials,
    suggest_inertials,
    xacro_suggestions,
)

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
# The ROS 2 learner's notes write them without a position or rotation, with (m/12), (2/5).
NOTES = f"""<robot {XACRO_NS}>
  <xacro:macro name="box_inertia" params="m w h d">
    <inertial><mass value="${{m}}"/>
      <inertia ixx="${{(m/12) * (h*h + d*d)}}" ixy="0.0" ixz="0.0"
               iyy="${{(m/12) * (w*w + d*d)}}" iyz="0.0" izz="${{(m/12) * (w*w + h*h)}}"/>
    </inertial>
  </xacro:macro>
  <xacro:macro name="cylinder_inertia" params="m r h">
    <inertial><mass value="${{m}}"/>
      <inertia ixx="${{(m/12) * (3*r*r + h*h)}}" ixy="0" ixz="0"
               iyy="${{(m/12) * (3*r*r + h*h)}}" iyz="0" izz="${{(m/2) * (r*r)}}"/>
    </inertial>
  </xacro:macro>
  <xacro:macro name="sphere_inertia" params="m r">
    <inertial><mass value="${{m}}"/>
      <inertia ixx="${{(2/5) * m * (r*r)}}" ixy="0.0" ixz="0.0"
               iyy="${{(2/5) * m * (r*r)}}" iyz="0.0" izz="${{(2/5) * m * (r*r)}}"/>
    </inertial>
  </xacro:macro>
</robot>
"""


def _robot(folder: Path, macros: str, links: str) -> Path:
    (folder / "inertias.xacro").write_text(macros)
    robot = folder / "robot.urdf.xacro"
    robot.write_text(
        f'<robot name="r" {XACRO_NS}>\n'
        '  <xacro:include filename="inertias.xacro"/>\n'
        '  <link name="base"/>\n'
        f"{links}"
        "</robot>\n"
    )
    return robot


def test_the_fishbots_macros_are_found_with_their_parameters() -> None:
    common = shown_path(str(FISHBOT / "urdf" / "fishbot" / "common_inertia.xacro"))
    found = inertia_macros(FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro")
    assert [(m.shape, m.name, m.mass, m.sizes, m.xyz, m.rpy) for m in found] == [
        ("box", "box_inertia", "m", ("w", "h", "d"), "xyz", "rpy"),
        ("cylinder", "cylinder_inertia", "m", ("r", "h"), "xyz", "rpy"),
        ("sphere", "sphere_inertia", "m", ("r",), "xyz", "rpy"),
    ]
    # Where each is defined, in the file that defines it (the include), not the robot.
    assert [(m.source.path, m.source.line) for m in found if m.source] == [
        (common, 11),
        (common, 22),
        (common, 33),
    ]


def test_the_notes_macros_are_found_without_a_place(tmp_path: Path) -> None:
    robot = _robot(tmp_path, NOTES, "")
    found = inertia_macros(robot)
    assert [(m.name, m.mass, m.sizes, m.xyz, m.rpy) for m in found] == [
        ("box_inertia", "m", ("w", "h", "d"), None, None),
        ("cylinder_inertia", "m", ("r", "h"), None, None),
        ("sphere_inertia", "m", ("r",), None, None),
    ]


def test_names_and_parameter_order_do_not_matter(tmp_path: Path) -> None:
    macros = f"""<robot {XACRO_NS}>
  <xacro:macro name="solid_tube" params="length kg radius at:='0 0 0' turn:='0 0 0'">
    <inertial><origin xyz="${{at}}" rpy="${{turn}}"/><mass value="${{kg}}"/>
      <inertia ixx="${{kg*(3*radius**2 + length**2)/12}}" ixy="0" ixz="0"
               iyy="${{kg*(3*radius**2 + length**2)/12}}" iyz="0" izz="${{kg*radius**2/2}}"/>
    </inertial>
  </xacro:macro>
  <xacro:macro name="brick" params="z x kg y">
    <inertial><mass value="${{kg}}"/>
      <inertia ixx="${{kg*(y*y+z*z)/12}}" ixy="0" ixz="0" iyy="${{kg*(x*x+z*z)/12}}" iyz="0"
               izz="${{kg*(x*x+y*y)/12}}"/>
    </inertial>
  </xacro:macro>
</robot>
"""
    found = inertia_macros(_robot(tmp_path, macros, ""))
    assert [(m.shape, m.name, m.mass, m.sizes, m.xyz, m.rpy) for m in found] == [
        ("cylinder", "solid_tube", "kg", ("radius", "length"), "at", "turn"),
        ("box", "brick", "kg", ("x", "y", "z"), None, None),
    ]


@pytest.mark.parametrize(
    "body",
    [
        # a diameter, not a radius
        '<inertial><mass value="${m}"/><inertia ixx="${m*(3*(r/2)**2+h*h)/12}" ixy="0" '
        'ixz="0" iyy="${m*(3*(r/2)**2+h*h)/12}" iyz="0" izz="${m*(r/2)**2/2}"/></inertial>',
        # the right numbers, and a link besides
        '<inertial><mass value="${m}"/><inertia ixx="${m*(3*r*r+h*h)/12}" ixy="0" ixz="0" '
        'iyy="${m*(3*r*r+h*h)/12}" iyz="0" izz="${m*r*r/2}"/></inertial><link name="x"/>',
        # not an inertial at all
        '<link name="${m}_${r}_${h}"/>',
        # an expression that fails on the values
        '<inertial><mass value="${m[0]}"/></inertial>',
    ],
    ids=["diameter", "more", "link", "fails"],
)
def test_a_macro_that_writes_something_else_is_not_one(tmp_path: Path, body: str) -> None:
    macros = (
        f'<robot {XACRO_NS}><xacro:macro name="cyl" params="m r h">{body}</xacro:macro></robot>'
    )
    assert inertia_macros(_robot(tmp_path, macros, "")) == ()


WHEEL = """  <link name="wheel">
    <collision>
      <origin xyz="0 0 0" rpy="1.57079 0 0"/>
      <geometry><cylinder radius="0.032" length="0.04"/></geometry>
    </collision>
  </link>
  <joint name="j" type="continuous"><parent link="base"/><child link="wheel"/></joint>
"""


def test_a_turned_shape_and_a_macro_without_a_rotation_give_the_inertial(tmp_path: Path) -> None:
    robot = _robot(tmp_path, NOTES, WHEEL)
    analysis = fishbot_urdf.check_file(robot).analysis
    assert analysis is not None
    filled = fill_inertials(analysis, masses={"wheel": 0.1}).inertials
    (made,) = xacro_suggestions(robot, analysis, filled)
    assert made.macro is None
    why = "cylinder_inertia takes no position or rotation, and the cylinder is moved"
    assert made.plain_because == why
    assert made.text.startswith("<inertial>\n")
    assert (made.source, made.line) == ((str(robot), 4, 3), 5)


def test_a_suggested_call_rounds_to_six_digits_and_leaves_out_a_zero_place() -> None:
    robot = fishbot_urdf.parse(
        '<robot name="r"><link name="a"><collision><geometry>'
        '<cylinder radius="0.1" length="0.12"/></geometry></collision></link></robot>'
    )
    macro = InertiaMacro("cylinder", "cyl", "mass", ("radius", "height"), "xyz", None)
    (made,) = suggest_inertials(robot, {"a": cylinder_inertia(1 / 3, 0.1, 0.12)}, [macro])
    assert made.text == '<xacro:cyl mass="0.333333" radius="0.1" height="0.12"/>\n'
    # Its collision starts on the <link>'s line: no line of its own to write at.
    assert made.line is None


def test_the_call_as_written_in_the_macros_body(tmp_path: Path) -> None:
    copy = tmp_path / "fishbot"
    shutil.copytree(FISHBOT, copy)
    imu = copy / "urdf" / "fishbot" / "sensor" / "imu.urdf.xacro"
    text = imu.read_text()
    imu.write_text(
        text.replace('<xacro:box_inertia m="${mass}" w="${size}" h="${size}" d="${size}"/>', "")
    )
    robot = copy / "urdf" / "fishbot" / "fishbot.urdf.xacro"
    analysis = fishbot_urdf.check_file(robot).analysis
    assert analysis is not None
    filled = fill_inertials(analysis, masses={"imu_link": 0.01}).inertials
    (made,) = xacro_suggestions(robot, analysis, filled)
    assert made.text == '<xacro:box_inertia m="0.01" w="0.02" h="0.02" d="0.02"/>\n'
    assert (
        made.written_text == '<xacro:box_inertia m="0.01" w="${size}" h="${size}" d="${size}"/>\n'
    )
    assert [name for name, _ in made.made_by] == ["imu_xacro"]


def test_a_collision_another_macro_writes_gives_no_line_and_no_expressions(
    tmp_path: Path,
) -> None:
    # tube's ${r} and ${h} mean nothing in arm's body, where the call would go; and tube's
    # <collision>, though below arm's <link> in the file, is not inside it.
    links = """  <xacro:macro name="arm" params="len">
    <link name="arm">
      <xacro:tube r="0.02" h="${len}"/>
    </link>
    <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
  </xacro:macro>
  <xacro:macro name="tube" params="r h">
    <collision>
      <geometry><cylinder radius="${r}" length="${h}"/></geometry>
    </collision>
  </xacro:macro>
  <xacro:arm len="0.3"/>
"""
    robot = _robot(tmp_path, NOTES, links)
    analysis = fishbot_urdf.check_file(robot).analysis
    assert analysis is not None
    filled = fill_inertials(analysis, masses={"arm": 0.5}).inertials
    (made,) = xacro_suggestions(robot, analysis, filled)
    assert made.text == '<xacro:cylinder_inertia m="0.5" r="0.02" h="0.3"/>\n'
    assert (made.source, made.line, made.written) == ((str(robot), 5, 5), None, ())
    assert [name for name, _ in made.made_by] == ["arm"]


def test_the_links_one_macro_makes_share_one_call_through_its_mass_parameter(
    tmp_path: Path,
) -> None:
    copy = tmp_path / "fishbot"
    shutil.copytree(FISHBOT, copy)
    wheel = copy / "urdf" / "fishbot" / "actuator" / "wheel.urdf.xacro"
    text = wheel.read_text()
    start = text.index("<xacro:cylinder_inertia")
    wheel.write_text(text[:start] + text[text.index("/>", start) + 2 :])
    robot = copy / "urdf" / "fishbot" / "fishbot.urdf.xacro"
    masses = {"left_wheel_link": 0.1, "right_wheel_link": 0.2, "imu_link": 0.01}
    imu = copy / "urdf" / "fishbot" / "sensor" / "imu.urdf.xacro"
    imu.write_text(
        imu.read_text()
        .replace('<xacro:box_inertia m="${mass}"', "<!--")
        .replace('d="${size}"/>', "-->")
    )
    analysis = fishbot_urdf.check_file(robot).analysis
    assert analysis is not None
    made = xacro_suggestions(robot, analysis, fill_inertials(analysis, masses=masses).inertials)
    # What each wheel's call gave wheel_xacro, as written and as a number.
    left = next(s for s in made if s.link == "left_wheel_link")
    assert dict(left.given)["mass"] == ("${wheel_mass}", 0.1)
    assert dict(left.given)["name"] == ("left", None)
    assert left.maker is not None and left.maker.name == "wheel_xacro"
    # The IMU, alone in its macro, shares with none.
    (shared,) = shared_inertials(made)
    assert [s.link for s in shared.suggestions] == ["left_wheel_link", "right_wheel_link"]
    assert (shared.parameter, shared.added, shared.fits) == ("mass", None, True)
    assert shared.text == (
        '<xacro:cylinder_inertia m="${mass}" r="${radius}" h="${length}" rpy="1.57079 0.0 0.0"/>\n'
    )
    assert [c["write"] for c in shared.calls()] == [None, 'mass="0.2"']
