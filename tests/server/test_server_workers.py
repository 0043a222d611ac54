"""`verigraph serve --workers 2`: two processes on one socket sharing one SQLite store."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx2
import pytest
from mcp_helpers import JSON_HEADERS, RunningServer, http_server, rpc, verigraph_command

TOKEN = "workers-token"
HEADERS = {**JSON_HEADERS, "Authorization": f"Bearer {TOKEN}",
           "MCP-Protocol-Version": "2025-11-25"}


@pytest.fixture()
def workers(tmp_path: Path) -> Iterator[RunningServer]:
    store = f"sqlite:///{tmp_path / 'episodes.db'}"
    with http_server(token=TOKEN, extra=["--workers", "2", "--store", store]) as running:
        yield running


def serving_processes(server: RunningServer) -> list[int]:
    """The two children, once both have built their server (the port opens before:
    the parent binds it, then forks)."""
    parent = server.proc.pid
    deadline = time.monotonic() + 60  # only so that a broken server fails the test
    while True:
        children = [int(pid) for pid in
                    Path(f"/proc/{parent}/task/{parent}/children").read_text().split()]
        logged = os.pread(server.stderr.fileno(), 1 << 20, 0).count(b"MCP server on")
        if (len(children) == 2 and logged == 2) or time.monotonic() > deadline:
            return children
        time.sleep(0.05)


def call(url: str, name: str, arguments: dict[str, Any]) -> dict[str, Any]:
    """One tools/call on a connection of its own (so any free process may take it)."""
    body = rpc("tools/call", {"name": name, "arguments": arguments})
    with httpx2.Client(headers=HEADERS, timeout=30) as http:
        reply = http.post(url, content=body).json()
    assert reply["result"].get("isError") is not True, reply
    return dict(reply["result"]["structuredContent"])


def test_either_process_serves_the_episodes_of_the_other(workers: RunningServer) -> None:
    first, second = serving_processes(workers)
    os.kill(first, signal.SIGSTOP)  # only `second` can take connections now
    try:
        episode = call(workers.url, "load_scene", {"scene_id": "cup_on_book"})["episode_id"]
        call(workers.url, "execute_actions", {"episode_id": episode,
                                              "actions": ["move(cup, on, desk)"]})
    finally:
        os.kill(first, signal.SIGCONT)
    os.kill(second, signal.SIGSTOP)  # and now only `first`
    try:
        state = call(workers.url, "get_state", {"episode_id": episode})
    finally:
        os.kill(second, signal.SIGCONT)
    assert state["executed"] == ["move(cup, on, desk)"]
    edges = {(e["source"], e["relation"], e["target"]) for e in state["graph"]["edges"]}
    assert ("cup", "on", "desk") in edges and ("cup", "on", "book") not in edges


def test_sigterm_to_the_parent_stops_every_process(workers: RunningServer) -> None:
    children = serving_processes(workers)
    assert len(children) == 2
    workers.proc.send_signal(signal.SIGTERM)
    assert workers.proc.wait(timeout=30) == 0
    assert not any(Path(f"/proc/{pid}").exists() and
                   Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
                   for pid in children)


@pytest.mark.parametrize(("extra", "named"), [
    (["--transport", "http", "--store", "memory://"], "--store"),
    (["--transport", "stdio"], "--workers"),
])
def test_workers_without_a_shared_store_are_refused(extra: list[str], named: str) -> None:
    done = subprocess.run([*verigraph_command(), "serve", "--workers", "2", *extra],
                          capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)
    assert done.returncode == 2, done.stderr
    assert named in done.stderr and "Traceback" not in done.stderr
