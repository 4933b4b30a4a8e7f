"""What sdformat's URDF converter loses or moves before Gazebo sees the robot: links left out
for lack of mass, the blocks and plugin names of lumped links, switches it passes over."""

from __future__ import annotations

import math
import os
from collections import Counter
from collections.abc import Iterator

from ...analysis import Analysis, Body
from ...analysis.gazebo import Block, Lumping, place, text
from ...analysis.meshpaths import robot_meshes
from ...analysis.sensors import sdf_pose
from ...catalog.conversion import (
    GAZEBO_DROPPED_LINK,
    GAZEBO_LUMPED_LINK,
    GAZEBO_LUMPING_FLAG,
    GAZEBO_MIMIC,
    GAZEBO_MODEL_PATH,
    GAZEBO_PLUGIN_LINK,
)
from ...diagnostics import Diagnostic, Kind, Subject
from ...errors import FishbotUrdfError
from ...model import Joint, JointType, Link
from ...packages import gazebo_model_path
from ...spatial import Pose, euler_ypr

__all__ = ["losses", "pose_text"]

_SWITCHES = ("preserveFixedJoint", "disableFixedJointLumping")
# Link settings of a <gazebo reference> block the converter writes into the link it names.
_LINK_SETTINGS = ("gravity", "turnGravityOff", "selfCollide", "dampingFactor")
# Plugin parameters a plugin looks up as a link of Gazebo's model; a p3d plugin looks up its
# reference frame too. Others (a camera's frame_name) name a frame for ROS's tf, which keeps
# every link.
_LINK_NAMES = frozenset({"bodyName", "body_name", "linkName", "link_name"})
_P3D_NAMES = frozenset({"frameName", "frame_name"})
# The converter renames these in a <plugin> written directly in a <gazebo> block
# (ReduceSDFExtensionPluginFrameReplace).
_RENAMED = frozenset({"bodyName", "frameName"})
_MASSLESS = 1e-15  # the mass rules' (`fishbot_urdf.rules.physics`) zero


def losses(analysis: Analysis, *, select: frozenset[str]) -> Iterator[Diagnostic]:
    """Findings about what the converter loses or moves, of the rules in ``select``."""
    try:
        lumping = analysis.gazebo_lumping
    except FishbotUrdfError:  # no single root: the structure rules' finding
        return
    if GAZEBO_DROPPED_LINK.id in select:
        yield from _dropped(analysis, lumping)
    if GAZEBO_LUMPING_FLAG.id in select:
        yield from _switches(analysis, lumping)
    if GAZEBO_MODEL_PATH.id in select:
        yield from _model_paths(analysis)
    if GAZEBO_MIMIC.id in select:
        yield from _mimics(analysis, lumping)
    for block in analysis.gazebo_blocks:
        if block.element.tag != "gazebo":
            continue
        if GAZEBO_LUMPED_LINK.id in select:
            yield from _lumped_block(analysis, lumping, block)
        if GAZEBO_PLUGIN_LINK.id in select:
            yield from _plugin_links(analysis, lumping, block)


def pose_text(pose: Pose) -> str:
    """``xyz X Y Z rpy R P Y`` (metres, radians), as short as the numbers allow."""
    rpy = euler_ypr([list(row) for row in pose.rotation])
    return f"xyz {_numbers(pose.translation)} rpy {_numbers(rpy)}"


def _numbers(values: tuple[float, float, float]) -> str:
    return " ".join(f"{round(v, 6) + 0.0:g}" for v in values)


def _names(names: tuple[str, ...] | list[str]) -> str:
    shown = ", ".join(repr(n) for n in names[:8])
    return shown + (f" and {len(names) - 8} more" if len(names) > 8 else "")


# -- links left out ------------------------------------------------------------------------


def _dropped(analysis: Analysis, lumping: Lumping) -> Iterator[Diagnostic]:
    bodies = {body.base.name: body for body in analysis.bodies}
    root = analysis.root
    held = Counter(landing.link for landing in lumping.landings.values())
    links = analysis.links
    for name, gone in lumping.dropped.items():
        if not any(_mass(links.get(n)) > 0 for n in gone):
            continue  # frames without matter: they move nothing in Gazebo (nor in the others)
        body = bodies.get(name)
        if body is not None and _mass_rules_report(analysis, body):
            continue  # missing-inertial's or massless-link's, which name the links lost
        link = analysis.links.get(name)
        landing = lumping.landings[name]
        below = [n for n in gone if n != name]
        if landing.link != name:
            joint = _lumping_joint(analysis, name)
            message = (
                f"link {name!r} is fixed to {joint.parent!r} (joint {joint.name!r}) and has no "
                "mass, nor has anything fixed below it: sdformat's converter goes no further "
                f"down the tree, so Gazebo leaves out {_names(below)} below it"
            )
            hint = f"give {name!r} a mass, or hang what moves below it on {joint.parent!r}"
        else:
            fixed = held[name] > 1  # itself and the links lumped into it
            what = "nor has anything fixed to it" if fixed else "and nothing is fixed to it"
            whole = " (the whole robot: the model is empty)" if name == root else ""
            lost = f", and with it {_names(below)}" if below else ""
            message = f"link {name!r} has no mass, {what}: Gazebo leaves it out{lost}{whole}"
            hint = f"give {name!r}, or a link fixed to it, a mass"
        yield GAZEBO_DROPPED_LINK.report(
            message,
            link.source if link is not None else None,
            path=analysis.path,
            subject=Subject(Kind.LINK, name),
            hint=hint,
        )


