"""Rules for xacro input: what stops an expansion, and the warnings xacro gives.

These are data only; ``fishbot_urdf.expand`` raises them as XacroError and the reader
reports xacro's warnings.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..diagnostics import Consumer, Facts, Family, Rule, Severity

_XACRO = (Consumer.XACRO,)
E, W = Severity.ERROR, Severity.WARNING

XACRO_ERROR = Rule(
    "xacro-error",
    E,
    Family.XACRO,
    summary="xacro refuses the file (anything not covered by a more precise xacro rule).",
    explanation="xacro stopped for a reason no narrower xacro rule covers: a `${...}` expression "
    "Python cannot evaluate, a condition that is neither true nor false, a macro used in a way "
    "xacro does not allow. The message is xacro's own, placed at the element that caused it. "
    "Below, `<xacro:if>` gets `yes`, where xacro accepts only true, false or a whole number.",
    bad="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="use_laser" default="yes"/>
  <link name="base_link"/>
  <xacro:if value="$(arg use_laser)">
    <link name="laser_link"/>
    <joint name="laser_joint" type="fixed">
      <parent link="base_link"/><child link="laser_link"/>
    </joint>
  </xacro:if>
</robot>
""",
    good="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="use_laser" default="true"/>
  <link name="base_link"/>
  <xacro:if value="$(arg use_laser)">
    <link name="laser_link"/>
    <joint name="laser_joint" type="fixed">
      <parent link="base_link"/><child link="laser_link"/>
    </joint>
  </xacro:if>
</robot>
""",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
# A top file that includes its wheel macro by the name given.
_INCLUDING = """\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="{name}"/>
  <link name="base_link"/>
  <xacro:wheel side="left"/>
</robot>
"""

XACRO_INCLUDE = Rule(
    "xacro-include",
    E,
    Family.XACRO,
    summary="<xacro:include> names a file that cannot be read.",
    explanation='`<xacro:include filename="...">` reads another file: a relative name is looked '
    "up beside the file that includes it, and `$(find pkg)/...` in a ROS package. When the file "
    "does not exist or cannot be read, xacro stops with `No such file or directory`, and fishbot "
    "names the closest file in that folder. A path made from `$(arg ...)` is named with the "
    "arguments' values, and those left at their defaults (`none/none_none.xacro` from a top "
    "file run without its arguments) are the ones to give as `name:=value`, with the values "
    "that name files there. Correct the name, "
    "and use `$(find your_package)/urdf/...` for a file of another package.",
    bad=_INCLUDING.format(name="wheel_urdf.xacro"),
    good=_INCLUDING.format(name="wheel.urdf.xacro"),
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_UNDEFINED = Rule(
    "xacro-undefined",
    E,
    Family.XACRO,
    summary="A property, macro, parameter or argument is used but not defined.",
    explanation="xacro stops when a `${...}` expression uses a property that is not defined, a "
    "macro is called that is not defined or without a value for one of its parameters, or `$(arg "
    "...)` names an argument no `<xacro:arg>` declares. The cause is usually a typo, or a "
    "definition in a file that is not included; fishbot suggests the closest name defined, and "
    "names the macro calls that led there.",
    bad="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="wheel_radius" value="0.032"/>
  <link name="left_wheel_link">
    <visual>
      <geometry><cylinder radius="${wheel_radus}" length="0.04"/></geometry>
    </visual>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="wheel_radius" value="0.032"/>
  <link name="left_wheel_link">
    <visual>
      <geometry><cylinder radius="${wheel_radius}" length="0.04"/></geometry>
    </visual>
  </link>
</robot>
""",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)


@dataclass(frozen=True, slots=True, kw_only=True)
class UnknownArgFacts(Facts):
    """The facts of a `xacro-unknown-arg` finding."""

    argument: str
    """The ``name`` of the ``name:=value`` given."""


