"""Plugins of the wrong ROS or the wrong Gazebo for the robot they are written in."""

from __future__ import annotations

import os
from collections.abc import Iterator, Sequence

from lxml import etree

from ...analysis import Analysis
from ...analysis.gazebo import Block, place, plugins
from ...catalog.gazebo import PLUGIN_ROS_VERSION, PLUGIN_SIMULATOR
from ...diagnostics import Diagnostic, Kind, Subject
from ...packages import ros_version, upward_folders

__all__ = ["ros_versions", "simulators"]

# Plugin files of gazebo_ros_pkgs' ROS 1 branch (noetic-devel) that its ROS 2 branch does not
# build, with what takes their place there (None: nothing does); and gazebo_ros_control's.
_ROS1_ONLY: dict[str, str | None] = {
    "libgazebo_ros_laser.so": "libgazebo_ros_ray_sensor.so",
    "libgazebo_ros_gpu_laser.so": "libgazebo_ros_ray_sensor.so on a gpu_ray sensor",
    "libgazebo_ros_block_laser.so": "libgazebo_ros_ray_sensor.so",
    "libgazebo_ros_range.so": "libgazebo_ros_ray_sensor.so with output_type sensor_msgs/Range",
    "libgazebo_ros_openni_kinect.so": "libgazebo_ros_camera.so on a depth sensor",
    "libgazebo_ros_depth_camera.so": "libgazebo_ros_camera.so on a depth sensor",
    "libgazebo_ros_multicamera.so": "libgazebo_ros_camera.so on a multicamera sensor",
    "libgazebo_ros_triggered_camera.so": "libgazebo_ros_camera.so with <triggered>",
    "libgazebo_ros_triggered_multicamera.so": "libgazebo_ros_camera.so on a multicamera sensor",
    "libgazebo_ros_imu.so": "libgazebo_ros_imu_sensor.so",
    "libgazebo_ros_skid_steer_drive.so": "libgazebo_ros_diff_drive.so with num_wheel_pairs",
    "libgazebo_ros_control.so": "libgazebo_ros2_control.so, of gazebo_ros2_control",
    "libgazebo_ros_f3d.so": None,
    "libgazebo_ros_prosilica.so": None,
}
# Plugin files only ROS 2 has: a robot that loads one is a ROS 2 robot.
_ROS2_ONLY = frozenset(
    {
        "libgazebo_ros_ray_sensor.so",
        "libgazebo_ros_gps_sensor.so",
        "libgazebo_ros_ackermann_drive.so",
        "libgazebo_ros2_control.so",
        "libgz_ros2_control-system.so",
        "gz_ros2_control-system",
        "libign_ros2_control-system.so",
        "ign_ros2_control-system",
    }
)
# ROS 1 parameters of gazebo_ros_pkgs' plugins, which the ROS 2 versions pass over.
_ROS1_PARAMETERS = {
    "leftJoint": "<left_joint>",
    "rightJoint": "<right_joint>",
    "wheelSeparation": "<wheel_separation>",
    "wheelDiameter": "<wheel_diameter>",
    "wheelTorque": "<max_wheel_torque>",
    "wheelAcceleration": "<max_wheel_acceleration>",
    "robotBaseFrame": "<robot_base_frame>",
    "odometryFrame": "<odometry_frame>",
    "frameName": "<frame_name>",
    "bodyName": "<body_name>",
    "jointName": "<joint_name>",
    "updateRate": "<update_rate>",
    "robotNamespace": "<ros><namespace>",
    "topicName": "<ros><remapping>",
    "commandTopic": "<ros><remapping>",
    "odometryTopic": "<ros><remapping>",
    "imageTopicName": "<ros><remapping>",
    "cameraName": "<camera_name>",
}
_CLASSIC = ("libgazebo_", "gazebo_ros2_control/")
_NEW = (
    "gz-sim",
    "libgz-sim",
    "ignition-gazebo",
    "libignition-gazebo",
    "gz_ros2_control",
    "libgz_ros2_control",
    "ign_ros2_control",
    "libign_ros2_control",
)


