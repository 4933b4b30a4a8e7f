"""Rules about what surrounds a robot: files, programs, packages, and this tool's own
suppression comments.

These are data only; errors of the setup stop a command with exit status 2.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..diagnostics import Consumer, Facts, Family, Rule, Severity

E, W = Severity.ERROR, Severity.WARNING

IO = Rule(
    "io",
    E,
    Family.SETUP,
    summary="A file cannot be read or written.",
    explanation="fishbot could not read an input or write an output: the file does not exist "
    "(often a typo in its path or extension), is a folder, is not readable or writable, or the "
    "disk is full. The message names the file and the reason. The command stops with exit status "
    "2, as for every fault of the setup rather than of the robot.",
    bad="""\
fishbot check fishbot.udrf
""",
    good="""\
fishbot check fishbot.urdf
""",
    consumers=(),
    language="shell",
    fatal=True,
)
LIMIT = Rule(
    "limit",
    E,
    Family.SETUP,
    summary="The work on a robot went past the time limit or a size bound.",
    explanation="Every command works within a deadline (`--timeout`, 60 s by default) and "
    "within bounds on what it reads and builds (`--max-size`, 256 MiB by default, and the "
    "pixels of a picture: 4096 x 4096 at most). Expanding, globbing includes, loading YAML, "
    "reading, matching "
    "suppression comments, analysing and rendering all stop when the deadline passes, and a "
    "picture whose memory would pass the bound is refused before it is drawn. The message "
    "names the work that was stopped. A real robot takes well under a second; raise the limit "
    "only for a file you trust, and expect the same input to keep growing otherwise. The "
    "command stops with exit status 2.",
    bad="""\
fishbot render fishbot.urdf -o fishbot.png --size 30000x30000
""",
    good="""\
fishbot render fishbot.urdf -o fishbot.png --size 1600x1200
""",
    consumers=(),
    language="shell",
    fatal=True,
)
PACKAGE_NOT_FOUND = Rule(
    "package-not-found",
    E,
    Family.SETUP,
    summary="A ROS package named by $(find) or package:// is found nowhere.",
    explanation="`$(find fishbot_description)` in a xacro file, and a mesh's "
    "`package://fishbot_description/...`, name a ROS package, which fishbot looks for without "
    "ROS: given by `--package NAME=PATH`, in the folders above the file (a `package.xml` with "
    "that `<name>`), in `ROS_PACKAGE_PATH` and `AMENT_PREFIX_PATH`, and in the colcon workspace "
    "around the file. The message lists every place searched. Name the package's folder with "
    "`--package`, or source the workspace that installs it; xacro fails the same way without it, "
    "and RViz cannot load a mesh from a package it cannot find.",
    bad="""\
fishbot check fishbot.urdf.xacro
""",
    good="""\
fishbot check fishbot.urdf.xacro --package fishbot_description=src/fishbot_description
""",
    consumers=(Consumer.XACRO, Consumer.URDFDOM),
    language="shell",
    fatal=True,
)
TOOL_MISSING = Rule(
    "tool-missing",
    E,
    Family.SETUP,
    summary="A program or Python package the job needs is not installed.",
    explanation="Some jobs need a program or a Python package that fishbot does not install "
    "itself: Graphviz's `dot` draws the PDF, SVG and PNG of `fishbot graph`, and the optional "
    "trimesh package computes the volume of a mesh. The message says what is missing and how to "
    "install it, and the command stops with exit status 2. DOT (`.gv`) and Mermaid (`.mmd`) "
    "drawings need no Graphviz.",
    bad="""\
# Graphviz is not installed
fishbot graph fishbot.urdf -o fishbot.png
""",
    good="""\
sudo apt install graphviz  # or: brew, winget or conda install graphviz
fishbot graph fishbot.urdf -o fishbot.png
""",
    consumers=(),
    language="shell",
    fatal=True,
)
CONVERSION = Rule(
    "conversion",
    E,
    Family.SETUP,
    summary="A robot cannot be converted to another format: its converter refuses it.",
    explanation="`fishbot sdf` writes what sdformat's own URDF converter writes, `<gazebo>` "
    "blocks included, and refuses what it refuses beyond what the reader does: links lumped "
    "over fixed joints that weigh 0 kg together (the converter divides by their mass), and a "
    "`<gazebo>` setting it reads as a number that is none, such as a xacro expression left "
    "in `<mu1>${mu}</mu1>` (the converter stops on it). The message names the link or the "
    "block at fault (and the line and column of a value at fault), nothing is written, and "
    "the command stops with exit status 1.",
    bad="""\
