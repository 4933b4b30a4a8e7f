"""Load the first fishbot and print its links and joints.

Run from the repository root:  python examples/inspect_first_robot.py
"""

from __future__ import annotations

from pathlib import Path

import fishbot_urdf

ROBOT = Path(__file__).resolve().parent.parent / "robots" / "fishbot" / "urdf" / "first_robot.urdf"


def main() -> None:
    robot = fishbot_urdf.load(ROBOT)
    print(f"robot {robot.name}: {len(robot.links)} links, {len(robot.joints)} joints")
    for link in robot.links:
        shapes = ", ".join(type(v.geometry).__name__.lower() for v in link.visuals) or "no visual"
        print(f"  link  {link.name:<10} {shapes}")
    for joint in robot.joints:
        x, y, z = joint.origin.xyz
        print(
            f"  joint {joint.name:<10} {joint.type.value:<10} {joint.parent} -> {joint.child}"
            f" at ({x:g}, {y:g}, {z:g}) m"
        )
    findings = fishbot_urdf.check(robot)
    print("check:", "ok" if not findings else f"{len(findings)} finding(s)")


if __name__ == "__main__":
    main()