def ros_versions(analysis: Analysis, found: Sequence[Block]) -> Iterator[Diagnostic]:
    """ROS 1 plugins and plugin parameters, in a robot of ROS 2."""
    if not any(_ros1(plugin) for block in found for plugin in plugins(block)):
        return  # (nearly always): no package.xml is read
    if _ros(analysis, found) != 2:
        return
    subject = Subject(Kind.ROBOT, analysis.robot.name)
    for block in found:
        for plugin in plugins(block):
            filename = plugin.get("filename") or ""
            where = place(analysis.references, block, plugin)
            if filename in _ROS1_ONLY:
                instead = _ROS1_ONLY[filename]
                yield PLUGIN_ROS_VERSION.report(
                    f"plugin {filename!r} is ROS 1's; this robot is for ROS 2, which has no "
                    "such file",
                    where,
                    path=analysis.path,
                    subject=subject,
                    hint=f"use {instead}"
                    if instead
                    else "ROS 2's gazebo_plugins has no "
                    "version of it: leave it out or write your own",
                )
                continue
            if not filename.startswith("libgazebo_ros"):
                continue
            old = [child.tag for child in plugin if child.tag in _ROS1_PARAMETERS]
            if old:
                listed = ", ".join(f"<{tag}>" for tag in old)
                instead = ", ".join(f"<{tag}> -> {_ROS1_PARAMETERS[tag]}" for tag in old)
                yield PLUGIN_ROS_VERSION.report(
                    f"plugin {filename!r} is given ROS 1 parameters {listed}, which its ROS 2 "
                    "version does not read",
                    where,
                    path=analysis.path,
                    subject=subject,
                    hint=f"write them as ROS 2 does: {instead}",
                )


def _ros1(plugin: etree._Element) -> bool:
    """Whether ``plugin`` is a ROS 1 plugin file or is given a ROS 1 parameter."""
    filename = plugin.get("filename") or ""
    if filename in _ROS1_ONLY:
        return True
    return filename.startswith("libgazebo_ros") and any(
        child.tag in _ROS1_PARAMETERS for child in plugin
    )


def simulators(analysis: Analysis, found: Sequence[Block]) -> Iterator[Diagnostic]:
    """Gazebo Classic plugins among the new Gazebo's systems, or the reverse: those of the
    kind fewer in number (on a tie, of the kind that comes second)."""
    classic: list[tuple[Block, etree._Element, str]] = []
    new: list[tuple[Block, etree._Element, str]] = []
    new_first = False  # whether the first of either kind, in file order, is the new Gazebo's
    for block in found:
        for element, name in _loaded(block):
            if name.startswith(_CLASSIC):
                classic.append((block, element, name))
            elif name.startswith(_NEW):
                new_first = new_first or not classic
                new.append((block, element, name))
    if not classic or not new:
        return
    if len(classic) < len(new) or (len(classic) == len(new) and new_first):
        odd, kind, other = classic, "Gazebo Classic", "the new Gazebo (gz-sim)"
    else:
        odd, kind, other = new, "the new Gazebo (gz-sim)", "Gazebo Classic"
    subject = Subject(Kind.ROBOT, analysis.robot.name)
    others = {name for _, _, name in (new if odd is classic else classic)}
    for block, element, name in odd:
        yield PLUGIN_SIMULATOR.report(
            f"plugin {name!r} is {kind}'s, but this robot's other plugins "
            f"({', '.join(sorted(others))}) are for {other}",
            place(analysis.references, block, element),
            path=analysis.path,
            subject=subject,
            hint=f"use {other}'s plugin for it, or move the whole robot to {kind}",
        )


def _loaded(block: Block) -> Iterator[tuple[etree._Element, str]]:
    """What a block loads: its plugins' files, a ``<ros2_control>``'s hardware plugin."""
    if block.element.tag == "ros2_control":
        for hardware in block.element.iter("hardware"):
            for plugin in hardware.iter("plugin"):
                if plugin.text and plugin.text.strip():
                    yield plugin, plugin.text.strip()
        return
    for plugin in plugins(block):
        yield plugin, plugin.get("filename") or ""


def _ros(analysis: Analysis, found: Sequence[Block]) -> int | None:
    """2 for a ROS 2 robot: its package.xml builds with ament, or (with no package.xml that
    says) it uses ROS 2's plugins, ``<ros>`` settings or ``<ros2_control>``; else 1 or None."""
    if os.path.isfile(analysis.path):
        folder = os.path.dirname(os.path.abspath(analysis.path))
        for above in upward_folders(folder):
            manifest = os.path.join(above, "package.xml")
            if os.path.isfile(manifest):
                version = ros_version(manifest)
                if version is not None:
                    return version
                break
    for block in found:
        if block.element.tag == "ros2_control":
            return 2
        for plugin in plugins(block):
            if plugin.get("filename") in _ROS2_ONLY or plugin.find("ros") is not None:
                return 2
    return None
