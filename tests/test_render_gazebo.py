"""`fishbot render --show sensors,gazebo`: what Gazebo will simulate, checked by the pixels a
person sees: a lidar's fan as far as its range, a camera's frustum ahead of it, the links
sdformat lumps together in one colour."""

from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import DATA
from PIL import Image

import fishbot_urdf
from fishbot_urdf.analysis import analyse
from fishbot_urdf.cli import cli
from fishbot_urdf.drawing._sensors import LIDAR_DEPTH
from fishbot_urdf.drawing.scene import build_scene

ROBOT = DATA / "gazebo" / "fishbot_description" / "urdf" / "fishbot.urdf.xacro"
MARGIN = 1.12  # the picture frames everything with 12 % to spare (drawing/picture.py)


def _render(tmp_path: Path, robot: Path, *options: str) -> np.ndarray:
    out = tmp_path / "out.png"
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(out), *options])
    assert (result.exit_code, result.output) == (0, ""), result.stderr
    image = Image.open(io.BytesIO(out.read_bytes()))
    return np.asarray(image).astype(int)


def _orange(pixels: np.ndarray) -> np.ndarray:
    """Where the picture is a lidar's orange (shaded, not blended)."""
    r, g, b = (pixels[..., i] for i in range(3))
    return (r > 80) & (g > 0.3 * r) & (g < 0.7 * r) & (b < 0.3 * r)


def _purple(pixels: np.ndarray) -> np.ndarray:
    """Where the picture is a camera frustum's purple edges."""
    r, g, b = (pixels[..., i] for i in range(3))
    return (b > 80) & (g < 0.4 * b) & (r > 0.45 * b) & (r < 0.85 * b)


PLATE = """\
<robot name="plate">
  <link name="plate"><visual><geometry><box size="8 8 0.01"/></geometry></visual></link>
  <link name="lidar">
    <visual><geometry><cylinder radius="0.05" length="0.05"/></geometry></visual>
  </link>
  <joint name="mount" type="fixed">
    <parent link="plate"/><child link="lidar"/><origin xyz="0 0 0.5"/>
  </joint>
  <gazebo reference="lidar">
    <sensor name="scan" type="gpu_ray">
      <ray>
        <scan><horizontal>
          <samples>181</samples><min_angle>-1.5708</min_angle><max_angle>1.5708</max_angle>
        </horizontal></scan>
        <range><min>0.1</min><max>3</max></range>
      </ray>
    </sensor>
  </gazebo>
</robot>
"""


def test_a_lidars_fan_reaches_its_maximum_range(tmp_path: Path) -> None:
    robot = tmp_path / "plate.urdf"
    robot.write_text(PLATE, encoding="utf-8")
    orange = _orange(
        _render(tmp_path, robot, "--show", "visual,sensors", "--view", "top", "--size", "800x800")
    )
    assert not _orange(_render(tmp_path, robot, "--view", "top")).any()  # not by default
    # From the top: x up the picture, y to the left. The 8 m plate frames the square
    # picture: 8 * 1.12 m over 800 pixels, the lidar in the middle (400, 400). Its rays go
    # from -90 to 90 degrees (+y round to -y, through +x), 3 m long.
    metre = 800 / (8 * MARGIN)
    rows, columns = np.nonzero(orange)
    assert 400 - rows.min() == pytest.approx(3 * metre, abs=3)  # straight ahead, +x
    assert 400 - columns.min() == pytest.approx(3 * metre, abs=3)  # to +y
    assert columns.max() + 1 - 400 == pytest.approx(3 * metre, abs=3)  # to -y
    assert rows.max() <= 402  # nothing behind it
    # The arc at 3 m: orange 3 m from the lidar at every angle of the fan.
    for degrees in range(-80, 81, 20):
        a = math.radians(degrees)
        row = round(400 - 3 * metre * math.cos(a))
        column = round(400 - 3 * metre * math.sin(a))
        assert orange[row - 3 : row + 4, column - 3 : column + 4].any(), degrees


