"""Topology, tree queries, check_urdf's tree text and the networkx export."""

from __future__ import annotations

import sys

import pytest
from conftest import DATA
from hypothesis import given, settings
from hypothesis import strategies as st

import fishbot_urdf
from fishbot_urdf import FishbotUrdfError, Joint, JointType, Link, Robot, analysis
from fishbot_urdf.analysis import analyse

ORDERING = DATA / "valid" / "ordering.urdf"
ALL = DATA / "valid" / "all_elements.urdf"


def _chain(depth: int) -> Robot:
    links = tuple(Link(f"l{i}") for i in range(depth))
    joints = tuple(Joint(f"j{i}", JointType.FIXED, f"l{i - 1}", f"l{i}") for i in range(1, depth))
    return Robot("chain", links, joints)


def test_children_follow_joint_names() -> None:
    robot = fishbot_urdf.load(ORDERING)
    topo = fishbot_urdf.topology(robot)
    # Joint names J_upper < j_a < j_b < j_c in byte order, as urdfdom's std::map has them.
    assert [j.name for j in topo.children["base"]] == ["j_a", "j_b", "j_c"]
    assert topo.roots == ("base",)
    assert topo.reachable == {"base", "zebra", "apple", "mango", "kiwi"}


def test_tree_text() -> None:
    robot = fishbot_urdf.load(ORDERING)
    assert "".join(fishbot_urdf.tree_text(robot)) == (
        "robot name is: ordering\n"
        "---------- Successfully Parsed XML ---------------\n"
        "root Link: base has 3 child(ren)\n"
        "    child(1):  mango\n"
        "        child(1):  kiwi\n"
        "    child(2):  zebra\n"
        "    child(3):  apple\n"
    )


def test_deep_chain_does_not_recurse() -> None:
    depth = sys.getrecursionlimit() * 3
    robot = _chain(depth)
    lines = "".join(fishbot_urdf.tree_text(robot)).splitlines()
    assert len(lines) == depth + 2
    assert lines[-1] == " " * 4 * (depth - 1) + f"child(1):  l{depth - 1}"
    assert fishbot_urdf.chain(robot, "l0", f"l{depth - 1}")[-1] == f"l{depth - 1}"
    assert len(fishbot_urdf.subtree(robot, "l0")) == depth


def test_root_leaves_subtree_chain() -> None:
    robot = fishbot_urdf.load(ALL)
    assert fishbot_urdf.root(robot) == "base_link"
    assert fishbot_urdf.leaves(robot) == [
        "finger_a",
        "finger_b",
        "world_marker",
        "drawer",
        "puck",
        "camera_link",
    ]
    assert fishbot_urdf.subtree(robot, "arm") == ["arm", "finger_a", "finger_b"]
    assert fishbot_urdf.chain(robot, "base_link", "finger_b") == ["base_link", "arm", "finger_b"]
    # Up to the common ancestor, then down.
    assert fishbot_urdf.chain(robot, "finger_a", "puck") == ["finger_a", "arm", "base_link", "puck"]
    with pytest.raises(KeyError):
        fishbot_urdf.chain(robot, "base_link", "nope")


def test_root_of_a_robot_with_two_roots_raises() -> None:
    robot = Robot("two", (Link("a"), Link("b")))
    with pytest.raises(FishbotUrdfError, match="needs one root link, and has 2"):
        fishbot_urdf.root(robot)


def test_unconnected_links_raise_in_chain() -> None:
    robot = Robot("two", (Link("a"), Link("b")))
    with pytest.raises(FishbotUrdfError, match="not connected"):
        fishbot_urdf.chain(robot, "a", "b")


def test_to_networkx() -> None:
    robot = fishbot_urdf.load(ALL)
    graph = fishbot_urdf.to_networkx(robot)
    assert graph.graph["name"] == "everything"
    assert set(graph.nodes) == {link.name for link in robot.links}
    assert graph.number_of_edges() == len(robot.joints)
    edge = graph.edges["base_link", "arm", "shoulder"]
    assert edge["type"] == "revolute"
    assert edge["joint"] is robot.joint("shoulder")
    assert graph.nodes["arm"]["link"] is robot.link("arm")
    import networkx as nx

    assert nx.is_arborescence(graph)


def test_networkx_is_not_imported_by_check() -> None:
    """`fishbot check` starts without the heavy imports: networkx, numpy, graphviz."""
    import subprocess

    code = (
        "import sys, fishbot_urdf, fishbot_urdf.cli;"
        f"fishbot_urdf.check_file({str(ALL)!r});"
        "print([m for m in ('networkx', 'numpy', 'graphviz') if m in sys.modules])"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_tree_text_of_a_deep_chain_indents_four_spaces_per_level() -> None:
    from fishbot_urdf.graph import tree_text
    from fishbot_urdf.parsing import parse

    depth = 3000
    links = "".join(f'<link name="l{i}"/>' for i in range(depth + 1))
    joints = "".join(
        f'<joint name="j{i}" type="fixed"><parent link="l{i - 1}"/><child link="l{i}"/></joint>'
        for i in range(1, depth + 1)
    )
    robot = parse(f'<robot name="c">{links}{joints}</robot>')
    lines = "".join(tree_text(robot)).splitlines()
    assert lines[3:] == [f"{'    ' * i}child(1):  l{i}" for i in range(1, depth + 1)]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 5), st.integers(0, 5)), max_size=8))
def test_every_joint_loop_is_found_the_tree_taken_only_when_there_is_none(
    edges: list[tuple[int, int]],
) -> None:
    links = tuple(Link(f"l{i}") for i in range(6))
    joints = tuple(
        Joint(f"j{k}", JointType.FIXED, f"l{parent}", f"l{child}")
        for k, (parent, child) in enumerate(edges)
    )
    robot = Robot("r", links, joints)
    found = analyse(robot).loops
    assert found == analysis._loops(robot, fishbot_urdf.topology(robot))  # the whole search
