"""`fishbot lsp`'s navigation, driven over standard input and output as an editor drives it:
definitions, references, rename, completion, hover over a name and the document's symbols
across the fishbot's files, found through `$(find fishbot_description)`."""

from __future__ import annotations

import asyncio
import re
import shutil
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path

import pytest
from conftest import FISHBOT, ROOT
from lsp_client import Client, running
from lsprotocol import types
from pygls.exceptions import JsonRpcException

from fishbot_urdf.catalog import ids
from fishbot_urdf.lint import check_file

pytestmark = pytest.mark.asyncio

URDF = Path("urdf") / "fishbot"


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """A copy of the fishbot_description package, alone in a folder."""
    copy = tmp_path / "packages" / "fishbot_description"
    shutil.copytree(FISHBOT, copy)
    return copy


def _files(package: Path) -> list[Path]:
    return sorted((package / URDF).rglob("*.xacro"))


def _position(text: str, needle: str, into: int = 0, nth: int = 0) -> types.Position:
    """The position ``into`` characters into the ``nth`` occurrence of ``needle`` (the texts
    are ASCII: a character is a UTF-16 unit)."""
    offset = -1
    for _ in range(nth + 1):
        offset = text.index(needle, offset + 1)
    offset += into
    return types.Position(text.count("\n", 0, offset), offset - text.rfind("\n", 0, offset) - 1)


def _at(path: Path, needle: str, into: int = 0, nth: int = 0) -> types.Position:
    return _position(path.read_text(encoding="utf-8"), needle, into, nth)


def _location(path: Path, needle: str, name: str, text: str | None = None) -> types.Location:
    """Where ``name`` is written inside ``needle`` in ``path``."""
    text = path.read_text(encoding="utf-8") if text is None else text
    start = _position(text, needle, needle.index(name))
    end = types.Position(start.line, start.character + len(name))
    return types.Location(path.as_uri(), types.Range(start, end))


def _doc(path: Path) -> types.TextDocumentIdentifier:
    return types.TextDocumentIdentifier(path.as_uri())


async def _definition(client: Client, path: Path, where: types.Position) -> list[types.Location]:
    found = await client.text_document_definition_async(types.DefinitionParams(_doc(path), where))
    assert isinstance(found, list)
    return found  # type: ignore[return-value]


async def _completion(client: Client, path: Path, where: types.Position) -> set[str]:
    found = await client.text_document_completion_async(types.CompletionParams(_doc(path), where))
    items = found.items if isinstance(found, types.CompletionList) else found or []
    return {item.label for item in items}


async def _hover(client: Client, path: Path, where: types.Position) -> str:
    said = await client.text_document_hover_async(types.HoverParams(_doc(path), where))
    assert said is not None and isinstance(said.contents, types.MarkupContent)
    return said.contents.value


async def _symbols(client: Client, path: Path) -> list[types.DocumentSymbol]:
    found = await client.text_document_document_symbol_async(types.DocumentSymbolParams(_doc(path)))
    assert found is not None
    assert all(isinstance(s, types.DocumentSymbol) for s in found)
    return found  # type: ignore[return-value]


def _applied(text: str, edits: Sequence[types.TextEdit]) -> str:
    """``text`` with ``edits`` made, the last first."""
    lines = text.split("\n")
    for edit in sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character))[::-1]:
        start, end = edit.range.start, edit.range.end
        assert start.line == end.line
        line = lines[start.line]
        lines[start.line] = line[: start.character] + edit.new_text + line[end.character :]
    return "\n".join(lines)


def _check(top: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "fishbot_urdf", "check", str(top)],
        capture_output=True,
        text=True,
        env={"PYTHONPATH": str(ROOT / "src"), "PATH": ""},
        cwd=top.parent,
    )


async def test_a_link_used_in_an_included_file_goes_to_its_definition(
    package: Path, tmp_path: Path
) -> None:
    caster, base = (
        package / URDF / "actuator" / "caster.urdf.xacro",
        package / URDF / "base.urdf.xacro",
    )
    async with running(tmp_path) as client:
        client.open(caster)
        used = _at(caster, '<parent link="base_link"/>', len('<parent link="') + 3)
        found = await _definition(client, caster, used)
        assert found == [_location(base, '<link name="base_link">', "base_link")]


