"""Each error class: its type, its rule id and its message."""

from __future__ import annotations

from pathlib import Path

import pytest

import fishbot_urdf
from fishbot_urdf import (
    ArgumentError,
    ConfigError,
    ConversionError,
    FishbotUrdfError,
    InertiaUnderflowError,
    InputError,
    PackageNotFoundError,
    RobotError,
    ShapeError,
    StructureError,
    ToolNotFoundError,
    UnknownNameError,
    XacroError,
    XmlSyntaxError,
)


def test_input_error(tmp_path: Path) -> None:
    missing = tmp_path / "missing.urdf"
    with pytest.raises(InputError) as info:
        fishbot_urdf.load(missing)
    error = info.value
    assert isinstance(error, FishbotUrdfError)
    assert error.rule == "io"
    assert (error.path, error.line, error.message) == (str(missing), None, "no such file")
    assert str(error) == f"{missing}: no such file"


def test_xml_syntax_error() -> None:
    with pytest.raises(XmlSyntaxError) as info:
        fishbot_urdf.parse('<robot name="r">\n  <link name="a">\n</robot>', path="t.urdf")
    error = info.value
    assert error.rule == "xml-syntax"
    assert (error.path, error.line) == ("t.urdf", 3)
    assert (
        error.message == "XML syntax error: Opening and ending tag mismatch: link line 2 and robot"
    )


def test_xacro_error(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n<xacro:nope/></robot>'
    )
    with pytest.raises(XacroError) as info:
        fishbot_urdf.load(path)
    error = info.value
    assert isinstance(error, FishbotUrdfError)
    assert (error.rule, error.line, error.column) == ("xacro-undefined", 2, 1)
    assert error.message == "macro 'nope' is not defined"


def test_package_not_found_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    with pytest.raises(PackageNotFoundError) as info:
        fishbot_urdf.find_package("ghost_description", near=tmp_path / "robot.xacro")
    error = info.value
    assert isinstance(error, FishbotUrdfError)
    assert (error.rule, error.package) == ("package-not-found", "ghost_description")
    assert error.searched[0] == "the packages given (none)"
    assert error.given == ()
    assert error.message.startswith("package 'ghost_description' not found (searched: ")


def test_robot_error_lists_every_finding() -> None:
    text = '<robot name="r"><link name="a"><visual><geometry><box size="1 1"/></geometry></visual>'
    text += "<collision><geometry><sphere/></geometry></collision></link></robot>"
    with pytest.raises(RobotError) as info:
        fishbot_urdf.parse(text, path="r.urdf")
    error = info.value
    assert error.rule == "invalid-robot"
    assert [(d.rule, d.column) for d in error.diagnostics] == [
        ("bad-vector", text.index('size="1 1"') + 1),
        ("missing-attribute", text.index("<sphere") + 1),
    ]
    assert str(error) == (
        f"r.urdf:1:{text.index('size=') + 1}: link 'a': <box size=\"1 1\"> has 2 values, "
        "3 are needed [bad-vector] (and 1 more)"
    )


def test_base_error_from_tree_queries() -> None:
    robot = fishbot_urdf.Robot("r", (fishbot_urdf.Link("a"), fishbot_urdf.Link("b")))
    with pytest.raises(StructureError) as info:
        fishbot_urdf.root(robot)
    assert isinstance(info.value, FishbotUrdfError)
    assert info.value.rule == "structure"
    assert info.value.roots == ("a", "b")
    assert info.value.message == "robot 'r' needs one root link, and has 2: 'a', 'b'"
    # The same condition is the same error wherever a question needs one root.
    with pytest.raises(StructureError) as again:
        fishbot_urdf.mass_properties(robot)
    assert again.value.message == info.value.message


def test_tool_not_found_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("PATH", str(tmp_path))  # no `dot` here
    robot = fishbot_urdf.Robot("r", (fishbot_urdf.Link("a"),))
    with pytest.raises(ToolNotFoundError) as info:
        fishbot_urdf.render_graph(robot, tmp_path / "r.svg")
    error = info.value
    assert isinstance(error, FishbotUrdfError)
    assert (error.rule, error.tool) == ("tool-missing", "dot")
    assert error.message == "Graphviz's dot program is needed for SVG output and was not found"
    assert error.hint.startswith("install Graphviz: apt install graphviz, brew install graphviz")
    assert not (tmp_path / "r.svg").exists()


