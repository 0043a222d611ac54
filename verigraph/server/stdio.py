"""stdio transport that answers every request and bounds every message.

The SDK's `stdio_server` reads unbounded lines and silently drops the ones it cannot
validate. Here stdin is read in bounded chunks: a message above the size limit is
discarded as it streams in (only its first bytes are kept, to recover the id), and
every line the SDK's validator rejects gets the JSON-RPC error it is owed (see
jsonrpc_screen). Good lines go to the SDK unchanged, and its stdout writer stays the
only writer of the wire.
"""

from __future__ import annotations

import os
from collections.abc import AsyncIterator
from typing import Any

import anyio
import anyio.to_thread
import mcp_types as types
from mcp.server.mcpserver import MCPServer
from mcp.server.stdio import stdio_server
from mcp.shared.message import SessionMessage

from verigraph.server.jsonrpc_screen import oversized, screen

CHUNK = 1 << 16
KEEP_OF_OVERSIZED = 1 << 16  # bytes of a too-large message kept to find its id
PARSE_OFF_LOOP = 1 << 16  # lines longer than this are validated on a worker thread


async def read_bounded_lines(fd: int, limit: int) -> AsyncIterator[tuple[bytes, int]]:
    """(line, size) for each line of `fd`; lines above `limit` bytes come back cut to
    their first KEEP_OF_OVERSIZED bytes with their full size, never held whole."""
    buffer = bytearray()
    size = 0
    while True:
        chunk = await anyio.to_thread.run_sync(os.read, fd, CHUNK, abandon_on_cancel=True)
        if not chunk:
            if buffer.strip():
                yield bytes(buffer), size
            return
        start = 0
        while True:
            end = chunk.find(b"\n", start)
            piece = chunk[start:] if end < 0 else chunk[start:end]
            size += len(piece)
            cap = limit if size <= limit else KEEP_OF_OVERSIZED
            if len(buffer) < cap:
                buffer += piece[:cap - len(buffer)]
            elif len(buffer) > cap:
                del buffer[cap:]
            if end < 0:
                break
            yield bytes(buffer), size
            buffer.clear()
            size = 0
            start = end + 1


def _validate(text: str) -> types.JSONRPCMessage | Exception:
    try:
        return types.jsonrpc_message_adapter.validate_json(text, by_name=False)
    except Exception as exc:  # pydantic ValidationError, or a too-deep document
        return exc


class ScreenedInput:
    """The stdin the SDK reads: only lines it will accept; the rest are answered here."""

    def __init__(self, fd: int, limit: int) -> None:
        self.fd = fd
        self.limit = limit
        self.replies: Any = None  # the transport's write stream, set once it exists
        self.ready = anyio.Event()

    async def _answer(self, errors: list[types.JSONRPCError]) -> None:
        await self.ready.wait()
        for error in errors:
            try:
                await self.replies.send(SessionMessage(error))
            except (anyio.ClosedResourceError, anyio.BrokenResourceError):
                return

    async def __aiter__(self) -> AsyncIterator[str]:
        async for raw, size in read_bounded_lines(self.fd, self.limit):
            text = raw.decode("utf-8", errors="replace")
            if not text.strip():
                continue
            if size > self.limit:
                await self._answer(oversized(text, size, self.limit))
                continue
            if len(raw) > PARSE_OFF_LOOP:
                checked = await anyio.to_thread.run_sync(_validate, text)
            else:
                checked = _validate(text)
            if isinstance(checked, Exception):
                await self._answer(screen(text, checked))
                continue
            if isinstance(checked, types.JSONRPCNotification) and '"id"' in text:
                # `"id": true` or `null` makes the SDK read a request as a notification
                await self._answer(screen(text, ValueError("the id is not valid")))
                continue
            yield text


def _private_stdin() -> int:
    """A private duplicate of fd 0; fd 0 itself then reads the null device, so a child
    process or stray read cannot steal protocol bytes."""
    private = os.dup(0)
    try:
        null = os.open(os.devnull, os.O_RDONLY)
        os.dup2(null, 0)
        os.close(null)
    except OSError:
        pass
    return private


async def run_stdio(server: MCPServer[Any], max_message_bytes: int) -> None:
    """Serve `server` over stdin/stdout until stdin closes."""
    fd = _private_stdin()
    screened = ScreenedInput(fd, max_message_bytes)
    try:
        async with stdio_server(stdin=screened) as (read_stream, write_stream):  # type: ignore[arg-type]
            screened.replies = write_stream
            screened.ready.set()
            lowlevel = server._lowlevel_server  # the SDK's own run_stdio_async does the same
            await lowlevel.run(read_stream, write_stream,
                               lowlevel.create_initialization_options())
    finally:
        os.close(fd)
