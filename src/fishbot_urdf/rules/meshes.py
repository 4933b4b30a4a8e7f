"""Rules about mesh files: the name resolves to a file, with the right case, in a format the
robot's programs load."""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path

from ..analysis import Analysis, of
from ..diagnostics import Diagnostic, Kind, Severity, Subject
from ..errors import FishbotUrdfError, ShapeError
from ..meshpaths import MeshPath, State, robot_meshes
from ..model import Box, Cylinder, Link, Mesh, Sphere
from ..packages import PackageFinder
from . import Consumer, Family, Rule

__all__ = ["REPORTS", "meshes", "unresolved"]

E, W = Severity.ERROR, Severity.WARNING
_VIEWERS = (Consumer.URDFDOM, Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET)

_ONE_BOX = """\
<robot name="fishbot">
  <link name="base_link">
    <visual>
      <geometry><mesh filename="{name}"/></geometry>
    </visual>
  </link>
</robot>
"""
_COLLIDING = """\
<robot name="fishbot">
  <link name="base_link">
    <collision>
      <geometry><mesh filename="{name}"/></geometry>
    </collision>
    <inertial><mass value="1"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
</robot>
"""
# The examples' folder holds meshes/base_link.stl (a box in metres) and .step (empty),
# base_link_mm.stl (a box 200 x 200 x 100 units), base_link_cut.stl (a binary STL cut
# short) and base_link_fine.stl (30 000 triangles).
_FOUND = "meshes/base_link.stl"

MESH_NOT_FOUND = Rule(
    "mesh-not-found",
    E,
    Family.MESHES,
    summary="A <mesh filename> names a file that is not there.",
    explanation="check_urdf never opens meshes, so a wrong mesh name passes it; RViz then shows "
    "nothing for the part and Gazebo, MuJoCo and PyBullet refuse the robot. `package://` names "
    "are looked up as for xacro's `$(find)`, and a package that is not found makes one warning "
    "naming the places searched (`--package NAME=PATH` tells where it is). Relative names are "
    "read beside the robot file, never beside an included xacro file that wrote them: after "
    "xacro the robot is one text, and Gazebo, MuJoCo, PyBullet, pinocchio and yourdfpy read "
    "relative names beside the file they load (RViz reads only `package://` and `file://`). "
    "Among robots shipped in PyPI packages about 7% fail it: packages that "
    "ship a robot without its meshes (fetched later, or left behind when it was copied), "
    "absolute paths of the author's machine, and a package whose folder is not its name.",
    bad=_ONE_BOX.format(name="meshes/base.stl"),
    good=_ONE_BOX.format(name=_FOUND),
    consumers=_VIEWERS,
)
MESH_CASE = Rule(
    "mesh-case",
    E,
    Family.MESHES,
    summary="A mesh file name differs from the file's only in upper and lower case.",
    explanation="macOS and Windows find `Base_Link.STL` when the file is `base_link.stl`, Linux "
    "does not: the robot works on the laptop it was written on and loses its meshes on the "
    "robot's computer and in CI. Write the name exactly as the file is named.",
    bad=_ONE_BOX.format(name="meshes/Base_Link.stl"),
    good=_ONE_BOX.format(name=_FOUND),
    consumers=_VIEWERS,
)
MESH_URI = Rule(
    "mesh-uri",
    E,
    Family.MESHES,
    summary="A mesh file name is a malformed URI (package:///, package:/, file://relative, "
    "backslashes).",
    explanation="`package://NAME/path` names a file in ROS package NAME, so `package:///x` names "
    "a package with no name and ROS's resource retriever fails on it. `file://` must be "
    "followed by an absolute path, and backslashes only work on Windows. Write "
    "`package://my_robot/meshes/base.stl`, a `file:///` path, or a path relative to the robot "
    "file with forward slashes.",
    bad=_ONE_BOX.format(name="package:///meshes/base_link.stl"),
    good=_ONE_BOX.format(name=_FOUND),
    consumers=_VIEWERS,
)
MESH_FORMAT = Rule(
    "mesh-format",
    W,
    Family.MESHES,
    summary="A mesh is in a format most robot programs cannot load (not STL, OBJ or COLLADA).",
    explanation="RViz loads many formats, but Gazebo Classic loads STL, OBJ and COLLADA (.dae) "
    "only, MuJoCo and PyBullet STL and OBJ, and CAD formats (STEP, IGES) or files without an "
    "extension load nowhere. Export the mesh as STL or OBJ (COLLADA keeps colours for RViz and "
    "Gazebo).",
    bad=_ONE_BOX.format(name="meshes/base_link.step"),
    good=_ONE_BOX.format(name=_FOUND),
    consumers=(Consumer.GAZEBO, Consumer.MUJOCO, Consumer.PYBULLET),
)

