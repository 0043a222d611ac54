"""The large-body checker over real HTTP: a stopped child (SIGSTOP) is killed and replaced
after its deadline, and bodies near the body limit never queue in front of smaller ones."""

from __future__ import annotations

import json
import os
import signal
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import httpx2
from mcp_helpers import JSON_HEADERS, http_server, rpc

from verigraph.tools.registry import TOOLS, Toolbox, parse_arguments

TOKEN = "checker-token"
HEADERS = {**JSON_HEADERS, "Authorization": f"Bearer {TOKEN}",
           "MCP-Protocol-Version": "2025-11-25"}


def tower(n: int) -> dict[str, Any]:
    nodes = [{"id": "table", "label": "table"}] + [
        {"id": f"b{i}", "label": "block"} for i in range(n - 1)]
    edges = [{"source": f"b{i}", "relation": "on", "target": f"b{i - 1}" if i else "table"}
             for i in range(n - 1)]
    return {"nodes": nodes, "edges": edges, "dictionary": "blocks"}


PLAN = {"graph": tower(1500), "plan": [f"move(b{i}, on, table)" for i in range(1498, 1398, -1)]}
# Far beyond the node limit and above 4 MiB: the other child checks (and refuses) it.
HUGE = {"graph": {"nodes": [{"id": f"n{i}", "label": "block"} for i in range(150_000)],
                  "edges": []}, "plan": "done"}


def post(url: str, arguments: dict[str, Any], request_id: int = 1) -> httpx2.Response:
    body = rpc("tools/call", {"name": "validate_plan", "arguments": arguments}, request_id)
    return httpx2.post(url, content=body, headers=HEADERS, timeout=40)


def library_answer(arguments: dict[str, Any]) -> dict[str, Any]:
    spec = TOOLS["validate_plan"]
    return json.loads(Toolbox().run(spec, parse_arguments(spec, arguments)).model_dump_json())


def checking_processes(server_pid: int) -> set[int]:
    children = Path(f"/proc/{server_pid}/task/{server_pid}/children").read_text().split()
    return {int(pid) for pid in children
            if b"spawn_main" in Path(f"/proc/{pid}/cmdline").read_bytes()}


def gone(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except FileNotFoundError:
        return True
    return state == "Z"


def wait_until(condition: Callable[[], bool], what: str) -> None:
    deadline = time.monotonic() + 30  # only so that a broken server fails the test
    while not condition():
        assert time.monotonic() < deadline, what
        time.sleep(0.05)


def test_a_stopped_checker_is_killed_and_replaced_after_its_deadline() -> None:
    with http_server(token=TOKEN, extra=["--check-seconds", "2"]) as running:
        assert post(running.url, PLAN).status_code == 200
        [child] = checking_processes(running.proc.pid)
        os.kill(child, signal.SIGSTOP)
        try:
            response = post(running.url, PLAN, request_id=41)
        finally:
            if not gone(child):
                os.kill(child, signal.SIGCONT)
        assert response.status_code == 503
        assert response.headers["retry-after"] == "1"
        error = response.json()["error"]
        assert response.json()["id"] == 41
        assert "within 2 s" in error["message"] and "send the request again" in error["message"]
        wait_until(lambda: gone(child), "the stopped checking process was not killed")
        reply = post(running.url, PLAN).json()
        assert reply["result"]["structuredContent"] == library_answer(PLAN)
        assert checking_processes(running.proc.pid) - {child}


def test_a_smaller_large_call_does_not_wait_for_a_huge_one() -> None:
    """With the child for huge bodies stopped, a 100 KB call is still answered, well
    before that child's deadline would have let it through."""
    with http_server(token=TOKEN, extra=["--check-seconds", "120"]) as running:
        refused = post(running.url, HUGE).json()["result"]
        assert refused["isError"] is True and "at most 5000 nodes" in refused["content"][0]["text"]
        [huge_child] = checking_processes(running.proc.pid)
        assert post(running.url, PLAN).status_code == 200
        assert len(checking_processes(running.proc.pid)) == 2
        os.kill(huge_child, signal.SIGSTOP)
        try:
            reply = post(running.url, PLAN).json()  # the client gives up after 40 s
        finally:
            os.kill(huge_child, signal.SIGCONT)
        assert reply["result"]["structuredContent"] == library_answer(PLAN)
        assert post(running.url, HUGE).json()["result"]["isError"] is True
