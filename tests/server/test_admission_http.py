"""Connection admission against a real `verigraph serve --transport http` on loopback:
a flood of half-open connections without the token, and one client holding hundreds of
event streams, cannot keep another client from being answered (raw sockets for the
hostile side, the official SDK client for the one that must be served)."""

from __future__ import annotations

import selectors
import socket
from collections.abc import Iterator
from urllib.parse import urlsplit

import httpx2
import pytest
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp_helpers import http_server, structured

TOKEN = "admission-token-51c2"
AUTH = {"Authorization": f"Bearer {TOKEN}"}
SAFETY_S = 60  # only so that a broken server fails the test; never a measure
PARTIAL = b"POST /mcp HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"


@pytest.fixture(scope="module")
def server() -> Iterator[tuple[str, int]]:
    # 512 slots, so at most 128 may wait for headers; streams idle out after 2 s.
    with http_server(token=TOKEN, extra=["--max-connections", "512",
                                         "--stream-idle", "2"]) as running:
        yield running.url, int(urlsplit(running.url).port or 0)


def read_replies(socks: list[socket.socket], until: bytes, want: int) -> dict[socket.socket,
                                                                                 bytes]:
    """What each socket received, read until `want` of them saw `until` or were closed
    (waiting on readiness, bounded by SAFETY_S)."""
    got = {s: b"" for s in socks}
    done: set[socket.socket] = set()
    selector = selectors.DefaultSelector()
    for s in socks:
        s.setblocking(False)
        selector.register(s, selectors.EVENT_READ)
    while len(done) < want:
        events = selector.select(SAFETY_S)
        assert events, f"only {len(done)} of {want} sockets answered"
        for key, _ in events:
            s = key.fileobj
            assert isinstance(s, socket.socket)
            try:
                chunk = s.recv(65536)
            except ConnectionResetError:
                chunk = b""
            got[s] += chunk
            if not chunk or until in got[s]:
                selector.unregister(s)
                done.add(s)
    selector.close()
    return got


async def ping_with_sdk(url: str) -> None:
    async with httpx2.AsyncClient(headers=AUTH, timeout=SAFETY_S) as http, \
            Client(streamable_http_client(url, http_client=http)) as c:
        out = structured(await c.call_tool("load_scene", {"scene_id": "cup_on_book"}))
        assert out["episode_id"]


@pytest.mark.anyio
async def test_a_token_client_is_answered_while_1000_anonymous_connections_hang(
        server: tuple[str, int]) -> None:
    url, port = server
    flood = [socket.create_connection(("127.0.0.1", port), timeout=SAFETY_S)
             for _ in range(1000)]
    try:
        for s in flood:
            s.sendall(PARTIAL)  # ...and never the end of the headers
        # The server keeps the newest 128 waiting and closes the older ones with a 503.
        replies = read_replies(flood, b"\r\n\r\n", 1000 - 128)
        evicted = [r for r in replies.values() if r]
        assert len(evicted) >= 1000 - 128
        assert all(r.startswith(b"HTTP/1.1 503") and b"waiting for their request headers"
                   in r for r in evicted)
        await ping_with_sdk(url)  # the SDK client, with the token, opens new connections
    finally:
        for s in flood:
            s.close()


def stream_request(port: int) -> bytes:
    return (f"GET /mcp HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nAuthorization: Bearer {TOKEN}\r\n"
            "Accept: text/event-stream\r\nMCP-Protocol-Version: 2025-11-25\r\n\r\n").encode()


@pytest.mark.anyio
async def test_600_event_streams_from_one_client_leave_room_for_another(
        server: tuple[str, int]) -> None:
    url, port = server
    holder: list[socket.socket] = []
    try:
        for _ in range(600):  # each sends its request at once, as a client does
            holder.append(socket.create_connection(("127.0.0.1", port), timeout=SAFETY_S))
            holder[-1].sendall(stream_request(port))
        replies = read_replies(holder, b"text/event-stream", 600)  # or closed after an error
        opened = [s for s, r in replies.items() if r.startswith(b"HTTP/1.1 200")]
        # The rest are refused: 429 once the client holds 8, or 503 while a burst of new
        # connections holds more than the 512 slots (the refused ones not yet closed).
        per_client = [r for r in replies.values() if r.startswith(b"HTTP/1.1 429")]
        busy = [r for r in replies.values() if r.startswith(b"HTTP/1.1 503")]
        assert len(opened) == 8, [r[:600] for r in replies.values()][:1]
        assert len(per_client) + len(busy) == 592 and per_client
        assert all(b"already has 8 open" in r for r in per_client)
        assert all(b"requests in progress" in r or b"waiting for their request headers" in r
                   for r in busy), {r[-160:] for r in busy}
        await ping_with_sdk(url)  # another client, while the 8 streams are held
        # Nothing is sent on the streams: each ends after 2 s idle (chunked terminator).
        ended = read_replies(opened, b"0\r\n\r\n", 8)
        assert all(b"text/event-stream" in replies[s] for s in opened)
        assert all(r.endswith(b"0\r\n\r\n") or not r for r in ended.values())
        assert any(r.endswith(b"0\r\n\r\n") for r in ended.values())
    finally:
        for s in holder:
            s.close()
