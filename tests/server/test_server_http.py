"""End to end over real streamable HTTP: `verigraph serve --transport http` on a free
loopback port, with the SDK client and raw requests (auth, DNS rebinding, body limit)."""

from __future__ import annotations

import base64
import subprocess
from collections.abc import Iterator
from typing import Any

import anyio
import cv2
import httpx2
import numpy as np
import pytest
from mcp import Client, MCPError
from mcp.client.streamable_http import streamable_http_client
from mcp_helpers import JSON_HEADERS, http_server, rpc, structured, verigraph_command

from verigraph.tools import TOOL_SPECS

TOKEN = "test-token-7f3a"
AUTH = {"Authorization": f"Bearer {TOKEN}"}


@pytest.fixture(scope="module")
def url() -> Iterator[str]:
    with http_server(token=TOKEN) as running:
        yield running.url


def client(url: str, http: httpx2.AsyncClient) -> Client:
    return Client(streamable_http_client(url, http_client=http))


def authed() -> httpx2.AsyncClient:
    return httpx2.AsyncClient(headers=AUTH, timeout=httpx2.Timeout(30, read=60))


@pytest.mark.anyio
async def test_sdk_client_with_the_token(url: str) -> None:
    async with authed() as http, client(url, http) as c:
        assert c.protocol_version == "2026-07-28"
        eid = structured(await c.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
            "episode_id"]
        out = structured(await c.call_tool("execute_actions", {
            "episode_id": eid, "actions": ["move(cup, desk)", "move(book, shelf)"]}))
        assert out["goal_satisfied"] is True
        bad = await c.call_tool("validate_action", {"episode_id": eid, "action": "fly(cup)"})
        assert bad.is_error and "unknown action 'fly'" in bad.content[0].text


def test_missing_or_wrong_token_gets_403(url: str) -> None:
    body = rpc("tools/list")
    for headers in ({}, {"Authorization": "Bearer wrong"}, {"Authorization": TOKEN}):
        response = httpx2.post(url, headers={**JSON_HEADERS, **headers}, content=body)
        assert response.status_code == 403  # not 401: that starts OAuth in MCP clients
        assert "www-authenticate" not in response.headers
        error = response.json()["error"]
        assert error["code"] == -32001 and "Authorization: Bearer <token>" in error["message"]
    ok = httpx2.post(url, headers={**JSON_HEADERS, **AUTH}, content=body)
    assert ok.status_code == 200 and len(ok.json()["result"]["tools"]) == len(TOOL_SPECS)


@pytest.mark.anyio
async def test_sdk_client_without_token_is_refused(url: str) -> None:
    with pytest.raises(BaseException) as caught:  # noqa: B017 - an ExceptionGroup
        async with httpx2.AsyncClient() as http, client(url, http) as c:
            await c.list_tools()
    errors = list(caught.value.exceptions) if isinstance(caught.value, BaseExceptionGroup) \
        else [caught.value]
    flat: list[BaseException] = []
    while errors:
        e = errors.pop()
        if isinstance(e, BaseExceptionGroup):
            errors.extend(e.exceptions)
        else:
            flat.append(e)
    assert any(isinstance(e, MCPError) and e.code == -32001 for e in flat), flat


def test_foreign_host_and_origin_are_rejected(url: str) -> None:
    body = rpc("tools/list")
    foreign = httpx2.post(url, headers={**JSON_HEADERS, **AUTH, "Host": "evil.example:80"},
                          content=body)
    assert foreign.status_code == 421
    origin = httpx2.post(url, headers={**JSON_HEADERS, **AUTH,
                                       "Origin": "http://evil.example"}, content=body)
    assert origin.status_code == 403
    local = httpx2.post(url, headers={**JSON_HEADERS, **AUTH,
                                      "Origin": "http://localhost:1234"}, content=body)
    assert local.status_code == 200


def noisy_png_b64(megabytes: float) -> str:
    side = int((megabytes * 1024 * 1024 / 3) ** 0.5)
    image = np.random.default_rng(0).integers(0, 256, (side, side, 3), dtype=np.uint8)
    ok, buf = cv2.imencode(".png", image)
    assert ok
    return base64.b64encode(buf.tobytes()).decode()


