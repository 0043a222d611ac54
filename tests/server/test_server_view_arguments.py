"""view_episode takes the same argument path as every tool (ToolCalls): unknown or
over-long arguments are refused with the field and the fix at any body size, over a
real SDK client; and a large body that is not usable JSON gets the parse error with
where it went wrong."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import anyio
import httpx2
import pytest
from mcp import Client
from mcp.client.extension import advertise
from mcp.client.streamable_http import streamable_http_client
from mcp.types import CallToolResult
from mcp_helpers import JSON_HEADERS, free_port, http_in_thread, structured, text, tower_graph

from verigraph.server import build_server
from verigraph.server.http import HttpOptions
from verigraph.server.http.offload import DEFAULT_THRESHOLD_BYTES
from verigraph.tools import Toolbox

TOKEN = "view-arguments-token"
AUTH = {"Authorization": f"Bearer {TOKEN}"}
APPS = advertise("io.modelcontextprotocol/ui", {"mimeTypes": ["text/html;profile=mcp-app"]})


LARGE_GRAPH = tower_graph(1500)
assert len(json.dumps(LARGE_GRAPH)) > DEFAULT_THRESHOLD_BYTES


@pytest.fixture(scope="module")
def url() -> Iterator[str]:
    with http_in_thread(Toolbox(), HttpOptions(port=free_port(), tokens=(TOKEN,))) as here:
        yield here


def over_http(url: str, arguments: dict[str, Any]) -> CallToolResult:
    async def call() -> CallToolResult:
        async with httpx2.AsyncClient(headers=AUTH, timeout=60) as http, \
                Client(streamable_http_client(url, http_client=http),
                       extensions=[APPS]) as client:
            return await client.call_tool("view_episode", arguments)

    return anyio.run(call)


def in_memory(arguments: dict[str, Any]) -> CallToolResult:
    async def call() -> CallToolResult:
        async with Client(build_server(Toolbox()), extensions=[APPS]) as client:
            return await client.call_tool("view_episode", arguments)

    return anyio.run(call)


def refusal(result: CallToolResult) -> str:
    assert result.is_error, text(result)[:300]
    message = text(result)
    assert message.startswith("Error executing tool view_episode: invalid arguments"), message
    assert len(message) < 1000, "the reason, not the value echoed back"
    return message


def test_an_unknown_argument_is_refused_in_a_small_body() -> None:
    message = refusal(in_memory({"scene_id": "three_blocks", "plan": "done", "goall": {}}))
    assert "goall: unknown argument" in message and "did you mean 'goal'" in message


def test_an_unknown_argument_is_refused_in_a_small_http_body(url: str) -> None:
    message = refusal(over_http(url, {"scene_id": "three_blocks", "plan": "done",
                                      "goall": {}}))
    assert "goall: unknown argument" in message and "did you mean 'goal'" in message


def test_an_unknown_argument_is_refused_in_a_large_body(url: str) -> None:
    message = refusal(over_http(url, {"graph": LARGE_GRAPH, "plan": "done", "goall": {}}))
    assert "goall: unknown argument" in message and "did you mean 'goal'" in message


@pytest.mark.parametrize("field", ["episode_id", "scene_id"])
@pytest.mark.parametrize("size", ["small", "large"])
def test_an_over_long_id_gets_its_field_and_limit(url: str, field: str, size: str) -> None:
    arguments: dict[str, Any] = {field: "x" * 5000, "plan": "done"}
    if size == "large":
        arguments = {**arguments, "goal": {"graph": LARGE_GRAPH, "partial": True}}
        assert len(json.dumps(arguments)) > DEFAULT_THRESHOLD_BYTES
    message = refusal(over_http(url, arguments))
    assert f"{field}: " in message and "at most 64 characters" in message, message
    assert "validation error" not in message and "view_episodeArguments" not in message


def test_the_same_arguments_without_the_typo_are_shown(url: str) -> None:
    out = structured(over_http(url, {"graph": LARGE_GRAPH, "plan": "move(b1498, on, table)"}))
    assert [step["ok"] for step in out["steps"]] == [True]


@pytest.mark.parametrize(("body", "reason"), [
    (b'{"jsonrpc": "2.0", "id": 9, "method": "tools/call", "params": '
     + b"[" * 100_000, "nesting too deep at line 1 column "),
    (b'{"jsonrpc": "2.0", "id": 9, "method": "tools/call", "params": {"name": '
     b'"validate_plan", "arguments": {"plan": ' + b'{"a": ' * 40_000, "nesting too deep at "),
    (b'{"jsonrpc": "2.0", "id": 9, "method": "tools/call", "params": ' + b"1," * 50_000,
     "at line 1 column 65"),
])
def test_a_large_body_that_is_not_usable_json_gets_the_parse_error_with_where(
        url: str, body: bytes, reason: str) -> None:
    assert len(body) > DEFAULT_THRESHOLD_BYTES
    response = httpx2.post(url, content=body, headers={**JSON_HEADERS, **AUTH}, timeout=60)
    assert response.status_code == 400, response.text[:300]
    error = response.json()["error"]
    assert error["code"] == -32700
    assert error["message"].startswith("Parse error: ") and reason in error["message"], error
    assert "EOF while parsing" not in error["message"]
    assert response.json()["id"] == 9
