"""Large tool calls over real HTTP: parsed and serialised off the event loop (offload),
with answers equal to the library's, on both protocol eras and on the SDK's own path."""

from __future__ import annotations

import json
import os
import signal
from collections.abc import Iterator
from typing import Any

import anyio
import httpx2
import pytest
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import CallToolResult
from mcp_helpers import (
    JSON_HEADERS,
    RunningServer,
    checking_processes,
    free_port,
    http_in_thread,
    http_server,
    process_gone,
    rpc,
    structured,
    tower_graph,
    wait_until,
)

from verigraph.server.http import HttpOptions
from verigraph.server.http.offload import (
    DEFAULT_THRESHOLD_BYTES,
    PLACEHOLDER_KEY,
    CallSlot,
)
from verigraph.tools.registry import TOOLS, Toolbox, parse_arguments

TOKEN = "large-calls-token"
AUTH = {"Authorization": f"Bearer {TOKEN}"}
LEGACY = "2025-11-25"


@pytest.fixture(scope="module")
def server() -> Iterator[RunningServer]:
    with http_server(token=TOKEN) as running:
        yield running


@pytest.fixture()
def url(server: RunningServer) -> str:
    return server.url


def unstack(n: int, moves: int) -> list[str]:
    return [f"move(b{i}, on, table)" for i in range(n - 2, n - 2 - moves, -1)]


def library_answer(tool: str, arguments: dict[str, Any]) -> dict[str, Any]:
    spec = TOOLS[tool]
    result = Toolbox().run(spec, parse_arguments(spec, arguments))
    return json.loads(result.model_dump_json())


LARGE_PLAN = {"graph": tower_graph(2000), "plan": unstack(2000, 600)}


def test_the_request_is_large_and_so_is_the_answer() -> None:
    assert len(json.dumps(LARGE_PLAN)) > DEFAULT_THRESHOLD_BYTES
    assert len(json.dumps(library_answer("validate_plan", LARGE_PLAN))) > 16 * 1024


def test_sdk_client_gets_the_library_s_answer(url: str) -> None:
    async def call() -> CallToolResult:
        async with httpx2.AsyncClient(headers=AUTH, timeout=60) as http, \
                Client(streamable_http_client(url, http_client=http)) as client:
            return await client.call_tool("validate_plan", LARGE_PLAN)

    result = anyio.run(call)
    assert not result.is_error
    assert structured(result) == library_answer("validate_plan", LARGE_PLAN)
    assert "valid" in result.content[0].text.lower()


def legacy_call(url: str, name: str, arguments: dict[str, Any]) -> httpx2.Response:
    body = rpc("tools/call", {"name": name, "arguments": arguments}, request_id=7)
    headers = {**JSON_HEADERS, **AUTH, "MCP-Protocol-Version": LEGACY}
    return httpx2.post(url, content=body, headers=headers, timeout=60)


def test_a_2025_era_client_gets_the_library_s_answer(url: str) -> None:
    response = legacy_call(url, "validate_plan", LARGE_PLAN)
    assert response.status_code == 200
    assert int(response.headers["content-length"]) == len(response.content)
    reply = response.json()
    assert reply["id"] == 7
    assert reply["result"]["structuredContent"] == library_answer("validate_plan", LARGE_PLAN)


