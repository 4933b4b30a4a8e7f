"""`fishbot lsp` under random edits (a fixed seed): truncations, garbage, a huge text, NUL
and other control characters, a file deleted under its open buffer, URIs it does not know.
After each, it still answers; mended, its findings are the robot's again; told to, it exits
cleanly."""

from __future__ import annotations

import asyncio
import random
import shutil
from pathlib import Path

import pytest
from conftest import FISHBOT
from lsp_client import TIMEOUT, Client, running
from lsprotocol import types

pytestmark = pytest.mark.asyncio

SEED = 20261127
EDITS = 200
FILES = ("fishbot.urdf.xacro", "base.urdf.xacro", "actuator/wheel.urdf.xacro")
GARBAGE = ["\x00", "\x01", "\x1b[31m", "\ufffd", "😀", "<", ">", "&", "${", "}", '"', "\r", "\n"]


class Editor:
    """The open files of a session: their texts and versions as the client last sent them."""

    def __init__(self, client: Client, folder: Path) -> None:
        self.client = client
        self.folder = folder
        self.texts: dict[str, str] = {}
        self.versions: dict[str, int] = {}

    def open(self, path: Path) -> str:
        uri = self.client.open(path)
        self.texts[uri] = path.read_text(encoding="utf-8")
        self.versions[uri] = 1
        return uri

    def replace(self, uri: str, text: str) -> None:
        self.versions[uri] += 1
        self.texts[uri] = text
        self.client.change(uri, self.versions[uri], text)

    def splice(self, uri: str, rng: random.Random, new: str) -> None:
        """Replace a random stretch of one line (in UTF-16 units, as the client counts)."""
        lines = self.texts[uri].split("\n")
        line = rng.randrange(len(lines))
        units = len(lines[line].encode("utf-16-le")) // 2
        start = rng.randint(0, units)
        end = rng.randint(start, units)
        prefix = lines[line].encode("utf-16-le")
        if _splits_a_pair(prefix, start) or _splits_a_pair(prefix, end):
            return  # a client never sends a position inside a character
        head = prefix[: 2 * start].decode("utf-16-le")
        tail = prefix[2 * end :].decode("utf-16-le")
        lines[line] = head + new + tail
        self.versions[uri] += 1
        self.texts[uri] = "\n".join(lines)
        where = types.Range(types.Position(line, start), types.Position(line, end))
        self.client.change(uri, self.versions[uri], new, where)


def _splits_a_pair(utf16: bytes, unit: int) -> bool:
    if unit == 0 or 2 * unit >= len(utf16):
        return False
    high = int.from_bytes(utf16[2 * unit - 2 : 2 * unit], "little")
    return 0xD800 <= high <= 0xDBFF


async def _answers(client: Client, uri: str) -> None:
    """The server answers a request (a hover and a code action) within the time allowed."""
    where = types.Position(0, 0)
    document = types.TextDocumentIdentifier(uri)
    await asyncio.wait_for(
        client.text_document_hover_async(types.HoverParams(document, where)), TIMEOUT
    )
    await asyncio.wait_for(
        client.text_document_code_action_async(
            types.CodeActionParams(
                document, types.Range(where, where), types.CodeActionContext(diagnostics=[])
            )
        ),
        TIMEOUT,
    )


async def test_random_edits_never_stop_the_server(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    rng = random.Random(SEED)
    package = tmp_path / "fishbot_description"
    shutil.copytree(FISHBOT, package)
    urdf = package / "urdf" / "fishbot"
    originals = {name: (urdf / name).read_text(encoding="utf-8") for name in FILES}
    wheel = urdf / "actuator" / "wheel.urdf.xacro"
    unknown = [
        "untitled:Untitled-1",
        (tmp_path / "nowhere" / "robot.urdf").as_uri(),
        "https://example.com/robot.urdf",
    ]
    async with running(tmp_path) as client:
        editor = Editor(client, urdf)
        uris = [editor.open(urdf / name) for name in FILES]
        for step in range(EDITS):
            uri = rng.choice(uris)
            kind = rng.choice(
                ["truncate", "garbage", "garbage", "splice", "huge", "binary", "unknown",
                 "delete", "restore"]
            )  # fmt: skip
            text = editor.texts[uri]
            if kind == "truncate":
                editor.replace(uri, text[: rng.randrange(len(text) + 1)])
            elif kind == "garbage":
                editor.splice(uri, rng, "".join(rng.choices(GARBAGE, k=rng.randint(1, 8))))
            elif kind == "splice":
                editor.splice(uri, rng, "")
            elif kind == "huge" and step % 30 == 0:
                editor.replace(uri, text + "<!--" + "x" * 3_000_000 + "-->")
            elif kind == "binary":
                editor.replace(uri, "".join(chr(rng.randrange(256)) for _ in range(2000)))
            elif kind == "unknown":
                other = rng.choice(unknown)
                client.change(other, 7, "<robot/>")  # never opened
                client.close(other)
                client.text_document_did_open(
                    types.DidOpenTextDocumentParams(
                        types.TextDocumentItem(other, "xml", 1, "<robot name='x'><link/>")
                    )
                )
                await _answers(client, other)
                client.close(other)
            elif kind == "delete" and wheel.exists():
                wheel.unlink()
                client.workspace_did_change_watched_files(
                    types.DidChangeWatchedFilesParams(
                        [types.FileEvent(wheel.as_uri(), types.FileChangeType.Deleted)]
                    )
                )
            elif kind == "restore":
                wheel.write_text(originals["actuator/wheel.urdf.xacro"], encoding="utf-8")
                editor.replace(uri, originals[_name(uri, urdf)])
            await _answers(client, uri)
            if rng.random() < 0.25:  # let a check start, to be cancelled or finish
                await asyncio.sleep(rng.choice((0.05, 0.1, 0.3)))

        # mended, on disk and in the editor: the robot's findings are its own again
        wheel.write_text(originals["actuator/wheel.urdf.xacro"], encoding="utf-8")
        for uri in uris:
            editor.replace(uri, originals[_name(uri, urdf)])
        top = uris[0]
        found = await client.diagnostics_for(top, editor.versions[top])
        assert [d for d in found if d.severity == types.DiagnosticSeverity.Error] == []
    assert "Traceback" not in capfd.readouterr().err


def _name(uri: str, folder: Path) -> str:
    return next(name for name in FILES if (folder / name).as_uri() == uri)
