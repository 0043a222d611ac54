"""Request ids against a real `verigraph serve` (HTTP on loopback, and stdio): an id too
long to echo is refused for its id, naming the field and the limit, on a large body and
a small one, whatever the method; ids up to the limit are echoed as sent."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import httpx2
import pytest
from mcp_helpers import JSON_HEADERS, RawStdio, http_server

from verigraph.server.rpc_errors import MAX_ID_CHARS

LEGACY = "2025-11-25"
CALL = {"name": "load_scene", "arguments": {"scene_id": "cup_on_book"}}


@pytest.fixture(scope="module")
def url() -> Iterator[str]:
    with http_server(extra=["--store", "memory://"]) as running:
        yield running.url


def post(url: str, request_id: Any, method: str = "tools/call",
         params: dict[str, Any] | None = None) -> httpx2.Response:
    body = json.dumps({"jsonrpc": "2.0", "id": request_id, "method": method,
                       "params": CALL if params is None else params})
    return httpx2.post(url, content=body, timeout=60,
                       headers={**JSON_HEADERS, "MCP-Protocol-Version": LEGACY})


def assert_refused_for_its_id(message: str, length: int) -> None:
    assert f"{length} characters" in message and f"at most {MAX_ID_CHARS}" in message
    assert "field: id" in message and "tools/call arguments" not in message


@pytest.mark.parametrize("length", [70_000, MAX_ID_CHARS + 1])  # a large body, a small one
@pytest.mark.parametrize("method", ["tools/call", "tools/list", "ping"])
def test_a_long_id_is_refused_for_its_id(url: str, length: int, method: str) -> None:
    response = post(url, "i" * length, method, None if method == "tools/call" else {})
    reply = response.json()
    assert "result" not in reply
    assert_refused_for_its_id(reply["error"]["message"], length)


def test_an_id_at_the_limit_is_echoed(url: str) -> None:
    request_id = "i" * MAX_ID_CHARS
    reply = post(url, request_id).json()
    assert reply["id"] == request_id and reply["result"]["structuredContent"]["episode_id"]


def test_stdio_refuses_a_long_id_too() -> None:
    server = RawStdio("--store", "memory://")
    try:
        server.initialize()
        server.send(json.dumps({"jsonrpc": "2.0", "id": "s" * (MAX_ID_CHARS + 5),
                                "method": "tools/call", "params": CALL}))
        assert_refused_for_its_id(server.reply()["error"]["message"], MAX_ID_CHARS + 5)
        server.still_serving()
    finally:
        server.close()


@pytest.mark.parametrize(("params", "named"), [
    ({"name": "n" * 70_000, "arguments": {}}, "params.name"),
    ({"name": "load_scene", "arguments": {"scene_id": "cup_on_book"},
      "_meta": {"note": "m" * 70_000}}, "params._meta"),
])
def test_a_large_tools_call_names_the_field_that_is_not_its_arguments(
        url: str, params: dict[str, Any], named: str) -> None:
    reply = post(url, 5, params=params).json()
    message = reply["error"]["message"]
    assert reply["id"] == 5 and f"its field {named} is" in message
    assert f"send a shorter {named}" in message


def test_large_tools_call_arguments_that_are_no_object_are_named(url: str) -> None:
    reply = post(url, 6, params={"name": "load_scene", "arguments": ["x" * 70_000]}).json()
    assert "params.arguments must be an object" in reply["error"]["message"]


def test_stdio_does_not_echo_a_long_id_of_a_line_it_cannot_accept() -> None:
    server = RawStdio("--store", "memory://")
    try:
        server.initialize()
        server.send(json.dumps({"jsonrpc": "2.0", "id": "s" * 100_000, "method": "tools/call",
                                "params": {"name": "\ud800"}}))  # a lone surrogate
        reply = server.reply()
        assert reply["id"] is None
        assert_refused_for_its_id(reply["error"]["message"], 100_000)
        server.still_serving()
    finally:
        server.close()
