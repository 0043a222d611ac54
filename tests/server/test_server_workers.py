"""`verigraph serve --workers 2`: two processes on one socket sharing one SQLite store."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx2
import pytest
from mcp_helpers import (
    JSON_HEADERS,
    RunningServer,
    checking_processes,
    http_server,
    process_gone,
    rpc,
    tower_graph,
    verigraph_command,
    wait_until,
)

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



def large_plan() -> dict[str, Any]:
    """A validate_plan body above 64 KiB, so the process's body checker takes it first."""
    return {"graph": tower_graph(1000), "plan": ["move(b1, on, table)"]}


def sockets(pid: int) -> set[str]:
    """The sockets `pid` holds, by inode ("socket:[N]"): a connection the parent holds a
    copy of has the inode of the child's connection. A set, not a count: the copy of an
    earlier, answered request may be released while the next one is taken."""
    held = set()
    for fd in os.listdir(f"/proc/{pid}/fd"):
        with contextlib.suppress(FileNotFoundError):
            target = os.readlink(f"/proc/{pid}/fd/{fd}")
            if target.startswith("socket:"):
                held.add(target)
    return held


def test_a_killed_process_is_replaced_and_its_call_answered(workers: RunningServer) -> None:
    first, second = serving_processes(workers)
    parent = workers.proc.pid
    os.kill(first, signal.SIGSTOP)  # only `second` takes the calls
    reply: dict[str, Any] = {}
    try:
        body = rpc("tools/call", {"name": "validate_plan", "arguments": large_plan()}, 40)
        with httpx2.Client(headers=HEADERS, timeout=60) as http:  # starts its body checkers
            assert http.post(workers.url, content=body).status_code == 200
        checkers = checking_processes(second)
        assert checkers
        for pid in checkers:  # the next large call waits in `second` for its check
            os.kill(pid, signal.SIGSTOP)
        baseline = sockets(parent)
        body = rpc("tools/call", {"name": "validate_plan", "arguments": large_plan()}, 41)

        def post() -> None:
            with httpx2.Client(headers=HEADERS, timeout=60) as http:
                response = http.post(workers.url, content=body)
            reply["status"] = response.status_code
            reply["body"] = response.json()

        thread = threading.Thread(target=post)
        thread.start()
        # The parent holds a copy of the connection once `second` has the request.
        wait_until(lambda: bool(sockets(parent) - baseline), "the call reached the server")
        os.kill(second, signal.SIGKILL)
        thread.join(60)
    finally:
        os.kill(first, signal.SIGCONT)
    assert reply["status"] == 500, reply
    error = reply["body"]["error"]
    assert error["code"] == -32603 and "may or may not have taken effect" in error["message"]

    def replaced() -> bool:
        children = Path(f"/proc/{parent}/task/{parent}/children").read_text().split()
        return len(children) >= 2 and str(second) not in children

    wait_until(replaced, "a new process in place of the killed one", timeout=30)
    assert process_gone(second) and not Path(f"/proc/{second}").exists()  # reaped
    episode = call(workers.url, "load_scene", {"scene_id": "cup_on_book"})["episode_id"]
    assert call(workers.url, "get_state", {"episode_id": episode})["executed"] == []
    log = os.pread(workers.stderr.fileno(), 1 << 20, 0).decode()
    assert f"server process {second} died (signal 9) with 1 call(s) in progress" in log, \
        log[-2000:]
    assert "in place of the one that died" in log