MESH_INVALID = Rule(
    "mesh-invalid",
    W,
    Family.MESHES,
    summary="An STL or OBJ mesh file cannot be read: cut short, or bad numbers.",
    explanation="The file is there, but a binary STL is shorter or "
    "longer than its header says (a copy cut short, a file written as text), a number is not "
    "one or is not finite (nan, inf), or an OBJ face names a vertex that does not exist. RViz "
    "and Gazebo show nothing or stop loading, MuJoCo refuses the model, and `fishbot render` "
    "draws the mesh as its box. The message says what is wrong; export the mesh again.",
    bad=_ONE_BOX.format(name="meshes/base_link_cut.stl"),
    good=_ONE_BOX.format(name=_FOUND),
    consumers=_VIEWERS,
)
MESH_UNITS = Rule(
    "mesh-units",
    W,
    Family.MESHES,
    summary="A mesh's size says it is in millimetres (an STL or OBJ file read as metres).",
    explanation="URDF lengths are metres, and STL and OBJ files carry no unit, so a part "
    "exported from CAD in millimetres comes in a thousand times too big: RViz shows a giant, "
    "and `fishbot inertia --fill` makes a link of tonnes. The mesh is judged by plain sense (a "
    "part more than 5 m across) and against the link's other shapes and its inertia. Add "
    '`scale="0.001 0.001 0.001"` to the `<mesh>`, or export in metres.',
    bad=_ONE_BOX.format(name="meshes/base_link_mm.stl"),
    good=_ONE_BOX.format(name=_FOUND),
    consumers=_VIEWERS,
)
MESH_FACES = Rule(
    "mesh-faces",
    Severity.NOTE,
    Family.MESHES,
    summary="A collision mesh has so many faces that simulators slow down.",
    explanation="Physics engines test collision meshes triangle by triangle, and a mesh of tens "
    "of thousands of faces (a visual mesh reused for collision, often) makes every step slow; "
    "MuJoCo and PyBullet replace it with its convex hull anyway. Simplify it (a few hundred "
    "faces, or its convex hull) or use boxes, cylinders and spheres for collision.",
    bad=_COLLIDING.format(name="meshes/base_link_fine.stl"),
    good=_COLLIDING.format(name=_FOUND),
    consumers=(Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET),
)

SHAPE_NOT_DRAWN = Rule(
    "shape-not-drawn",
    W,
    Family.MESHES,
    summary="A shape `fishbot render` and `fishbot view` cannot draw: its corners, posed, are "
    "not finite or lie farther than 1e9 m from the root.",
    explanation="render and view pose every shape at the joint configuration asked for, and "
    "leave out one whose corners are not finite numbers or lie farther than 1e9 m from the "
    "root: no robot reaches that far, and drawing it would overflow. Such a shape comes from "
    "a scale, a size or an origin with a wild number (an exponent mistyped, a unit mistaken), "
    "or a mesh file whose numbers are garbage. The picture is drawn without it and the command "
    "succeeds; fix the number.",
    bad="""\
# far.urdf places a box 1e10 m from its link
fishbot render far.urdf -o far.png
""",
    good="""\
fishbot render fishbot.urdf -o fishbot.png
""",
    consumers=(),
    language="shell",
)

_LOADED = frozenset({".stl", ".obj", ".dae"})
_MOST_FACES = 20_000  # a collision mesh above this is slow to simulate
_LARGEST_PART = 5.0  # metres: a robot part larger than this is implausible


def meshes(
    analysis: Analysis,
    packages: Mapping[str, str | Path] | PackageFinder | None = None,
    environ: Mapping[str, str] | None = None,
) -> Iterator[Diagnostic]:
    """Every finding about the robot's mesh files, found by the analysis's
    ``mesh_paths`` (see `fishbot_urdf.meshpaths`). ``packages`` and ``environ``, when
    given, are where ``package://`` names are looked up instead (as for xacro's
    ``$(find)``); or ``packages`` is a `fishbot_urdf.packages.PackageFinder` that keeps its
    answers for other robots (its own environment is read then)."""
    if environ is not None and not isinstance(packages, PackageFinder):
        packages = PackageFinder(packages, environ)
    analysis = of(analysis, packages)
    uses = list(robot_meshes(analysis.robot))
    for link, mesh, collides in uses:
        yield from _mesh(analysis, link, mesh, collides)
    yield from unresolved(analysis, ((link, mesh) for link, mesh, _ in uses))


