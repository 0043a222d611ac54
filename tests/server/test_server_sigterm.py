"""SIGTERM with heavy calls in flight: the HTTP server cancels them and exits cleanly."""

from __future__ import annotations

import os
import signal
import subprocess
import tempfile
import threading
import time

import httpx2
from mcp_helpers import JSON_HEADERS, free_port, rpc, verigraph_command

SAFETY_S = 60  # only so that a broken server fails the test instead of hanging it


def tower(n: int) -> dict:
    nodes = [{"id": "table", "label": "table"}] + [{"id": f"b{i}", "label": "block"}
                                                   for i in range(n - 1)]
    edges = [{"source": f"b{i}", "relation": "on", "target": f"b{i - 1}" if i else "table"}
             for i in range(n - 1)]
    return {"nodes": nodes, "edges": edges, "dictionary": "blocks"}


def test_sigterm_cancels_calls_in_flight_and_exits() -> None:
    port = free_port()
    url = f"http://127.0.0.1:{port}/mcp"
    env = {k: v for k, v in os.environ.items() if k != "VERIGRAPH_TOKEN"}
    body = rpc("tools/call", {"name": "validate_plan", "arguments": {
        "graph": tower(5000), "plan": [f"move(b{i}, on, table)" for i in range(4998, 3998, -1)]}})
    with tempfile.TemporaryFile() as err:
        proc = subprocess.Popen([*verigraph_command(), "serve", "--transport", "http", "--port",
                                 str(port), "--log-level", "DEBUG"], env=env, stderr=err)
        outcomes: list[str] = []

        def client() -> None:
            try:
                reply = httpx2.post(url, content=body, headers=JSON_HEADERS, timeout=SAFETY_S)
                outcomes.append(f"status {reply.status_code}")
            except httpx2.HTTPError as exc:
                outcomes.append(type(exc).__name__)

        try:
            deadline = time.monotonic() + SAFETY_S
            while b"Uvicorn running" not in _read(err) and time.monotonic() < deadline:
                time.sleep(0.05)
            threads = [threading.Thread(target=client) for _ in range(2)]
            for t in threads:
                t.start()
            while b"heavy call validate_plan started" not in _read(err):
                assert time.monotonic() < deadline, "no heavy call started"
                time.sleep(0.02)
            proc.send_signal(signal.SIGTERM)
            # uvicorn re-raises the signal once it has shut down; the grace timer exits 0
            assert proc.wait(timeout=SAFETY_S) in (0, -signal.SIGTERM)
            for t in threads:
                t.join(SAFETY_S)
        finally:
            if proc.poll() is None:
                proc.kill()
        log = _read(err).decode(errors="replace")
    assert len(outcomes) == 2  # every client got an answer or a closed connection
    assert "Traceback" not in log, log[-3000:]
    # calls still running after the grace time were cancelled (the others had finished)
    cancelled = "cancelling its request" in log or "running task(s)" in log
    assert cancelled or outcomes == ["status 200"] * 2, (outcomes, log[-3000:])


def _read(handle: tempfile._TemporaryFileWrapper) -> bytes:  # type: ignore[type-arg]
    handle.seek(0)
    return handle.read()
