"""End to end over real stdio: `verigraph serve` as a subprocess, the SDK's stdio client."""

from __future__ import annotations

import json
import subprocess
import tempfile
from typing import Any

import pytest
from mcp import Client, StdioServerParameters, stdio_client
from mcp_helpers import decode_png, structured, text, verigraph_command

from verigraph.tools import TOOL_SPECS

pytestmark = pytest.mark.anyio


def params(*extra: str) -> StdioServerParameters:
    cmd = verigraph_command()
    return StdioServerParameters(command=cmd[0], args=[*cmd[1:], "serve", *extra])


async def test_a_whole_session_over_stdio() -> None:
    with tempfile.TemporaryFile("w+") as errlog:
        async with Client(stdio_client(params("--log-level", "INFO"), errlog=errlog)) as c:
            assert c.protocol_version == "2026-07-28"
            names = [t.name for t in (await c.list_tools()).tools]
            assert names == [s.name for s in TOOL_SPECS]
            eid = structured(await c.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
                "episode_id"]
            check = structured(await c.call_tool("validate_action", {
                "episode_id": eid, "action": "move(book, on, shelf)"}))
            assert check["violation"]["constraint"] == "object_not_clear"
            ran = structured(await c.call_tool("execute_actions", {
                "episode_id": eid, "actions": ["move(cup, desk)", "move(book, shelf)", "done"]}))
            assert ran["goal_satisfied"] and ran["done"]
            image = await c.call_tool("render_scene", {"episode_id": eid, "width": 160,
                                                       "height": 120})
            assert decode_png(image.content[0].data).shape == (120, 160, 3)
            graph = json.loads((await c.read_resource(
                f"verigraph://episodes/{eid}/graph")).contents[0].text)
            assert {"source": "book", "relation": "on", "target": "shelf"}.items() <= \
                graph["edges"][0].items()
            prompt = await c.get_prompt("iterative_planner", {"episode_id": eid})
            assert "- book on shelf" in prompt.messages[0].content.text
            failed = await c.call_tool("get_state", {"episode_id": "ep_gone"})
            assert failed.is_error and "no open episode" in text(failed)
            verdict = structured(await c.call_tool("end_episode", {"episode_id": eid}))
            assert verdict["success"] is True
        errlog.seek(0)
        logged = errlog.read()
    # Logs went to stderr (the protocol on stdout stayed clean, or the client would fail).
    assert "Tool 'get_state' failed" in logged and "no open episode" in logged


def test_garbage_on_stdin_does_not_stop_the_server() -> None:
    proc = subprocess.Popen([*verigraph_command(), "serve"], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    stdin, stdout = proc.stdin, proc.stdout
    assert stdin is not None and stdout is not None

    def send(message: Any) -> None:
        line = message if isinstance(message, str) else json.dumps(message)
        stdin.write(line.encode() + b"\n")
        stdin.flush()

    try:
        send("this is not JSON-RPC")
        parse_error = json.loads(stdout.readline())
        assert parse_error["id"] is None and parse_error["error"]["code"] == -32700
        send({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {
            "protocolVersion": "2025-11-25", "capabilities": {},
            "clientInfo": {"name": "raw", "version": "0"}}})
        init = json.loads(stdout.readline())
        assert init["id"] == 1 and init["result"]["serverInfo"]["name"] == "verigraph"
        send({"jsonrpc": "2.0", "method": "notifications/initialized"})
        send({"jsonrpc": "2.0", "id": 2, "method": "tools/call", "params": {
            "name": "validate_plan", "arguments": {"scene_id": "cup_on_book",
                                                   "plan": "move(cup, desk)"}}})
        reply = json.loads(stdout.readline())
        assert reply["id"] == 2 and reply["result"]["structuredContent"]["plan_valid"] is True
    finally:
        stdin.close()
        proc.wait(timeout=10)
    assert proc.returncode == 0
