"""Print the fishbot's mass table: each part's mass and where it sits, then the whole robot's
mass, centre of mass and inertia, and how they change when a wheel turns.

Run from the repository root:  python examples/fishbot_mass.py
"""

from __future__ import annotations

import math
from pathlib import Path

import fishbot_urdf

ROBOT = Path(__file__).resolve().parent.parent / "robots" / "fishbot" / "urdf" / "fishbot"


def main() -> None:
    robot = fishbot_urdf.load(ROBOT / "fishbot.urdf.xacro")
    poses = fishbot_urdf.link_poses(robot)  # every link's frame in base_footprint
    print(f"{'link':<20} {'mass kg':>8}  centre of mass in base_footprint (m)")
    for link in robot.links:
        if link.inertial is None:
            continue
        x, y, z = poses[link.name].apply(link.inertial.origin.xyz)
        print(f"{link.name:<20} {link.inertial.mass:>8g}  {x:7.3f} {y:7.3f} {z:7.3f}")

    whole = fishbot_urdf.mass_properties(robot)
    x, y, z = whole.com
    print(f"total {whole.mass:g} kg, centre of mass ({x:.4f}, {y:.4f}, {z:.4f}) m")
    moments = ", ".join(f"{m:.3e}" for m in whole.principal_moments)
    print(f"principal moments about it: {moments} kg*m^2")

    # A round wheel turning does not move the robot's centre of mass.
    turned = fishbot_urdf.mass_properties(robot, {"left_wheel_joint": math.pi / 3})
    moved = max(abs(a - b) for a, b in zip(turned.com, whole.com, strict=True))
    print(f"left wheel turned 60 degrees: centre of mass moves {moved:.1e} m")


if __name__ == "__main__":
    main()