XACRO_UNKNOWN_ARG = Rule(
    "xacro-unknown-arg",
    W,
    Family.XACRO,
    summary="A name:=value argument names an argument the xacro files never declare.",
    explanation="xacro takes any `name:=value` and quietly ignores the ones no `<xacro:arg>` "
    "or `$(arg ...)` reads, so a misspelt argument leaves its default in place and the robot "
    "is built without the arm, the sensor or the simulation tags that were asked for. Spell the "
    "argument as the file declares it; `--strict` makes this an error for CI. `tf`, `render` "
    "and `view` warn too, and when the argument is named as a joint they say that `-j "
    "NAME=VALUE` places joints. A URDF file reads no arguments: every command warns of each "
    "one given with it (`check` only when none of the files it checks is a `.xacro` file, "
    "which takes them).",
    bad="""\
# fishbot.urdf.xacro declares <xacro:arg name="use_sim" default="false"/>
fishbot check --strict --package fishbot_description=src/fishbot_description \\
  fishbot.urdf.xacro use_simm:=true
""",
    good="""\
# fishbot.urdf.xacro declares <xacro:arg name="use_sim" default="false"/>
fishbot check --strict --package fishbot_description=src/fishbot_description \\
  fishbot.urdf.xacro use_sim:=true
""",
    consumers=_XACRO,
    language="shell",
)
XACRO_NAMESPACE = Rule(
    "xacro-namespace",
    E,
    Family.XACRO,
    summary="The xacro: prefix is used but not declared.",
    explanation="Every `xacro:` element needs the prefix declared on the root element, "
    '`xmlns:xacro="http://www.ros.org/wiki/xacro"`. Without it the file is not valid XML with '
    "namespaces, and xacro stops with `unbound prefix` before it expands anything. Add the "
    "declaration to `<robot>`.",
    bad="""\
<robot name="fishbot">
  <xacro:property name="wheel_radius" value="0.032"/>
  <link name="left_wheel_link">
    <visual>
      <geometry><cylinder radius="${wheel_radius}" length="0.04"/></geometry>
    </visual>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="wheel_radius" value="0.032"/>
  <link name="left_wheel_link">
    <visual>
      <geometry><cylinder radius="${wheel_radius}" length="0.04"/></geometry>
    </visual>
  </link>
</robot>
""",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_SYNTAX = Rule(
    "xacro-syntax",
    E,
    Family.XACRO,
    summary="A xacro file is not well-formed XML.",
    explanation="A xacro file must be well-formed XML before xacro can expand it: every element "
    "closed, every attribute value quoted, no bare `<` or `&` in a value (write `&lt;` and "
    "`&amp;`, even inside `${...}`). xacro stops with the XML parser's message, here `mismatched "
    "tag` because the `<xacro:property>` lacks its closing `/`. fishbot reports the file the "
    "mistake is in, an included one too; fix it there.",
    bad="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="wheel_radius" value="0.032">
  <link name="left_wheel_link">
    <visual>
      <geometry><cylinder radius="${wheel_radius}" length="0.04"/></geometry>
    </visual>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="wheel_radius" value="0.032"/>
  <link name="left_wheel_link">
    <visual>
      <geometry><cylinder radius="${wheel_radius}" length="0.04"/></geometry>
    </visual>
  </link>
</robot>
""",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_CIRCULAR = Rule(
    "xacro-circular",
    E,
    Family.XACRO,
    summary="Properties are defined in terms of each other, without end.",
    explanation="xacro works out a property's value when it is used, so a property may refer to "
    "one defined after it; but two properties defined in terms of each other never get a value. "
    "xacro stops with `circular variable definition`, and fishbot names the whole loop. Give one "
    "property of the loop a plain value.",
    bad="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="wheel_radius" value="${wheel_diameter / 2}"/>
  <xacro:property name="wheel_diameter" value="${2 * wheel_radius}"/>
  <link name="left_wheel_link">
    <visual>
      <geometry><cylinder radius="${wheel_radius}" length="0.04"/></geometry>
    </visual>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="wheel_radius" value="${wheel_diameter / 2}"/>
  <xacro:property name="wheel_diameter" value="0.064"/>
  <link name="left_wheel_link">
    <visual>
      <geometry><cylinder radius="${wheel_radius}" length="0.04"/></geometry>
    </visual>
  </link>
</robot>
""",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_WARNING = Rule(
    "xacro-warning",
    W,
    Family.XACRO,
    summary="xacro warned while expanding the file (a deprecated form, say).",
    explanation="xacro printed a warning while it expanded the file; fishbot reports it as a "
    "finding, so that it is not lost among other output. A common one is `redefining global "
    "symbol: pi`: xacro already knows `pi` (as Python's `math.pi`), and a property of that name "
    "replaces it, here with a less exact value that turns the wheel 0.0008 rad too little. Do "
    "what the warning says; here, delete the property.",
    bad="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="pi" value="3.14"/>
  <link name="left_wheel_link">
    <visual>
      <origin rpy="${pi / 2} 0 0"/>
      <geometry><cylinder radius="0.032" length="0.04"/></geometry>
    </visual>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="left_wheel_link">
    <visual>
      <origin rpy="${pi / 2} 0 0"/>
      <geometry><cylinder radius="0.032" length="0.04"/></geometry>
    </visual>
  </link>
</robot>
""",
    consumers=_XACRO,
    language="xacro",
)
XACRO_UNSAFE = Rule(
    "xacro-unsafe",
    E,
    Family.XACRO,
    summary="A xacro expression does what the expression allowlist does not allow.",
    explanation="A `${...}` or `$(eval ...)` expression is Python code, and ROS's xacro runs it "
    "with Python's `eval`: a robot file can read and write the files of whoever expands it. "
    "fishbot interprets every expression itself, by an allowlist: literals, properties and "
    "arguments, the operators, conditionals, subscripts, comprehensions, lambdas, the `math`, "
    "`python` and `xacro` functions xacro exposes (less `python.type` and `python.vars`), and "
    "listed methods of strings, lists, dicts, tuples, sets and numbers. An attribute or name "
    "that starts with `_`, `:=`, `str.format` with a field that reads an attribute or an item "
    "(`{0.x}`, `{0[k]}`), `format_map`, and any function not listed are refused, naming the "
    "construct. An expression that would build a value too large to be a robot's (a number of "
    "more than a million bits, a string, list or range of more than ten million items, twenty "
    "million in all, a factorial past 100,000) or take more than a million steps is stopped "
    "before it does. A file you trust that needs more of Python can be expanded with "
    "`--trust-expressions`, which runs its expressions as ROS's xacro does.",
    bad="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="prefix" value="left"/>
  <link name="${prefix.__class__.__name__}_wheel_link"/>
</robot>
""",
    good="""\
<robot name="fishbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="prefix" value="left"/>
  <link name="${prefix}_wheel_link"/>
</robot>
""",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_READ_OUTSIDE = Rule(
    "xacro-read-outside",
    E,
    Family.XACRO,
    summary="A xacro file reads a file outside the robot's tree and the folders allowed.",
    explanation="A xacro file names the files it reads, and one from a stranger can name "
    "`~/.ssh/id_rsa` as easily as `wheel.urdf.xacro`: ROS's xacro reads it, and the error it "
    "then gives (not XML, not YAML) can print its lines. Unless `--trust-expressions` is "
    "given, fishbot reads an include, the folders of an include pattern and a "
    "`xacro.load_yaml` file only inside the robot's tree (the git repository that holds the "
    "robot file, else its ROS package, else its folder), the packages `$(find)` finds, and "
    "the folders allowed by `--allow-read DIR` or `allow-read` in `[tool.fishbot]`, links "
    "resolved. The error names the file and the tree, never what the file holds. Name a "
    "file of another package with `$(find pkg)/...`, move the file into the tree, or allow "
    "its folder.",
    bad=_INCLUDING.format(name="../../common/wheel.urdf.xacro"),
    good=_INCLUDING.format(name="wheel.urdf.xacro"),
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
