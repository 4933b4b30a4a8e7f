"""What the physics rules share: tolerances, number formats, and how a finding is made."""

from __future__ import annotations

from ...diagnostics import Kind, Severity, Subject
from ...model import Link, Location
from .. import Consumer, Family, Rule

# MuJoCo refuses a moving body whose mass or a principal moment is below this (mjMINVAL).
TINY = 1e-15


def tolerance(moments: tuple[float, float, float]) -> float:
    # Inertias are printed with a handful of digits: allow their rounding, and nothing near
    # a real violation.
    return max(1e-6 * max(abs(moments[0]), abs(moments[1]), abs(moments[2])), TINY)


def physical(moments: tuple[float, float, float], tol: float | None = None) -> bool:
    """Moments no lower than zero that obey the triangle inequality (within rounding;
    ``tol``: their `tolerance`, when known)."""
    if tol is None:
        tol = tolerance(moments)
    return moments[0] >= -tol and moments[0] + moments[1] >= moments[2] - tol


def short(value: float) -> str:
    """A length or moment, short: 0.10, 0.12, 0.032, 3.9e-05."""
    if value == 0.0:
        return "0"
    return f"{value:.2f}" if abs(value) >= 0.1 else f"{value:.2g}"


def moments_text(values: tuple[float, float, float]) -> str:
    """Principal moments for a message; rounding noise (-1e-22 next to 3e-06) shows as 0."""
    return ", ".join(moment_text(v, values) for v in values)


def moment_text(value: float, values: tuple[float, float, float]) -> str:
    return "0" if abs(value) <= tolerance(values) else f"{value:.3g}"


def place(link: Link, where: Location | None) -> Location | None:
    """Where to report about a part of ``link``: the part itself, unless a xacro macro from
    another file wrote it (common_inertia.xacro's inertia, say); then the link, which is
    near the macro's call."""
    if where is None or link.source is None or where.path == link.source.path:
        return where or link.source
    return link.source


def link_subject(link: Link) -> Subject:
    return Subject(Kind.LINK, link.name)


_SIMULATORS = (Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET)
E, W = Severity.ERROR, Severity.WARNING

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
    "definite, and in PyBullet the joint never moves. Give the link its real mass, and the "
    "inertia of its shape (`fishbot inertia cylinder ...` prints one).",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link">
    <inertial>
      <mass value="0"/>
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
  <link name="base_link"/>
  <link name="left_wheel_link">
    <inertial>
      <mass value="0.1"/>
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
  <link name="base_link"/>
  <link name="left_wheel_link">
    <inertial>
      <mass value="0.1"/>
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
  <link name="base_link"/>
  <link name="left_wheel_link">
    <inertial>
      <mass value="0.1"/>
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
  <link name="base_link"/>
  <link name="left_wheel_link">
    <inertial>
      <mass value="0.1"/>
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
  <link name="base_link"/>
  <link name="left_wheel_link">
    <inertial>
      <mass value="0.1"/>
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
    W,
    Family.PHYSICS,
    summary="A moving link, or the robot's base, has collision shapes but no <inertial>.",
    explanation="A link without `<inertial>` has no mass in URDF, and a simulator cannot use it "
    "as written when it moves or is the robot's base: Gazebo drops it with everything below it "
    "(the whole robot, for the base), Drake stops because the body has no mass, PyBullet gives it "
    "1 kg and an inertia of 1 `kg*m^2` about each axis, and MuJoCo computes one from the "
    "collision shapes at the density of water. Links held by fixed joints count with what they "
    "are fixed to, so a sensor frame needs none. Add an `<inertial>`: `fishbot inertia ROBOT "
    "--fill --density KG_PER_M3 -o OUT` computes them from the collision shapes.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
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
  <link name="base_link"/>
  <link name="left_wheel_link">
    <collision><geometry><cylinder radius="0.032" length="0.04"/></geometry></collision>
    <inertial>
      <mass value="0.1"/>
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
