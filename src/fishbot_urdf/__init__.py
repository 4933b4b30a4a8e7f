"""fishbot_urdf: read, check and explore URDF robot descriptions, with or without ROS.

>>> import fishbot_urdf
>>> robot = fishbot_urdf.load("robots/fishbot/urdf/first_robot.urdf")  # doctest: +SKIP
>>> [link.name for link in robot.links]  # doctest: +SKIP
['base_link', 'imu_link']
"""

from __future__ import annotations

from typing import Any

from .check import CheckResult, check, check_file
from .diagnostics import Diagnostic, Severity
from .dot import draw, render, to_dot
from .errors import (
    FishbotUrdfError,
    InputError,
    RobotError,
    ToolError,
    ToolNotFoundError,
    XmlSyntaxError,
)
from .expand import Expansion, XacroError, expand
from .graph import Topology, chain, leaves, root, subtree, to_networkx, topology, tree_text
from .inertia import (
    MassProperties,
    box_inertia,
    combine,
    cylinder_inertia,
    geometry_inertia,
    link_inertial,
    mass_properties,
    mesh_inertia,
    principal_moments,
    sphere_inertia,
    volume,
)
from .kinematics import joint_positions, link_poses
from .mermaid import to_mermaid
from .model import (
    Box,
    Calibration,
    Collision,
    Cylinder,
    Dynamics,
    Geometry,
    Inertia,
    Inertial,
    Joint,
    JointType,
    Limit,
    Link,
    Location,
    Material,
    Mesh,
    Mimic,
    Origin,
    Robot,
    SafetyController,
    Sphere,
    Visual,
)
from .packages import PackageNotFoundError, find_package, resolve_package_uri
from .parse import Parsed, load, parse, read
from .spatial import Pose
from .write import add_inertials, inertial_xml, to_urdf

__all__ = [
    "Box",
    "Calibration",
    "CheckResult",
    "Collision",
    "Cylinder",
    "Diagnostic",
    "Dynamics",
    "Expansion",
    "FishbotUrdfError",
    "Geometry",
    "Inertia",
    "Inertial",
    "InputError",
    "Joint",
    "JointType",
    "Limit",
    "Link",
    "Location",
    "MassProperties",
    "Material",
    "Mesh",
    "Mimic",
    "Origin",
    "PackageNotFoundError",
    "Parsed",
    "Pose",
    "Robot",
    "RobotError",
    "SafetyController",
    "Severity",
    "Sphere",
    "ToolError",
    "ToolNotFoundError",
    "Topology",
    "Visual",
    "XacroError",
    "XmlSyntaxError",
    "__version__",
    "add_inertials",
    "box_inertia",
    "chain",
    "check",
    "check_file",
    "combine",
    "cylinder_inertia",
    "draw",
    "expand",
    "find_package",
    "geometry_inertia",
    "inertial_xml",
    "joint_positions",
    "leaves",
    "link_inertial",
    "link_poses",
    "load",
    "mass_properties",
    "mesh_inertia",
    "parse",
    "principal_moments",
    "read",
    "render",
    "resolve_package_uri",
    "root",
    "sphere_inertia",
    "subtree",
    "to_dot",
    "to_mermaid",
    "to_networkx",
    "to_urdf",
    "topology",
    "tree_text",
    "volume",
]


def __getattr__(name: str) -> Any:
    # importlib.metadata costs several milliseconds: only pay for it when asked.
    if name == "__version__":
        from importlib.metadata import version

        return version("fishbot-urdf")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
