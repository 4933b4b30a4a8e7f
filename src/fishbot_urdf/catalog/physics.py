"""The rules on mass, inertia and where the robot stands.

Data only: the checks that report them are in `fishbot_urdf.rules`.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..diagnostics import Consumer, Facts, Family, Rule, Severity

_SIMULATORS = (Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET)
E, W = Severity.ERROR, Severity.WARNING


@dataclass(frozen=True, slots=True, kw_only=True)
class MassFacts(Facts):
    """The facts of a `massless-link` finding: the moving body's mass, and its principal
    moments when the mass is there but a moment is not."""

    mass: float
    """The body's mass, kg."""
    principal_moments: tuple[float, float, float] | None = None
    """Its principal moments of inertia, kg*m^2, smallest first."""


@dataclass(frozen=True, slots=True, kw_only=True)
class InertiaFacts(Facts):
    """The facts of an `inertia-not-positive` or `inertia-triangle` finding."""

    principal_moments: tuple[float, float, float]
    """The link's principal moments of inertia, kg*m^2, smallest first."""
    merged_body_physical: bool
    """Whether the body made by merging the links fixed to it is physical."""


@dataclass(frozen=True, slots=True, kw_only=True)
class CollisionFacts(Facts):
    """The facts of an `inertia-mismatch` finding: what it takes to compute the inertial
    that matches the collision (``shape`` with its ``size``, or ``radius`` and
    ``length``)."""

    shape: str
    """``box``, ``cylinder`` or ``sphere``."""
    mass: float
    """The link's mass, kg."""
    xyz: tuple[float, float, float]
    """Where the collision is, in the link frame."""
    rpy: tuple[float, float, float]
    """How the collision is turned, in the link frame."""
    size: tuple[float, float, float] | None = None
    """A box's size."""
    radius: float | None = None
    """A cylinder's or a sphere's radius."""
    length: float | None = None
    """A cylinder's length."""


@dataclass(frozen=True, slots=True, kw_only=True)
class GroundFacts(Facts):
    """The facts of a `below-ground` or `above-ground` finding."""

    distance_mm: float
    """How far the lowest point is below (or above) the ground, mm."""
    tolerance_mm: float
    """The distance taken as touching, mm."""