def unresolved(
    analysis: Analysis, uses: Iterable[tuple[Link, Mesh]], *, drawing: bool = False
) -> Iterator[Diagnostic]:
    """The findings about meshes whose names lead to no file (by the analysis's
    ``mesh_paths``): one for each such mesh, and one for each package not found, for all
    of its meshes. For ``drawing`` (a scene), each says the mesh is not drawn, as a
    warning, and names that lead to nothing to draw (a remote file, a relative name of a
    robot read from text) are findings too."""
    paths = analysis.mesh_paths
    missing: dict[str, list[tuple[Link, Mesh]]] = {}
    for link, mesh in uses:
        path = paths.get(mesh.filename)
        if path.state is State.NO_PACKAGE:
            missing.setdefault(str(path.package), []).append((link, mesh))
            continue
        finding = _unresolved(analysis, link, mesh, path, drawing)
        if finding is not None:
            yield finding
    for package, named in missing.items():
        link, mesh = named[0]
        path = paths.get(mesh.filename)
        others = len(named) - 1
        also = f" (nor {others} other mesh{'es' if others > 1 else ''} of it)" if others else ""
        then = "it is not drawn" if drawing else "the file cannot be checked"
        yield MESH_NOT_FOUND.report(
            f"link {link.name!r}: mesh {mesh.filename!r} is in package {package!r}, "
            f"which is not found, so {then}{also}",
            mesh.source,
            path=analysis.path,
            subject=Subject(Kind.LINK, link.name),
            hint=f"searched: {'; '.join(path.searched)}",
            data={"package": package},
            severity=Severity.WARNING,
        )


def _unresolved(
    analysis: Analysis, link: Link, mesh: Mesh, path: MeshPath, drawing: bool
) -> Diagnostic | None:
    state = path.state
    if state is State.FOUND or (not drawing and state in (State.REMOTE, State.NO_FOLDER)):
        return None  # found, or not ours to judge
    named = f"link {link.name!r}: mesh {mesh.filename!r}"
    then = ", so it is not drawn" if drawing else ""
    data: dict[str, str] = {}
    if state is State.MALFORMED:
        rule, what, hint = MESH_URI, f"{path.problem}{then}", path.fix
    elif state is State.OTHER_CASE:
        rule, what = MESH_CASE, f"is found only as {path.other!r}, a name that differs in case"
        what += then
        hint = "Linux file names are case-sensitive: write the name exactly as the file's"
    elif state is State.MISSING:
        rule, what = MESH_NOT_FOUND, analysis.mesh_paths.why(path) + then
        hint, data = _not_found(analysis, mesh, path)
    elif state is State.REMOTE:
        rule, what = MESH_NOT_FOUND, f"is not a file on this machine{then}"
        hint = "http://, https:// and model:// files are not fetched"
    else:  # NO_FOLDER
        rule, what = MESH_NOT_FOUND, f"is a relative name, and the robot was read from text{then}"
        hint = "a relative name is read beside the robot file, and text has none"
    return rule.report(
        f"{named} {what}",
        mesh.source,
        path=analysis.path,
        subject=Subject(Kind.LINK, link.name),
        hint=hint,
        data=data,
        severity=Severity.WARNING if drawing else None,
    )


def _not_found(analysis: Analysis, mesh: Mesh, path: MeshPath) -> tuple[str, dict[str, str]]:
    """The hint and the data of a mesh whose file is not where programs look for it."""
    paths = analysis.mesh_paths
    assert path.file is not None
    data = {"looked_for": str(path.file)}
    beside = paths.beside_writer(mesh)
    if beside is not None:
        # The classic mistake: the name is right beside the xacro file that wrote it.
        data["beside_writer"] = str(beside)
        writer = mesh.source.path if mesh.source else "the file that wrote it"
        held = paths.in_package(beside)
        package, inside = held if held is not None else ("PACKAGE", "path")
        return (
            f"it is beside {writer}, which wrote it, but the expanded robot keeps no trace of "
            f"that file: write package://{package}/{inside} (or $(find {package})/{inside})",
            data,
        )
    close = paths.closest(path.file)
    guess = f"did you mean {close!r}? " if close else ""
    return guess + _fix(mesh.filename), data


