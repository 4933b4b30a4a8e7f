"""The rules on what sdformat's URDF converter loses or moves before Gazebo simulates a robot
(Gazebo Classic and the new Gazebo both read a URDF through it, as `ign sdf -p` does).

Data only: the checks that report them are in `fishbot_urdf.rules`.
"""

from __future__ import annotations

from ..diagnostics import Consumer, Family, Rule, Severity

E, W = Severity.ERROR, Severity.WARNING
_MASS = (
    '\n    <inertial><mass value="{}"/>'
    '<inertia ixx="{}" iyy="{}" izz="{}" ixy="0" ixz="0" iyz="0"/>'
)
_HEAVY = _MASS.format(1, *["0.01"] * 3) + "</inertial>"
_LIGHT = _MASS.format(0.1, *["1e-4"] * 3) + "</inertial>"
_ARM = f"""\
<robot name="fishbot">
  <link name="base_link">{_HEAVY}</link>
  <link name="arm_mount"{{mount}}
  <joint name="mount_joint" type="fixed"><origin xyz="0 0 0.1"/>
    <parent link="base_link"/><child link="arm_mount"/></joint>
  <link name="arm">{_LIGHT}</link>
  <joint name="arm_joint" type="continuous"><axis xyz="0 0 1"/>
    <parent link="arm_mount"/><child link="arm"/></joint>
</robot>
"""
_CAMERA = f"""\
<robot name="fishbot">
  <link name="base_link">{_HEAVY}</link>
  <link name="camera_link">{_LIGHT}</link>
  <joint name="camera_joint" type="fixed"><origin xyz="0.1 0 0.05"/>
    <parent link="base_link"/><child link="camera_link"/></joint>
  {{blocks}}
</robot>
"""
_KEEP = '<gazebo reference="{}"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'

_SENSOR = """<gazebo reference="camera_link"><sensor name="camera" type="camera">
    <camera><horizontal_fov>1.39</horizontal_fov></camera>
    <plugin name="camera" filename="libgazebo_ros_camera.so">{frame}</plugin>
  </sensor></gazebo>"""
_P3D = """<gazebo><plugin name="ground_truth" filename="libgazebo_ros_p3d.so">
    <body_name>{body}</body_name><frame_name>world</frame_name></plugin></gazebo>"""

