"""The one warning each recovery rule gives: what is wrong, what urdfdom does, what strict
XML tools do with it and how to fix the file."""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass

from ...catalog import Rule
from ...catalog.xml import (
    XML_ATTRIBUTE,
    XML_COMMENT,
    XML_CONTROL_CHAR,
    XML_DECLARATION,
    XML_DEFAULT_NAMESPACE,
    XML_ENCODING,
    XML_ESCAPE,
    XML_MARKUP,
    XML_OUTSIDE_ROOT,
    XML_UNDECLARED_PREFIX,
)
from ._nodes import Note

# What strict tools do (measured: lxml 6.1, xacro 2.1.1 on expat, yourdfpy 0.0.60, which reads
# with lxml and falls back to lxml's recover mode when that fails).
_STRICT = (
    "lxml and xacro refuse the file, and yourdfpy falls back to lxml's recover mode, which may "
    "drop or garble content"
)


@dataclass(frozen=True, slots=True)
class Recovery:
    """One rule that had to be applied to read a file as urdfdom does.

    Attributes:
        rule: The rule (one of ``fishbot_urdf.catalog.xml``).
        offset: Byte offset of the first place it applies, in the original file.
        message: What is wrong and what urdfdom does with it.
        hint: What strict XML tools do with it and how to fix the file.
    """

    rule: Rule
    offset: int
    message: str
    hint: str


def summary(notes: list[Note], data: bytes) -> tuple[Recovery, ...]:
    """One Recovery per rule, at its first place, saying how many places there are."""
    by_rule: dict[Rule, list[Note]] = {}
    for note in sorted(notes, key=lambda n: n.offset):
        by_rule.setdefault(note.rule, []).append(note)
    found = []
    for rule, group in by_rule.items():
        message, hint = _describe(group[0], group, data)
        places = len({n.offset for n in group})
        if places > 1 and rule is not XML_UNDECLARED_PREFIX:
            message += f" (and {places - 1} more place{'s' if places > 2 else ''})"
        found.append(Recovery(rule, group[0].offset, message, hint))
    return tuple(sorted(found, key=lambda r: r.offset))


def _snippet(data: bytes, offset: int, end: bytes = b">") -> str:
    stop = data.find(end, offset)
    stop = len(data) if stop < 0 else stop + len(end)
    text = data[offset : min(stop, offset + 48)].decode("utf-8", "replace")
    return text.replace("\n", " ") + ("..." if stop > offset + 48 else "")