def test_the_fishbots_lidar_and_camera_as_gazebo_sees_them(tmp_path: Path) -> None:
    pixels = _render(
        tmp_path, ROBOT, "--show", "visual,sensors", "--view", "top", "--size", "800x800"
    )
    orange, purple = _orange(pixels), _purple(pixels)
    # The lidar's rays, all round (0 to 6.28 rad), reach 8 m: drawn 2 m long (LIDAR_DEPTH,
    # more than 4 times the robot's 0.3 m), they frame the picture: 4 m across.
    metre = 800 / (4 * MARGIN)
    rows, columns = np.nonzero(orange)
    assert rows.max() + 1 - rows.min() == pytest.approx(4 * metre, abs=4)
    assert columns.max() + 1 - columns.min() == pytest.approx(4 * metre, abs=4)
    # The camera, on camera_link at x = 0.1 m (the lidar, the middle of the picture, is at
    # x = 0.05), looks ahead (+x, up the picture): its frustum is drawn 1 m deep (its far
    # clip is 300 m), 2 tan(80 deg / 2) = 1.68 m across there; the depth camera's 60 deg.
    camera_row = 400 - 0.05 * metre
    rows, columns = np.nonzero(purple)
    assert rows.max() <= camera_row + 1.5  # all ahead of the camera
    assert camera_row - rows.min() == pytest.approx(1.0 * metre, abs=3)
    assert (columns.min() + columns.max() + 1) / 2 == pytest.approx(400, abs=1.5)
    across = 2 * math.tan(1.3962634 / 2) * metre
    assert columns.max() + 1 - columns.min() == pytest.approx(across, abs=3)
    far = purple[rows.min() : rows.min() + 3].any(axis=0).nonzero()[0]
    assert far.max() + 1 - far.min() == pytest.approx(across, abs=3)
    # Not drawn unless asked for.
    plain = _render(tmp_path, ROBOT, "--view", "top", "--size", "800x800")
    assert not _orange(plain).any() and not _purple(plain).any()


def test_a_sensor_on_a_lumped_link_is_drawn_where_it_is() -> None:
    analysis = analyse(fishbot_urdf.load(ROBOT))
    lumping = analysis.gazebo_lumping
    landing = lumping.landings["laser_link"]
    assert landing.link == "base_footprint"  # part of base_footprint in Gazebo
    # sdformat writes the sensor's pose in base_footprint's frame: laser_joint's origin
    # after base_joint's, 0.05 m ahead and 0.076 + 0.1 m up.
    assert landing.pose.translation == pytest.approx((0.05, 0.0, 0.176))
    scene = build_scene(analysis, show=("sensors", "gazebo"))
    [fan] = [p for p in scene.parts if p.layer == "sensors" and p.link == "laser_link"]
    corners = fan.triangles.reshape(-1, 3)
    middle = (corners.min(axis=0) + corners.max(axis=0)) / 2
    # The fan is drawn round laser_link, 8 m each way, in its plane.
    assert middle[:2] == pytest.approx((0.05, 0.0), abs=0.02)
    assert corners[:, 2].mean() == pytest.approx(0.176, abs=1e-6)


def test_a_sensor_is_drawn_in_the_same_place_with_the_links_lumped(tmp_path: Path) -> None:
    plain = _orange(_render(tmp_path, ROBOT, "--show", "visual,sensors", "--view", "iso"))
    lumped = _orange(_render(tmp_path, ROBOT, "--show", "gazebo,sensors", "--view", "iso"))
    assert plain.mean() > 0.01
    assert (plain != lumped).mean() < 0.001


def test_the_links_sdformat_lumps_together_share_a_colour(tmp_path: Path) -> None:
    scene = build_scene(analyse(fishbot_urdf.load(ROBOT)), show=("gazebo",))
    colours = {part.link: part.color for part in scene.parts}
    assert {part.layer for part in scene.parts} == {"gazebo"}
    # base_link, laser_link and camera_link are lumped into base_footprint (which has no
    # shape): one Gazebo link, one colour; each wheel turns on its own joint, its own link.
    body = colours["base_link"]
    assert colours["laser_link"] == colours["camera_link"] == body
    assert len({body, colours["left_wheel_link"], colours["right_wheel_link"]}) == 3
    # In the picture, from the top: the body is blue, as are the laser and the camera on it.
    pixels = _render(tmp_path, ROBOT, "--show", "gazebo", "--view", "top")
    r, g, b = (pixels[..., i] for i in range(3))
    blue = (b > 100) & (b > r + 50) & (b > g + 20)
    grey = (abs(r - g) < 8) & (abs(g - b) < 8) & (r < 235)  # no visual in its own colour
    assert blue.mean() > 0.2 and not grey.any()


DROPPED = """\
<robot name="dropped">
  <link name="base">
    <visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual>
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
  <link name="arm"><visual><geometry><box size="0.05 0.05 0.3"/></geometry></visual></link>
  <joint name="turn" type="revolute">
    <parent link="base"/><child link="arm"/><origin xyz="0 0 0.25"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
"""


