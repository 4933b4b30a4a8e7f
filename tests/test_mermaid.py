"""`fishbot_urdf.to_mermaid`: the same drawing as the DOT, as a Mermaid flowchart."""

from __future__ import annotations

import re

from conftest import DATA, FISHBOT

import fishbot_urdf
from fishbot_urdf.drawing.dot import drawing

FISHBOT_XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"


def _nodes(text: str) -> dict[str, str]:
    """Node id -> label, from lines like `L0["base_link"]` and `J0(["base_joint"])`."""
    found = re.findall(r'^    ([LJ]\d+)\(?\["(.*)"\]\)?$', text, flags=re.M)
    return dict(found)


def test_fishbot_flowchart() -> None:
    robot = fishbot_urdf.load(FISHBOT_XACRO)
    text = fishbot_urdf.to_mermaid(robot)
    lines = text.splitlines()
    assert lines[0] == "flowchart TD"
    nodes = _nodes(text)
    links = [label for node, label in nodes.items() if node.startswith("L")]
    joints = [label for node, label in nodes.items() if node.startswith("J")]
    # The same order as the DOT: the tree depth-first, children by joint name.
    assert links == list(drawing(robot).links)
    assert sorted(joints) == sorted(j.name for j in robot.joints)
    # Per joint: an edge from the parent with the origin, and one to the child.
    ids = {label: node for node, label in nodes.items()}
    base_joint = ids["base_joint"]
    # The origin as written (DOT copies urdf_to_graphviz's recovered "rpy: 0 -0 0").
    assert (
        f'    {ids["base_footprint"]} -->|"xyz: 0 0 0.091<br>rpy: 0 0 0"| {base_joint}'
    ) in lines
    assert f"    {base_joint} --> {ids['base_link']}" in lines
    assert len([line for line in lines if " --> " in line or " -->|" in line]) == 2 * len(joints)
    assert "    classDef joint stroke:blue,color:blue" in lines


def test_names_are_written_as_mermaid_entities() -> None:
    robot = fishbot_urdf.Robot(
        "r",
        (fishbot_urdf.Link('a "b" #1 <c> & d|e`'), fishbot_urdf.Link("x")),
        (fishbot_urdf.Joint("j", fishbot_urdf.JointType.FIXED, 'a "b" #1 <c> & d|e`', "x"),),
    )
    text = fishbot_urdf.to_mermaid(robot)
    assert '    L0["a #quot;b#quot; #35;1 #lt;c#gt; #amp; d#124;e#96;"]' in text.splitlines()


def test_unreachable_and_undefined_links_are_marked() -> None:
    text = fishbot_urdf.to_mermaid(fishbot_urdf.load(DATA / "invalid" / "cycle.urdf"))
    assert '    L1["a<br>(not reached from the root)"]' in text.splitlines()
    assert "    classDef unreachable stroke:red,color:red,stroke-dasharray:6 3" in text
    assert re.search(r"^    class L1,L2,L3 unreachable$", text, flags=re.M)
    robot = fishbot_urdf.read(DATA / "invalid" / "undefined_parent.urdf").robot
    text = fishbot_urdf.to_mermaid(robot)
    assert "<br>(not defined)" in text and "classDef undefined" in text


def test_detail_colours_joints_by_type() -> None:
    robot = fishbot_urdf.load(FISHBOT_XACRO)
    text = fishbot_urdf.to_mermaid(robot, detail=True)
    assert "    classDef continuous stroke:darkgreen,color:darkgreen" in text
    assert "    classDef fixed stroke:dimgray,color:dimgray" in text
    nodes = _nodes(text)
    wheel = next(label for label in nodes.values() if label.startswith("left_wheel_joint"))
    assert wheel == "left_wheel_joint<br>continuous<br>axis 0 1 0"


def test_a_mermaid_directive_in_a_name_stays_a_name() -> None:
    robot = fishbot_urdf.Robot("r", (fishbot_urdf.Link("%%{init: {}}%%"),))
    assert '    L0["#37;#37;{init: {}}#37;#37;"]' in fishbot_urdf.to_mermaid(robot).splitlines()


def test_angles_are_shown_as_written_without_negative_zero() -> None:
    robot = fishbot_urdf.parse(
        '<robot name="r"><link name="a"/><link name="b"/>'
        '<joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
        '<origin xyz="-0 0 0" rpy="1.5708 -0.0 3"/></joint></robot>'
    )
    assert '-->|"xyz: 0 0 0<br>rpy: 1.5708 0 3"|' in fishbot_urdf.to_mermaid(robot)
