"""`fishbot_urdf.diagnostics`: a finding's line is one line, safe to print."""

from __future__ import annotations

import pytest

from fishbot_urdf.diagnostics import Severity, diagnostic, escape_controls


@pytest.mark.parametrize(
    ("text", "shown"),
    [
        ("plain base_link", "plain base_link"),
        ("a\nb", "a\\nb"),
        ("a\r\nb\tc", "a\\r\\nb\\tc"),
        ("\x1b[31mred\x1b[0m", "\\x1b[31mred\\x1b[0m"),
        ("\x00\x07\x7f", "\\x00\\x07\\x7f"),
        ("\x85\x9b", "\\x85\\x9b"),  # C1: NEL, CSI
        ("\u2028\u2029", "\\u2028\\u2029"),
        ("no-utf8-\udc9b-\udce9", "no-utf8-\\x9b-\udce9"),  # a C1 byte of a file name
        ("back\\nslash", "back\\nslash"),  # not a control character: left alone
        ("é ü 日本", "é ü 日本"),
    ],
)
def test_escape_controls(text: str, shown: str) -> None:
    assert escape_controls(text) == shown


def test_a_finding_is_one_line_whatever_its_path_and_message() -> None:
    finding = diagnostic(
        "io",
        Severity.ERROR,
        "no such file\n::error file=x::pwned",
        path="a\n::error file=x::pwned.urdf",
        line=3,
        column=1,
        hint="look \x1b]0;title\x07 here",
    )
    assert finding.format() == (
        "a\\n::error file=x::pwned.urdf:3:1: error: no such file\\n::error file=x::pwned "
        "(look \\x1b]0;title\\x07 here) [io]"
    )
    assert finding.format_with("a\rb") == (
        "a\\n::error file=x::pwned.urdf:3:1: error: no such file\\n::error file=x::pwned "
        "(a\\rb) [io]"
    )
    assert finding.message.count("\n") == 1  # the finding itself keeps its text