async def test_the_references_of_a_link_across_files(package: Path, tmp_path: Path) -> None:
    base = package / URDF / "base.urdf.xacro"
    plugin = package / URDF / "plugins" / "gazebo_control_plugin.xacro"
    texts = [path.read_text(encoding="utf-8") for path in _files(package)]
    async with running(tmp_path) as client:
        client.open(base)
        where = _at(base, '<link name="base_link">', len('<link name="'))
        for declaration in (True, False):
            found = await client.text_document_references_async(
                types.ReferenceParams(
                    context=types.ReferenceContext(include_declaration=declaration),
                    text_document=_doc(base),
                    position=where,
                )
            )
            assert found is not None
            # each joint's parent or child, the <gazebo reference>, and the link itself
            ends = sum(text.count(' link="base_link"/>') for text in texts)
            assert len(found) == ends + 1 + declaration
            gazebo = _location(base, '<gazebo reference="base_link">', "base_link")
            assert gazebo in found
            link = _location(base, '<link name="base_link">', "base_link")
            assert (link in found) == declaration
        # a frame a Gazebo plugin names, in another file
        footprint = _at(base, '<link name="base_footprint"/>', len('<link name="'))
        found = await client.text_document_references_async(
            types.ReferenceParams(
                context=types.ReferenceContext(include_declaration=True),
                text_document=_doc(base),
                position=footprint,
            )
        )
        frame = "<robot_base_frame>base_footprint</robot_base_frame>"
        assert found is not None and _location(plugin, frame, "base_footprint") in found


async def test_a_macro_call_a_property_and_an_include_go_to_their_definitions(
    package: Path, tmp_path: Path
) -> None:
    top = package / URDF / "fishbot.urdf.xacro"
    wheel = package / URDF / "actuator" / "wheel.urdf.xacro"
    async with running(tmp_path) as client:
        client.open(top)
        call = await _definition(client, top, _at(top, "<xacro:wheel_xacro", len("<xacro:") + 2))
        assert call == [_location(wheel, '<xacro:macro name="wheel_xacro"', "wheel_xacro")]
        used = _at(top, 'mass="${wheel_mass}"', len('mass="${') + 1)
        assert await _definition(client, top, used) == [
            _location(top, '<xacro:property name="wheel_mass"', "wheel_mass")
        ]
        include = _at(top, "$(find fishbot_description)/urdf/fishbot/common_inertia", 3)
        start = types.Position(0, 0)
        assert await _definition(client, top, include) == [
            types.Location(
                (package / URDF / "common_inertia.xacro").as_uri(), types.Range(start, start)
            )
        ]


async def test_renaming_a_link_across_files_keeps_the_robot_clean(
    package: Path, tmp_path: Path
) -> None:
    caster, top = (
        package / URDF / "actuator" / "caster.urdf.xacro",
        package / URDF / "fishbot.urdf.xacro",
    )
    before = _check(top)
    assert before.returncode == 0 and "base_link" in before.stdout
    async with running(tmp_path) as client:
        client.open(caster)
        where = _at(caster, '<parent link="base_link"/>', len('<parent link="') + 1)
        name = await client.text_document_prepare_rename_async(
            types.PrepareRenameParams(_doc(caster), where)
        )
        assert name == _location(caster, '<parent link="base_link"/>', "base_link").range
        edit = await client.text_document_rename_async(
            types.RenameParams(_doc(caster), where, "chassis_link")
        )
        assert edit is not None and edit.changes is not None
        assert len(edit.changes) > 1  # across files
        for uri, edits in edit.changes.items():
            path = Path(uri.removeprefix("file://"))
            assert path.is_relative_to(package)
            text = path.read_text(encoding="utf-8")
            for change in edits:
                start, end = change.range.start, change.range.end
                assert text.split("\n")[start.line][start.character : end.character] == "base_link"
            path.write_text(_applied(text, edits), encoding="utf-8")
    after = _check(top)
    assert after.returncode == 0
    assert after.stdout == before.stdout.replace("base_link", "chassis_link")
    for path in _files(package):
        assert not re.search(r"[\">]base_link[\"<]", path.read_text(encoding="utf-8"))


async def test_a_name_built_by_an_expression_is_not_renamed_and_the_client_is_told_why(
    package: Path, tmp_path: Path
) -> None:
    caster = package / URDF / "actuator" / "caster.urdf.xacro"
    async with running(tmp_path) as client:
        client.open(caster)
        where = _at(caster, '<link name="${name}_caster_link">', len('<link name="${name}_c'))
        with pytest.raises(JsonRpcException, match="builds several names") as refused:
            await client.text_document_prepare_rename_async(
                types.PrepareRenameParams(_doc(caster), where)
            )
        assert refused.value.code == types.LSPErrorCodes.RequestFailed
        nothing = await client.text_document_prepare_rename_async(
            types.PrepareRenameParams(_doc(caster), types.Position(0, 0))
        )
        assert nothing is None  # no name there
        with pytest.raises(JsonRpcException, match="builds several names") as raised:
            await client.text_document_rename_async(
                types.RenameParams(_doc(caster), where, "ball_link")
            )
        assert raised.value.code == types.LSPErrorCodes.RequestFailed
        # the server is still there
        assert await _definition(client, caster, where)


