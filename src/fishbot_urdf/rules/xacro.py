"""Rules for xacro input: what stops an expansion, and the warnings xacro gives.

These are data only; ``fishbot_urdf.expand`` raises them as XacroError and the reader
reports xacro's warnings.
"""

from __future__ import annotations

from ..diagnostics import Severity
from . import Consumer, Family, Rule

_XACRO = (Consumer.XACRO,)
E, W = Severity.ERROR, Severity.WARNING

XACRO_ERROR = Rule(
    "xacro-error",
    E,
    Family.XACRO,
    summary="xacro refuses the file (anything not covered by a more precise xacro rule).",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_INCLUDE = Rule(
    "xacro-include",
    E,
    Family.XACRO,
    summary="<xacro:include> names a file that cannot be read.",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_UNDEFINED = Rule(
    "xacro-undefined",
    E,
    Family.XACRO,
    summary="A property, macro, parameter or argument is used but not defined.",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_NAMESPACE = Rule(
    "xacro-namespace",
    E,
    Family.XACRO,
    summary="The xacro: prefix is used but not declared.",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_SYNTAX = Rule(
    "xacro-syntax",
    E,
    Family.XACRO,
    summary="A xacro file is not well-formed XML.",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_CIRCULAR = Rule(
    "xacro-circular",
    E,
    Family.XACRO,
    summary="Properties are defined in terms of each other, without end.",
    consumers=_XACRO,
    language="xacro",
    fatal=True,
)
XACRO_WARNING = Rule(
    "xacro-warning",
    W,
    Family.XACRO,
    summary="xacro warned while expanding the file (a deprecated form, say).",
    consumers=_XACRO,
    language="xacro",
)