def test_unknown_name_error() -> None:
    robot = fishbot_urdf.load(Path(__file__).parent.parent / "robots/fishbot/urdf/first_robot.urdf")
    with pytest.raises(UnknownNameError) as info:
        fishbot_urdf.subtree(robot, "base")
    error = info.value
    assert isinstance(error, FishbotUrdfError) and isinstance(error, KeyError)
    assert (error.rule, error.kind, error.name) == ("unknown-name", "link", "base")
    assert error.known == ("base_link", "imu_link")
    assert str(error) == "no link 'base' (did you mean 'base_link'? links: base_link, imu_link)"


def test_argument_error() -> None:
    link = fishbot_urdf.Link(
        "wheel", collisions=(fishbot_urdf.Collision(fishbot_urdf.Sphere(0.1)),)
    )
    with pytest.raises(ArgumentError) as info:
        fishbot_urdf.link_inertial(link, density=-1.0)
    error = info.value
    assert isinstance(error, FishbotUrdfError) and isinstance(error, ValueError)
    assert (error.rule, error.name) == ("argument", "density")
    assert error.message == "the density must be a finite number > 0, not -1"


def test_conversion_error() -> None:
    robot = fishbot_urdf.parse(
        '<robot name="r"><link name="a"/><gazebo><static>1</static><maxContacts>many'
        "</maxContacts></gazebo></robot>"
    )
    with pytest.raises(ConversionError) as info:
        fishbot_urdf.to_sdf(robot)
    error = info.value
    assert isinstance(error, FishbotUrdfError) and isinstance(error, ValueError)
    assert (error.rule, error.target, error.subject) == ("conversion", "sdf", None)
    assert error.message == (
        "<gazebo>: <maxContacts> is 'many', not a number: sdformat's converter stops on it"
    )


def test_shape_error() -> None:
    with pytest.raises(ShapeError) as info:
        fishbot_urdf.link_inertial(fishbot_urdf.Link("bare"), mass=1.0)
    error = info.value
    assert isinstance(error, FishbotUrdfError) and isinstance(error, ValueError)
    assert error.rule == "shape"
    assert error.message == "link 'bare' has no collision shape"


def test_inertia_underflow_error() -> None:
    with pytest.raises(InertiaUnderflowError) as info:
        fishbot_urdf.box_inertia(2.0, 1e-170, 1e-170, 1e-170)
    error = info.value
    assert isinstance(error, ShapeError) and isinstance(error, ValueError)
    assert error.rule == "shape"
    assert (error.shape, error.sizes, error.mass, error.moments) == (
        "box",
        (("x", 1e-170), ("y", 1e-170), ("z", 1e-170)),
        2.0,
        (0.0, 0.0, 0.0),
    )
    assert error.message == (
        "the box's inertia underflows to 0 kg*m^2 (x 1e-170 m, y 1e-170 m, z 1e-170 m, mass "
        "2 kg): too small for a float; give a larger size or mass"
    )


def test_structure_error() -> None:
    loop = fishbot_urdf.Robot(
        "loop",
        (fishbot_urdf.Link("a"), fishbot_urdf.Link("b")),
        (
            fishbot_urdf.Joint("ab", fishbot_urdf.JointType.FIXED, "a", "b"),
            fishbot_urdf.Joint("ba", fishbot_urdf.JointType.FIXED, "b", "a"),
        ),
    )
    with pytest.raises(StructureError) as info:
        fishbot_urdf.root(loop)
    error = info.value
    assert isinstance(error, FishbotUrdfError)
    assert (error.rule, error.roots) == ("structure", ())
    assert error.message == (
        "robot 'loop' needs one root link, and has none (every link is some joint's child)"
    )


def test_config_error(tmp_path: Path) -> None:
    config = tmp_path / "fishbot.toml"
    config.write_text('select = ["physics"]\nignroe = ["massless-link"]\n')
    with pytest.raises(ConfigError) as info:
        fishbot_urdf.load_config(config)
    error = info.value
    assert isinstance(error, FishbotUrdfError)
    assert (error.rule, error.path, error.line) == ("config", str(config), 2)
    assert error.message == (
        "unknown key 'ignroe' (did you mean 'ignore'? keys: select, extend-select, ignore, "
        "severity, strict, ground-tolerance, allow-read, targets)"
    )
