"""The rules on mesh files.

Data only: the checks that report them are in `fishbot_urdf.rules`.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..diagnostics import Consumer, Facts, Family, Rule, Severity

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
# short), base_link_fine.stl (30 000 triangles) and base_link_flat.stl (a box 0.2 x 0.2 x 0).
_FOUND = "meshes/base_link.stl"


@dataclass(frozen=True, slots=True, kw_only=True)
class MeshNotFoundFacts(Facts):
    """The facts of a `mesh-not-found` finding."""

    package: str | None = None
    """The package that is not found, when the file is named ``package://`` of it."""
    looked_for: str | None = None
    """The file that programs look for, and is not there."""
    beside_writer: str | None = None
    """The file of that name beside the xacro file that wrote the name, when there is one."""
    unexpanded: str | None = None
    """The xacro substitution the name holds (``$(arg model)``), left unexpanded, when it
    holds one."""


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
    "absolute paths of the author's machine, and a package whose folder is not its name. "
    "A name that holds a xacro substitution (`$(find pkg)`, `$(arg model)`, `${path}`) comes "
    "from a .xacro file shipped as URDF without running xacro on it: the finding says so "
    "instead of suggesting another name; run xacro on the .xacro file, or check that file.",
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
    summary="A mesh file name is a malformed URI (package:/, package://NAME alone, "
    "file://relative, backslashes).",
    explanation="`package://NAME/path` names a file in ROS package NAME: with one slash, or "
    "with no path after the package, it names none. `file://` must be followed by an absolute "
    "path (`file://meshes/x.stl` reads `meshes` as a host name), and backslashes only work on "
    "Windows. Write `package://my_robot/meshes/base.stl`, a `file:///` path, or a path "
    "relative to the robot file with forward slashes.",
    bad=_ONE_BOX.format(name="file://meshes/base_link.stl"),
    good=_ONE_BOX.format(name=_FOUND),
    consumers=_VIEWERS,
)
PACKAGE_NO_NAME = Rule(
    "package-no-name",
    W,
    Family.MESHES,
    summary="A mesh is named `package:///path`: a package URI without the package's name.",
    explanation="ROS's resource_retriever, which RViz, MoveIt and robot_state_publisher's "
    "users load meshes through, refuses it (`Package name must not be empty`), so they show "
    "and collide with nothing. Programs that look for the path instead find it: PyBullet and "
    "yourdfpy in the robot file's folder or one above it, pinocchio in each of its package "
    "folders (`package_dirs`); sdformat hands Gazebo `model:///path`, to look up on its "
    "model path, as it does any `package://` name, and MuJoCo reads none. fishbot looks where "
    "those find it: a warning when the file is there, `mesh-not-found` too when it is not. "
    "Write the package's name after the two slashes (`package://my_robot/meshes/base.stl`).",
    bad=_ONE_BOX.format(name="package:///meshes/base_link.stl"),
    good=_ONE_BOX.format(name=_FOUND),
    consumers=(Consumer.URDFDOM,),
)
MESH_FORMAT = Rule(
    "mesh-format",
    W,
    Family.MESHES,
    summary="A mesh is in a format most robot programs cannot load (not STL, OBJ or COLLADA).",
    explanation="RViz loads many formats, but Gazebo Classic and Gazebo Fortress (ignition-common "
    "4) load STL, OBJ and COLLADA (.dae) only (glTF and GLB from the Gazebo of gz-common 5 on), "
    "MuJoCo and PyBullet STL and OBJ, and CAD formats (STEP, IGES) or files without an "
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
MESH_FLAT = Rule(
    "mesh-flat",
    W,
    Family.MESHES,
    summary="A collision mesh has no volume: its vertices lie in one plane (or on a line).",
    explanation="Simulators collide with a mesh's convex hull, and a flat mesh (a plate "
    "exported as one face, a decal, a sheet of fewer than 4 vertices) has none. MuJoCo refuses "
    "the robot (`mesh 'x' has coplanar vertices, cannot compute convex hull`, or `at least 4 "
    "vertices required`); a mesh flat but for the file's rounding passes its test with a hull "
    "as thin as that rounding, and still has no volume to weigh. urdfdom never "
    "opens meshes, and pinocchio and PyBullet load it. Collide with a thin box instead, or "
    "give the mesh its thickness.",
    bad=_COLLIDING.format(name="meshes/base_link_flat.stl"),
    good=_COLLIDING.format(name=_FOUND),
    consumers=(Consumer.MUJOCO,),
)
SHAPE_SIZE = Rule(
    "shape-size",
    E,
    Family.MESHES,
    summary="A collision box, cylinder or sphere has a size of 0 or less, or a collision mesh "
    "a scale of 0; a visual a negative size.",
    explanation="urdfdom and pinocchio take any number for a size, but a collision shape of "
    "size 0 has nothing to collide with, and one of a negative size is no shape at all. MuJoCo "
    "refuses such a collision, and so the robot (`size 0 must be positive in geom`; a mesh "
    "scaled by 0: `mesh volume is too small`). A visual of size 0 is drawn as nothing, a "
    "placeholder many robots use for frames (MuJoCo leaves a URDF's visuals out), so only a "
    "negative one is reported, as a warning; a negative mesh scale mirrors the mesh and is fine. "
    "Give the shape its real size, or delete it.",
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0"/></geometry></collision>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
</robot>
""",
    consumers=(Consumer.MUJOCO,),
)
MJCF_EMPTY_SHAPE = Rule(
    "mjcf-empty-shape",
    W,
    Family.MESHES,
    summary="A shape of no size `fishbot mjcf` leaves out of the MJCF: a box, cylinder or "
    "sphere with a size of 0 or less, or a mesh scaled by 0.",
    explanation="MuJoCo refuses a model with a geom whose size is not positive (`size 0 must "
    "be positive in geom`), visual or not, and a visual box of size 0 is a placeholder many "
    "robots use for a frame (upkie's, laikago's). Such a shape draws nothing and collides with "
    "nothing, so `fishbot mjcf` writes the model without it, says so with this warning, and "
    "the command succeeds; the body keeps its inertial. A collision of no size is an error of "
    "its own (`shape-size`). Give the shape its real size, or delete it.",
    bad="""\
# frame.urdf: a visual box of size 0 0 0
fishbot mjcf frame.urdf -o frame.xml
""",
    good="""\
fishbot mjcf fishbot.urdf -o fishbot.xml
""",
    consumers=(Consumer.MUJOCO,),
    language="shell",
)
SHAPE_NOT_DRAWN = Rule(
    "shape-not-drawn",
    W,
    Family.MESHES,
    summary="A shape `fishbot render` and `fishbot view` cannot draw: its corners, posed, are "
    "not finite or lie farther than 1e9 m from the root; or an inertia no box has.",
    explanation="render and view pose every shape at the joint configuration asked for, and "
    "leave out one whose corners are not finite numbers or lie farther than 1e9 m from the "
    "root: no robot reaches that far, and drawing it would overflow. Such a shape comes from "
    "a scale, a size or an origin with a wild number (an exponent mistyped, a unit mistaken), "
    "or a mesh file whose numbers are garbage. The picture is drawn without it and the command "
    "succeeds; fix the number. Asked to show each link's inertia (`--show inertia`, the "
    "viewer's Inertia toggle), they draw the box of uniform density with the link's mass and "
    "principal moments, as RViz does; a mass that is not positive, an inertia that is not "
    "positive definite, or one whose largest principal moment is more than the other two "
    "together has no such box (no solid has it): RViz leaves it out, and so do they, with "
    "this warning, which says which of the three it is.",
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


@dataclass(frozen=True, slots=True, kw_only=True)
class MjcfLeftOutFacts(Facts):
    """The facts of an `mjcf-left-out` finding."""

    convertible: bool = False
    """Whether the mesh would have been converted, had the MJCF been written to a file."""


MJCF_LEFT_OUT = Rule(
    "mjcf-left-out",
    W,
    Family.MESHES,
    summary="A mesh `fishbot mjcf` leaves out of the MJCF: its file is not found, or MuJoCo "
    "cannot read it and it could not be converted.",
    explanation="MuJoCo reads binary STL and OBJ mesh files, and refuses a model that names a "
    "file it cannot decode (`no decoder found for mesh file` for COLLADA, PLY or glTF, `number "
    "of faces should be between 1 and 200000` for an ASCII STL), or a file that is not there. "
    "Written to a file, `fishbot mjcf` converts such a mesh into a folder beside the model "
    "(`mjcf-mesh-converted`); written to standard output, or when the conversion fails (a "
    "file that holds no triangles or fewer than 4 distinct vertices, or a collision mesh all "
    "in one plane, of which MuJoCo cannot make the convex hull it collides with; COLLADA "
    "without the `mesh` extra), it leaves "
    "the shape out of its body, with this warning, and the command succeeds. The body keeps "
    "its inertial, so only what is drawn or collides is lost; write the MJCF to a file, "
    "export the mesh as binary STL or OBJ, or name the file that is there.",
    bad="""\
# mixed.urdf: a visual mesh in COLLADA, meshes/base_link.dae, written to standard output
fishbot mjcf mixed.urdf
""",
    good="""\
fishbot mjcf fishbot.urdf -o fishbot.xml
""",
    consumers=(Consumer.MUJOCO,),
    language="shell",
)

MJCF_MESH_CONVERTED = Rule(
    "mjcf-mesh-converted",
    Severity.NOTE,
    Family.MESHES,
    summary="A mesh `fishbot mjcf` converted for MuJoCo into the folder beside the model: "
    "COLLADA, PLY, glTF, an ASCII STL, or an STL of more triangles than MuJoCo reads.",
    explanation="MuJoCo reads only binary STL (of 1 to 200,000 triangles) and OBJ. Written to "
    "a file (`-o robot.xml`), `fishbot mjcf` writes the triangles of any other mesh, placed "
    "as RViz draws them (a COLLADA file's node transforms and `<unit meter>` applied), as a "
    "binary STL (OBJ past 200,000 triangles) in the folder `robot_meshes/` beside the model, "
    "which the model's `<compiler meshdir>` names; the source file is left as it is. This "
    "note says which; the converted file loses the source's colours and textures, and the "
    "geom takes the URDF material's colour instead. Export the mesh as binary STL or OBJ to "
    "have MuJoCo read it where it is.",
    bad="""\
# ascii.urdf: a visual mesh in ASCII STL, meshes/base_link_ascii.stl
fishbot mjcf ascii.urdf -o ascii.xml
""",
    good="""\
fishbot mjcf fishbot.urdf -o fishbot.xml
""",
    consumers=(Consumer.MUJOCO,),
    language="shell",
)


@dataclass(frozen=True, slots=True, kw_only=True)
class NothingDrawnFacts(Facts):
    """The facts of a `nothing-drawn` finding."""

    kind: str
    """What was asked to be drawn: ``visual`` or ``collision``, or the layers asked for,
    joined by commas (``mass,inertia``)."""
    visuals: int
    """The robot's visual shapes."""
    collisions: int
    """The robot's collision shapes."""
    other_drawable: int = 0
    """The shapes of the other kind that could be drawn: boxes, cylinders and spheres, and
    meshes whose file is found."""
    meshes_not_found: int = 0
    """The shapes of the kind asked for that are meshes whose file is not found."""
    packages: tuple[str, ...] = ()
    """The packages not found that hold meshes of the kind asked for."""


NOTHING_DRAWN = Rule(
    "nothing-drawn",
    E,
    Family.MESHES,
    summary="A robot of which `fishbot render` would draw nothing: no link has a shape of the "
    "kind asked for, or none of them can be drawn.",
    explanation="A robot of links and joints alone is valid URDF, and RViz shows only its "
    "frames; but a picture of it is a blank rectangle, which a script would publish as if it "
    "were the robot. `fishbot render` says so and writes nothing, with exit status 1 (a "
    "configuration that ignores the rule, or makes it a warning, gets the blank picture); "
    "`fishbot view` shows the link frames and prints it as a warning. Give a link a "
    "`<visual>`, draw the collision shapes with `--collision` (offered when some of them "
    "can be drawn), or fix the shapes that the other warnings say cannot be drawn: most "
    "often mesh files that are not found, in a package `--package NAME=PATH` locates.",
    bad="""\
# frames.urdf: base_link and two wheel links, none with a <visual>
fishbot render frames.urdf -o frames.png
""",
    good="""\
# fishbot.urdf: the same links, base_link with a <visual>
fishbot render fishbot.urdf -o fishbot.png
""",
    consumers=(),
    language="shell",
)