def _mass(link: Link | None) -> float:
    return link.inertial.mass if link is not None and link.inertial is not None else 0.0


def _mass_rules_report(analysis: Analysis, body: Body) -> bool:
    """Whether `missing-inertial` or `massless-link` reports ``body`` (links welded by fixed
    joints) for having no mass, as `fishbot_urdf.rules.physics` judges it."""
    having = [link.inertial for link, _ in body.members if link.inertial is not None]
    collides = any(link.collisions for link, _ in body.members)
    if body.moved_by is None:  # the robot's base: only missing-inertial speaks of it
        return not having and collides and bool(analysis.robot.joints)
    if not having:
        return collides
    masses = [inertial.mass for inertial in having]
    if any(m < 0 or not math.isfinite(m) for m in masses):
        return False  # a negative or unreadable mass: another rule's
    return sum(masses) <= _MASSLESS


# -- mimic joints ---------------------------------------------------------------------------


def _mimics(analysis: Analysis, lumping: Lumping) -> Iterator[Diagnostic]:
    lost = lumping.lost()
    for joint in analysis.robot.joints:
        mimic = joint.mimic
        if mimic is None or joint.type is JointType.FIXED or joint.child in lost:
            continue
        yield GAZEBO_MIMIC.report(
            f"joint {joint.name!r} follows {mimic.joint!r} by <mimic>, which sdformat 12's "
            "converter leaves out: in Gazebo Fortress and Classic it moves on its own",
            mimic.source or joint.source,
            path=analysis.path,
            subject=Subject(Kind.JOINT, joint.name),
            hint="drive it with a controller or plugin of its own, or use Gazebo Harmonic "
            "(sdformat 14), whose converter keeps it",
        )


# -- switches the converter passes over ----------------------------------------------------


def _switches(analysis: Analysis, lumping: Lumping) -> Iterator[Diagnostic]:
    for name, block in lumping.ignored.items():
        written = [tag for tag in _SWITCHES if block.element.find(tag) is not None]
        switch = " and ".join(f"<{tag}>" for tag in written)
        joint = analysis.joints.get(name)
        if joint is not None:
            message = (
                f"<gazebo reference={name!r}>: {switch} does nothing on a "
                f"{joint.type.value} joint: the converter lumps only fixed joints"
            )
            hint = "leave it out"
        elif name in analysis.links:
            up = analysis.parent_joint.get(name)
            message = (
                f"<gazebo reference={name!r}>: {switch} does nothing on a link: the converter "
                "reads it on a fixed joint's name only"
            )
            hint = (
                f"write it in <gazebo reference={up.name!r}>"
                if up is not None and up.type is JointType.FIXED
                else "write it in the block of the fixed joint to keep"
            )
        else:
            continue  # a name of nothing: unknown-reference's
        yield GAZEBO_LUMPING_FLAG.report(
            message,
            block.where,
            path=analysis.path,
            subject=Subject(Kind.JOINT if joint is not None else Kind.LINK, name),
            hint=hint,
        )


# -- meshes Gazebo looks for on its resource path ------------------------------------------

