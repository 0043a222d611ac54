"""The MCP Apps extension over the SDK client: advertised only to clients that declare it,
the ui:// resource with an empty CSP allow-list, and the app-only view tool."""

from __future__ import annotations

import pytest
from mcp import Client
from mcp_helpers import APP_MIME, apps_client, structured

from verigraph.server import build_server
from verigraph.server.apps import EPISODE_UI, UI_TOOLS


@pytest.mark.anyio
async def test_clients_with_the_extension_get_the_links_resource_and_view_tool() -> None:
    async with apps_client() as c:
        tools = {t.name: t for t in (await c.list_tools()).tools}
        for name in UI_TOOLS:
            assert (tools[name].meta or {})["ui"]["resourceUri"] == EPISODE_UI
        assert (tools["view_episode"].meta or {})["ui"]["visibility"] == ["app"]
        assert tools["load_scene"].meta is None
        listed = {str(r.uri): r for r in (await c.list_resources()).resources}
        assert listed[EPISODE_UI].mime_type == APP_MIME
        content = (await c.read_resource(EPISODE_UI)).contents[0]
        assert content.mime_type == APP_MIME
        assert content.meta is not None
        csp = content.meta["ui"]["csp"]
        assert csp == {"connectDomains": [], "resourceDomains": [], "frameDomains": [],
                       "baseUriDomains": []}
        html = getattr(content, "text", "")
        assert html.startswith("<!DOCTYPE html>") and "ui/initialize" in html
        assert "src=\"http" not in html and "href=\"http" not in html  # nothing fetched


@pytest.mark.anyio
async def test_clients_without_it_see_nothing_of_it_and_get_the_same_content() -> None:
    async with Client(build_server()) as c:
        tools = (await c.list_tools()).tools
        assert "view_episode" not in {t.name for t in tools}
        assert all(t.meta is None for t in tools)
        assert not [r for r in (await c.list_resources()).resources
                    if str(r.uri).startswith("ui://")]
        eid = structured(await c.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
            "episode_id"]
        image = await c.call_tool("render_scene", {"episode_id": eid})
        assert [b.type for b in image.content] == ["image", "text"]  # the image, its caption
        assert image.structured_content is None


@pytest.mark.anyio
async def test_view_tool_answers_with_the_per_step_view() -> None:
    async with apps_client() as c:
        eid = structured(await c.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
            "episode_id"]
        await c.call_tool("execute_actions", {"episode_id": eid,
                                              "actions": ["move(book, on, shelf)"]})
        out = structured(await c.call_tool("view_episode", {"episode_id": eid}))
        assert [s["ok"] for s in out["steps"]] == [False]
        violation = out["steps"][0]["violation"]
        assert violation["constraint"] == "object_not_clear" and violation["blocking"] == ["cup"]
        plan = structured(await c.call_tool("view_episode", {
            "plan": "move(cup, on, desk)", "scene_id": "cup_on_book"}))
        assert plan["steps"][0]["ok"] is True and plan["goal_reached"] is False
        assert plan["steps"][0]["render"].startswith("data:image/png")
        bad = await c.call_tool("view_episode", {"scene_id": "cup_on_book"})
        assert bad.is_error and "episode_id" in bad.content[0].text