# gazebo.urdf: the arm, its <gazebo reference="upper_arm"> block with <mu1>${mu}</mu1>
fishbot sdf gazebo.urdf -o arm.sdf
""",
    good="""\
# arm.urdf: the same arm, the block with <mu1>0.8</mu1>
fishbot sdf arm.urdf -o arm.sdf
""",
    consumers=(Consumer.GAZEBO,),
    language="shell",
)
TOOL_FAILED = Rule(
    "tool-failed",
    E,
    Family.SETUP,
    summary="A program the job runs (Graphviz's dot) failed.",
    explanation="A program fishbot ran, Graphviz's `dot`, stopped with an error; the message "
    'gives the first line it printed, and the command stops with exit status 2. `Format: "png" '
    "not recognized` means Graphviz is installed but its output plugins are not registered, which "
    "`dot -c` does (as root, or as administrator on Windows).",
    bad="""\
# Graphviz is installed, its plugins are not registered
fishbot graph fishbot.urdf -o fishbot.png
""",
    good="""\
sudo dot -c
fishbot graph fishbot.urdf -o fishbot.png
""",
    consumers=(),
    language="shell",
    fatal=True,
)


@dataclass(frozen=True, slots=True, kw_only=True)
class FillFacts(Facts):
    """The facts of a `fill-skipped` finding."""

    reason: str
    """Why no inertial was added: the rule id of the error that stopped it (``no-mass``,
    ``mesh-not-found``, ...)."""


FILL_SKIPPED = Rule(
    "fill-skipped",
    E,
    Family.SETUP,
    summary="fishbot inertia --fill could not compute a link's inertial.",
    explanation="`fishbot inertia ROBOT --fill` computes an `<inertial>` for each link that has "
    "collision shapes and none. A link it cannot compute is left as it is, with this error: it "
    "has no `--mass` and there is no `--density`, its mesh is open (so it has no volume) or in a "
    "package not found, or trimesh is not installed for a mesh. The other links are filled (and "
    "written with `-o`, or what to write in them said without) all the same, and the exit status "
    "is 1. Give the link a mass, close the mesh, or "
    "name its package with `--package`.",
    bad="""\
fishbot inertia fishbot.urdf --fill -o filled.urdf --mass left_wheel_link=0.1
""",
    good="""\
fishbot inertia fishbot.urdf --fill -o filled.urdf \\
    --mass left_wheel_link=0.1 --mass right_wheel_link=0.1
""",
    consumers=(),
    language="shell",
)
UNUSED_SUPPRESSION = Rule(
    "unused-suppression",
    W,
    Family.LINT,
    summary="A fishbot: ignore[...] comment silences nothing, or names no rule.",
    explanation="A comment `<!-- fishbot: ignore[rule-id] -->` right before an element silences "
    "that rule's findings about the element and what it holds (right before `<robot>`, about the "
    "whole file). One that silences nothing is reported, so that such comments do not outlive the "
    "fault they hid, nor hide nothing because the id is misspelt, as below. Correct the id, move "
    "the comment right before the element the finding is about, or delete it.",
    bad="""\
<robot name="fishbot">
  <!-- fishbot: ignore[inertia-missmatch] -->
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.0017"/>
    </inertial>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <!-- fishbot: ignore[inertia-mismatch] -->
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.0017"/>
    </inertial>
  </link>
</robot>
""",
    consumers=(),
)
CONFIG = Rule(
    "config",
    E,
    Family.SETUP,
    summary="A configuration file or option is wrong (an unknown rule or key, a bad value).",
    explanation="`fishbot check` takes its settings from `[tool.fishbot]` in the nearest "
    "pyproject.toml, or from a fishbot.toml, above each checked file, and from its options. A key "
    "or rule id it does not know (a typo, as below), a value of the wrong type, or a rule that "
    "cannot be turned off because it stops the reading, make it stop before it checks anything, "
    "with exit status 2 and the file and line at fault. `fishbot rules` lists the rule ids and "
    "families.",
    bad="""\
# pyproject.toml, in the robot's folder or above it
[tool.fishbot]
ignore = ["inertia-missmatch"]
""",
    good="""\
# pyproject.toml, in the robot's folder or above it
[tool.fishbot]
ignore = ["inertia-mismatch"]
""",
    consumers=(),
    language="toml",
    fatal=True,
)
