"""Rules for XML that urdfdom reads and strict XML parsers refuse (or read otherwise).

These are data only: ``fishbot_urdf.xml.recover`` reads such files as urdfdom's TinyXML
does, and each rule it applied is one warning per file (at the first place).
"""

from __future__ import annotations

from ..diagnostics import Consumer, Family, Rule, Severity

_STRICT = (Consumer.XACRO, Consumer.XML_TOOLS)
W = Severity.WARNING

XML_DECLARATION = Rule(
    "xml-declaration",
    W,
    Family.XML,
    summary="An XML declaration strict parsers refuse (a version other than 1.x, misplaced, "
    "twice, malformed), which urdfdom ignores.",
    explanation=(
        "urdfdom (check_urdf, robot_state_publisher) reads any `<?xml ...?>` it meets and "
        "ignores what it says, so a declaration with version 0.0, one after a blank line or a"
        " comment, or two of them pass there. XML allows one declaration, as the very first "
        "bytes of the file, with version 1.x: lxml and every Python tool built on it refuse "
        "such a file, and xacro refuses all but the wrong version. Keep one `<?xml "
        'version="1.0"?>` on the first line, or none.'
    ),
    bad="""\
<?xml version="0.0" ?>
<robot name="fishbot">
  <link name="base_link"/>
</robot>
""",
    good="""\
<?xml version="1.0"?>
<robot name="fishbot">
  <link name="base_link"/>
</robot>
""",
    consumers=_STRICT,
)
XML_UNDECLARED_PREFIX = Rule(
    "xml-undeclared-prefix",
    W,
    Family.XML,
    summary="A namespace prefix (drake:, gazebo:) used without an xmlns declaration.",
    explanation=(
        "urdfdom knows no namespaces, so `<drake:mu_static>` or `<sensor:camera>` is just an "
        "element it does not know. A namespace-aware parser (lxml, xacro's expat, Python URDF"
        " libraries) refuses a prefix that no `xmlns:` attribute declares. Declare it on "
        "`<robot>`; the URI is the one the tool that reads the element documents."
    ),
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <drake:mu_static value="0.8"/>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot" xmlns:drake="http://drake.mit.edu">
  <link name="base_link">
    <drake:mu_static value="0.8"/>
  </link>
</robot>
""",
    consumers=_STRICT,
)
XML_DEFAULT_NAMESPACE = Rule(
    "xml-default-namespace",
    W,
    Family.XML,
    summary='xmlns="..." on <robot> puts the URDF elements in a namespace.',
    explanation=(
        "urdfdom ignores namespaces and reads the elements by their names. A namespace-aware "
        "reader sees `{uri}robot` and `{uri}link` instead: lxml-based tools find no robot, or"
        ' a robot without links. URDF has no namespace of its own; leave `xmlns="..."` out.'
    ),
    bad="""\
<robot name="fishbot" xmlns="http://example.org/urdf">
  <link name="base_link"/>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
</robot>
""",
    consumers=(Consumer.XML_TOOLS,),
)
XML_ENCODING = Rule(
    "xml-encoding",
    W,
    Family.XML,
    summary="Bytes that are not UTF-8, or an encoding declaration that does not fit the file.",
    explanation=(
        "urdfdom reads bytes as they are and never looks at the encoding declaration, so "
        "names and text reach ROS as raw bytes. Strict parsers read the declaration: one that"
        " does not fit the file (ISO-8859-1 declared, the file UTF-8) garbles every non-ASCII"
        " character, bytes that are not UTF-8 without a declaration are refused, and xacro "
        "refuses non-UTF-8 files outright. Save the file as UTF-8 and declare UTF-8, or "
        "nothing."
    ),
    bad="""\
<?xml version="1.0" encoding="ISO-8859-1"?>
<robot name="fishbot">
  <!-- Réglages du châssis -->
  <link name="base_link"/>
</robot>
""",
    good="""\
<?xml version="1.0" encoding="UTF-8"?>
<robot name="fishbot">
  <!-- Réglages du châssis -->
  <link name="base_link"/>
</robot>
""",
    consumers=_STRICT,
)
XML_ESCAPE = Rule(
    "xml-escape",
    W,
    Family.XML,
    summary="An ampersand, a less-than sign or ]]> not escaped, or a reference to a "
    "character XML forbids.",
    explanation=(
        "In XML, `&` starts a reference and `<` starts a tag, so inside text and attribute "
        "values they must be written `&amp;` and `&lt;`. urdfdom lets a stray `&` through and"
        " drops it (`fish&chips` reads `fishchips`; `&foo;` reads `foo;`), and keeps `<` as "
        "written; lxml and xacro refuse the file. Escape them, and decide which name you "
        "meant: the escaped one is read with the `&`."
    ),
    bad="""\
<robot name="fishbot">
  <link name="base&amp_link"/>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
</robot>
""",
    consumers=_STRICT,
)
XML_ATTRIBUTE = Rule(
    "xml-attribute",
    W,
    Family.XML,
    summary="An attribute value without quotes, or not separated from the one before.",
    explanation=(
        "An attribute value in XML is quoted, and attributes are separated by white space. "
        "urdfdom's old parser reads an unquoted value up to the next space or `>`, and a "
        "value run into the next attribute; lxml, xacro and urdfdom 4 (ROS 2 Jazzy and later)"
        " refuse the file. Quote every value."
    ),
    bad="""\
<robot name="fishbot">
  <link name=base_link/>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
</robot>
""",
    consumers=(*_STRICT, Consumer.URDFDOM),
)
XML_COMMENT = Rule(
    "xml-comment",
    W,
    Family.XML,
    summary="Two dashes (--) inside a comment.",
    explanation=(
        "XML forbids `--` inside a comment (and a comment ending `--->`). urdfdom reads a "
        "comment up to the first `-->` whatever it holds; lxml and xacro refuse the file, and"
        " a reader that recovers from errors may drop the element after the comment. Use "
        "another mark than a double dash."
    ),
    bad="""\
<robot name="fishbot">
  <!-- base -- no inertia yet -->
  <link name="base_link"/>
</robot>
""",
    good="""\
<robot name="fishbot">
  <!-- base: no inertia yet -->
  <link name="base_link"/>
</robot>
""",
    consumers=_STRICT,
)
XML_CONTROL_CHAR = Rule(
    "xml-control-char",
    W,
    Family.XML,
    summary="A control character, or a form feed or vertical tab used as white space.",
    explanation=(
        "XML 1.0 allows no control character but tab, line feed and carriage return, not even"
        " written as `&#27;`, and a form feed or vertical tab is no white space to it. "
        "urdfdom keeps them (and reads a form feed between attributes as a space); lxml and "
        "xacro refuse the file. They usually come from copying terminal output or from an "
        "exporter: delete them."
    ),
    bad="""\
<robot name="fishbot">
  <!-- \x1b[1mbase\x1b[0m -->
  <link name="base_link"/>
</robot>
""",
    good="""\
<robot name="fishbot">
  <!-- base -->
  <link name="base_link"/>
</robot>
""",
    consumers=_STRICT,
)
XML_MARKUP = Rule(
    "xml-markup",
    W,
    Family.XML,
    summary="Markup that is not XML (urdfdom skips it), or a name XML cannot hold.",
    explanation=(
        "urdfdom skips a `<` followed by something that cannot start a name (`<1st/>`, "
        "`<!foo>`) up to the next `>`, and reads names XML cannot hold (`a:b:c`) as plain "
        "names. lxml and xacro refuse such a file. Remove the stray markup, or write it as a "
        "comment."
    ),
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <!todo>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <!-- todo -->
  </link>
</robot>
""",
    consumers=_STRICT,
)
XML_OUTSIDE_ROOT = Rule(
    "xml-outside-root",
    W,
    Family.XML,
    summary="Content after (or before) the <robot> element, which urdfdom ignores.",
    explanation=(
        "An XML file has one root element, here `<robot>`, and nothing but comments and white"
        " space around it. urdfdom reads the first `<robot>` and ignores what follows (text, "
        "a second robot, leftovers of an editor); lxml and xacro refuse the file, so a second"
        " robot pasted below the first is never what anyone reads. Delete what stands outside"
        " `<robot>`, or make it a comment."
    ),
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
</robot>
exported by the CAD plugin
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
</robot>
""",
    consumers=_STRICT,
)
