"""`fishbot lsp` driven over standard input and output as an editor drives it: the findings of
the fishbot robot as its files are opened and edited, where they are shown, hover and quick
fixes."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import FISHBOT, ROOT
from lsp_client import Client, running
from lsprotocol import types

pytestmark = pytest.mark.asyncio

URDF = Path("urdf") / "fishbot"


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """A copy of the fishbot_description package, alone in a folder."""
    copy = tmp_path / "fishbot_description"
    shutil.copytree(FISHBOT, copy)
    return copy


def _line_of(path: Path, text: str) -> int:
    """The 0-based line of ``path`` holding ``text``."""
    lines = path.read_text(encoding="utf-8").split("\n")
    return next(i for i, line in enumerate(lines) if text in line)


def _errors(diagnostics: object) -> list[types.Diagnostic]:
    return [d for d in diagnostics if d.severity == types.DiagnosticSeverity.Error]  # type: ignore[attr-defined]


async def test_the_top_file_has_no_errors(package: Path) -> None:
    async with running() as client:
        uri = client.open(package / URDF / "fishbot.urdf.xacro")
        assert _errors(await client.diagnostics_for(uri, 1)) == []


async def _misspell_base_footprint(client: Client, base: Path) -> tuple[str, types.Range]:
    """Open base.urdf.xacro and misspell the parent link of its joint: its URI and the range
    of the misspelt name, now 'base_fooprint'."""
    uri = client.open(base)
    await client.diagnostics_for(uri, 1)
    line = _line_of(base, '<parent link="base_footprint"/>')
    start = base.read_text(encoding="utf-8").split("\n")[line].index("base_footprint")
    typo = types.Range(types.Position(line, start + 8), types.Position(line, start + 9))
    client.change(uri, 2, "", typo)  # base_footprint -> base_fooprint
    return uri, typo


async def test_a_broken_edit_of_an_included_file_is_shown_there_and_at_the_macro_call(
    package: Path,
) -> None:
    base = package / URDF / "base.urdf.xacro"
    top = package / URDF / "fishbot.urdf.xacro"
    async with running() as client:
        uri, typo = await _misspell_base_footprint(client, base)
        found = _errors(await client.diagnostics_for(uri, 2))
        assert [d.code for d in found] == ["undefined-link"]
        (finding,) = found
        assert finding.source == "fishbot"
        assert "'base_fooprint' is not defined" in finding.message
        # the parent element's start tag, where `fishbot check` places the finding
        line = typo.start.line
        text = base.read_text(encoding="utf-8").split("\n")[line]
        tag = types.Range(
            types.Position(line, text.index("<parent")), types.Position(line, len(text) - 1)
        )
        assert finding.range == tag
        # shown at the macro's call in the top file too, each pointing at the other
        call_line = _line_of(top, "<xacro:base_xacro")
        await client.until(lambda: client.last(top.as_uri()) is not None, "the call")
        published = client.last(top.as_uri())
        assert published is not None
        (at_call,) = _errors(published.diagnostics)
        assert at_call.code == "undefined-link"
        assert at_call.range.start == types.Position(call_line, 2)
        assert at_call.message.startswith("in macro base_xacro: ")
        assert at_call.related_information is not None
        assert at_call.related_information[0].location.uri == uri
        assert at_call.related_information[0].location.range == finding.range
        assert finding.related_information is not None
        assert finding.related_information[0].location.uri == top.as_uri()

        # mended: cleared in both files
        client.change(uri, 3, "t", types.Range(typo.start, typo.start))
        assert _errors(await client.diagnostics_for(uri, 3)) == []
        await client.until(
            lambda: not _errors(client.last(top.as_uri()).diagnostics),  # type: ignore[union-attr]
            "the call cleared",
        )


async def test_an_included_file_finds_its_package_from_elsewhere(
    package: Path, tmp_path: Path
) -> None:
    # the server runs in another folder: $(find fishbot_description) is found from the file
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    async with running(elsewhere) as client:
        uri = client.open(package / URDF / "actuator" / "wheel.urdf.xacro")
        assert _errors(await client.diagnostics_for(uri, 1)) == []
        text = (package / URDF / "actuator" / "wheel.urdf.xacro").read_text(encoding="utf-8")
        client.change(uri, 2, text.replace('<parent link="base_link"/>', '<parent link="bse"/>'))
        found = _errors(await client.diagnostics_for(uri, 2))
        assert [d.code for d in found] == ["undefined-link", "undefined-link"]  # two wheels


async def test_hover_on_a_finding_explains_its_rule(package: Path) -> None:
    base = package / URDF / "base.urdf.xacro"
    async with running() as client:
        uri, _ = await _misspell_base_footprint(client, base)
        (finding,) = _errors(await client.diagnostics_for(uri, 2))
        hover = await client.text_document_hover_async(
            types.HoverParams(types.TextDocumentIdentifier(uri), finding.range.start)
        )
        assert hover is not None
        assert isinstance(hover.contents, types.MarkupContent)
        assert hover.contents.kind == types.MarkupKind.Markdown
        # the rule as `fishbot rules` explains it
        rules = subprocess.run(
            [
                sys.executable,
                "-m",
                "fishbot_urdf",
                "rules",
                "undefined-link",
                "--format",
                "markdown",
            ],
            capture_output=True,
            text=True,
            check=True,
            env={"PYTHONPATH": str(ROOT / "src"), "PATH": ""},
        )
        assert rules.stdout.strip().startswith("## `undefined-link`")
        assert hover.contents.value == f"**{finding.message}**\n\n{rules.stdout.strip()}"
        # nothing to say where there is no finding
        nothing = await client.text_document_hover_async(
            types.HoverParams(types.TextDocumentIdentifier(uri), types.Position(0, 0))
        )
        assert nothing is None


async def test_a_finding_with_a_fix_offers_it_as_a_quick_fix(package: Path) -> None:
    base = package / URDF / "base.urdf.xacro"
    async with running() as client:
        uri, typo = await _misspell_base_footprint(client, base)
        (finding,) = _errors(await client.diagnostics_for(uri, 2))
        actions = await client.text_document_code_action_async(
            types.CodeActionParams(
                types.TextDocumentIdentifier(uri),
                finding.range,
                types.CodeActionContext(diagnostics=[finding]),
            )
        )
        assert actions
        preferred = [a for a in actions if isinstance(a, types.CodeAction) and a.is_preferred]
        assert len(preferred) == 1
        (fix,) = preferred
        assert fix.kind == types.CodeActionKind.QuickFix
        assert fix.edit is not None and fix.edit.changes is not None
        # the misspelt name, 'base_fooprint', replaced by the link's
        line = typo.start.line
        text = base.read_text(encoding="utf-8").split("\n")[line]
        start = text.index("base_footprint")
        name = types.Range(types.Position(line, start), types.Position(line, start + 13))
        assert list(fix.edit.changes[uri]) == [types.TextEdit(name, "base_footprint")]


async def test_the_nearest_configuration_applies_saved_or_as_the_editor_holds_it(
    package: Path,
) -> None:
    base = package / URDF / "base.urdf.xacro"
    async with running() as client:
        uri, _ = await _misspell_base_footprint(client, base)
        assert [d.code for d in _errors(await client.diagnostics_for(uri, 2))] == ["undefined-link"]
        config = package / "fishbot.toml"
        config.write_text('ignore = ["undefined-link"]\n', encoding="utf-8")
        client.workspace_did_change_watched_files(
            types.DidChangeWatchedFilesParams(
                [types.FileEvent(config.as_uri(), types.FileChangeType.Created)]
            )
        )
        # (its consequence, a second root, is reported in its place)
        await client.until(lambda: "undefined-link" not in _codes(client, uri), "it ignored")
        # the configuration as the editor holds it, unsaved
        client.open(config, "ignore = []\n")
        await client.until(lambda: "undefined-link" in _codes(client, uri), "the finding back")
        # a configuration that does not read: said in it, and atop the robot it is for
        client.change(config.as_uri(), 2, "ignore = [")
        top = (package / URDF / "fishbot.urdf.xacro").as_uri()
        await client.until(lambda: "config" in _codes(client, top), "the robot told")
        assert "config" in _codes(client, config.as_uri())


def _codes(client: Client, uri: str) -> list[object]:
    published = client.last(uri)
    return [] if published is None else [d.code for d in published.diagnostics]


async def test_a_client_that_can_watch_files_is_asked_to_watch_the_robots_files() -> None:
    watching = types.ClientCapabilities(
        workspace=types.WorkspaceClientCapabilities(
            did_change_watched_files=types.DidChangeWatchedFilesClientCapabilities(
                dynamic_registration=True
            )
        )
    )
    async with running(capabilities=watching) as client:
        await client.until(lambda: client.registrations, "a registration")
        (registration,) = client.registrations
        assert registration.method == types.WORKSPACE_DID_CHANGE_WATCHED_FILES
        options = registration.register_options
        globs = [w["globPattern"] for w in options["watchers"]]  # type: ignore[index]
        assert globs == ["**/*.{urdf,xacro,yaml,yml,toml,xml,stl,STL,dae,obj,OBJ}"]


async def test_no_quick_fix_is_offered_for_a_text_changed_since_its_findings(
    package: Path,
) -> None:
    """An edit made before the next check: the fixes' places are the old text's, and
    applying one would write into the wrong columns."""
    base = package / URDF / "base.urdf.xacro"
    async with running(ROOT, "--debounce", "2000") as client:
        uri, typo = await _misspell_base_footprint(client, base)
        (finding,) = _errors(await client.diagnostics_for(uri, 2))
        start = types.Position(typo.start.line, 0)
        client.change(uri, 3, "<!--a-->", types.Range(start, start))  # columns move
        actions = await client.text_document_code_action_async(
            types.CodeActionParams(
                types.TextDocumentIdentifier(uri),
                finding.range,
                types.CodeActionContext(diagnostics=[finding]),
            )
        )
        assert not actions
        assert _errors(await client.diagnostics_for(uri, 3))  # the new text's, once checked
