"""The sensors of a robot's ``<gazebo>`` blocks as the analysis reads them: the values the
fishbot's xacro writes, and what is None when not written or not a number."""

from __future__ import annotations

import math

import pytest
from conftest import DATA

from fishbot_urdf import load
from fishbot_urdf.analysis import analyse
from fishbot_urdf.analysis.sensors import Camera, Rays, Scan, Sensor, sdf_pose
from fishbot_urdf.parsing import parse
from fishbot_urdf.spatial import Pose, rpy_matrix

ROBOT = DATA / "gazebo" / "fishbot_description" / "urdf" / "fishbot.urdf.xacro"


def test_the_fishbots_lidar_and_cameras_are_read_as_written() -> None:
    analysis = analyse(load(ROBOT))
    laser, camera, depth = analysis.sensors
    assert (laser.kind, laser.name, laser.link, laser.update_rate) == (
        "ray",
        "laser",
        "laser_link",
        5,
    )
    assert laser.pose == Pose()
    assert laser.rays == (Rays(Scan(360, 0.0, 6.28), None, 0.12, 8.0),)
    assert laser.cameras == ()
    assert (camera.kind, camera.name, camera.link, camera.update_rate) == (
        "camera",
        "camera",
        "camera_link",
        30,
    )
    assert camera.cameras == (Camera(1.3962634, 640, 480, 0.02, 300, Pose()),)
    assert camera.rays == ()
    assert (depth.kind, depth.cameras) == ("depth", (Camera(1.0472, 640, 480, 0.05, 8.0, Pose()),))
    assert laser.block is analysis.gazebo_blocks[1]  # after the drive's block
    assert laser.where == laser.block.where
    assert analysis.sensors is analysis.sensors  # read once


def test_the_xacro_arguments_reach_the_facts() -> None:
    laser = analyse(load(ROBOT, args={"samples": "90", "range_min": "0.3"})).sensors[0]
    assert laser.rays[0].horizontal.samples == 90
    assert laser.rays[0].range_min == 0.3


OTHERS = """\
<robot name="r">
  <link name="a"/>
  <gazebo reference="a">
    <sensor name="velodyne" type="gpu_lidar">
      <pose>0.1 0 0.2 0 0.5 1.5708</pose>
      <lidar>
        <scan>
          <horizontal><samples>1800</samples><min_angle>-3.14</min_angle>
            <max_angle>3.14</max_angle></horizontal>
          <vertical><samples>16</samples><min_angle>-0.26</min_angle>
            <max_angle>0.26</max_angle></vertical>
        </scan>
        <range><min>0.9</min><max>${range}</max></range>
      </lidar>
    </sensor>
    <sensor name="imu" type="imu"><update_rate>100</update_rate></sensor>
    <sensor name="eyes" type="multicamera">
      <pose>1 2 3</pose>
      <camera name="left"><pose>0 0.05 0 0 0 0</pose><horizontal_fov>1</horizontal_fov></camera>
      <camera name="right"><pose>0 -0.05 0 0 0 0</pose></camera>
    </sensor>
  </gazebo>
  <gazebo><sensor type="contact"/></gazebo>
  <ros2_control name="c" type="system"><sensor name="ft"/></ros2_control>
</robot>
"""


def test_a_3d_lidar_an_imu_and_a_multicamera_and_what_is_not_written() -> None:
    velodyne, imu, eyes, contact = analyse(parse(OTHERS)).sensors
    assert velodyne.pose.translation == (0.1, 0.0, 0.2)
    assert velodyne.pose.rotation == rpy_matrix((0.0, 0.5, 1.5708))
    [rays] = velodyne.rays
    assert rays.vertical == Scan(16, -0.26, 0.26)
    assert (rays.range_min, rays.range_max) == (0.9, None)  # an expression left: no number
    assert (imu.kind, imu.update_rate, imu.rays, imu.cameras) == ("imu", 100, (), ())
    assert eyes.pose == Pose()  # three numbers are no pose
    left, right = eyes.cameras
    assert left.pose.translation == (0.0, 0.05, 0.0)
    assert (left.horizontal_fov, right.horizontal_fov, right.width, right.far) == (
        1.0,
        None,
        None,
        None,
    )
    assert (contact.kind, contact.name, contact.link) == ("contact", "", None)
    assert all(isinstance(s, Sensor) for s in (velodyne, imu, eyes, contact))


@pytest.mark.parametrize(
    ("written", "translation", "rpy"),
    [
        ("1 2 3 0 0 0", (1.0, 2.0, 3.0), (0.0, 0.0, 0.0)),
        ("  0 0 0.5  0 0 3.14159 ", (0.0, 0.0, 0.5), (0.0, 0.0, 3.14159)),
        (None, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
        ("1 2 3 0 0 x", (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
    ],
)
def test_an_sdf_pose(
    written: str | None, translation: tuple[float, ...], rpy: tuple[float, float, float]
) -> None:
    pose = sdf_pose(written)
    assert pose.translation == translation
    assert all(
        math.isclose(a, b, abs_tol=1e-12)
        for row, want in zip(pose.rotation, rpy_matrix(rpy), strict=True)
        for a, b in zip(row, want, strict=True)
    )
