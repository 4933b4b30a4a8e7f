"""Findings and their fixes as the protocol writes them: ranges in UTF-16 code units, the
finding of a macro at its call, quick fixes."""

from __future__ import annotations

import asyncio
import os

import pytest

pytest.importorskip("pygls")

from lsprotocol import types

from fishbot_urdf.diagnostics import Diagnostic, Edit, Fix, Severity
from fishbot_urdf.location import Location
from fishbot_urdf.lsp._convert import (
    Lines,
    Shown,
    code_actions,
    shown_findings,
    to_range,
    uri_of,
)

# "😀" is 1 character, 2 UTF-16 code units, 4 UTF-8 bytes
TEXT = '<robot name="r">\n  <link name="😀x"/>\n  <joint name="j" type="fixed">\n</robot>\n'


def _p(line: int, character: int) -> types.Position:
    return types.Position(line, character)


def test_a_range_counts_utf16_code_units() -> None:
    lines = Lines.of(TEXT)
    # the name's value: characters 14 to 16 of line 2 (1-based, end exclusive: "😀x")
    assert to_range(lines, 2, 15, 2, 17) == types.Range(_p(1, 14), _p(1, 17))
    # no end: the tag from its '<' to its '>'
    assert to_range(lines, 2, 3) == types.Range(_p(1, 2), _p(1, 20))
    # no end, inside a tag: the word
    assert to_range(lines, 3, 10) == types.Range(_p(2, 9), _p(2, 13))
    # no column: the line, from its first character; no line: the first line
    assert to_range(lines, 3, None) == types.Range(_p(2, 2), _p(2, 31))
    assert to_range(lines, None, None) == types.Range(_p(0, 0), _p(0, 16))
    # past the end of the text: the start of the line after
    assert to_range(lines, 9, 4) == types.Range(_p(8, 0), _p(8, 0))


def test_a_lone_cr_ends_a_line_of_the_protocol_not_of_the_reader() -> None:
    # the reader (libxml2) counts lines at LF only; the protocol at CR LF, CR and LF
    lines = Lines.of("<a>\r<b/>\r\n <c/>\n<d/>\r<e/>")
    assert [lines.line(i) for i in range(4)] == ["<a>\r<b/>", " <c/>", "<d/>\r<e/>", ""]
    assert lines.position(1, 5) == _p(1, 0)  # <b/>, after the lone CR
    assert to_range(lines, 1, 5) == types.Range(_p(1, 0), _p(1, 4))
    assert to_range(lines, 2, 2) == types.Range(_p(2, 1), _p(2, 5))
    assert lines.position(3, 6) == _p(4, 0)  # <e/>
    assert lines.position(5, 1) == _p(6, 0)  # past the end


def test_a_clients_position_back_to_a_line_and_character_column() -> None:
    lines = Lines.of(TEXT)
    assert lines.place(_p(1, 14)) == (2, 15)  # the emoji
    assert lines.place(_p(1, 15)) == (2, 15)  # inside it: its start
    assert lines.place(_p(1, 16)) == (2, 16)  # x
    assert lines.place(_p(1, 99)) == (2, 20)  # past the end: the line's end
    assert lines.place(_p(9, 3)) == (10, 1)
    crs = Lines.of("<a>\r<b/>\r\n <c/>\n<d/>\r<e/>")
    for line, column in [(1, 1), (1, 5), (1, 7), (2, 2), (3, 1), (3, 6), (3, 8)]:
        assert crs.place(crs.position(line, column)) == (line, column)
    assert crs.place(_p(6, 0)) == (5, 1)  # past the end


def test_a_range_in_utf8_or_utf32_when_the_client_chose_them() -> None:
    utf8 = Lines.of(TEXT, lambda s: len(s.encode("utf-8")))
    utf32 = Lines.of(TEXT, len)
    assert to_range(utf8, 2, 15, 2, 17) == types.Range(_p(1, 14), _p(1, 19))
    assert to_range(utf32, 2, 15, 2, 17) == types.Range(_p(1, 14), _p(1, 16))


def _finding(tmp: str, **fields: object) -> Diagnostic:
    return Diagnostic(
        "undefined-link",
        Severity.ERROR,
        "joint 'j': parent link 'bse' is not defined",
        os.path.join(tmp, "part.xacro"),
        2,
        5,
        hint="did you mean 'base'?",
        **fields,  # type: ignore[arg-type]
    )


