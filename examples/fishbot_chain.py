"""Build the fishbot's networkx graph and print the kinematic chain from the footprint to the lidar.

Run from the repository root:  python examples/fishbot_chain.py
"""

from __future__ import annotations

from itertools import pairwise
from pathlib import Path

import networkx as nx

import fishbot_urdf

ROBOT = Path(__file__).resolve().parent.parent / "robots" / "fishbot" / "urdf" / "fishbot"


def main() -> None:
    robot = fishbot_urdf.load(ROBOT / "fishbot.urdf.xacro")
    graph = fishbot_urdf.to_networkx(robot)  # links are nodes, joints are edges keyed by name
    print(f"{robot.name}: {graph.number_of_nodes()} links, {graph.number_of_edges()} joints")
    print("tree:", "yes" if nx.is_arborescence(graph) else "no")

    path = nx.shortest_path(graph, "base_footprint", "laser_link")
    print("chain base_footprint -> laser_link:")
    offset = [0.0, 0.0, 0.0]
    rotated = False
    for parent, child in pairwise(path):
        (joint,) = (data["joint"] for data in graph[parent][child].values())
        xyz = joint.origin.xyz
        rotated = rotated or any(joint.origin.rpy)
        offset = [a + b for a, b in zip(offset, xyz, strict=True)]
        print(
            f"  {parent} --[{joint.name}, {joint.type.value}, "
            f"xyz {xyz[0]:g} {xyz[1]:g} {xyz[2]:g}]--> {child}"
        )
    if not rotated:  # with no rotation on the way, the offsets simply add up
        x, y, z = offset
        print(f"laser_link sits at ({x:g}, {y:g}, {z:g}) m in base_footprint")


if __name__ == "__main__":
    main()
