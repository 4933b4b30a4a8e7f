"""fishbot_urdf: read, check and explore URDF robot descriptions, with or without ROS.

>>> import fishbot_urdf
>>> robot = fishbot_urdf.load("robots/fishbot/urdf/first_robot.urdf")  # doctest: +SKIP
>>> [link.name for link in robot.links]  # doctest: +SKIP
['base_link', 'imu_link']
"""

# Every public name is imported when first used (PEP 562), so that `import fishbot_urdf`
# (and every `fishbot` command) loads only what it uses.
from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .analysis import Analysis, Body, analyse
    from .analysis.topology import Topology, topology
    from .catalog import Rule
    from .config import Config, find_config, load_config
    from .diagnostics import Diagnostic, Kind, Severity, Subject
    from .drawing.dot import draw, render, render_graph, to_dot
    from .drawing.mermaid import to_mermaid
    from .drawing.picture import picture
    from .errors import (
        ArgumentError,
        ConfigError,
        FieldTypeError,
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
    from .expansion import Expansion, XacroError, expand
    from .graph import chain, leaves, root, subtree, to_networkx, tree_text
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
    from .lint import CheckResult, check, check_file
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
    from .packages import PackageFinder, PackageNotFoundError, find_package, resolve_package_uri
    from .parsing import Parsed, load, parse, read
    from .report import FileReport, github_annotations, json_report, sarif_report
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
    "FieldTypeError",
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
    "PackageFinder",
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
    "picture",
    "principal_moments",
    "read",
    "render",
    "render_graph",
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

_WHERE = {
    "Analysis": "analysis",
    "ArgumentError": "errors",
    "Body": "analysis",
    "Box": "model",
    "Calibration": "model",
    "CheckResult": "lint",
    "Collision": "model",
    "Config": "config",
    "ConfigError": "errors",
    "Cylinder": "model",
    "Diagnostic": "diagnostics",
    "Dynamics": "model",
    "Expansion": "expansion",
    "FieldTypeError": "errors",
    "FileReport": "report",
    "Filling": "inertia",
    "FishbotUrdfError": "errors",
    "Geometry": "model",
    "Inertia": "model",
    "Inertial": "model",
    "InputError": "errors",
    "Joint": "model",
    "JointType": "model",
    "Kind": "diagnostics",
    "Kinematics": "kinematics",
    "Limit": "model",
    "Link": "model",
    "LinkMass": "inertia",
    "Location": "location",
    "MassProperties": "inertia",
    "MassTable": "inertia",
    "Material": "model",
    "Mesh": "model",
    "Mimic": "model",
    "Origin": "model",
    "PackageFinder": "packages",
    "PackageNotFoundError": "packages",
    "Parsed": "parsing",
    "Pose": "spatial",
    "Robot": "model",
    "RobotError": "errors",
    "Rule": "catalog",
    "SafetyController": "model",
    "Severity": "diagnostics",
    "ShapeError": "errors",
    "Sphere": "model",
    "StructureError": "errors",
    "Subject": "diagnostics",
    "ToolError": "errors",
    "ToolNotFoundError": "errors",
    "Topology": "analysis.topology",
    "UnknownNameError": "errors",
    "Visual": "model",
    "XacroError": "expansion",
    "XmlSyntaxError": "errors",
    "add_inertials": "write",
    "analyse": "analysis",
    "box_inertia": "inertia",
    "chain": "graph",
    "check": "lint",
    "check_file": "lint",
    "combine": "inertia",
    "cylinder_inertia": "inertia",
    "draw": "drawing.dot",
    "expand": "expansion",
    "fill_inertials": "inertia",
    "find_config": "config",
    "find_package": "packages",
    "forward_kinematics": "kinematics",
    "geometry_inertia": "inertia",
    "github_annotations": "report",
    "inertial_xml": "write",
    "jacobian": "kinematics",
    "joint_positions": "kinematics",
    "json_report": "report",
    "leaves": "graph",
    "link_inertial": "inertia",
    "link_poses": "kinematics",
    "load": "parsing",
    "load_config": "config",
    "mass_properties": "inertia",
    "mass_table": "inertia",
    "mesh_inertia": "inertia",
    "parse": "parsing",
    "picture": "drawing.picture",
    "principal_moments": "inertia",
    "read": "parsing",
    "render": "drawing.dot",
    "render_graph": "drawing.dot",
    "resolve_package_uri": "packages",
    "root": "graph",
    "sarif_report": "report",
    "sphere_inertia": "inertia",
    "subtree": "graph",
    "to_dot": "drawing.dot",
    "to_mermaid": "drawing.mermaid",
    "to_networkx": "graph",
    "to_urdf": "write",
    "topology": "analysis.topology",
    "transform": "kinematics",
    "tree_text": "graph",
    "volume": "inertia",
}


def __getattr__(name: str) -> Any:
    module = _WHERE.get(name)
    if module is not None:
        value = getattr(import_module(f".{module}", __name__), name)
        globals()[name] = value  # the next use is a plain attribute
        return value
    # importlib.metadata costs several milliseconds: only pay for it when asked.
    if name == "__version__":
        from importlib.metadata import version  # ~50 ms to load: only when asked

        return version("fishbot-urdf")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