def test_body_limit_fits_images_and_refuses_more(url: str) -> None:
    image = noisy_png_b64(5.5)  # about 7.4 MB of base64: above the SDK's 4 MiB default
    call = rpc("tools/call", {"name": "load_scene", "arguments": {"image": image}})
    assert len(call) > 6 * 1024 * 1024
    accepted = httpx2.post(url, headers={**JSON_HEADERS, **AUTH}, content=call, timeout=60)
    assert accepted.status_code == 200
    assert accepted.json()["result"]["structuredContent"]["awaiting_scene_graph"] is True
    huge = b'{"jsonrpc": "2.0", "id": 1, "method": "tools/list", "pad": "' + \
        b"x" * (17 * 1024 * 1024) + b'"}'
    refused = httpx2.post(url, headers={**JSON_HEADERS, **AUTH}, content=huge, timeout=60)
    assert refused.status_code == 413
    message = refused.json()["error"]["message"]
    assert "at most 16 MiB" in message and "downscale" in message
    after = httpx2.post(url, headers={**JSON_HEADERS, **AUTH}, content=rpc("tools/list"))
    assert after.status_code == 200


@pytest.mark.anyio
async def test_two_clients_episodes_do_not_interfere(url: str) -> None:
    results: dict[str, Any] = {}

    async def agent(name: str, actions: list[str]) -> None:
        async with authed() as http, client(url, http) as c:
            eid = structured(await c.call_tool("load_scene", {"scene_id": "three_blocks"}))[
                "episode_id"]
            for action in actions:
                await c.call_tool("execute_actions", {"episode_id": eid, "actions": [action]})
                await anyio.sleep(0)
            results[name] = (eid, structured(await c.call_tool("get_state",
                                                               {"episode_id": eid})))

    async with anyio.create_task_group() as tg:
        tg.start_soon(agent, "a", ["move(green_block, on, red_block)"] * 3)
        tg.start_soon(agent, "b", ["move(red_block, on, table)", "move(blue_block, red_block)"])
    (eid_a, a), (eid_b, b) = results["a"], results["b"]
    assert eid_a != eid_b
    assert "green_block on red_block" in _sentences(a) and a["executed"] == [
        "move(green_block, on, red_block)"] and a["tau"] == 2  # two already_there repeats
    assert _sentences(b) == {"blue_block on red_block", "green_block on table",
                             "red_block on table"}
    assert b["tau"] == 0 and len(b["executed"]) == 2


def _sentences(state: dict[str, Any]) -> set[str]:
    return {f"{e['source']} {e['relation']} {e['target']}" for e in state["graph"]["edges"]}


def test_http_logs_go_to_stderr_only() -> None:
    with http_server(token=TOKEN, extra=["--log-level", "INFO"]) as running:
        body = rpc("tools/call", {"name": "get_state", "arguments": {"episode_id": "ep_x"}})
        reply = httpx2.post(running.url, headers={**JSON_HEADERS, **AUTH}, content=body)
        assert reply.json()["result"]["isError"] is True
        out, err = running.stop()
    assert out == b""
    assert b"VeriGraph MCP server on http://127.0.0.1:" in err
    assert b"Tool 'get_state' failed" in err


def test_non_loopback_bind_needs_a_token() -> None:
    done = subprocess.run([*verigraph_command(), "serve", "--transport", "http", "--host",
                           "0.0.0.0", "--port", "1"], capture_output=True, text=True,
                          timeout=60, env={"PATH": "/usr/bin:/bin"})
    assert done.returncode == 2
    assert "refusing to serve on 0.0.0.0 without a token" in done.stderr
    assert done.stdout == ""


def test_each_client_s_own_token_is_accepted_and_counted_apart() -> None:
    """`--token` repeated: every listed token is accepted, any other refused, and each
    token is a client of its own for the per-client limits: with 2 event streams per
    client, the first token's third stream is refused while the second token, on the
    same address, still opens one."""
    second = "second-client-token"
    with http_server(token=TOKEN, extra=["--token", second, "--streams-per-client", "2"]
                     ) as running, httpx2.Client(timeout=30) as http:
        for token, status in ((TOKEN, 200), (second, 200), ("third", 403)):
            answer = http.post(running.url, content=rpc("tools/list"), headers={
                **JSON_HEADERS, "Authorization": f"Bearer {token}"})
            assert answer.status_code == status, (token, answer.text[:200])

        def stream(token: str) -> Any:
            return http.stream("GET", running.url, headers={
                "Accept": "text/event-stream", "Authorization": f"Bearer {token}",
                "MCP-Protocol-Version": "2025-11-25"})

        with stream(TOKEN) as a1, stream(TOKEN) as a2, stream(TOKEN) as a3, \
                stream(second) as b1:
            assert [a1.status_code, a2.status_code, b1.status_code] == [200, 200, 200]
            assert a3.status_code == 429 and b"already has 2 open" in a3.read()


def test_a_blank_token_is_refused_at_start() -> None:
    done = subprocess.run([*verigraph_command(), "serve", "--transport", "http", "--port",
                           "1", "--token", " "], capture_output=True, text=True, timeout=60,
                          env={"PATH": "/usr/bin:/bin"})
    assert done.returncode == 2 and "--token" in done.stderr and "Traceback" not in done.stderr