def test_a_finding_in_a_macro_is_shown_at_its_outermost_call_in_another_file(tmp_path) -> None:
    part, top = str(tmp_path / "part.xacro"), str(tmp_path / "top.xacro")
    calls = (
        ("inner", Location(part, 9, 3)),  # a call inside the macro's own file
        ("outer", Location(top, 4, 3)),
    )
    finding = _finding(str(tmp_path), calls=calls)
    texts = {part: "\n    <parent link='bse'/>\n", top: "a\nb\nc\n  <xacro:outer/>\n"}
    shown = shown_findings([finding], top, lambda p: Lines.of(texts.get(p, "")))
    assert sorted(shown) == sorted([part, top])
    (here,), (there,) = shown[part], shown[top]
    assert here.diagnostic.range == types.Range(_p(1, 4), _p(1, 24))
    assert here.diagnostic.message == f"{finding.message} ({finding.hint})"
    assert here.diagnostic.code == "undefined-link"
    assert here.diagnostic.source == "fishbot"
    assert here.diagnostic.severity == types.DiagnosticSeverity.Error
    assert there.at_call and not here.at_call
    assert there.diagnostic.range == types.Range(_p(3, 2), _p(3, 16))
    assert there.diagnostic.message == f"in macro outer: {here.diagnostic.message}"
    (to_call,) = here.diagnostic.related_information or []
    (to_finding,) = there.diagnostic.related_information or []
    assert to_call.location == types.Location(uri_of(top), there.diagnostic.range)
    assert to_finding.location == types.Location(uri_of(part), here.diagnostic.range)


def test_a_call_written_over_two_lines_is_shown_over_both(tmp_path) -> None:
    part, top = str(tmp_path / "part.xacro"), str(tmp_path / "top.xacro")
    finding = _finding(str(tmp_path), calls=(("wheel", Location(top, 2, 3)),))
    texts = {
        part: "\n    <parent link='bse'/>\n",
        top: 'a\n  <xacro:wheel name="left"\n    side="1"/>\n',
    }
    shown = shown_findings([finding], top, lambda p: Lines.of(texts.get(p, "")))
    (there,) = shown[top]
    # from "<xacro:wheel" to just past "/>" on the next line
    assert there.diagnostic.range == types.Range(_p(1, 2), _p(2, 14))


def test_fixes_are_quick_fixes_the_safe_one_preferred(tmp_path) -> None:
    path = str(tmp_path / "part.xacro")
    text = "\n  <parent link='😀bse'/>\n"
    guess = Fix("replace '😀bse' with 'base'", (Edit(path, 2, 17, 2, 21, "base"),), safe=False)
    exact = Fix(
        "replace 'bse' with 'base', twice",
        (Edit(path, 2, 18, 2, 21, "base"), Edit(path, 1, 1, 1, 1, "<!-- -->")),
    )
    finding = _finding(str(tmp_path), fixes=(guess, exact))
    lines = Lines.of(text)
    shown = Shown(types.Diagnostic(to_range(lines, 2, 3), "m"), finding)
    first, second = code_actions(shown, lambda p: lines)
    assert (first.title, second.title) == (guess.title, exact.title)
    assert first.kind == second.kind == types.CodeActionKind.QuickFix
    assert (first.is_preferred, second.is_preferred) == (None, True)
    assert first.diagnostics == [shown.diagnostic]
    assert second.edit == types.WorkspaceEdit(
        changes={
            uri_of(path): [
                # after "😀" (2 code units): characters 17 to 20 are code units 18 to 21
                types.TextEdit(types.Range(_p(1, 18), _p(1, 21)), "base"),
                types.TextEdit(types.Range(_p(0, 0), _p(0, 0)), "<!-- -->"),
            ]
        }
    )
    assert first.edit is not None and first.edit.changes is not None
    assert first.edit.changes[uri_of(path)] == [
        types.TextEdit(types.Range(_p(1, 16), _p(1, 21)), "base")
    ]


def test_hover_providers_each_say_their_part_in_order(tmp_path) -> None:
    from fishbot_urdf.catalog import get
    from fishbot_urdf.catalog.docs import markdown_explanation
    from fishbot_urdf.lsp._hover import Hovers

    finding = _finding(str(tmp_path), definition=get("undefined-link"))
    shown = Shown(types.Diagnostic(types.Range(_p(1, 4), _p(1, 9)), "the message"), finding)

    class Findings:  # what the hover asks of a session
        def findings_at(self, path: str, position: types.Position) -> list[Shown]:
            return [shown] if position.line == 1 else []

    hovers = Hovers()
    hovers.add(lambda session, path, position: f"a name at {position.line}:{position.character}")
    hovers.add(lambda session, path, position: None)  # says nothing
    said = asyncio.run(hovers.hover(Findings(), "robot.urdf", _p(1, 5)))  # type: ignore[arg-type]
    assert said is not None and isinstance(said.contents, types.MarkupContent)
    rule = markdown_explanation(get("undefined-link")).strip()
    assert said.contents.value == f"**the message**\n\n{rule}\n\n---\n\na name at 1:5"
    elsewhere = asyncio.run(hovers.hover(Findings(), "robot.urdf", _p(4, 0)))  # type: ignore[arg-type]
    assert elsewhere is not None and elsewhere.contents.value == "a name at 4:0"  # type: ignore[union-attr]
