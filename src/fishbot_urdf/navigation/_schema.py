"""URDF's elements, what each may hold and the attributes each takes, as the URDF
specification (wiki.ros.org/urdf/XML) lists them."""

from __future__ import annotations

__all__ = ["ATTRIBUTES", "CHILDREN", "DESCRIPTIONS"]

CHILDREN: dict[str, tuple[str, ...]] = {
    "": ("robot",),
    "robot": ("link", "joint", "material", "transmission", "gazebo", "ros2_control"),
    "link": ("inertial", "visual", "collision"),
    "joint": (
        "origin",
        "parent",
        "child",
        "axis",
        "calibration",
        "dynamics",
        "limit",
        "mimic",
        "safety_controller",
    ),
    "inertial": ("origin", "mass", "inertia"),
    "visual": ("origin", "geometry", "material"),
    "collision": ("origin", "geometry"),
    "geometry": ("box", "cylinder", "sphere", "mesh"),
    "material": ("color", "texture"),
    "transmission": ("type", "joint", "actuator"),
}

ATTRIBUTES: dict[str, tuple[str, ...]] = {
    "robot": ("name", "version"),
    "link": ("name",),
    "joint": ("name", "type"),
    "origin": ("xyz", "rpy"),
    "mass": ("value",),
    "inertia": ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"),
    "visual": ("name",),
    "collision": ("name",),
    "box": ("size",),
    "cylinder": ("radius", "length"),
    "sphere": ("radius",),
    "mesh": ("filename", "scale"),
    "material": ("name",),
    "color": ("rgba",),
    "texture": ("filename",),
    "parent": ("link",),
    "child": ("link",),
    "axis": ("xyz",),
    "calibration": ("rising", "falling"),
    "dynamics": ("damping", "friction"),
    "limit": ("lower", "upper", "effort", "velocity"),
    "mimic": ("joint", "multiplier", "offset"),
    "safety_controller": ("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"),
    "transmission": ("name",),
    "gazebo": ("reference",),
    "ros2_control": ("name", "type"),
}

DESCRIPTIONS: dict[str, str] = {
    "robot": "the robot: its links, joints and materials",
    "link": "a rigid body: its inertial, visuals and collision shapes",
    "joint": "how a child link moves relative to its parent link",
    "inertial": "mass, centre of mass and inertia",
    "visual": "a shape drawn for the link",
    "collision": "a shape the link collides with",
    "geometry": "one shape: box, cylinder, sphere or mesh",
    "origin": "a pose: xyz (m), then roll, pitch, yaw (rad)",
    "material": "a colour or texture, by name",
    "parent": "the parent link",
    "child": "the child link",
    "axis": "the joint's axis in the joint frame",
    "limit": "position limits (rad or m), effort (N·m or N), velocity (rad/s or m/s)",
    "dynamics": "damping and friction",
    "mimic": "this joint follows another",
    "mass": "mass (kg)",
    "inertia": "the inertia tensor (kg·m²) about the centre of mass",
}
