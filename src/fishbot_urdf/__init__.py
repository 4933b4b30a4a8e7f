"""fishbot_urdf: read, check and explore URDF robot descriptions, with or without ROS.

>>> import fishbot_urdf
>>> robot = fishbot_urdf.load("robots/fishbot/urdf/first_robot.urdf")  # doctest: +SKIP
>>> [link.name for link in robot.links]  # doctest: +SKIP
['base_link', 'imu_link']
"""

from .analysis import Analysis, Body, analyse
from .check import CheckResult, check, check_file
from .config import Config, find_config, load_config
from .diagnostics import Diagnostic, Kind, Severity, Subject
from .dot import draw, render, to_dot
from .errors import (
    ArgumentError,
    ConfigError,
    FishbotUrdfError,
    InputError,
    RobotError,
    ShapeError,
    StructureError,
    ToolError,
    ToolNotFoundError,
    UnknownNameError,
    XmlSyntaxError,
)
from .expand import Expansion, XacroError, expand
from .graph import Topology, chain, leaves, root, subtree, to_networkx, topology, tree_text
from .inertia import (
    Filling,
    LinkMass,
    MassProperties,
    MassTable,
    box_inertia,
    combine,
    cylinder_inertia,
    fill_inertials,
    geometry_inertia,
    link_inertial,
    mass_properties,
    mass_table,
    mesh_inertia,
    principal_moments,
    sphere_inertia,
    volume,
)
from .kinematics import (
    Kinematics,
    forward_kinematics,
    jacobian,
    joint_positions,
    link_poses,
    transform,
)
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
from .report import FileReport, github_annotations, json_report, sarif_report
from .rules import Rule
from .spatial import Pose
from .write import add_inertials, inertial_xml, to_urdf

__all__ = [
    "Analysis",
    "ArgumentError",
    "Body",
    "Box",
    "Calibration",
    "CheckResult",
    "Collision",
    "Config",
    "ConfigError",
    "Cylinder",
    "Diagnostic",
    "Dynamics",
    "Expansion",
    "FileReport",
    "Filling",
    "FishbotUrdfError",
    "Geometry",
    "Inertia",
    "Inertial",
    "InputError",
    "Joint",
    "JointType",
    "Kind",
    "Kinematics",
    "Limit",
    "Link",
    "LinkMass",
    "Location",
    "MassProperties",
    "MassTable",
    "Material",
    "Mesh",
    "Mimic",
    "Origin",
    "PackageNotFoundError",
    "Parsed",
    "Pose",
    "Robot",
    "RobotError",
    "Rule",
    "SafetyController",
    "Severity",
    "ShapeError",
    "Sphere",
    "StructureError",
    "Subject",
    "ToolError",
    "ToolNotFoundError",
    "Topology",
    "UnknownNameError",
    "Visual",
    "XacroError",
    "XmlSyntaxError",
    "__version__",
    "add_inertials",
    "analyse",
    "box_inertia",
    "chain",
    "check",
    "check_file",
    "combine",
    "cylinder_inertia",
    "draw",
    "expand",
    "fill_inertials",
    "find_config",
    "find_package",
    "forward_kinematics",
    "geometry_inertia",
    "github_annotations",
    "inertial_xml",
    "jacobian",
    "joint_positions",
    "json_report",
    "leaves",
    "link_inertial",
    "link_poses",
    "load",
    "load_config",
    "mass_properties",
    "mass_table",
    "mesh_inertia",
    "parse",
    "principal_moments",
    "read",
    "render",
    "resolve_package_uri",
    "root",
    "sarif_report",
    "sphere_inertia",
    "subtree",
    "to_dot",
    "to_mermaid",
    "to_networkx",
    "to_urdf",
    "topology",
    "transform",
    "tree_text",
    "volume",
]


def __getattr__(name: str) -> str:
    # importlib.metadata costs several milliseconds: only pay for it when asked.
    if name == "__version__":
        from importlib.metadata import version

        return version("fishbot-urdf")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