def test_a_link_sdformat_leaves_out_is_a_dark_ghost(tmp_path: Path) -> None:
    robot = tmp_path / "dropped.urdf"
    robot.write_text(DROPPED, encoding="utf-8")
    scene = build_scene(analyse(fishbot_urdf.load(robot)), show=("gazebo",))
    colours = {part.link: part.color for part in scene.parts}
    assert colours["arm"][3] < 1 and max(colours["arm"][:3]) < 0.2  # no mass: left out
    assert colours["base"][3] == 1
    pixels = _render(tmp_path, robot, "--show", "gazebo", "--view", "front")
    r, g, b = (pixels[..., i] for i in range(3))
    ghost = (abs(r - g) < 6) & (abs(g - b) < 6) & (r > 100) & (r < 200)
    assert ghost.mean() > 0.02


LIDAR_3D = """\
<robot name="car">
  <link name="base"><visual><geometry><box size="4 2 1"/></geometry></visual></link>
  <link name="roof"/>
  <joint name="mount" type="fixed">
    <parent link="base"/><child link="roof"/><origin xyz="0 0 0.5"/>
  </joint>
  <gazebo reference="roof">
    <sensor name="velodyne" type="gpu_lidar">
      <pose>0 0 0.2 0 0 0</pose>
      <lidar>
        <scan>
          <horizontal><samples>1800</samples><min_angle>-3.14159</min_angle>
            <max_angle>3.14159</max_angle></horizontal>
          <vertical><samples>16</samples><min_angle>-0.26</min_angle>
            <max_angle>0.26</max_angle></vertical>
        </scan>
        <range><min>0.9</min><max>30</max></range>
      </lidar>
    </sensor>
    <sensor name="eyes" type="multicamera">
      <camera name="left"><pose>0 0.05 0 0 0 0</pose><horizontal_fov>1</horizontal_fov>
        <clip><near>0.1</near><far>0.5</far></clip></camera>
      <camera name="right"><pose>0 -0.05 0 0 0 0</pose><horizontal_fov>1</horizontal_fov>
        <clip><near>0.1</near><far>0.5</far></clip></camera>
    </sensor>
  </gazebo>
</robot>
"""


def test_a_3d_lidar_is_drawn_in_rows_of_rays_and_a_multicamera_in_frustums() -> None:
    scene = build_scene(fishbot_urdf.parse(LIDAR_3D), show=("sensors",))
    fan, left, left_sides, right, right_sides = scene.parts
    assert {p.link for p in scene.parts} == {"roof"}
    # The roof is 0.5 m up, the lidar 0.2 m above it: its rays start 0.9 m from there; they
    # reach 30 m, drawn 2 m long (LIDAR_DEPTH: the robot is small), with no arc at their end.
    assert fan.lines is not None
    start, end = fan.lines[:, 0] - (0, 0, 0.2), fan.lines[:, 1] - (0, 0, 0.2)
    rays = np.isclose(np.linalg.norm(start, axis=1), 0.9)
    assert np.allclose(np.linalg.norm(end, axis=1), LIDAR_DEPTH)
    # 1800 samples: every 31st (ceil(1799 / 59)) and the last, 60 rays a row; 16 rows: every
    # 3rd (ceil(15 / 7)), 6 rows, the last (0.26 rad up) among them.
    assert rays.sum() == 60 * 6
    elevations = np.unique(np.round(np.arcsin(end[rays, 2] / LIDAR_DEPTH), 6))
    assert elevations == pytest.approx(np.linspace(-0.26, 0.26, 16)[::3])
    assert rays.all()
    assert fan.triangles.reshape(-1, 3)[:, 2].max() == pytest.approx(
        0.5 + 0.2 + LIDAR_DEPTH * math.sin(0.26), abs=0.02
    )
    # Each camera's frustum at its own pose: 0.5 m deep (its far clip), 1 rad across.
    for edges, y in ((left, 0.05), (right, -0.05)):
        corners = edges.lines.reshape(-1, 3) - (0, y, 0)
        assert corners[:, 0].max() == pytest.approx(0.5)
        assert corners[:, 1].max() == pytest.approx(0.5 * math.tan(0.5))
    assert left_sides.color[3] < 1 and right_sides.lines is None


def test_a_robot_without_sensors_has_none_to_draw(tmp_path: Path) -> None:
    robot = DATA / "valid" / "all_elements.urdf"
    out = tmp_path / "x.png"
    result = CliRunner().invoke(cli, ["render", str(robot), "-o", str(out), "--show", "sensors"])
    assert result.exit_code == 1 and not out.exists()
    assert result.stderr.splitlines()[-2].endswith(
        "no link has a lidar or camera <sensor> in its <gazebo reference> block: there is "
        'nothing to draw (write a <sensor type="ray"> or "camera" in a <gazebo '
        'reference="LINK"> block) [nothing-drawn]'
    )
