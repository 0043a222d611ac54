"""Admission scenarios of the load suite (run through bench_server_load.py --only admission).

* a token client's validate_action p99 while another process holds 1,000 connections
  that never finish their headers (reconnecting each one the server closes);
* another client's p99 while one client holds 600 event streams (`GET /mcp`).

Each is compared with the same client alone, measured in the same run on the same server.
The hostile side runs in a process of its own, on raw sockets, so that its work does not
slow the measuring client's event loop.
"""

from __future__ import annotations

import asyncio
import multiprocessing
import selectors
import socket
import sys
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

sys.path.insert(0, str(Path(__file__).parent))

import httpx2  # noqa: E402
from bench_server import TOKEN, light_latencies, percentile, start_http, wire_call  # noqa: E402

PARTIAL = b"POST /mcp HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"


def stream_request(port: int) -> bytes:
    return (f"GET /mcp HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nAuthorization: Bearer {TOKEN}\r\n"
            "Accept: text/event-stream\r\nMCP-Protocol-Version: 2025-11-25\r\n\r\n").encode()


def hold(port: int, kind: str, count: int, stop: Any, ready: Any, held: Any) -> None:
    """Keep `count` hostile connections open until `stop`: partial headers ("partial",
    each one the server closes is opened again) or event streams ("streams", opened
    once and held). `held` reports how many the server still keeps open."""
    selector = selectors.DefaultSelector()
    request = PARTIAL if kind == "partial" else stream_request(port)

    def open_one() -> None:
        sock = socket.create_connection(("127.0.0.1", port), timeout=10)
        sock.sendall(request)
        sock.setblocking(False)
        selector.register(sock, selectors.EVENT_READ)

    for _ in range(count):
        open_one()
    ready.set()
    while not stop.is_set():
        for key, _ in selector.select(0.2):
            sock = key.fileobj
            assert isinstance(sock, socket.socket)
            try:
                chunk = sock.recv(65536)
            except BlockingIOError:
                continue
            except ConnectionResetError:
                chunk = b""
            if not chunk:
                selector.unregister(sock)
                sock.close()
                if kind == "partial":
                    open_one()  # reconnect, as a hostile client does
            elif kind == "streams" and not chunk.startswith(b"HTTP/1.1 200"):
                selector.unregister(sock)  # refused (429): the answer says why; closed
                sock.close()
        held.value = len(selector.get_map())


async def light_p99(url: str, calls: int) -> list[float]:
    headers, body = wire_call("load_scene", {"scene_id": "cup_on_book"}, 1)
    async with httpx2.AsyncClient(headers=headers, timeout=60) as http:
        reply = (await http.post(url, content=body)).json()
        episode = reply["result"]["structuredContent"]["episode_id"]
    return await light_latencies(url, episode, calls, timeout=60)


async def beside(url: str, kind: str, count: int, calls: int) -> tuple[list[float], int]:
    port = int(urlsplit(url).port or 0)
    spawn = multiprocessing.get_context("spawn")
    stop, ready, held = spawn.Event(), spawn.Event(), spawn.Value("i", 0)
    process = spawn.Process(target=hold, args=(port, kind, count, stop, ready, held))
    process.start()
    try:
        while not ready.is_set():
            await asyncio.sleep(0.05)  # polling another process's start, not a measure
        times = await light_p99(url, calls)
        kept = held.value
    finally:
        stop.set()
        process.join(timeout=60)
    return times, kept


def ms(values: list[float], q: float) -> str:
    return f"{percentile(values, q) * 1000:.1f}"


async def admission_rows(quick: bool) -> list[list[str]]:
    calls = 50 if quick else 500
    proc, url = start_http()
    try:
        alone = await light_p99(url, calls)
        flood, flood_held = await beside(url, "partial", 1000, calls)
        streams, streams_held = await beside(url, "streams", 600, calls)
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    base = percentile(alone, 0.99)
    return [
        ["admission: token client alone (peer)", "-", ms(alone, 0.5), ms(alone, 0.99),
         f"{calls} validate_action calls"],
        ["admission: token client beside 1,000 partial-header connections", "-",
         ms(flood, 0.5), ms(flood, 0.99),
         f"{calls} calls, all answered; p99 {percentile(flood, 0.99) / base:.1f}x alone; the "
         f"flood reconnects every connection closed; {flood_held} open at the end"],
        ["admission: another client beside one holding 600 event streams", "-",
         ms(streams, 0.5), ms(streams, 0.99),
         f"{calls} calls, all answered; p99 {percentile(streams, 0.99) / base:.1f}x alone; "
         f"{streams_held} of 600 streams kept (8 per client), the rest refused with 429"],
    ]


if __name__ == "__main__":
    for row in asyncio.run(admission_rows("--quick" in sys.argv)):
        print(" | ".join(row))
