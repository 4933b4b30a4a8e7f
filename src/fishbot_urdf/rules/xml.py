"""Rules for XML that urdfdom reads and strict XML parsers refuse (or read otherwise).

These are data only: ``fishbot_urdf.xmlrecover`` reads such files as urdfdom's TinyXML
does, and each rule it applied is one warning per file (at the first place).
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType

from ..diagnostics import Severity
from . import Consumer, Family, Rule

_STRICT = (Consumer.XACRO, Consumer.XML_TOOLS)
W = Severity.WARNING

XML_DECLARATION = Rule(
    "xml-declaration",
    W,
    Family.XML,
    summary="An XML declaration strict parsers refuse (a version other than 1.x, misplaced, "
    "twice, malformed), which urdfdom ignores.",
    consumers=_STRICT,
)
XML_UNDECLARED_PREFIX = Rule(
    "xml-undeclared-prefix",
    W,
    Family.XML,
    summary="A namespace prefix (drake:, gazebo:) used without an xmlns declaration.",
    consumers=_STRICT,
)
XML_DEFAULT_NAMESPACE = Rule(
    "xml-default-namespace",
    W,
    Family.XML,
    summary='xmlns="..." on <robot> puts the URDF elements in a namespace.',
    consumers=(Consumer.XML_TOOLS,),
)
XML_ENCODING = Rule(
    "xml-encoding",
    W,
    Family.XML,
    summary="Bytes that are not UTF-8, or an encoding declaration that does not fit the file.",
    consumers=_STRICT,
)
XML_ESCAPE = Rule(
    "xml-escape",
    W,
    Family.XML,
    summary="'&', '<' or ']]>' not escaped, or a reference to a character XML forbids.",
    consumers=_STRICT,
)
XML_ATTRIBUTE = Rule(
    "xml-attribute",
    W,
    Family.XML,
    summary="An attribute value without quotes, or not separated from the one before.",
    consumers=(*_STRICT, Consumer.URDFDOM),
)
XML_COMMENT = Rule(
    "xml-comment", W, Family.XML, summary="'--' inside a comment.", consumers=_STRICT
)
XML_CONTROL_CHAR = Rule(
    "xml-control-char",
    W,
    Family.XML,
    summary="A control character, or a form feed or vertical tab used as white space.",
    consumers=_STRICT,
)
XML_MARKUP = Rule(
    "xml-markup",
    W,
    Family.XML,
    summary="Markup that is not XML (urdfdom skips it), or a name XML cannot hold.",
    consumers=_STRICT,
)
XML_OUTSIDE_ROOT = Rule(
    "xml-outside-root",
    W,
    Family.XML,
    summary="Content after (or before) the <robot> element, which urdfdom ignores.",
    consumers=_STRICT,
)

BY_ID: Mapping[str, Rule] = MappingProxyType(
    {
        rule.id: rule
        for rule in (
            XML_DECLARATION,
            XML_UNDECLARED_PREFIX,
            XML_DEFAULT_NAMESPACE,
            XML_ENCODING,
            XML_ESCAPE,
            XML_ATTRIBUTE,
            XML_COMMENT,
            XML_CONTROL_CHAR,
            XML_MARKUP,
            XML_OUTSIDE_ROOT,
        )
    }
)
"""The rules of the XML recoveries, by id."""