def _describe(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    """The message and hint of a rule's warning, from its first note."""
    return _DESCRIBE[first.rule](first, group, data)


def _declaration(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    kind = first.detail.partition(":")[0]
    at = first.offset
    written = _snippet(data, at)
    if kind == "malformed":
        version_only = re.fullmatch(
            r"<\?xml\s+version\s*=\s*([\"'])[^\"']*\1(\s+encoding\s*=\s*([\"'])[\w.-]+\3)?"
            r"(\s+standalone\s*=\s*([\"'])(yes|no)\5)?\s*\?>",
            written,
        )
        strict = "lxml refuses the file (xacro's expat accepts it)" if version_only else _STRICT
        return (
            f"the XML declaration {written} is not valid XML 1.0 (urdfdom ignores it)",
            f'{strict}: write <?xml version="1.0" encoding="UTF-8"?>',
        )
    where = "inside an element" if kind == "inside" else "after the start of the file"
    return (
        f"XML declaration {written} {where} (urdfdom ignores it)",
        f"{_STRICT}: a declaration goes first in the file, once, before any blank line "
        "or comment; move it there or delete it",
    )


def _undeclared_prefix(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    kind, _, arg = first.detail.partition(":")
    prefixes = sorted({n.detail.rpartition(":")[2] for n in group})
    names = ", ".join(f"{p}:" for p in prefixes)
    if kind == "empty":
        return (
            f'xmlns:{arg}="" declares no namespace; prefix {names} is used undeclared '
            "(urdfdom ignores namespaces)",
            f'{_STRICT}: give xmlns:{arg} a URI, e.g. xmlns:{arg}="http://example.org/{arg}"',
        )
    plural = "es" if len(prefixes) > 1 else ""
    return (
        f"prefix{plural} {names} used without an xmlns declaration (urdfdom ignores "
        f"namespaces: <{prefixes[0]}:...> is just an element it does not know)",
        f"{_STRICT}: declare it on <robot>, e.g. "
        f'xmlns:{prefixes[0]}="http://example.org/{prefixes[0]}"',
    )


def _default_namespace(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    detail = first.detail
    return (
        f'xmlns="{detail}" puts the URDF elements in a namespace (urdfdom ignores it)',
        "lxml sees {namespace}robot, and yourdfpy finds no <link>: delete it, URDF "
        "elements have no namespace",
    )


def _encoding(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    kind, _, arg = first.detail.partition(":")
    return _encoding_text(kind, arg, data, first.offset)


def _escape(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    kind = first.detail.partition(":")[0]
    at = first.offset
    if kind == "amp" and b"<!DOCTYPE" in data and re.match(rb"&[A-Za-z_][\w.-]*;", data[at:]):
        return (
            f"{_snippet(data, at, b';')} is an entity the file does not define: urdfdom drops "
            "the '&' and keeps the rest",
            "after a DOCTYPE, lxml and xacro read it as nothing, without an error: write "
            "&amp; for '&'",
        )
    return {
        "amp": (
            "'&' that starts no reference XML knows (&amp; &lt; &gt; &quot; &apos; &#N;): "
            "urdfdom drops the '&' and keeps the rest (&foo; reads foo;)",
            f"{_STRICT}: write &amp; for '&'",
        ),
        "lt": (
            "'<' inside an attribute value (urdfdom keeps it)",
            f"{_STRICT}: write &lt; for '<'",
        ),
        "brackets": ("']]>' in text (urdfdom keeps it)", f"{_STRICT}: write ]]&gt;"),
        "charref": (
            f"{_snippet(data, at, b';')} refers to a character XML forbids (urdfdom "
            "stores it; &#0; ends the value)",
            f"{_STRICT}: delete it",
        ),
    }[kind]


def _attribute(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    kind = first.detail.partition(":")[0]
    at = first.offset
    if kind == "unquoted":
        value = re.match(rb"[^\s/>]*", data[at:])
        assert value is not None
        return (
            f"attribute value without quotes: {value[0].decode('utf-8', 'replace')} "
            "(urdfdom reads it up to the next space, '/' or '>', with no references replaced)",
            f'{_STRICT}: quote it: name="value"',
        )
    return (
        f"no white space before attribute {_snippet(data, at, b'=')} (urdfdom reads it)",
        f"{_STRICT}: put a space between attributes",
    )


def _comment(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    return (
        "'--' inside a comment (urdfdom reads a comment up to the first '-->')",
        f"{_STRICT}: XML forbids '--' in comments; remove the extra dashes",
    )


def _control_char(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    kind = first.detail.partition(":")[0]
    at = first.offset
    if kind == "control":
        what = f"control character 0x{data[at]:02X} (urdfdom keeps it)"
    elif kind == "space":
        name = "form feed" if data[at] == 12 else "vertical tab"
        what = f"{name} used as white space (urdfdom takes it for a space)"
    else:
        character = "FFFE" if data[at + 2] == 0xBE else "FFFF"
        what = f"U+{character}, not a character (urdfdom skips it as white space or keeps it)"
    return (what, f"{_STRICT}: XML 1.0 forbids it; delete it")


def _markup(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    kind, _, arg = first.detail.partition(":")
    at = first.offset
    if kind == "name":
        return (
            f"{arg!r} is not a name XML allows (urdfdom reads it; kept here with dots "
            "for the bad characters)",
            f"{_STRICT}: rename it",
        )
    what = "malformed DOCTYPE" if kind == "doctype" else f"{_snippet(data, at)} is not XML"
    return (f"{what} (urdfdom skips it up to its first '>')", f"{_STRICT}: delete it")


def _outside_root(first: Note, group: list[Note], data: bytes) -> tuple[str, str]:
    kind = first.detail.partition(":")[0]
    at = first.offset
    if kind == "nul":
        return (
            "NUL byte: urdfdom reads nothing after it",
            f"{_STRICT}: delete it and whatever follows it",
        )
    second = kind == "element" and data.startswith(b"<robot", at)
    what = {
        "element": "a second <robot>" if second else f"{_snippet(data, at)} outside <robot>",
        "text": "text after the <robot> element",
        "comment": "unclosed comment after the <robot> element",
        "markup": f"{_snippet(data, at)} outside the <robot> element",
    }[kind]
    return (
        f"{what} (urdfdom reads the first top-level <robot> only and ignores the rest)",
        f"{_STRICT}: an XML file holds one root element; delete it",
    )


def _encoding_text(kind: str, arg: str, data: bytes, at: int) -> tuple[str, str]:
    if kind == "invalid":
        byte = arg.rpartition(":")[2]
        char = bytes([int(byte, 16)]).decode("latin-1")
        return (
            f"byte 0x{byte} is not UTF-8 (urdfdom keeps the raw byte; read here as "
            f"ISO-8859-1 {char!r})",
            f"{_STRICT}: save the file as UTF-8",
        )
    if kind == "declared":
        return (
            f"the file is {arg}, not UTF-8: urdfdom does not convert it, so non-ASCII "
            f"names reach ROS as {arg} bytes",
            f"xacro refuses non-UTF-8 files: convert it (iconv -f {arg} -t UTF-8) and declare "
            'encoding="UTF-8"',
        )
    if kind == "mislabelled":
        return (
            f"the declaration says {arg} but the file is UTF-8 (urdfdom reads the UTF-8 "
            "bytes as they are)",
            f"lxml (and yourdfpy) decode it as {arg} and garble non-ASCII names; xacro reads it "
            'as UTF-8: declare encoding="UTF-8"',
        )
    if kind == "label":
        wide = arg.lower().replace("_", "-").startswith(("utf-16", "utf-32", "ucs"))
        what = "but the file is not in it" if wide else "a name lxml does not know"
        return (
            f'declared encoding "{arg}", {what} (urdfdom ignores the name)',
            'lxml refuses the file: declare encoding="UTF-8" and save the file as UTF-8',
        )
    if kind == "bom":
        return (
            "byte-order mark after the start of the file (urdfdom skips it as white space)",
            f"{_STRICT}: delete it",
        )
    assert kind == "charref", kind
    reference = _snippet(data, at, b";")
    return (
        f"{reference} in a file urdfdom reads byte by byte (no UTF-8 declaration): urdfdom "
        "stores a single byte for it, not UTF-8",
        'declare <?xml version="1.0" encoding="UTF-8"?> first, or write the character itself',
    )


_DESCRIBE: dict[Rule, Callable[[Note, list[Note], bytes], tuple[str, str]]] = {
    XML_DECLARATION: _declaration,
    XML_UNDECLARED_PREFIX: _undeclared_prefix,
    XML_DEFAULT_NAMESPACE: _default_namespace,
    XML_ENCODING: _encoding,
    XML_ESCAPE: _escape,
    XML_ATTRIBUTE: _attribute,
    XML_COMMENT: _comment,
    XML_CONTROL_CHAR: _control_char,
    XML_MARKUP: _markup,
    XML_OUTSIDE_ROOT: _outside_root,
}
