"""What `fishbot lsp` publishes is what `fishbot check` finds: every robot of tests/data
opened in one session; and a big robot changed while it is checked."""

from __future__ import annotations

import asyncio
import json
from collections import Counter
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import DATA, ROOT
from lsp_client import running
from lsprotocol import types

from fishbot_urdf.cli import cli
from fishbot_urdf.tops import find_tops
from fishbot_urdf.workspace import Workspace

pytestmark = pytest.mark.asyncio

FIXTURES = sorted(
    p for p in DATA.rglob("*") if p.is_file() and p.name.endswith((".urdf", ".xacro"))
)

_SEVERITY = {
    "error": types.DiagnosticSeverity.Error,
    "warning": types.DiagnosticSeverity.Warning,
    "note": types.DiagnosticSeverity.Information,
}


def _text(path: Path) -> str | None:
    try:
        return path.read_bytes().decode("utf-8")
    except UnicodeDecodeError:  # an editor would not hold it as it is on disk
        return None


def _expected(path: Path) -> list[tuple[str, int, int | None, types.DiagnosticSeverity]]:
    """`fishbot check --format json` on each robot the file belongs to (the file itself,
    unless it is a file of macros another file of its folder includes): its findings in
    the file, as (rule, line, column, severity)."""
    found = []
    for top in find_tops(path, Workspace()):
        run = CliRunner().invoke(cli, ["check", "--format", "json", top])
        assert run.exit_code in (0, 1, 2), run.output
        for report in json.loads(run.stdout)["files"]:
            for d in report["diagnostics"]:
                if (ROOT / d["path"]).resolve() == path.resolve():
                    found.append((d["rule"], d["line"] or 1, d["column"], _SEVERITY[d["severity"]]))
    return found


def _published(diagnostics: object, text: str) -> list[tuple[str, int, int, object]]:
    """The findings a server published in a file (not those shown at a macro's call), with
    their 1-based line and character column."""
    lines = text.split("\n")
    found = []
    for d in diagnostics:  # type: ignore[attr-defined]
        related = d.related_information or []
        if any(r.message == "the finding, in the macro" for r in related):
            continue
        start = d.range.start
        line = lines[start.line] if start.line < len(lines) else ""
        column = len(line.encode("utf-16-le")[: 2 * start.character].decode("utf-16-le")) + 1
        found.append((d.code, start.line + 1, column, d.severity))
    return found


async def test_every_fixture_is_published_as_check_finds_it() -> None:
    assert len(FIXTURES) > 100
    wrong = []
    compared = 0
    async with running(ROOT, "--debounce", "0") as client:
        for path in FIXTURES:
            text = _text(path)
            if text is None:
                continue
            uri = client.open(path, text)
            published = _published(await client.diagnostics_for(uri, 1), text)
            client.close(uri)
            expected = _expected(path)
            compared += 1
            # every finding on the same line, and at the same column where check gives one
            same_lines = Counter((r, line, s) for r, line, _, s in published) == Counter(
                (r, line, s) for r, line, _, s in expected
            )
            columns = Counter(published)
            same_columns = all(
                columns[finding] > 0 for finding in expected if finding[2] is not None
            )
            if not (same_lines and same_columns):
                wrong.append((path.relative_to(ROOT), sorted(published), sorted(expected)))
    assert wrong == []
    assert compared == len(FIXTURES) - sum(_text(p) is None for p in FIXTURES) > 100


def _robot(size: int, parent: str = "link_0") -> str:
    """A URDF robot of ``size`` links (each a box with its inertia), each hanging from the
    last on a revolute joint; the first joint's parent is ``parent``."""
    box = '<geometry><box size="0.1 0.1 0.1"/></geometry>'
    inertia = 'ixx="0.00167" ixy="0" ixz="0" iyy="0.00167" iyz="0" izz="0.00167"'  # m/12*(2a^2)
    links = "".join(
        f'  <link name="link_{i}"><inertial><mass value="1"/><inertia {inertia}/></inertial>'
        f"<visual>{box}</visual><collision>{box}</collision></link>\n"
        for i in range(size)
    )
    joints = "".join(
        f'  <joint name="joint_{i}" type="revolute">'
        f'<parent link="{parent if i == 1 else f"link_{i - 1}"}"/><child link="link_{i}"/>'
        '<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n'
        for i in range(1, size)
    )
    return f'<?xml version="1.0"?>\n<robot name="big">\n{links}{joints}</robot>\n'


async def test_a_big_robot_changed_while_checked_publishes_the_last_version(
    tmp_path: Path,
) -> None:
    # (a check of it takes about a second: a pause of 0.3 s lets a check start, 75 ms after
    # the change, so that what comes next comes while it runs)
    path = tmp_path / "big.urdf"
    path.write_text(_robot(10_000), encoding="utf-8")
    async with running(tmp_path) as client:
        uri = client.open(path)
        assert [d.code for d in await client.diagnostics_for(uri, 1)] == []
        # two changes at once: the second comes before the first is checked
        after = len(client.published)
        client.change(uri, 2, _robot(10_000, "link_x"))
        client.change(uri, 3, _robot(10_000, "link_y"))
        await asyncio.sleep(0.3)
        # (the quick fixes are asked: the navigation's answers wait for the check, being
        # made from it)
        here = types.Range(types.Position(3, 2), types.Position(3, 2))
        fixes = asyncio.ensure_future(
            client.text_document_code_action_async(
                types.CodeActionParams(
                    types.TextDocumentIdentifier(uri), here, types.CodeActionContext([])
                )
            )
        )
        last = await client.diagnostics_for(uri, 3)
        # answered while the check ran: before its findings came
        assert fixes.done()
        assert not fixes.result()  # no finding was there when it was asked
        assert [d.code for d in last] == ["undefined-link"]
        assert "'link_y' is not defined" in last[0].message
        assert [p.version for p in client.published[after:] if p.uri == uri] == [3]

        # a change while the check of the one before runs: it is cancelled, or published
        # before the next is (each version with its own findings), the last one last
        after = len(client.published)
        client.change(uri, 4, _robot(10_000, "link_z"))
        await asyncio.sleep(0.3)
        client.change(uri, 5, _robot(10_000, "link_w"))
        await client.diagnostics_for(uri, 5)
        versions = [p for p in client.published[after:] if p.uri == uri]
        assert [p.version for p in versions] in ([5], [4, 5])
        for published, name in zip(versions[::-1], ("link_w", "link_z"), strict=False):
            assert [d.code for d in published.diagnostics] == ["undefined-link"]
            assert f"'{name}' is not defined" in published.diagnostics[0].message
