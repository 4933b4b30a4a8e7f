"""Drive the fishbot's wheels in numpy: where the left wheel is for a thousand wheel angles at
once, one frame in another, and the Jacobian of the lidar.

Run from the repository root:  python examples/fishbot_kinematics.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import fishbot_urdf

ROBOT = Path(__file__).resolve().parent.parent / "robots" / "fishbot" / "urdf" / "fishbot"


def main() -> None:
    kin = fishbot_urdf.Kinematics(fishbot_urdf.load(ROBOT / "fishbot.urdf.xacro"))
    print("variables:", ", ".join(kin.variables))  # the configuration's entries, in order

    angles = np.linspace(0.0, 2 * np.pi, 1000)
    batch = np.column_stack([angles, -angles])  # left forward, right backward: a turn on the spot
    poses = kin.forward(batch)  # (1000, links, 4, 4), every link in base_footprint's frame
    wheel = poses[:, kin.link_index("left_wheel_link")]
    print("left wheel centre, always:", np.round(wheel[0, :3, 3], 3))
    # the wheel link's x axis turns about y as the wheel rolls: its z component is -sin(angle)
    print("x axis z-component at 90 degrees:", round(float(wheel[250, 2, 0]), 3))

    pose = kin.transform({"left_wheel_joint": np.pi / 2}, "laser_link", "left_wheel_link")
    print("left wheel in the lidar's frame:", np.round(pose[:3, 3], 3))

    jac = kin.jacobian(np.zeros(len(kin.variables)), "left_wheel_link")  # 6 x n, root axes
    print("left wheel's angular velocity per wheel rad/s:", jac[3:, 0])


if __name__ == "__main__":
    main()
