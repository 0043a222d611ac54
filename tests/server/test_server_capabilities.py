"""The same capabilities in every protocol era: nothing changes lists or pushes updates.

`initialize` (2025-11-25 and older) and `server/discover` (2026-07-28) must agree; a
client that trusts either must never be told it can subscribe when it cannot.
"""

from __future__ import annotations

import json
import urllib.request

import pytest
from mcp import Client
from mcp_helpers import JSON_HEADERS, http_server, rpc

from verigraph.server import build_server

NOTHING_CHANGES = {"prompts": {"listChanged": False},
                   "resources": {"subscribe": False, "listChanged": False},
                   "tools": {"listChanged": False}}


@pytest.mark.anyio
@pytest.mark.parametrize(("mode", "version"), [("auto", "2026-07-28"),
                                               ("legacy", "2025-11-25")])
async def test_capabilities_agree_across_eras(mode: str, version: str) -> None:
    async with Client(build_server(), mode=mode) as client:  # type: ignore[arg-type]
        assert client.protocol_version == version
        assert client.server_capabilities is not None
        caps = client.server_capabilities.model_dump(by_alias=True, exclude_none=True)
    assert {k: caps[k] for k in NOTHING_CHANGES} == NOTHING_CHANGES


def test_initialize_over_http_says_the_same() -> None:
    with http_server() as server:
        request = urllib.request.Request(server.url, method="POST", headers=JSON_HEADERS,
                                         data=rpc("initialize", {
                                             "protocolVersion": "2025-06-18", "capabilities": {},
                                             "clientInfo": {"name": "t", "version": "1"}}))
        with urllib.request.urlopen(request, timeout=30) as response:
            caps = json.loads(response.read())["result"]["capabilities"]
    assert {k: caps[k] for k in NOTHING_CHANGES} == NOTHING_CHANGES
