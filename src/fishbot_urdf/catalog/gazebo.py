"""The rules on Gazebo's plugins and sensors, held to the robot they are written in.

Data only: the checks that report them are in `fishbot_urdf.rules`.
"""

from __future__ import annotations

from ..diagnostics import Consumer, Family, Rule, Severity

E, W = Severity.ERROR, Severity.WARNING
_DRIVE = """\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel"/>
  <link name="right_wheel"/>
  <joint name="left_wheel_joint" type="{type}"><origin xyz="0 {left} 0"/><axis xyz="0 1 0"/>
    <parent link="base_link"/><child link="left_wheel"/></joint>
  <joint name="right_wheel_joint" type="continuous"><origin xyz="0 {right} 0"/><axis xyz="0 1 0"/>
    <parent link="base_link"/><child link="right_wheel"/></joint>
  <gazebo><plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
    <left_joint>left_wheel_joint</left_joint><right_joint>right_wheel_joint</right_joint>
    <wheel_separation>{separation}</wheel_separation>
  </plugin></gazebo>
</robot>
"""
# a body 0.12 m high, 1 kg, with its inertia
_BOX_BASE = """\
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.12"/></geometry></collision>
    <inertial><mass value="1"/>
      <inertia ixx="0.004533" iyy="0.004533" izz="0.006667" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
"""
_LASER = (
    """\
<robot name="fishbot">
"""
    + _BOX_BASE
    + """\
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed"><origin xyz="0 0 {z}"/>
    <parent link="base_link"/><child link="laser_link"/></joint>
  <gazebo reference="laser_link"><sensor name="laser" type="ray">
    <ray><range><min>0.05</min><max>8</max></range></ray></sensor></gazebo>
</robot>
"""
)
_CAMERA = """\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="fixed"><origin xyz="0.1 0 0.05"/>
    <parent link="base_link"/><child link="camera_link"/></joint>
  <gazebo reference="{reference}"><sensor name="camera" type="camera"><camera>
    <horizontal_fov>{fov}</horizontal_fov>
    <image><width>640</width><height>480</height></image>
  </camera></sensor></gazebo>
</robot>
"""
_PLUGINS = """\
<robot name="fishbot">
  <link name="base_link"/>
  <gazebo>
    <plugin filename="{first}" name="{first_name}"/>
    <plugin filename="{second}" name="{second_name}"/>
  </gazebo>
</robot>
"""

