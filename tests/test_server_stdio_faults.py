"""Over a real stdio subprocess: every malformed request with an id gets its JSON-RPC
error, oversized messages are refused without being held, and the server keeps serving."""

from __future__ import annotations

import json
import selectors
import subprocess
from collections.abc import Iterator
from typing import Any

import pytest
from mcp_helpers import verigraph_command


class RawStdio:
    """`verigraph serve` over stdio, spoken to line by line."""

    def __init__(self, *extra: str) -> None:
        self.proc = subprocess.Popen([*verigraph_command(), "serve", *extra],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL)
        assert self.proc.stdin is not None and self.proc.stdout is not None
        self.stdin, self.stdout = self.proc.stdin, self.proc.stdout
        self.selector = selectors.DefaultSelector()
        self.selector.register(self.stdout, selectors.EVENT_READ)

    def send(self, line: str | bytes) -> None:
        data = line.encode() if isinstance(line, str) else line
        self.stdin.write(data + b"\n")
        self.stdin.flush()

    def reply(self, timeout: float = 60) -> dict[str, Any]:
        assert self.selector.select(timeout), "no reply from the server"
        return json.loads(self.stdout.readline())

    def initialize(self) -> None:
        self.send(json.dumps({"jsonrpc": "2.0", "id": 0, "method": "initialize", "params": {
            "protocolVersion": "2025-11-25", "capabilities": {},
            "clientInfo": {"name": "raw", "version": "0"}}}))
        assert self.reply()["id"] == 0
        self.send(json.dumps({"jsonrpc": "2.0", "method": "notifications/initialized"}))

    def still_serving(self, request_id: int = 999) -> None:
        self.send(json.dumps({"jsonrpc": "2.0", "id": request_id, "method": "ping"}))
        assert self.reply() == {"jsonrpc": "2.0", "id": request_id, "result": {}}

    def close(self) -> int:
        self.stdin.close()
        return self.proc.wait(timeout=30)


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