MASSLESS_LINK = Rule(
    "massless-link",
    E,
    Family.PHYSICS,
    summary="A moving body (links fused over fixed joints) has no mass or no inertia about "
    "some axis.",
    explanation="A link that moves needs a mass and an inertia about every axis, or a simulator "
    "cannot accelerate it. Links joined by fixed joints count as one body, as simulators merge "
    "them, so a massless sensor frame fixed to a heavy link is fine. MuJoCo refuses a moving body "
    "whose mass or a principal moment is below 1e-15 (`mjMINVAL`), Gazebo drops a link of mass 0 "
    "together with everything below it, Drake stops with a mass matrix that is not positive "
    "definite, and in PyBullet the joint never moves. A moving link with no `<inertial>` at all is "
    "`missing-inertial`'s, an error too: Gazebo drops it in the same way (the finding names the "
    "links lost below it; `gazebo-dropped-link` reports the links Gazebo leaves out that no mass "
    "rule sees). Give the link its real "
    "mass, and the inertia of its shape (`fishbot inertia cylinder ...` prints one).",
    bad="""\
<robot name="fishbot">
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="left_wheel_link">
    <inertial><mass value="0"/>
      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>
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
    consumers=_SIMULATORS,
)
INERTIA_NOT_POSITIVE = Rule(
    "inertia-not-positive",
    E,
    Family.PHYSICS,
    summary="An inertia has a negative principal moment.",
    explanation="Moments of inertia (ixx, iyy, izz) are never negative, and the products (ixy, "
    "ixz, iyz) cannot be so large that the matrix has a negative principal moment: no solid has "
    "such an inertia. A sign typed by mistake, or products copied with the wrong sign or in other "
    "units than the moments, are typical causes. MuJoCo refuses it (`inertia must have positive "
    "eigenvalues`), sdformat reports the link's inertia as invalid when Gazebo loads the robot, "
    "Drake warns, and PyBullet, when told to use the file's inertia "
    "(`URDF_USE_INERTIA_FROM_FILE`), sets it to zero. Compute the inertia again, from the part's "
    "shape or its CAD model.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="left_wheel_link">
    <inertial><mass value="0.1"/>
      <inertia ixx="-3.9e-05" ixy="0" ixz="0" iyy="3.9e-05" iyz="0" izz="5.1e-05"/>
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
    consumers=_SIMULATORS,
)
INERTIA_TRIANGLE = Rule(
    "inertia-triangle",
    E,
    Family.PHYSICS,
    summary="One principal moment is larger than the other two together.",
    explanation="For any solid, each principal moment is at most the sum of the other two (ixx + "
    "iyy >= izz, and so on); a thin disc about its axis just reaches the limit. Numbers that "
    "break it come from a wrong formula (`m*r^2` for a disc, where `m*r^2/2` is right) or from "
    "values rounded too short. MuJoCo refuses them (`inertia must satisfy A + B >= C`), sdformat "
    "reports the inertia as invalid when Gazebo loads the robot, Drake warns, and PyBullet, when "
    "told to use the file's inertia, sets it to zero. Compute the inertia again from the part's "
    "shape.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="left_wheel_link">
    <inertial><mass value="0.1"/>
      <inertia ixx="3.9e-05" ixy="0" ixz="0" iyy="3.9e-05" iyz="0" izz="1.02e-04"/>
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
    # sdformat (Gazebo) and PyBullet check it too.
    consumers=_SIMULATORS,
)
MISSING_INERTIAL = Rule(
    "missing-inertial",
    E,
    Family.PHYSICS,
    summary="A moving link, or the robot's base, has collision shapes but no <inertial>.",
    explanation="A link without `<inertial>` has no mass in URDF, and the programs that read it "
    "take it as a link of mass 0, so a moving link without one is an error, as a moving link of "
    "mass 0 is (`massless-link`): sdformat, through which Gazebo (classic and gz-sim) loads a "
    "URDF, drops a link that has no `<inertial>` exactly as one whose mass is 0, with its joint "
    "and everything below it, which the finding names (for the robot's base, the whole robot; "
    "one with no collision shapes is `gazebo-dropped-link`'s); Drake stops because the "
    "body has no mass; pinocchio and KDL take it as massless. Others make one up: PyBullet gives "
    "it 1 kg and an inertia of 1 `kg*m^2` about each axis, and MuJoCo computes one from the "
    "collision shapes at the density of water. robot_state_publisher and RViz only place frames "
    "and do not care. Links held by fixed joints count with what they are fixed to, so a sensor "
    "frame needs none. Add an `<inertial>`: `fishbot inertia ROBOT --fill --mass LINK=KG` (or "
    "`--density KG_PER_M3`) computes it from the collision shapes and says what to write in the "
    "link and where (for a xacro robot, the call of its own inertia macro); with `-o OUT` it "
    "writes a copy with them.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="left_wheel_link">
    <collision>
      <geometry><cylinder radius="0.032" length="0.04"/></geometry>
    </collision>
  </link>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 0 1"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="left_wheel_link">
    <collision><geometry><cylinder radius="0.032" length="0.04"/></geometry></collision>
    <inertial><mass value="0.1"/>
      <inertia ixx="3.9e-05" ixy="0" ixz="0" iyy="3.9e-05" iyz="0" izz="5.1e-05"/>
    </inertial>
  </link>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 0 1"/>
  </joint>
</robot>
""",
    # Drake too: a body without mass on a joint that moves stops its simulation.
    consumers=_SIMULATORS,
)
INERTIA_MISMATCH = Rule(
    "inertia-mismatch",
    W,
    Family.PHYSICS,
    summary="An inertia is that of another shape than the link's one collision box, "
    "cylinder or sphere.",
    explanation="For a link with one collision box, cylinder or sphere, fishbot computes that "
    "shape's inertia at the link's mass; when the declared inertia is more than 10% of the "
    "largest moment away from it and is that of another shape of the same kind, it names that "
    "shape. A cylinder's radius and length swapped, as below, and values copied from another link "
    "are typical causes. Simulators take the numbers as written (PyBullet only with "
    "`URDF_USE_INERTIA_FROM_FILE`), so the link turns more or less easily than the real part. Fix "
    "whichever is wrong: `fishbot inertia box|cylinder|sphere` prints the inertia of a shape.",
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <collision>
      <geometry><cylinder radius="0.1" length="0.12"/></geometry>
    </collision>
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.0044" ixy="0" ixz="0" iyy="0.0044" iyz="0" izz="0.0072"/>
    </inertial>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <collision>
      <geometry><cylinder radius="0.1" length="0.12"/></geometry>
    </collision>
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.0037" ixy="0" ixz="0" iyy="0.0037" iyz="0" izz="0.005"/>
    </inertial>
  </link>
</robot>
""",
    consumers=_SIMULATORS,
)
_BUILT = """\
<robot name="fishbot">
  <link name="base_link">
    <collision><geometry><box size="{box}"/></geometry></collision>
    <inertial><mass value="2"/>
      <inertia ixx="{i}" iyy="{i}" izz="{iz}" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="lidar_link">
    <collision><geometry><cylinder radius="{r}" length="{h}"/></geometry></collision>
    <inertial><mass value="0.2"/>
      <inertia ixx="{li}" iyy="{li}" izz="{liz}" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="lidar_joint" type="continuous"><axis xyz="0 0 1"/>
    <origin xyz="0 0 {z}"/><parent link="base_link"/><child link="lidar_link"/></joint>
</robot>
"""


@dataclass(frozen=True, slots=True, kw_only=True)
class UnitsFacts(Facts):
    """The facts of a `robot-units` finding: what says the robot is in millimetres."""

    sizes: tuple[float, float, float]
    """Its boxes', cylinders' and spheres' sizes (the largest side), m: smallest, median,
    largest."""
    joints: float
    """How far its joints are from their parent links' frames (the median), m."""
    density: float | None
    """The mass of its links over their shapes' volume, kg/m^3 (None: no link to weigh)."""
    factor: float = 0.001
    """What to multiply every length by."""


ROBOT_UNITS = Rule(
    "robot-units",
    E,
    Family.PHYSICS,
    summary="A robot of boxes, cylinders and spheres whose sizes, joint origins and masses say "
    "it was written in millimetres.",
    explanation="URDF lengths are metres. When a robot's shapes are tens to hundreds of metres "
    "across, its joints metres apart, one of them moving, and its masses fill them a "
    "thousand times lighter than air (metal measured in millimetres and weighed in kilograms "
    "reads about 1e-6 kg/m^3), it was written in millimetres: RViz shows a giant, and "
    "simulators take it for a building of a few kilograms. fishbot judges these together, so "
    "that a ground plane or a room (big shapes, no joints apart), and a warehouse or a house "
    "in metres (nothing moves, nothing or a placeholder kilogram weighs it), are no finding; "
    "of a robot in millimetres it says so first, and "
    "proposes no inertia for a 200 m box. It is an error: no program reads such a robot at "
    "the size it was meant to have. Multiply every length by 0.001 (sizes and origins; "
    "inertias by 1e-6), or write them through a xacro property in metres.",
    bad=_BUILT.format(
        box="200 200 100", i="8333", iz="13333", r="40", h="50", li="121.7", liz="160", z="150"
    ),
    good=_BUILT.format(
        box="0.2 0.2 0.1",
        i="0.008333",
        iz="0.013333",
        r="0.04",
        h="0.05",
        li="0.0001217",
        liz="0.00016",
        z="0.15",
    ),
    consumers=(Consumer.URDFDOM, *_SIMULATORS),
)
BELOW_GROUND = Rule(
    "below-ground",
    W,
    Family.PHYSICS,
    summary="A collision shape reaches below the ground (z = 0 of a footprint root).",
    explanation="When the root link is a bare frame such as `base_footprint` (no shape, no "
    "inertial), its z = 0 is taken as the ground, and fishbot places the collision shapes of the "
    "links held to it by fixed joints and wheel axles at the zero configuration. A shape more "
    "than 2 mm below that ground means the robot starts inside the floor, and the simulator "
    "pushes it out in its first steps: in PyBullet the robot below rises 20 mm. Raise the joint "
    "below the footprint, usually by half the body's height or by the wheel radius; "
    "`--ground-tolerance MM` changes the 2 mm.",
    bad="""\
<robot name="fishbot">
  <link name="base_footprint"/>
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.0042" ixy="0" ixz="0" iyy="0.0042" iyz="0" izz="0.0067"/>
    </inertial>
  </link>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 0.03"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_footprint"/>
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.0042" ixy="0" ixz="0" iyy="0.0042" iyz="0" izz="0.0067"/>
    </inertial>
  </link>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 0.05"/>
  </joint>
</robot>
""",
    consumers=(Consumer.GAZEBO, Consumer.PYBULLET),
)
ABOVE_GROUND = Rule(
    "above-ground",
    W,
    Family.PHYSICS,
    summary="The robot's lowest point is above the ground (z = 0 of a footprint root): it floats.",
    explanation="When the root link is a bare frame such as `base_footprint`, its z = 0 is taken "
    "as the ground. If the lowest collision point of the links held to it by fixed joints and "
    "wheel axles is more than 2 mm above it, the robot floats: a simulator lets it drop in its "
    "first steps (30 mm for the robot below, in PyBullet), and every height measured from the "
    "footprint, a laser's included, is off by as much. A robot that may stand on a leg, an arm or "
    "a mesh is not reported. Lower the joint below the footprint by the distance given.",
    bad="""\
<robot name="fishbot">
  <link name="base_footprint"/>
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.0042" ixy="0" ixz="0" iyy="0.0042" iyz="0" izz="0.0067"/>
    </inertial>
  </link>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 0.08"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_footprint"/>
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.0042" ixy="0" ixz="0" iyy="0.0042" iyz="0" izz="0.0067"/>
    </inertial>
  </link>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 0.05"/>
  </joint>
</robot>
""",
    consumers=(Consumer.GAZEBO, Consumer.PYBULLET),
)
MJCF_JOINED_INERTIAL = Rule(
    "mjcf-joined-inertial",
    W,
    Family.PHYSICS,
    summary="`fishbot mjcf` adds a fixed link's inertial to the body it is fixed to, as MuJoCo "
    "refuses its inertia on a body of its own.",
    explanation="`fishbot mjcf` makes each link a body of MuJoCo's, and MuJoCo refuses a body "
    "whose inertia is not positive semi-definite or whose principal moments break the "
    "triangle inequality, even when the body cannot move. A link on a fixed joint with such an "
    "inertia (a sensor frame with made-up numbers, a base with a placeholder) is fine in the "
    "simulators that merge fixed links, and `inertia-not-positive` and `inertia-triangle` "
    "judge it so; `fishbot mjcf` adds its mass, centre of mass and inertia, exactly, to the "
    "body of its parent, or of the first link fixed below it (for a root or a moving link), "
    "says so with this warning, and the link keeps its own body and pose; `fishbot check "
    "--target mujoco` says so too. Give the link the inertia of its shape.",
    bad="""\
# antenna.urdf: a fixed link whose izz is more than ixx + iyy
fishbot mjcf antenna.urdf -o antenna.xml
""",
    good="""\
fishbot mjcf fishbot.urdf -o fishbot.xml
""",
    consumers=(Consumer.MUJOCO,),
    language="shell",
)
MJCF_REFUSED = Rule(
    "mjcf-refused",
    E,
    Family.PHYSICS,
    summary="The MJCF `fishbot mjcf` writes has a body MuJoCo refuses: a moving one without "
    "mass or inertia, or an inertia no solid has that no fixed link can take.",
    explanation="MuJoCo refuses a model with a moving body whose mass, or a principal moment, "
    "with the bodies fixed to it, is 0 (`mass and inertia of moving bodies must be larger "
    "than mjMINVAL`), such as a massless link between the two joints of a hip, or a free "
    "base whose izz is 0, and a body whose inertia is not positive semi-definite or breaks "
    "the triangle inequality. `fishbot mjcf` makes no mass up: it writes the model, names "
    "each such link with this error, and exits with status 1. `fishbot check --target "
    "mujoco` (or `--target all`) foretells the same errors from the robot's masses, without "
    "writing the model; for any other target it does not look. Give the link the mass and "
    "inertia of its part.",
    bad="""\
# hip.urdf: a massless link between two revolute joints
fishbot check --target mujoco hip.urdf
fishbot mjcf hip.urdf -o hip.xml
""",
    good="""\
fishbot check --target mujoco fishbot.urdf
fishbot mjcf fishbot.urdf -o fishbot.xml
""",
    consumers=(Consumer.MUJOCO,),
    language="shell",
)