@pytest.fixture()
def offloaded(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The sizes of the results a server in this process spliced in as bytes."""
    sizes: list[int] = []

    keep = CallSlot.keep

    def spying(slot: CallSlot, result: Any) -> dict[str, Any] | None:
        placeholder = keep(slot, result)
        if placeholder is not None:
            sizes.append(len(slot.structured or b""))
        return placeholder

    monkeypatch.setattr(CallSlot, "keep", spying)
    return sizes


@pytest.mark.parametrize("era", ["2026-07-28", LEGACY])
def test_the_answer_was_spliced_in_on_both_eras(era: str, offloaded: list[int]) -> None:
    with http_in_thread(Toolbox(), HttpOptions(port=free_port(), tokens=(TOKEN,))) as here:
        body = rpc("tools/call", {"name": "validate_plan", "arguments": LARGE_PLAN}, 3)
        headers = {**JSON_HEADERS, **AUTH, "MCP-Protocol-Version": era}
        if era != LEGACY:
            body = wire_call(body, era)
            headers |= {"Mcp-Method": "tools/call", "Mcp-Name": "validate_plan"}
        response = httpx2.post(here, content=body, headers=headers, timeout=60)
    assert response.status_code == 200, response.text[:300]
    answer = response.json()["result"]["structuredContent"]
    assert answer == library_answer("validate_plan", LARGE_PLAN)
    assert len(offloaded) == 1 and offloaded[0] > 16 * 1024


def wire_call(body: bytes, era: str) -> bytes:
    """A 2026-07-28 request carries the client's identity in `_meta`."""
    message = json.loads(body)
    message["params"]["_meta"] = {
        "io.modelcontextprotocol/protocolVersion": era,
        "io.modelcontextprotocol/clientInfo": {"name": "test", "version": "0"},
        "io.modelcontextprotocol/clientCapabilities": {}}
    return json.dumps(message).encode()


def test_a_large_call_with_a_bad_argument_names_the_field(url: str) -> None:
    response = legacy_call(url, "validate_plan", {**LARGE_PLAN, "plan": 42})
    result = response.json()["result"]
    assert result["isError"] is True
    assert "plan" in result["content"][0]["text"]
    assert PLACEHOLDER_KEY not in response.text


def test_a_confirmed_tool_gets_its_large_arguments_back() -> None:
    """execute_actions goes through the SDK's own path (it may ask the user first): the
    arguments taken out of the body are put back for it. Its arguments are never 64 KiB
    (at most 50 short actions), so this server offloads every body above 1 KiB."""
    options = HttpOptions(port=free_port(), tokens=(TOKEN,), large_call_bytes=1024)
    with http_in_thread(Toolbox(), options) as small_threshold_url:
        loaded = legacy_call(small_threshold_url, "load_scene",
                             {"graph": tower_graph(100), "k": 50})
        episode = loaded.json()["result"]["structuredContent"]["episode_id"]
        arguments = {"episode_id": episode, "actions": unstack(100, 50)}
        assert len(json.dumps(arguments)) > 1024
        result = legacy_call(small_threshold_url, "execute_actions", arguments).json()["result"]
        assert result.get("isError") is not True, result
        assert len(result["structuredContent"]["executed"]) == 50
        state = legacy_call(small_threshold_url, "get_state", {"episode_id": episode}).json()
    edges = state["result"]["structuredContent"]["graph"]["edges"]
    assert sum(e["target"] == "table" for e in edges) == 51


def test_execute_actions_without_an_arm_answers_large_results_too(offloaded: list[int]
                                                                  ) -> None:
    """execute_actions on an episode with no arm asks nothing, so the server answers it
    itself and its large answer (the whole new graph) is spliced in like any other."""
    with http_in_thread(Toolbox(), HttpOptions(port=free_port(), tokens=(TOKEN,))) as here:
        loaded = legacy_call(here, "load_scene", {"graph": tower_graph(2000)}).json()
        episode = loaded["result"]["structuredContent"]["episode_id"]
        offloaded.clear()
        response = legacy_call(here, "execute_actions", {"episode_id": episode,
                                                         "actions": unstack(2000, 1)})
    assert len(offloaded) == 1 and offloaded[0] > 16 * 1024
    assert PLACEHOLDER_KEY not in response.text
    result = response.json()["result"]
    assert result.get("isError") is not True, str(result)[:300]
    assert result["structuredContent"]["executed"] == unstack(2000, 1)


def test_the_viewer_s_tool_gets_its_large_arguments_too() -> None:
    """view_episode (the MCP Apps viewer's tool, outside the tool registry) goes through
    the SDK's path as well; this server offloads every body above 1 KiB."""
    arguments = {"graph": tower_graph(30), "plan": unstack(30, 20)}
    assert len(json.dumps(arguments)) > 1024
    options = HttpOptions(port=free_port(), tokens=(TOKEN,), large_call_bytes=1024)
    with http_in_thread(Toolbox(), options) as small_threshold_url:
        result = legacy_call(small_threshold_url, "view_episode", arguments).json()["result"]
    assert result.get("isError") is not True, str(result)[:300]
    steps = result["structuredContent"]["steps"]
    assert len(steps) == 20 and all(step["ok"] for step in steps)


def test_the_viewer_s_tool_gets_the_checking_process_s_argument_error() -> None:
    options = HttpOptions(port=free_port(), tokens=(TOKEN,), large_call_bytes=1024)
    with http_in_thread(Toolbox(), options) as small_threshold_url:
        result = legacy_call(small_threshold_url, "view_episode",
                             {"graph": tower_graph(30), "plan": unstack(30, 20),
                              "colour": "x" * 2000}).json()["result"]
    assert result["isError"] is True
    assert result["content"][0]["text"].startswith("Error executing tool view_episode: ")
    assert "colour" in result["content"][0]["text"]


def test_a_large_body_for_another_method_is_refused_by_name(url: str) -> None:
    body = rpc("prompts/get", {"name": "plan_episode", "arguments": {"x": "y" * 100_000}})
    response = httpx2.post(url, content=body, headers={**JSON_HEADERS, **AUTH}, timeout=60)
    assert response.status_code == 413
    error = response.json()["error"]
    assert error["code"] == -32600 and "'prompts/get'" in error["message"]
    assert response.json()["id"] == 1


def test_a_large_batch_is_refused_too(url: str) -> None:
    body = json.dumps([json.loads(rpc("ping", request_id=i)) for i in range(3000)]).encode()
    assert len(body) > DEFAULT_THRESHOLD_BYTES
    response = httpx2.post(url, content=body, headers={**JSON_HEADERS, **AUTH}, timeout=60)
    assert response.status_code == 413
    assert "no single request" in response.json()["error"]["message"]


def test_a_large_body_that_is_not_json_gets_the_parse_error(url: str) -> None:
    body = b'{"jsonrpc": "2.0", "id": 1, "method": "tools/call", "params": ' + b"[" * 1 \
        + b"1," * 50_000
    response = httpx2.post(url, content=body, headers={**JSON_HEADERS, **AUTH}, timeout=60)
    assert response.status_code == 400
    assert response.json()["error"]["code"] == -32700


def test_an_oversized_graph_is_refused_by_the_checking_process(url: str) -> None:
    nodes = [{"id": f"n{i}", "label": "block"} for i in range(100_000)]
    response = legacy_call(url, "validate_plan", {"graph": {"nodes": nodes, "edges": []},
                                                  "plan": "done"})
    result = response.json()["result"]
    assert result["isError"] is True
    assert "graph: " in result["content"][0]["text"]
    assert "at most 5000 nodes" in result["content"][0]["text"]


def test_a_body_beyond_the_memory_budget_is_refused_and_the_child_dies_with_the_server(
        ) -> None:
    with http_server(token=TOKEN, extra=["--tool-mib", "64"]) as running:
        nodes = [{"id": f"n{i}", "label": "block"} for i in range(400_000)]
        response = legacy_call(running.url, "validate_plan",
                               {"graph": {"nodes": nodes, "edges": []}, "plan": "done"})
        assert response.status_code == 413
        assert "needs more memory to parse" in response.json()["error"]["message"]
        children = checking_processes(running.proc.pid)
        assert len(children) == 1
        running.proc.kill()  # no chance to clean up: the kernel takes the child along
        running.proc.wait()
        wait_until(lambda: process_gone(children[0]), "the checking process outlived the server")


def test_a_checking_process_that_dies_is_replaced(server: RunningServer) -> None:
    assert legacy_call(server.url, "validate_plan", LARGE_PLAN).status_code == 200
    [child] = checking_processes(server.proc.pid)
    os.kill(child, signal.SIGKILL)
    wait_until(lambda: process_gone(child), "the checking process did not die")
    reply = legacy_call(server.url, "validate_plan", LARGE_PLAN).json()
    assert reply["result"]["structuredContent"] == library_answer("validate_plan", LARGE_PLAN)
    assert checking_processes(server.proc.pid) not in ([], [child])


def test_the_splice_replaces_only_its_own_placeholder() -> None:
    slot = CallSlot(structured=b'{"big":[1,2,3]}')
    mine = json.dumps({"result": {"structuredContent": slot.placeholder()}}).encode()
    assert slot.splice(mine) == b'{"result": {"structuredContent": {"big":[1,2,3]}}}'
    other = json.dumps({"result": {"structuredContent": CallSlot().placeholder()}}).encode()
    assert slot.splice(other) is None
    assert CallSlot().splice(mine) is None  # nothing serialised: nothing to put in
