"""`fishbot tf`: where one frame of the robot is in another, as ROS's tf2_echo prints it."""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Sequence
from typing import Any

import click

from ..errors import ArgumentError, StructureError, UnknownNameError
from ..kinematics import Kinematics
from ..spatial import euler_ypr, quaternion
from ._checking import posable_input
from ._common import (
    EXIT_OK,
    format_option,
    joint_option,
    joint_positions,
    limit_options,
    package_option,
    packages_option,
    stop_on,
    to_stdout,
    xacro_args,
)


@click.command()
@click.argument("file", type=click.Path(allow_dash=True))
@click.argument("frame_from", metavar="FROM")
@click.argument("frame_to", metavar="TO")
@click.argument("args", nargs=-1, metavar="[name:=value]...")
@joint_option()
@format_option(
    ("text", "json"), "text: as tf2_echo prints it; json: the same numbers for programs."
)
@package_option()
@limit_options()
def tf(
    file: str,
    frame_from: str,
    frame_to: str,
    args: Sequence[str],
    joint_items: Sequence[str],
    fmt: str,
    package_items: Sequence[str],
) -> None:
    """Where frame TO is in frame FROM (both links of FILE, a URDF or xacro file), as
    `ros2 run tf2_ros tf2_echo FROM TO` prints it with robot_state_publisher running.

    Joints are at 0 unless -j places them (mimic joints follow their leader). Planar and
    floating joints take JOINT.x, JOINT.y, JOINT.yaw (planar) or JOINT.x ... JOINT.yaw
    (floating: x y z roll pitch yaw). Findings about the robot are printed as check prints
    them. Exit status: 0 done (errors that leave the frames as they are, such as a fault in
    an <inertial>, do not stop it), 1 the robot has errors that leave its shape or tree in
    doubt (nothing is computed), 2 a frame or joint that does not exist, a position outside
    its limits, a file that cannot be read, or a wrong command line.

    \b
    Examples:
      fishbot tf robots/fishbot/urdf/fishbot/fishbot.urdf.xacro base_link laser_link
      fishbot tf arm.urdf base_link tool0 -j shoulder=90deg -j elbow=-0.5
      fishbot tf robot.urdf.xacro base_link camera_link use_sim:=true --format json
    """
    if file == "-" and args:
        raise click.UsageError("name:=value arguments are for a .xacro file, not standard input")
    values = xacro_args(args)
    positions = joint_positions(joint_items)
    result = posable_input(file, values, packages_option(package_items))
    assert result.analysis is not None
    try:
        kinematics = Kinematics(result.analysis)
        for name in (frame_from, frame_to):
            kinematics.link_index(name)
        pose = kinematics.transform(kinematics.configuration(positions), frame_from, frame_to)
    except UnknownNameError as exc:
        raise click.UsageError(exc.message) from None
    except ArgumentError as exc:
        raise click.BadParameter(exc.message, param_hint="--joint") from None
    except StructureError as exc:
        stop_on(exc)
    matrix = [[float(v) for v in row] for row in pose]
    report = _report(matrix)
    if fmt == "json":
        report = {"from": frame_from, "to": frame_to, "positions": positions, **report}
        to_stdout((json.dumps(report, indent=2) + "\n").encode("utf-8"))
    else:
        to_stdout(_tf2_echo(report).encode("utf-8"))
    sys.exit(EXIT_OK)


def _report(matrix: list[list[float]]) -> dict[str, Any]:
    rotation = [row[:3] for row in matrix[:3]]
    roll, pitch, yaw = euler_ypr(rotation)
    return {
        "translation": [matrix[0][3], matrix[1][3], matrix[2][3]],
        "quaternion_xyzw": list(quaternion(rotation)),
        "rpy": [roll, pitch, yaw],
        "rpy_degrees": [math.degrees(roll), math.degrees(pitch), math.degrees(yaw)],
        "matrix": matrix,
    }


def _tf2_echo(report: dict[str, Any]) -> str:
    def listed(values: list[float]) -> str:
        return "[" + ", ".join(f"{v:.3f}" for v in values) + "]"

    lines = [
        "At time 0.0",
        f"- Translation: {listed(report['translation'])}",
        f"- Rotation: in Quaternion (xyzw) {listed(report['quaternion_xyzw'])}",
        f"- Rotation: in RPY (radian) {listed(report['rpy'])}",
        f"- Rotation: in RPY (degree) {listed(report['rpy_degrees'])}",
        "- Matrix:",
    ]
    lines += ["".join(f" {v:6.3f}" for v in row) for row in report["matrix"]]
    return "\n".join(lines) + "\n"