# Where Gazebo looks for model://: the new Gazebo, Fortress, and Gazebo Classic.
_RESOURCE_PATHS = ("GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "GAZEBO_MODEL_PATH")


def _model_paths(analysis: Analysis) -> Iterator[Diagnostic]:
    paths = analysis.mesh_paths
    environ = paths.packages.environ
    env = os.environ if environ is None else environ
    on_path = {
        os.path.abspath(entry)
        for variable in _RESOURCE_PATHS
        for entry in env.get(variable, "").split(os.pathsep)
        if entry
    }
    seen: set[str] = set()
    for link, mesh, _ in robot_meshes(analysis.robot):
        name = mesh.filename
        if not name.startswith("package://") or name.startswith("package:///") or "$(" in name:
            continue
        package, _, rest = name[len("package://") :].partition("/")
        if package in seen or not package:
            continue
        seen.add(package)
        folder = paths.package_folder(package)
        if folder is None:
            continue  # package-not-found's
        if gazebo_model_path(folder / "package.xml") is not None:
            continue  # gazebo_ros puts it on GAZEBO_MODEL_PATH
        above = os.path.dirname(os.path.abspath(folder))
        named = folder.name == package
        if named and above in on_path:
            continue
        renamed = (
            ""
            if named
            else f"; its folder is named {folder.name!r}, so Gazebo finds it only where it "
            f"is installed, as share/{package}"
        )
        yield GAZEBO_MODEL_PATH.report(
            f"link {link.name!r}: mesh {name!r} is model://{package}/{rest} to Gazebo, which "
            f"looks for folder {package!r} on GZ_SIM_RESOURCE_PATH (Gazebo Classic: "
            f"GAZEBO_MODEL_PATH), and {above} is on neither{renamed}",
            mesh.source,
            path=analysis.path,
            subject=Subject(Kind.LINK, link.name),
            hint=f'add <gazebo_ros gazebo_model_path="${{prefix}}/.."/> to the <export> of '
            f"{folder / 'package.xml'}"
            + (f", or put {above} on the path" if named else ", and install the package"),
        )


# -- blocks and names of lumped links ------------------------------------------------------


def _lumped_block(analysis: Analysis, lumping: Lumping, block: Block) -> Iterator[Diagnostic]:
    name = block.reference
    if name is None or name not in analysis.links or not lumping.lumped(name):
        return
    landing = lumping.landings[name]
    into, joint = landing.link, _lumping_joint(analysis, name)
    lumped = f"link {name!r} is lumped into {into!r} (at {pose_text(landing.pose)})"
    keep = (
        f"or keep link {name!r} with <preserveFixedJoint>true</preserveFixedJoint> in "
        f"<gazebo reference={joint.name!r}>"
        + ("" if _mass(analysis.links.get(name)) > 0 else " and give it a mass")
    )
    for sensor in block.element.findall("sensor"):
        # ROS 2's gazebo_ros plugins name their messages' frame by the sensor's link when
        # they name none (gazebo_ros's SensorFrameID)
        plugin = next(
            (
                p
                for p in sensor.iter("plugin")
                if (p.get("filename") or "").startswith("libgazebo_ros")
                and p.find(".//frame_name") is None
                and p.find(".//frameName") is None
            ),
            None,
        )
        if plugin is None:
            continue  # its messages name their frame, or are not ROS's
        label = f"sensor {sensor.get('name') or ''!r} ({sensor.get('type') or ''})"
        pose = sensor.find("pose")
        if pose is not None and pose.get("relative_to"):
            at = "with its pose as written"
        else:
            at = f"at {pose_text(landing.pose.then(sdf_pose(text(sensor, 'pose'))))}"
        yield GAZEBO_LUMPED_LINK.report(
            f"{lumped}: Gazebo puts {label} in link {into!r} {at}, and its plugin "
            f"{plugin.get('name') or ''!r} ({plugin.get('filename')}), which names no "
            f"<frame_name>, stamps its messages with frame {into!r}",
            block.where,
            path=analysis.path,
            subject=Subject(Kind.LINK, name),
            hint=f"write <frame_name>{name}</frame_name> in the plugin, " + keep,
        )
    settings = [tag for tag in _LINK_SETTINGS if block.element.find(tag) is not None]
    if settings:
        listed = ", ".join(f"<{tag}>" for tag in settings)
        yield GAZEBO_LUMPED_LINK.report(
            f"{lumped}: Gazebo applies the block's {listed} to all of link {into!r}",
            block.where,
            path=analysis.path,
            subject=Subject(Kind.LINK, name),
            hint=f"write {'them' if len(settings) > 1 else 'it'} in <gazebo reference={into!r}> "
            "if meant for that link, " + keep,
        )


def _plugin_links(analysis: Analysis, lumping: Lumping, block: Block) -> Iterator[Diagnostic]:
    for plugin in block.element.iter("plugin"):
        filename = plugin.get("filename") or ""
        direct = plugin.getparent() is block.element
        for child in plugin.iter():
            tag = child.tag  # (a comment's is no str)
            if not isinstance(tag, str) or not (
                tag in _LINK_NAMES or (tag in _P3D_NAMES and "p3d" in filename)
            ):
                continue
            name = (child.text or "").strip()
            if name not in analysis.links or not lumping.lumped(name):
                continue
            if direct and tag in _RENAMED:
                continue  # the converter renames it, and moves the plugin's offsets with it
            landing = lumping.landings[name]
            yield GAZEBO_PLUGIN_LINK.report(
                f"plugin {plugin.get('name') or ''!r} ({filename}): <{tag}> names link "
                f"{name!r}, which the converter lumps into {landing.link!r} (at "
                f"{pose_text(landing.pose)}) without renaming it here: Gazebo has no link "
                f"{name!r}",
                place(analysis.references, block, child),
                path=analysis.path,
                subject=Subject(Kind.LINK, name),
                hint=f"name {landing.link!r}, or keep link {name!r} with <preserveFixedJoint> "
                f"in <gazebo reference={_lumping_joint(analysis, name).name!r}>",
            )


def _lumping_joint(analysis: Analysis, link: str) -> Joint:
    """The fixed joint that lumps ``link``, a link the converter lumps."""
    return analysis.parent_joint[link]
