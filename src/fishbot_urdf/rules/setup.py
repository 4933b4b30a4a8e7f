"""Rules about what surrounds a robot: files, programs, packages, and this tool's own
suppression comments.

These are data only; errors of the setup stop a command with exit status 2.
"""

from __future__ import annotations

from ..diagnostics import Severity
from . import Consumer, Family, Rule

E, W = Severity.ERROR, Severity.WARNING

IO = Rule(
    "io",
    E,
    Family.SETUP,
    summary="A file cannot be read or written.",
    consumers=(),
    language="shell",
    fatal=True,
)
PACKAGE_NOT_FOUND = Rule(
    "package-not-found",
    E,
    Family.SETUP,
    summary="A ROS package named by $(find) or package:// is found nowhere.",
    consumers=(Consumer.XACRO, Consumer.URDFDOM),
    language="shell",
    fatal=True,
)
TOOL_MISSING = Rule(
    "tool-missing",
    E,
    Family.SETUP,
    summary="A program or Python package the job needs is not installed.",
    consumers=(),
    language="shell",
    fatal=True,
)
TOOL_FAILED = Rule(
    "tool-failed",
    E,
    Family.SETUP,
    summary="A program the job runs (Graphviz's dot) failed.",
    consumers=(),
    language="shell",
    fatal=True,
)
FILL_SKIPPED = Rule(
    "fill-skipped",
    E,
    Family.SETUP,
    summary="fishbot inertia --fill could not compute a link's inertial.",
    consumers=(),
    language="shell",
)
UNUSED_SUPPRESSION = Rule(
    "unused-suppression",
    W,
    Family.LINT,
    summary="A fishbot: ignore[...] comment silences nothing, or names no rule.",
    consumers=(),
)
CONFIG = Rule(
    "config",
    E,
    Family.SETUP,
    summary="A configuration file or option is wrong (an unknown rule or key, a bad value).",
    consumers=(),
    language="toml",
    fatal=True,
)
