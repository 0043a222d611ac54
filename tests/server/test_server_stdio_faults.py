"""Over a real stdio subprocess: every malformed request with an id gets its JSON-RPC
error, oversized messages are refused without being held, and the server keeps serving."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import pytest
from mcp_helpers import RawStdio


@pytest.fixture(scope="module")
def server() -> Iterator[RawStdio]:
    raw = RawStdio("--max-body-mib", "0.0625")
    raw.initialize()
    yield raw
    assert raw.close() == 0


def call(request_id: Any, params: Any) -> str:
    return json.dumps({"jsonrpc": "2.0", "id": request_id, "method": "tools/call",
                       "params": params})


DEEP = ('{"jsonrpc": "2.0", "id": 7, "method": "tools/call", "params": {"name": "get_state", '
        '"arguments": {"episode_id": ' + "[" * 5000 + "]" * 5000 + "}}}")
SURROGATE = ('{"jsonrpc": "2.0", "id": 8, "method": "tools/call", "params": {"name": '
             '"validate_action", "arguments": {"episode_id": "\\ud800", "action": "done"}}}')

CASES = [
    ("parse error", '{"jsonrpc": "2.0", "id": 1, "method": ', 1, -32700),
    ("not JSON at all", "hello", None, -32700),
    ("params of the wrong type", call(2, [1, 2]), 2, -32602),
    ("params with wrong member types", call(3, {"name": 5, "arguments": "x"}), 3, -32602),
    ("null params", call(4, None), 4, -32602),
    ("null message", "null", None, -32600),
    ("a number", "42", None, -32600),
    ("empty batch", "[]", None, -32600),
    ("id of the wrong type", json.dumps({"jsonrpc": "2.0", "id": True, "method": "ping"}),
     None, -32600),
    ("no method", json.dumps({"jsonrpc": "2.0", "id": 5}), 5, -32600),
    ("wrong jsonrpc version", json.dumps({"jsonrpc": "1.0", "id": 6, "method": "ping"}), 6,
     -32600),
    ("deep nesting", DEEP, 7, -32600),
    ("lone surrogate", SURROGATE, 8, -32602),
    ("string id survives", call("req-9", 17), "req-9", -32602),
]


@pytest.mark.parametrize("line,request_id,code", [c[1:] for c in CASES],
                         ids=[c[0] for c in CASES])
def test_each_malformed_request_gets_its_error(server: RawStdio, line: str, request_id: Any,
                                               code: int) -> None:
    server.send(line)
    reply = server.reply()
    assert reply["id"] == request_id
    assert reply["error"]["code"] == code
    assert reply["error"]["message"]
    server.still_serving()


def test_a_batch_gets_one_error_per_request(server: RawStdio) -> None:
    server.send(json.dumps([{"jsonrpc": "2.0", "id": 21, "method": "ping"},
                            {"jsonrpc": "2.0", "method": "notifications/initialized"},
                            {"jsonrpc": "2.0", "id": 22, "method": "tools/list"}]))
    replies = [server.reply(), server.reply()]
    assert [r["id"] for r in replies] == [21, 22]
    assert all("batches are not supported" in r["error"]["message"] for r in replies)
    server.still_serving()


def test_a_malformed_notification_gets_no_reply(server: RawStdio) -> None:
    server.send(json.dumps({"jsonrpc": "2.0", "method": 12}))
    server.still_serving(31)  # the next line on stdout is the ping's reply


def test_a_message_above_the_limit_is_refused_with_its_id(server: RawStdio) -> None:
    big = json.dumps({"jsonrpc": "2.0", "id": 41, "method": "tools/call", "params": {
        "name": "load_scene", "arguments": {"graph": {"nodes": [
            {"id": "table", "label": "table", "attrs": {"note": "x" * 200_000}}]}}}})
    server.send(big)
    reply = server.reply()
    assert reply["id"] == 41 and reply["error"]["code"] == -32600
    assert "at most 0.0625 MiB" in reply["error"]["message"]
    server.still_serving()


def test_a_huge_node_attribute_is_refused_with_a_structured_error() -> None:
    raw = RawStdio()  # default limits: the 15 MB message itself is allowed in
    try:
        raw.initialize()
        raw.send(call(51, {"name": "load_scene", "arguments": {"graph": {"nodes": [
            {"id": "table", "label": "table", "attrs": {"note": "x" * 15_000_000}}]}}}))
        reply = raw.reply()
        assert reply["id"] == 51 and reply["result"]["isError"] is True
        message = reply["result"]["content"][0]["text"]
        assert "nodes[0].attrs" in message and "at most 4096 bytes" in message
        raw.still_serving()
    finally:
        assert raw.close() == 0