DIFF_DRIVE_SIZE = Rule(
    "diff-drive-size",
    E,
    Family.GAZEBO,
    summary="A differential drive plugin's wheel separation or wheel size differs from the "
    "robot's wheel joints and wheel collision cylinders.",
    explanation="The plugin turns a commanded speed into wheel speeds, and wheel speeds back "
    "into odometry, with the separation and diameter (or radius) it is given, not with the "
    "robot's: a wrong separation makes the robot turn by the wrong angle, and a wheel diameter "
    "written as the radius halves every speed and distance. Gazebo Classic's plugin takes "
    "`wheel_diameter` (ROS 1: `wheelDiameter`), the new Gazebo's takes `wheel_radius`, and both "
    "fall back to a default when the tag is left out. Write the distance between the wheel "
    "joints along the axle and the wheel collision cylinders' size.",
    bad=_DRIVE.format(type="continuous", left="0.1", right="-0.1", separation="0.34"),
    good=_DRIVE.format(type="continuous", left="0.1", right="-0.1", separation="0.2"),
    consumers=(Consumer.GAZEBO,),
)
DIFF_DRIVE_WHEELS = Rule(
    "diff-drive-wheels",
    E,
    Family.GAZEBO,
    summary="A differential drive plugin names a wheel joint that does not turn about the "
    "axle, or has its left and right wheels swapped.",
    explanation="The plugin sets the speed of the joints it is given, about their axes: a fixed "
    "or prismatic joint never rolls, and a joint whose axis is not the axle spins the wheel in "
    "place. Its left wheel must be the one on the robot's left (+y in the base frame, as ROS "
    "sets axes), or the robot turns right when told to turn left. Name the wheels' continuous "
    "joints, left as left.",
    bad=_DRIVE.format(type="continuous", left="-0.1", right="0.1", separation="0.2"),
    good=_DRIVE.format(type="continuous", left="0.1", right="-0.1", separation="0.2"),
    consumers=(Consumer.GAZEBO,),
)
PLUGIN_ROS_VERSION = Rule(
    "plugin-ros-version",
    E,
    Family.GAZEBO,
    summary="A ROS 1 Gazebo plugin, or a ROS 1 plugin parameter, in a ROS 2 robot.",
    explanation="ROS 2's gazebo_ros_pkgs dropped several ROS 1 plugins for others: "
    "`libgazebo_ros_laser.so` became `libgazebo_ros_ray_sensor.so`, and "
    "`libgazebo_ros_openni_kinect.so` became `libgazebo_ros_camera.so` on a depth sensor. Gazebo "
    "fails to load a plugin file that is not installed, and a ROS 2 plugin passes over the "
    "camelCase parameters of its ROS 1 version (`leftJoint`), so the sensor publishes nothing or "
    "the robot never moves. A robot is taken for ROS 2 when its package.xml builds with ament, "
    "or when it uses ROS 2's plugins or `<ros2_control>`.",
    bad=_PLUGINS.format(
        first="libgazebo_ros2_control.so",
        first_name="gazebo_ros2_control",
        second="libgazebo_ros_imu.so",
        second_name="imu",
    ),
    good=_PLUGINS.format(
        first="libgazebo_ros2_control.so",
        first_name="gazebo_ros2_control",
        second="libgazebo_ros_imu_sensor.so",
        second_name="imu",
    ),
    consumers=(Consumer.GAZEBO,),
)
PLUGIN_SIMULATOR = Rule(
    "plugin-simulator",
    E,
    Family.GAZEBO,
    summary="A Gazebo Classic plugin in a robot written for the new Gazebo, or the reverse.",
    explanation="Gazebo Classic loads plugin libraries such as `libgazebo_ros_diff_drive.so`; "
    "the new Gazebo (Ignition, then gz-sim) loads systems such as `gz-sim-diff-drive-system`, "
    "and `gz_ros2_control` instead of `gazebo_ros2_control`. Neither loads the other's, so a "
    "robot that mixes them loses the odd ones out in whichever simulator it runs in. Use the "
    "plugins of the simulator the rest of the robot is written for.",
    bad=_PLUGINS.format(
        first="gz-sim-sensors-system",
        first_name="gz::sim::systems::Sensors",
        second="libgazebo_ros_joint_state_publisher.so",
        second_name="joint_states",
    ),
    good=_PLUGINS.format(
        first="gz-sim-sensors-system",
        first_name="gz::sim::systems::Sensors",
        second="gz-sim-joint-state-publisher-system",
        second_name="gz::sim::systems::JointStatePublisher",
    ),
    consumers=(Consumer.GAZEBO,),
)
SENSOR_REFERENCE = Rule(
    "sensor-reference",
    E,
    Family.GAZEBO,
    summary="A Gazebo <sensor> is not in a <gazebo reference> that names a link.",
    explanation="Gazebo attaches a sensor to the link its `<gazebo reference>` names. A sensor "
    "in a block that names a joint (only a force-torque sensor belongs to a joint) or in a "
    "`<gazebo>` block with no reference is not attached to anything, and the simulator drops "
    "it without a word. Name the sensor's link.",
    bad=_CAMERA.format(reference="camera_joint", fov="1.3963"),
    good=_CAMERA.format(reference="camera_link", fov="1.3963"),
    consumers=(Consumer.GAZEBO,),
)
SENSOR_SETTINGS = Rule(
    "sensor-settings",
    E,
    Family.GAZEBO,
    summary="A camera or ray sensor's settings cannot work: a field of view outside (0, pi), "
    "an empty image or scan, or a range or angles in the wrong order.",
    explanation="A camera's `horizontal_fov` is in radians and must lie between 0 and pi; "
    "80 is degrees. An image of width or height 0, a scan of 0 samples, a range whose minimum "
    "is not below its maximum, or a scan whose minimum angle is past its maximum gives the "
    "sensor nothing to measure, and Gazebo refuses it or publishes empty messages. Write the "
    "field of view in radians and each range from low to high.",
    bad=_CAMERA.format(reference="camera_link", fov="80"),
    good=_CAMERA.format(reference="camera_link", fov="1.3963"),
    consumers=(Consumer.GAZEBO,),
)
SENSOR_SELF_HIT = Rule(
    "sensor-self-hit",
    W,
    Family.GAZEBO,
    summary="A ray sensor starts inside a collision shape of the robot and its minimum range "
    "does not reach out of it.",
    explanation="A `ray` (or `lidar`) sensor casts its rays through the physics engine's "
    "collision shapes, from its frame. When that frame lies inside one of the robot's collision "
    "shapes, every ray shorter than the way out of the shape hits the robot itself, and the "
    "scan shows an obstacle all around it (a `gpu_ray` sensor renders the visuals instead, and "
    "is not judged). Raise the sensor out of the shape, or set its minimum range past the "
    "shape's surface.",
    bad=_LASER.format(z="0.05"),
    good=_LASER.format(z="0.08"),
    consumers=(Consumer.GAZEBO,),
)
_SETTING = (
    """\
<robot name="fishbot">
"""
    + _BOX_BASE
    + """\
  <gazebo reference="base_link">
    <mu1>{mu1}</mu1>
    <mu2>{mu2}</mu2>
    <kinematic>{kinematic}</kinematic>
  </gazebo>
</robot>
"""
)
GAZEBO_SETTING = Rule(
    "gazebo-setting",
    E,
    Family.GAZEBO,
    summary="A value in a <gazebo> block that sdformat refuses: Gazebo cannot load the robot.",
    explanation="Gazebo reads a URDF through sdformat's URDF converter. The converter reads "
    "settings such as `<mu1>`, `<kp>` or `<dampingFactor>` as numbers with C++'s std::stod, "
    "and crashes (std::invalid_argument) on one that does not start as a number, such as a "
    "xacro expression left in `<mu1>${mu}</mu1>`. sdformat's reader then refuses the robot "
    "for a value its element's type or bounds do not allow: a friction `<mu1>` below 0, a "
    "`<kinematic>yes</kinematic>` that is none of true, false, 1, 0, a `<pose>` of other than "
    "6 numbers. Either way Gazebo loads nothing. Write what the message says is allowed.",
    bad=_SETTING.format(mu1="-1", mu2="abc", kinematic="yes"),
    good=_SETTING.format(mu1="1", mu2="0.8", kinematic="false"),
    consumers=(Consumer.GAZEBO,),
)
