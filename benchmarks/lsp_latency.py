"""Benchmark: how soon `fishbot lsp` publishes the findings of the fishbot after a change,
measured through a real client over standard input and output (pygls's). Run by hand:

    python benchmarks/lsp_latency.py [--edits 100] [--debounce 75]

On a copy of robots/fishbot, with fishbot.urdf.xacro and base.urdf.xacro open, each edit
changes one digit of a colour in base.urdf.xacro (to and fro: no finding changes), and the
time from sending the change to receiving the diagnostics of that version is taken; the
median and 90th percentile are printed, the server's wait after a change (--debounce)
included. Then, with no wait, the robot is checked as first opened in a new session and
again unchanged (the file closed and opened again with the same text): the two round trips
and their ratio; and the same two checks in process (`lint.check_file` with a Workspace).
"""

from __future__ import annotations

import argparse
import asyncio
import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

from lsprotocol import types
from pygls.lsp.client import LanguageClient

ROOT = Path(__file__).resolve().parent.parent
FISHBOT = ROOT / "robots" / "fishbot"
URDF = Path("urdf") / "fishbot"
COLOUR = 'rgba="0.1 0.1 1.0 0.5"'


class Client(LanguageClient):
    """A client that notes when each (uri, version)'s diagnostics arrive."""

    def __init__(self) -> None:
        super().__init__("lsp-latency", "1")
        self.arrived: dict[tuple[str, int | None], float] = {}
        self.event = asyncio.Event()

        @self.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        def published(params: types.PublishDiagnosticsParams) -> None:
            self.arrived[(params.uri, params.version)] = time.perf_counter()
            self.event.set()

    async def arrival(self, uri: str, version: int) -> float:
        while (uri, version) not in self.arrived:
            self.event.clear()
            await asyncio.wait_for(self.event.wait(), 60)
        return self.arrived[(uri, version)]

    def open(self, path: Path, version: int = 1) -> str:
        uri = path.as_uri()
        item = types.TextDocumentItem(uri, "xml", version, path.read_text(encoding="utf-8"))
        self.text_document_did_open(types.DidOpenTextDocumentParams(item))
        return uri


async def _started(debounce: int) -> Client:
    client = Client()
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    command = [sys.executable, "-m", "fishbot_urdf", "lsp", "--debounce", str(debounce)]
    await client.start_io(*command, env=env)
    await client.initialize_async(types.InitializeParams(capabilities=types.ClientCapabilities()))
    client.initialized(types.InitializedParams())
    return client


async def _stopped(client: Client) -> None:
    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()


async def latencies(package: Path, edits: int, debounce: int) -> list[float]:
    """Milliseconds from each edit of base.urdf.xacro to its diagnostics."""
    client = await _started(debounce)
    client.open(package / URDF / "fishbot.urdf.xacro")
    base = package / URDF / "base.urdf.xacro"
    uri = client.open(base)
    await client.arrival(uri, 1)
    lines = base.read_text(encoding="utf-8").split("\n")
    line = next(i for i, text in enumerate(lines) if COLOUR in text)
    # the colour's last digit: 0.5 -> 0.6 -> 0.5 ...
    at = lines[line].index(COLOUR) + len(COLOUR) - 2
    where = types.Range(types.Position(line, at), types.Position(line, at + 1))
    taken = []
    for version in range(2, edits + 2):
        digit = "6" if version % 2 == 0 else "5"
        change = types.TextDocumentContentChangePartial(range=where, text=digit)
        sent = time.perf_counter()
        client.text_document_did_change(
            types.DidChangeTextDocumentParams(
                types.VersionedTextDocumentIdentifier(uri=uri, version=version), [change]
            )
        )
        taken.append((await client.arrival(uri, version) - sent) * 1000)
    await _stopped(client)
    return taken


async def first_and_again(package: Path) -> tuple[float, float]:
    """Milliseconds from opening the top file to its diagnostics in a new session, and from
    opening it again, unchanged, once closed (no wait after a change)."""
    client = await _started(0)
    top = package / URDF / "fishbot.urdf.xacro"
    sent = time.perf_counter()
    uri = client.open(top, 1)
    first = await client.arrival(uri, 1) - sent
    again = []
    for version in range(2, 12):
        client.text_document_did_close(
            types.DidCloseTextDocumentParams(types.TextDocumentIdentifier(uri))
        )
        sent = time.perf_counter()
        client.open(top, version)
        again.append(await client.arrival(uri, version) - sent)
    await _stopped(client)
    return first * 1000, statistics.median(again) * 1000


def in_process(package: Path) -> tuple[float, float]:
    """Milliseconds of the first check of the fishbot in a workspace, and of the next."""
    sys.path.insert(0, str(ROOT / "src"))
    from fishbot_urdf.lint import check_file
    from fishbot_urdf.workspace import Workspace

    top = package / URDF / "fishbot.urdf.xacro"
    check_file(top)  # every module loaded, as in a session that has checked a robot
    workspace = Workspace()
    start = time.perf_counter()
    check_file(top, workspace=workspace)
    first = time.perf_counter() - start
    times = []
    for _ in range(100):
        start = time.perf_counter()
        check_file(top, workspace=workspace)
        times.append(time.perf_counter() - start)
    return first * 1000, statistics.median(times) * 1000


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--edits", type=int, default=100)
    parser.add_argument("--debounce", type=int, default=75, help="the server's, in ms")
    options = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        package = Path(folder) / "fishbot_description"
        shutil.copytree(FISHBOT, package)
        taken = asyncio.run(latencies(package, options.edits, options.debounce))
        undelayed = asyncio.run(latencies(package, options.edits, 0))
        first, again = asyncio.run(first_and_again(package))
        cold, warm = in_process(package)
    deciles = statistics.quantiles(taken, n=10)
    bare = statistics.quantiles(undelayed, n=10)
    print("| measure | value | goal |")
    print("| --- | ---: | ---: |")
    print(
        f"| change to diagnostics, median of {options.edits} edits "
        f"(--debounce {options.debounce}) | {statistics.median(taken):.0f} ms | < 150 ms |"
    )
    print(f"| the same, 90th percentile | {deciles[-1]:.0f} ms |  |")
    print(
        f"| the same with --debounce 0, median and 90th percentile | "
        f"{statistics.median(undelayed):.0f} ms, {bare[-1]:.0f} ms |  |"
    )
    print(
        f"| open to diagnostics, first check in a session vs the same robot unchanged "
        f"| {first:.0f} ms vs {again:.1f} ms ({again / first:.1%}) | < 10% |"
    )
    print(
        f"| in process, check_file with a workspace, first vs again "
        f"| {cold:.1f} ms vs {warm:.2f} ms ({warm / cold:.2%}) | < 10% |"
    )


if __name__ == "__main__":
    main()
