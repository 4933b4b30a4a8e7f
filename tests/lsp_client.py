"""A client that drives `fishbot lsp` over standard input and output, as an editor does, and
keeps every diagnostics notification with the version it was published for."""

from __future__ import annotations

import asyncio
import os
import sys
from collections.abc import AsyncIterator, Callable, Sequence
from contextlib import asynccontextmanager
from dataclasses import dataclass
from pathlib import Path

from lsprotocol import types
from pytest_lsp import LanguageClient
from pytest_lsp.client import (
    DEFAULT_CLIENT_FEATURES,
    default_converter,  # type: ignore[attr-defined]
    register_lsp_features,
)

ROOT = Path(__file__).resolve().parent.parent
TIMEOUT = 60.0  # seconds a test waits for the server before it fails (not a measure)


@dataclass(frozen=True)
class Published:
    uri: str
    version: int | None
    diagnostics: Sequence[types.Diagnostic]


class Client(LanguageClient):
    """pytest-lsp's client, with every publication kept in order."""

    def __init__(self) -> None:
        super().__init__(converter_factory=default_converter)
        self.published: list[Published] = []
        features = dict(DEFAULT_CLIENT_FEATURES)
        features[types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS] = _keep
        features[types.CLIENT_REGISTER_CAPABILITY] = _register
        register_lsp_features(self, features)
        self.registrations: list[types.Registration] = []

    async def until(self, test: Callable[[], object], what: str = "") -> None:
        """Wait until ``test()`` holds (failing after `TIMEOUT` seconds)."""

        async def wait() -> None:
            while not test():
                await asyncio.sleep(0.01)

        try:
            await asyncio.wait_for(wait(), TIMEOUT)
        except asyncio.TimeoutError:
            raise AssertionError(f"the server did not publish {what}") from None

    def last(self, uri: str) -> Published | None:
        """The last publication for ``uri``."""
        return next((p for p in reversed(self.published) if p.uri == uri), None)

    async def diagnostics_for(self, uri: str, version: int | None) -> Sequence[types.Diagnostic]:
        """The diagnostics published for ``uri`` at ``version`` (waiting for them)."""
        await self.until(
            lambda: any(p.uri == uri and p.version == version for p in self.published),
            f"diagnostics for {uri} version {version}",
        )
        found = [p for p in self.published if p.uri == uri and p.version == version]
        return found[-1].diagnostics

    def open(self, path: Path, text: str | None = None, version: int = 1) -> str:
        """Open ``path`` (with ``text``, else its content); its URI."""
        uri = path.as_uri()
        self.text_document_did_open(
            types.DidOpenTextDocumentParams(
                types.TextDocumentItem(
                    uri=uri,
                    language_id="xml",
                    version=version,
                    text=path.read_text(encoding="utf-8") if text is None else text,
                )
            )
        )
        return uri

    def change(self, uri: str, version: int, text: str, where: types.Range | None = None) -> None:
        """Replace ``where`` (else the whole text) with ``text``."""
        if where is None:
            event: types.TextDocumentContentChangeEvent = (
                types.TextDocumentContentChangeWholeDocument(text=text)
            )
        else:
            event = types.TextDocumentContentChangePartial(range=where, text=text)
        self.text_document_did_change(
            types.DidChangeTextDocumentParams(
                types.VersionedTextDocumentIdentifier(uri=uri, version=version), [event]
            )
        )

    def close(self, uri: str) -> None:
        self.text_document_did_close(
            types.DidCloseTextDocumentParams(types.TextDocumentIdentifier(uri=uri))
        )


def _register(client: Client, params: types.RegistrationParams) -> None:
    client.registrations.extend(params.registrations)


def _keep(client: Client, params: types.PublishDiagnosticsParams) -> None:
    client.diagnostics[params.uri] = params.diagnostics
    client.published.append(Published(params.uri, params.version, params.diagnostics))


@asynccontextmanager
async def running(
    cwd: Path = ROOT, *args: str, capabilities: types.ClientCapabilities | None = None
) -> AsyncIterator[Client]:
    """`python -m fishbot_urdf lsp` with this checkout's sources, started in ``cwd`` and
    initialised; shut down and exited at the end (its exit status checked)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    client = Client()
    await client.start_io(sys.executable, "-m", "fishbot_urdf", "lsp", *args, env=env, cwd=cwd)
    await client.initialize_session(types.InitializeParams(capabilities or CAPABILITIES))
    server = client._server
    assert server is not None
    try:
        yield client
        await client.shutdown_async(None)
        client.exit(None)
        assert await asyncio.wait_for(server.wait(), TIMEOUT) == 0
    finally:
        if server.returncode is None:  # a test failed: nothing more to ask it
            server.kill()
        await client.stop()


CAPABILITIES = types.ClientCapabilities(
    general=types.GeneralClientCapabilities(position_encodings=[types.PositionEncodingKind.Utf16]),
    text_document=types.TextDocumentClientCapabilities(
        hover=types.HoverClientCapabilities(content_format=[types.MarkupKind.Markdown]),
        publish_diagnostics=types.PublishDiagnosticsClientCapabilities(
            related_information=True, version_support=True
        ),
    ),
)
