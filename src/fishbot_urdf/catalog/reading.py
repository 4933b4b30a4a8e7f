"""Rules the reader applies while it builds the model: the XML, the elements, the values.

These are data only; the reader (``fishbot_urdf.parse``) reports them as it reads.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..diagnostics import Consumer, Facts, Family, Rule, Severity


@dataclass(frozen=True, slots=True, kw_only=True)
class FieldFacts(Facts):
    """The facts of a finding about one value of a model built in code."""

    field: str
    """Where the value is in the model: ``robot.joints[0].axis``."""


_SIMULATORS = (Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET)
_ALL = (Consumer.URDFDOM, *_SIMULATORS)
E, W = Severity.ERROR, Severity.WARNING

XML_SYNTAX = Rule(
    "xml-syntax",
    E,
    Family.XML,
    summary="The file is not well-formed XML, or declares entities.",
    explanation="Every program that reads a robot parses its XML first and stops at the first "
    "mistake: an element that is never closed, a missing quote, a bare `&` or `<` in a value. "
    "check_urdf fails with the XML parser's message (`Error reading end tag.` for the example "
    "below), and xacro, Gazebo, MuJoCo, Drake and PyBullet refuse the file too. Nothing else can "
    "be checked until it is fixed, so this is the only finding. fishbot also refuses `<!ENTITY>` "
    "declarations: URDF never needs them, and check_urdf cannot read a file that has them.",
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
    </visual>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
    </visual>
  </link>
</robot>
""",
    consumers=(*_ALL, Consumer.XACRO, Consumer.XML_TOOLS),
    fatal=True,
)
NO_ROBOT = Rule(
    "no-robot",
    E,
    Family.URDF,
    summary="The root element is not <robot>.",
    explanation='A URDF file holds one `<robot name="...">` element with every link and joint '
    "inside it. A file that starts with anything else, such as a `<link>` copied out of another "
    "robot, is not a URDF: check_urdf fails with `Could not find the 'robot' element in the xml "
    "file`, and Gazebo, MuJoCo, Drake and PyBullet refuse it too. Put the links and joints inside "
    '`<robot name="...">`.',
    bad="""\
<link name="base_link">
  <visual>
    <geometry><box size="0.2 0.2 0.1"/></geometry>
  </visual>
</link>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
    </visual>
  </link>
</robot>
""",
    consumers=_ALL,
)
ROBOT_NAME = Rule(
    "robot-name",
    E,
    Family.URDF,
    summary="<robot> has no name.",
    explanation="urdfdom requires a name on `<robot>`: without one check_urdf fails with `No name "
    "given for the robot.`, and so do robot_state_publisher and Gazebo, which read the file "
    "through urdfdom. Drake and PyBullet refuse the file too; only MuJoCo loads it. Give the "
    "robot a name: Gazebo and Drake name the model after it.",
    bad="""\
<robot>
  <link name="base_link"/>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
</robot>
""",
    # MuJoCo 4.0 loads a nameless robot.
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.DRAKE, Consumer.PYBULLET),
)
ROBOT_VERSION = Rule(
    "robot-version",
    E,
    Family.URDF,
    summary="<robot version> is not a URDF version urdfdom reads (1.0).",
    explanation="The `version` attribute of `<robot>` is optional, and urdfdom accepts only `1.0` "
    "there: any other value (`2.0`, `1.1`, `v1`) makes check_urdf fail with `Invalid 'version' "
    "specified; only version 1.0 is currently supported` or a complaint about its form, and "
    "Gazebo, which reads URDF through urdfdom, fails the same way. MuJoCo and PyBullet ignore the "
    'attribute, and Drake warns that it does. Write `version="1.0"` or leave the attribute out.',
    bad="""\
<robot name="fishbot" version="2.0">
  <link name="base_link"/>
</robot>
""",
    good="""\
<robot name="fishbot" version="1.0">
  <link name="base_link"/>
</robot>
""",
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO),
)
MISSING_ATTRIBUTE = Rule(
    "missing-attribute",
    E,
    Family.URDF,
    summary="An element lacks an attribute it needs.",
    explanation="Some attributes have no default: the `name` of a link or a joint, a box's "
    "`size`, a cylinder's `radius` and `length`, a mesh's `filename`, the `effort` and `velocity` "
    "of a `<limit>`, each of the six values of `<inertia>`. For a shape or an inertia that lacks "
    "one, check_urdf logs an error but still reports success, leaving that `<visual>`, "
    "`<collision>` or `<inertial>` out of the robot, and Gazebo loads the robot so; MuJoCo, Drake "
    "and PyBullet refuse a collision like the one below. Write the attribute.",
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <collision>
      <geometry><cylinder radius="0.1"/></geometry>
    </collision>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <collision>
      <geometry><cylinder radius="0.1" length="0.12"/></geometry>
    </collision>
  </link>
</robot>
""",
    consumers=_ALL,
)
MISSING_ELEMENT = Rule(
    "missing-element",
    E,
    Family.URDF,
    summary="An element lacks a child it needs (<geometry>, <mass>, <parent>, ...).",
    explanation="Some elements must hold a child: `<inertial>` a `<mass>` and an `<inertia>`, "
    "`<visual>` and `<collision>` a `<geometry>` with one shape in it, and a joint its `<parent>` "
    "and `<child>`. A joint without them makes check_urdf fail; for the parts of a link it only "
    "logs an error and reports success, with the part dropped or half read (the `<inertial>` "
    "below keeps its mass and gets no inertia at all, in Gazebo too). MuJoCo and PyBullet refuse "
    "the file. Write the missing element.",
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <inertial>
      <mass value="1.0"/>
    </inertial>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.0037" ixy="0" ixz="0" iyy="0.0037" iyz="0" izz="0.005"/>
    </inertial>
  </link>
</robot>
""",
    consumers=_ALL,
)
BAD_NUMBER = Rule(
    "bad-number",
    E,
    Family.URDF,
    summary="A value is not a finite number as urdfdom reads numbers.",
    explanation="urdfdom reads a value as a number only when the whole of it is one: `1kg`, "
    "`0,5`, `0.1 ` with a space after it, or a `${mass}` left over from a xacro file that was not "
    "expanded, are not numbers. Inside a link check_urdf logs an error but still reports success, "
    'dropping what it could not read: with `<mass value="1kg"/>` the link has no mass, and Gazebo '
    "then leaves the link out. MuJoCo refuses the value, while Drake and PyBullet read the digits "
    "they can and ignore the rest, so `1,5` becomes 1 kg. Write plain numbers, in metres, "
    "kilograms and radians, with no units.",
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <inertial>
      <mass value="1kg"/>
      <inertia ixx="0.0037" ixy="0" ixz="0" iyy="0.0037" iyz="0" izz="0.005"/>
    </inertial>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.0037" ixy="0" ixz="0" iyy="0.0037" iyz="0" izz="0.005"/>
    </inertial>
  </link>
</robot>
""",
    consumers=_ALL,
)
BAD_VECTOR = Rule(
    "bad-vector",
    E,
    Family.URDF,
    summary="A vector has the wrong count of numbers.",
    explanation="Positions, angles, sizes, axes and scales are three numbers separated by spaces "
    '(`xyz="0 0 0.1"`), and a colour is four. With too few or too many numbers, or commas between '
    "them, check_urdf fails (`Parser found 2 elements but 3 expected`), and Gazebo, MuJoCo and "
    "Drake refuse the file too; PyBullet warns that it could not read the vector and loads the "
    "robot anyway. Write every number, separated by spaces.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/>
    <child link="laser_link"/>
    <origin xyz="0 0.1" rpy="0 0 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/>
    <child link="laser_link"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
BAD_COLOR = Rule(
    "bad-color",
    E,
    Family.URDF,
    summary="A colour has a value outside 0..1.",
    explanation="The red, green, blue and alpha of `<color rgba>` are fractions from 0 to 1, not "
    "0 to 255. urdfdom refuses a value outside 0..1 and drops the whole material: check_urdf logs "
    "errors but still reports success, and the link loses its colour (Gazebo draws it black). "
    "Drake refuses the file. Divide 0-255 values by 255.",
    bad="""\
<robot name="fishbot">
  <material name="orange">
    <color rgba="255 108 10 255"/>
  </material>
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="orange"/>
    </visual>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <material name="orange">
    <color rgba="1 0.42 0.04 1"/>
  </material>
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="orange"/>
    </visual>
  </link>
</robot>
""",
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.DRAKE),
)
JOINT_TYPE = Rule(
    "joint-type",
    E,
    Family.URDF,
    summary="A joint has no type, or one URDF does not define.",
    explanation="A joint's `type` is one of revolute, continuous, prismatic, fixed, floating and "
    "planar, in lower case and spelt exactly so. A missing or misspelt type (`continous`, "
    "`Revolute`) makes check_urdf fail with `has no known type`, and Gazebo, MuJoCo, Drake and "
    "PyBullet refuse the joint too. A wheel's axle is continuous; a joint with end stops is "
    "revolute, with a `<limit>`.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <joint name="left_wheel_joint" type="continous">
    <parent link="base_link"/>
    <child link="left_wheel_link"/>
    <axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/>
    <child link="left_wheel_link"/>
    <axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
UNKNOWN_GEOMETRY = Rule(
    "unknown-geometry",
    E,
    Family.URDF,
    summary="<geometry> holds something other than a box, cylinder, sphere or mesh.",
    explanation="URDF has four shapes: `<box>`, `<cylinder>`, `<sphere>` and `<mesh>`. Any other, "
    "such as `<cube>`, is unknown to urdfdom: check_urdf logs `Unknown geometry type` but still "
    "reports success, and that visual or collision is missing from the robot, in RViz and in "
    "Gazebo. MuJoCo, Drake and PyBullet refuse the file. Use a box for a cube, and a mesh for any "
    "shape URDF does not have.",
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <collision>
      <geometry><cube size="0.2 0.2 0.1"/></geometry>
    </collision>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <collision>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
    </collision>
  </link>
</robot>
""",
    consumers=_ALL,
)
UNKNOWN_ELEMENT = Rule(
    "unknown-element",
    W,
    Family.URDF,
    summary="An element stands where URDF gives it no meaning, and is ignored.",
    explanation="URDF says what each element holds: `<visual>` an `<origin>`, a `<geometry>` and "
    "a `<material>`; `<inertial>` an `<origin>`, a `<mass>` and an `<inertia>`; `<material>` a "
    "`<color>` and a `<texture>`. Anything else inside them is skipped without a word by urdfdom "
    "and by the simulators, so it has no effect: the colour below is never shown. Move the "
    "element where it belongs (here, into a `<material>`). Extensions that other programs read, "
    "such as `<gazebo>` inside `<robot>` or a link, are not reported.",
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <color rgba="0 0 1 1"/>
    </visual>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="blue"><color rgba="0 0 1 1"/></material>
    </visual>
  </link>
</robot>
""",
    consumers=_ALL,
)
DUPLICATE_ELEMENT = Rule(
    "duplicate-element",
    W,
    Family.URDF,
    summary="A second element of a kind that may appear once (<inertial>, <origin>, a shape).",
    explanation="A link has at most one `<inertial>`, a joint at most one each of `<origin>`, "
    "`<axis>`, `<limit>` and the rest, and a `<geometry>` exactly one shape. urdfdom reads the "
    "first and ignores the others without a word, as Drake and PyBullet do, while MuJoCo refuses "
    "the file; if the second was the one meant, the robot is not what the file seems to say. Keep "
    "one, or put another shape in a `<visual>` or `<collision>` of its own.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed">
    <parent link="base_link"/>
    <child link="imu_link"/>
    <origin xyz="0 0 0.02"/>
    <origin xyz="0 0 0.05"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed">
    <parent link="base_link"/>
    <child link="imu_link"/>
    <origin xyz="0 0 0.05"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
COLLISION_MATERIAL = Rule(
    "collision-material",
    W,
    Family.URDF,
    summary="<material> inside <collision> is ignored.",
    explanation="Colours belong to what is drawn, the `<visual>`; a collision shape is only used "
    "to compute contacts. A `<material>` inside `<collision>` is not part of URDF, and urdfdom "
    "and the simulators skip it without a word, so it colours nothing. Move it into the link's "
    "`<visual>`.",
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <collision>
      <geometry><cylinder radius="0.1" length="0.12"/></geometry>
      <material name="blue"><color rgba="0 0 1 1"/></material>
    </collision>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <visual>
      <geometry><cylinder radius="0.1" length="0.12"/></geometry>
      <material name="blue"><color rgba="0 0 1 1"/></material>
    </visual>
    <collision>
      <geometry><cylinder radius="0.1" length="0.12"/></geometry>
    </collision>
  </link>
</robot>
""",
    consumers=_ALL,
)
NEGATIVE_MASS = Rule(
    "negative-mass",
    E,
    Family.URDF,
    summary="A mass is negative.",
    explanation="A mass is zero or more kilograms; a negative one is usually a sign typed by "
    "mistake. check_urdf accepts it, but MuJoCo refuses the body (`mass and inertia of moving "
    "bodies must be larger than mjMINVAL`), sdformat reports the link's inertia as invalid when "
    "Gazebo loads the robot, and Drake warns and simulates it anyway. Write the part's real mass.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="left_wheel_link">
    <inertial><mass value="-0.1"/>
      <inertia ixx="3.9e-05" ixy="0" ixz="0" iyy="3.9e-05" iyz="0" izz="5.1e-05"/>
    </inertial>
  </link>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="left_wheel_link">
    <inertial><mass value="0.1"/>
      <inertia ixx="3.9e-05" ixy="0" ixz="0" iyy="3.9e-05" iyz="0" izz="5.1e-05"/>
    </inertial>
  </link>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    # check_urdf accepts a negative mass, and PyBullet loads it as written.
    consumers=(Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE),
)