async def test_completion(package: Path, tmp_path: Path) -> None:
    top, caster = (
        package / URDF / "fishbot.urdf.xacro",
        package / URDF / "actuator" / "caster.urdf.xacro",
    )
    result = check_file(top)
    assert result.robot is not None
    texts = "".join(path.read_text(encoding="utf-8") for path in _files(package))
    async with running(tmp_path) as client:
        client.open(caster)
        links = await _completion(
            client, caster, _at(caster, '<parent link="base_link"/>', len('<parent link="'))
        )
        assert links == {link.name for link in result.robot.links}
        uri = client.open(top)
        macros = await _completion(client, top, _at(top, "<xacro:wheel_xacro", len("<xacro:")))
        assert set(re.findall(r'<xacro:macro name="(\w+)"', texts)) <= macros
        properties = await _completion(client, top, _at(top, "${wheel_radius}", 2))
        written = set(re.findall(r'<xacro:property name="(\w+)"', top.read_text(encoding="utf-8")))
        assert written <= properties
        # in a suppression comment, the rules' ids
        text = top.read_text(encoding="utf-8")
        edited = text.replace("<robot ", "<!-- fishbot: ignore[ -->\n<robot ", 1)
        client.change(uri, 2, edited)
        rules = await _completion(client, top, _position(edited, "ignore[", len("ignore[")))
        assert rules == set(ids())


async def test_hover_over_a_property_and_a_link(package: Path, tmp_path: Path) -> None:
    top, base = package / URDF / "fishbot.urdf.xacro", package / URDF / "base.urdf.xacro"
    values = dict(
        re.findall(r'<xacro:property name="(\w+)" value="([^"]*)"/>', top.read_text("utf-8"))
    )
    async with running(tmp_path) as client:
        client.open(top)
        said = await _hover(client, top, _at(top, "${wheel_radius}", 3))
        assert f"\n{values['wheel_radius']}\n" in said
        client.open(base)
        said = await _hover(client, base, _at(base, '<link name="base_link">', len('<link name="')))
        assert f"mass: {float(values['base_mass']):.6g} kg" in said
        # nothing where nothing is named
        nothing = await client.text_document_hover_async(
            types.HoverParams(_doc(base), types.Position(0, 0))
        )
        assert nothing is None


async def test_the_symbols_of_a_file_of_macros(package: Path, tmp_path: Path) -> None:
    base = package / URDF / "base.urdf.xacro"
    text = base.read_text(encoding="utf-8")
    async with running(tmp_path) as client:
        client.open(base)
        (macro,) = await _symbols(client, base)
        assert (macro.name, macro.kind) == ("base_xacro", types.SymbolKind.Function)
        assert (
            macro.selection_range == _location(base, 'macro name="base_xacro"', "base_xacro").range
        )
        kinds = {"link": types.SymbolKind.Class, "joint": types.SymbolKind.Interface}
        written = [(m[2], kinds[m[1]]) for m in re.finditer(r'<(link|joint) name="(\w+)"', text)]
        assert [(s.name, s.kind) for s in macro.children or ()] == written
        link = next(s for s in macro.children or () if s.name == "base_link")
        assert link.selection_range == _location(base, '<link name="base_link">', "base_link").range


async def test_a_broken_edit_still_answers_and_the_server_stays(
    package: Path, tmp_path: Path
) -> None:
    base = package / URDF / "base.urdf.xacro"
    text = base.read_text(encoding="utf-8")
    async with running(tmp_path) as client:
        uri = client.open(base)
        broken = text[: text.index('<child link="base_link"/>') + len('<child link="base_')]
        client.change(uri, 2, broken)
        end = _position(broken + "\n", "\n", 0, broken.count("\n"))
        await _definition(client, base, _position(broken, "base_footprint", 2))
        links = await _completion(client, base, end)  # in <child link="base_
        assert {"base_footprint"} <= links
        (macro,) = await _symbols(client, base)
        assert macro.name == "base_xacro"
        # places and files that are not there (a place past the end is the end)
        assert await _definition(client, base, types.Position(10_000, 3)) == []
        assert await _completion(client, base, types.Position(10_000, 3)) == links
        gone = tmp_path / "gone.urdf.xacro"
        assert await _definition(client, gone, types.Position(0, 0)) == []
        assert await _symbols(client, gone) == []
        # garbage
        client.change(uri, 3, "\x00<<robot <<<${${ \ufffd\n<xacro:\n" * 3)
        await _definition(client, base, types.Position(1, 3))
        await _completion(client, base, types.Position(1, 7))
        await _symbols(client, base)
        # and the whole text again: answered as before
        client.change(uri, 4, text)
        used = _at(base, '<parent link="base_footprint"/>', len('<parent link="'))
        assert await _definition(client, base, used) == [
            _location(base, '<link name="base_footprint"/>', "base_footprint")
        ]