def _mesh(analysis: Analysis, link: Link, mesh: Mesh, collides: bool) -> Iterator[Diagnostic]:
    """The findings about one mesh that need no file, or its file found."""
    paths = analysis.mesh_paths
    name = mesh.filename
    subject = Subject(Kind.LINK, link.name)
    named = f"link {link.name!r}: mesh {name!r}"

    def report(rule: Rule, what: str, hint: str) -> Diagnostic:
        return rule.report(
            f"{named} {what}", mesh.source, path=analysis.path, subject=subject, hint=hint
        )

    path = paths.get(name)
    if path.state in (State.MALFORMED, State.REMOTE):
        return
    extension = os.path.splitext(name)[1].lower()
    if extension not in _LOADED:
        kind = f"is a {extension} file" if extension else "has no file extension"
        yield report(
            MESH_FORMAT,
            kind,
            "Gazebo loads STL, OBJ and COLLADA; MuJoCo and PyBullet STL and OBJ: export it "
            "as one of those",
        )
    if not path.found or path.file is None:
        return
    facts = paths.facts(path.file)
    if facts is None:
        fault = _fault(path.file) if extension in (".stl", ".obj") else None
        if fault is not None:
            yield report(MESH_INVALID, fault, "export the mesh again")
        return
    if collides and facts.faces > _MOST_FACES:
        yield report(
            MESH_FACES,
            f"has {facts.faces} faces, too many for a collision shape",
            "simplify it to a few hundred faces or its convex hull, or collide with boxes, "
            "cylinders and spheres",
        )
    units = _millimetres(link, facts.extent(mesh.scale))
    if units is not None:
        yield report(
            MESH_UNITS,
            units,
            'if it is in millimetres, add scale="0.001 0.001 0.001" to the <mesh>',
        )


def _millimetres(link: Link, extent: float) -> str | None:
    """Why a mesh ``extent`` metres across reads as millimetres, or None if it does not.

    Plain sense: no robot part is more than 5 m across, unless the link's other shapes or
    its inertia say it is that large too. Against them: a mesh 200 to 5000 times larger
    than what they say.
    """
    shrunk = extent / 1000.0
    sizes = list(_sizes(link))
    if any(size >= extent / 20 for size, _ in sizes):
        return None  # the rest of the link is as large: a big part, in metres
    if extent > _LARGEST_PART and shrunk >= 0.001:
        return (
            f"is {extent:.4g} m across, more than any robot part; in millimetres it would be "
            f"{shrunk:.4g} m"
        )
    for size, what in sizes:
        if extent > 0.3 and 200 <= extent / size <= 5000:
            return (
                f"is {extent:.4g} m across, but {what} says the link is about {size:.3g} m; "
                f"in millimetres it would be {shrunk:.4g} m"
            )
    return None


def _sizes(link: Link) -> Iterator[tuple[float, str]]:
    """How large the link's other evidence says it is (m): its shapes, its inertia."""
    shapes = [part.geometry for part in link.visuals]
    shapes += [part.geometry for part in link.collisions]
    for shape in shapes:
        if isinstance(shape, Box):
            size, what = max(shape.size), "its box"
        elif isinstance(shape, Cylinder):
            size, what = max(2 * shape.radius, shape.length), "its cylinder"
        elif isinstance(shape, Sphere):
            size, what = 2 * shape.radius, "its sphere"
        else:
            continue
        if size > 0:
            yield size, what
    inertial = link.inertial
    if inertial is not None and inertial.mass > 0:
        i = inertial.inertia
        largest = max(i.ixx, i.iyy, i.izz)
        if largest > 0:
            # A rod of length L has I = m L^2 / 12: the longest the inertia allows.
            yield math.sqrt(12.0 * largest / inertial.mass), "its inertia"


def _fix(name: str) -> str:
    if name.startswith("package://"):
        return "package:// names a file inside the package's folder"
    if name.startswith("file://") or os.path.isabs(name):
        return "an absolute path names a file on this machine only: write package://PACKAGE/path"
    return "write package://PACKAGE/path for a file of a ROS package"


def _fault(file: Path) -> str | None:
    """What is wrong with an STL or OBJ file whose facts could not be read (looked at only
    then: a file read well pays nothing); None for a file that holds nothing (an empty
    placeholder) or cannot be read at all."""
    from ..meshfile import EmptyMeshError, mesh_triangles  # (for a mesh found malformed)

    try:
        mesh_triangles(file)
    except EmptyMeshError:
        return None
    except ShapeError as exc:
        return exc.message
    except FishbotUrdfError:
        return None  # not readable: another rule's matter
    return None


REPORTS: tuple[Rule, ...] = (
    MESH_CASE,
    MESH_FACES,
    MESH_FORMAT,
    MESH_INVALID,
    MESH_NOT_FOUND,
    MESH_UNITS,
    MESH_URI,
)
"""Every rule this module's check may report: the check runs only when one is selected."""