GAZEBO_DROPPED_LINK = Rule(
    "gazebo-dropped-link",
    E,
    Family.GAZEBO,
    summary="Gazebo leaves a link out of the robot, with links below it, for lack of mass.",
    explanation="sdformat's URDF converter, through which Gazebo reads a URDF, writes no link "
    "whose mass, with the masses of the links fixed below it, is 0, and goes no further down "
    "the tree from it: every link below is lost too, with no message but in "
    "`~/.sdformat/sdformat.log` (it exits 0, and `ign sdf -k` says the file is valid). Below a "
    "massless link on a fixed joint, such as a mount frame, that loses moving links that have "
    "mass of their own, which no mass rule sees. A moving link whose own body has no mass is "
    "`missing-inertial`'s or `massless-link`'s, which name the links lost below it; this rule "
    "reports the losses they do not, where a link with mass is lost (massless frames move "
    "nothing): give the massless link, or one fixed to it, a mass.",
    bad=_ARM.format(mount="/>"),
    good=_ARM.format(mount=f">{_LIGHT}</link>"),
    consumers=(Consumer.GAZEBO,),
)
GAZEBO_LUMPING_FLAG = Rule(
    "gazebo-lumping-flag",
    W,
    Family.GAZEBO,
    summary="<preserveFixedJoint> or <disableFixedJointLumping> is in a <gazebo reference> that "
    "names no fixed joint, where it does nothing.",
    explanation="sdformat's converter merges the links of each fixed joint into one (lumping) "
    "unless the joint's own `<gazebo reference>` holds `<preserveFixedJoint>` (keep the joint) "
    "or `<disableFixedJointLumping>` (write it as a revolute joint held at 0). It reads these "
    "switches on a fixed joint's name only: on a link, or on a moving joint, they are passed "
    "over without a word and the link is lumped all the same. Write the switch in a block that "
    "names the fixed joint.",
    bad=_CAMERA.format(blocks=_KEEP.format("camera_link")),
    good=_CAMERA.format(blocks=_KEEP.format("camera_joint")),
    consumers=(Consumer.GAZEBO,),
)
GAZEBO_LUMPED_LINK = Rule(
    "gazebo-lumped-link",
    W,
    Family.GAZEBO,
    summary="A <gazebo reference> names a link Gazebo lumps into another, and its sensor's "
    "messages or its link settings go with that link.",
    explanation="The converter merges a link held by a fixed joint into the link above it and "
    "hands that link the merged one's `<gazebo>` blocks: a sensor moves into it, re-posed in "
    "its frame, and link settings such as `<gravity>`, `<selfCollide>` or `<dampingFactor>` then "
    "apply to the whole merged link. A ROS 2 gazebo_ros sensor plugin with no `<frame_name>` "
    "stamps its messages with the sensor's link, so a scan or image is placed at the base, not "
    "at the sensor; colours, friction and sensors whose plugin names its frame stay right and "
    "are not reported. Write `<frame_name>` in the plugin, or keep the link with "
    "`<preserveFixedJoint>` on its joint (it then needs a mass).",
    bad=_CAMERA.format(blocks=_SENSOR.format(frame="")),
    good=_CAMERA.format(blocks=_SENSOR.format(frame="<frame_name>camera_link</frame_name>")),
    consumers=(Consumer.GAZEBO,),
)
GAZEBO_PLUGIN_LINK = Rule(
    "gazebo-plugin-link",
    E,
    Family.GAZEBO,
    summary="A Gazebo plugin names a link the converter lumps into another and does not "
    "rename for it.",
    explanation="After lumping, Gazebo's model has no link of the merged link's name. The "
    "converter renames it only in `<bodyName>` and `<frameName>` of a `<plugin>` written "
    "directly in a `<gazebo>` block (ROS 1's spelling); `<body_name>`, `<link_name>`, a p3d "
    "plugin's `<frame_name>` and any name in a sensor's plugin keep the old name, and the "
    "plugin finds no such link and does nothing. Name the link it lands in, or keep the link "
    "with `<preserveFixedJoint>` on its joint.",
    bad=_CAMERA.format(blocks=_P3D.format(body="camera_link")),
    good=_CAMERA.format(blocks=_P3D.format(body="base_link")),
    consumers=(Consumer.GAZEBO,),
)
_GRIPPER = f"""\
<robot name="gripper">
  <link name="palm">{_HEAVY}</link>
  <link name="left">{_LIGHT}</link>
  <link name="right">{_LIGHT}</link>
  <joint name="left_joint" type="prismatic"><parent link="palm"/><child link="left"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="10" velocity="0.1"/></joint>
  <joint name="right_joint" type="prismatic"><parent link="palm"/><child link="right"/>
    <axis xyz="0 -1 0"/><limit lower="0" upper="0.04" effort="10" velocity="0.1"/>{{mimic}}
  </joint>
</robot>
"""
GAZEBO_MIMIC = Rule(
    "gazebo-mimic",
    W,
    Family.GAZEBO,
    summary="A joint follows another by <mimic>, which sdformat 12's converter leaves out: in "
    "Gazebo Fortress and Classic it moves on its own.",
    explanation="SDFormat 1.9, what sdformat 12 (Gazebo Fortress, the Gazebo of ROS 2 Humble) "
    "and Gazebo Classic's sdformat read, has no mimic joints: the URDF converter writes the "
    "joint without its `<mimic>`, and exits 0. In the simulation the joint is a free joint of "
    "its own (a gripper's second finger hangs loose, or is pushed about) unless something "
    "drives it. SDFormat 1.11 added `<mimic>` under a joint's `<axis>`, and sdformat 14 (Gazebo "
    "Harmonic) converts URDF's into it. For the older Gazebo, drive the joint with a controller "
    "or plugin of its own, or target the newer one.",
    bad=_GRIPPER.format(mimic='<mimic joint="left_joint"/>'),
    good=_GRIPPER.format(mimic=""),
    consumers=(Consumer.GAZEBO,),
)
_MESH = f"""\
<robot name="fishbot">
  <link name="base_link">{_HEAVY}
    <visual><geometry><mesh filename="{{name}}"/></geometry></visual>
  </link>
</robot>
"""
GAZEBO_MODEL_PATH = Rule(
    "gazebo-model-path",
    W,
    Family.GAZEBO,
    summary="A `package://` mesh becomes `model://` for Gazebo, and nothing tells Gazebo "
    "where that package is.",
    explanation="sdformat's converter writes `package://PKG/meshes/x.stl` as "
    "`model://PKG/meshes/x.stl`, which Gazebo looks for in a folder named PKG on its resource "
    "path: `GZ_SIM_RESOURCE_PATH` (Fortress: `IGN_GAZEBO_RESOURCE_PATH`), or "
    "`GAZEBO_MODEL_PATH` for Gazebo Classic. When the folder above the package is on none of "
    "them and the package's package.xml exports no `gazebo_model_path` (which gazebo_ros puts "
    "on `GAZEBO_MODEL_PATH`), the mesh is not found and the part is drawn and collides as "
    'nothing. Add `<gazebo_ros gazebo_model_path="${prefix}/.."/>` to the package\'s '
    "`<export>`, put the folder above it on the path, or name the mesh relative to the robot "
    "file, which Gazebo reads beside the file it loads.",
    bad=_MESH.format(name="package://fishbot_description/meshes/base_link.stl"),
    good=_MESH.format(name="meshes/base_link.stl"),
    consumers=(Consumer.GAZEBO,),
)
