"""Expand the fishbot's xacro (no ROS needed) and print its links and joints.

Run from the repository root:  python examples/expand_fishbot.py
"""

from __future__ import annotations

from pathlib import Path

import fishbot_urdf

XACRO = Path(__file__).resolve().parent.parent / "robots/fishbot/urdf/fishbot/fishbot.urdf.xacro"


def main() -> None:
    # $(find fishbot_description) is found by walking up to robots/fishbot/package.xml.
    expansion = fishbot_urdf.expand(XACRO)
    robot = fishbot_urdf.parse(expansion.text)
    print(f"robot {robot.name}: {len(robot.links)} links from {len(expansion.dependencies)} files")
    for link in robot.links:
        mass = f"{link.inertial.mass:g} kg" if link.inertial else "no mass"
        shapes = ", ".join(type(v.geometry).__name__.lower() for v in link.visuals) or "no visual"
        print(f"  link  {link.name:<20} {shapes:<9} {mass}")
    for joint in robot.joints:
        print(f"  joint {joint.name:<20} {joint.type.value:<10} {joint.parent} -> {joint.child}")


if __name__ == "__main__":
    main()
