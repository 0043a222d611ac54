"""The viewer link in both forms the MCP Apps extension defines: the nested
`_meta.ui.resourceUri` and the flat, deprecated `_meta["ui/resourceUri"]` that some
hosts still read alone; neither reaches clients without the extension."""

from __future__ import annotations

import pytest
from mcp import Client
from mcp.client.extension import advertise
from mcp_helpers import text

from verigraph.server import build_server
from verigraph.server.apps import EPISODE_UI, FLAT_UI_KEY, UI_TOOLS

pytestmark = [pytest.mark.fast, pytest.mark.anyio]


async def test_hosts_find_the_viewer_under_both_keys() -> None:
    ui = advertise("io.modelcontextprotocol/ui", {"mimeTypes": ["text/html;profile=mcp-app"]})
    async with Client(build_server(), extensions=[ui]) as c:
        tools = {t.name: t for t in (await c.list_tools()).tools}
        assert set(UI_TOOLS) == {"execute_actions", "validate_plan", "render_scene",
                                 "get_state"}
        for name in UI_TOOLS:
            meta = tools[name].meta or {}
            assert meta["ui"]["resourceUri"] == EPISODE_UI
            assert meta[FLAT_UI_KEY] == EPISODE_UI == "ui://verigraph/episode"
        assert FLAT_UI_KEY not in (tools["view_episode"].meta or {})  # app-only: nested only


async def test_clients_without_the_extension_see_neither_key() -> None:
    async with Client(build_server()) as c:
        tools = (await c.list_tools()).tools
        assert all(t.meta is None for t in tools)
        state = await c.call_tool("load_scene", {"scene_id": "cup_on_book"})
        assert "episode" in text(state)