async def test_an_unsaved_link_is_found(package: Path, tmp_path: Path) -> None:
    top = package / URDF / "fishbot.urdf.xacro"
    added = (
        '  <link name="tray_link"/>\n'
        '  <joint name="tray_joint" type="fixed">\n'
        '    <parent link="base_link"/>\n    <child link="tray_link"/>\n  </joint>\n'
    )
    edited = top.read_text(encoding="utf-8").replace("</robot>", added + "</robot>")
    async with running(tmp_path) as client:
        uri = client.open(top)
        client.change(uri, 2, edited)
        used = _position(edited, '<child link="tray_link"', len('<child link="'))
        assert await _definition(client, top, used) == [
            _location(top, '<link name="tray_link"/>', "tray_link", edited)
        ]


def _chain(size: int) -> str:
    """A URDF robot of ``size`` links, each hanging from the last."""
    links = "".join(f'  <link name="link_{i}"/>\n' for i in range(size))
    joints = "".join(
        f'  <joint name="joint_{i}" type="fixed">'
        f'<parent link="link_{i - 1}"/><child link="link_{i}"/></joint>\n'
        for i in range(1, size)
    )
    return f'<?xml version="1.0"?>\n<robot name="chain">\n{links}{joints}</robot>\n'


async def test_a_change_cancels_a_question_under_way(tmp_path: Path) -> None:
    # (a check of it takes the better part of a second: the question, which waits for it,
    # is still under way when the next change comes)
    path = tmp_path / "chain.urdf"
    text = _chain(10_000)
    path.write_text(text, encoding="utf-8")
    used = _position(text, '<parent link="link_0"/>', len('<parent link="'))
    async with running(tmp_path) as client:
        uri = client.open(path)
        await client.diagnostics_for(uri, 1)
        client.change(uri, 2, text + "\n")
        asked = asyncio.ensure_future(_definition(client, path, used))
        await asyncio.sleep(0.05)
        client.change(uri, 3, text + "\n\n")
        assert await asked == []  # cancelled: answered at once, with nothing
        await client.diagnostics_for(uri, 3)
        found = await _definition(client, path, used)
        assert found == [_location(path, '<link name="link_0"/>', "link_0")]


async def test_renaming_a_property_and_a_macro(package: Path, tmp_path: Path) -> None:
    top = package / URDF / "fishbot.urdf.xacro"
    caster = package / URDF / "actuator" / "caster.urdf.xacro"
    text = top.read_text(encoding="utf-8")
    async with running(tmp_path) as client:
        client.open(top)
        where = _at(top, "${caster_radius}", 3)
        edit = await client.text_document_rename_async(
            types.RenameParams(_doc(top), where, "ball_radius")
        )
        assert edit is not None and edit.changes is not None
        assert list(edit.changes) == [top.as_uri()]
        renamed = _applied(text, edit.changes[top.as_uri()])
        assert "caster_radius" not in renamed
        assert renamed.count("ball_radius") == 1 + text.count("${caster_radius}")
        with pytest.raises(JsonRpcException, match="already defined"):
            await client.text_document_rename_async(
                types.RenameParams(_doc(top), where, "caster_mass")
            )
        call = _at(top, "<xacro:caster_xacro", len("<xacro:") + 1)
        edit = await client.text_document_rename_async(
            types.RenameParams(_doc(top), call, "ball_xacro")
        )
        assert edit is not None and edit.changes is not None
        assert set(edit.changes) == {top.as_uri(), caster.as_uri()}
        renamed = _applied(text, edit.changes[top.as_uri()])
        assert renamed.count("<xacro:ball_xacro ") == text.count("<xacro:caster_xacro ")


async def test_positions_count_utf16_units(tmp_path: Path) -> None:
    # an emoji is one character and two UTF-16 units
    path = tmp_path / "wide.urdf"
    text = (
        '<robot name="r"><!-- 🤖 --><link name="bäse"/><link name="arm"/>\n'
        '<joint name="j" type="fixed"><!-- 🤖🤖 --><parent link="bäse"/>'
        '<child link="arm"/></joint>\n'
        "</robot>\n"
    )
    path.write_text(text, encoding="utf-8")
    first, second = text.split("\n")[:2]

    def units(line: str, needle: str) -> int:
        return len(line[: line.index(needle)].encode("utf-16-le")) // 2

    async with running(tmp_path) as client:
        client.open(path)
        used = types.Position(1, units(second, '"bäse"') + 2)
        start = units(first, '"bäse"') + 1
        where = types.Range(types.Position(0, start), types.Position(0, start + 4))
        assert await _definition(client, path, used) == [types.Location(path.as_uri(), where)]
