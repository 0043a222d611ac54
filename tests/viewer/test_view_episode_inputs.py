"""view_episode through the real MCP server (SDK client, in memory): it shows what the
episode stored, whatever a refused action named, and every failure says why."""

from __future__ import annotations

import pytest
from mcp import Client
from mcp_helpers import apps_client, structured, text

pytestmark = pytest.mark.fast


async def episode(c: Client) -> str:
    return str(structured(await c.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
        "episode_id"])


@pytest.mark.anyio
async def test_a_refused_move_naming_an_unknown_object_is_shown_as_refused() -> None:
    async with apps_client() as c:
        eid = await episode(c)
        await c.call_tool("execute_actions", {"episode_id": eid,
                                              "actions": ["move(cup, on, desk)"]})
        refused = await c.call_tool("execute_actions", {"episode_id": eid, "actions": [
            {"action": "move", "object": "red cup", "relation": "on", "target": "table"}]})
        assert "red cup" in text(refused)
        for _ in range(2):  # every later view, not only the first
            out = structured(await c.call_tool("view_episode", {"episode_id": eid}))
            assert [s["ok"] for s in out["steps"]] == [True, False]
            last = out["steps"][-1]
            assert last["step"] == 2 and "red cup" in last["text"]
            assert last["violation"]["constraint"] == "unknown_object"
            assert last["violation"]["action"]["object"] == "red cup"
            assert last["graph"] == out["steps"][0]["graph"]  # a refusal changes nothing
            assert out["valid"] is False


@pytest.mark.anyio
async def test_an_over_long_object_name_gets_a_reason() -> None:
    async with apps_client() as c:
        for plan in (f"move({'x' * 5000}, on, desk)",
                     [{"action": "move", "object": "x" * 5000, "relation": "on",
                       "target": "desk"}]):
            bad = await c.call_tool("view_episode", {"scene_id": "cup_on_book", "plan": plan})
            assert bad.is_error
            message = text(bad)
            assert "plan" in message and ("at most 128 characters" in message
                                          or "not a valid object id" in message), message
            assert len(message) < 2000  # the reason, not the name echoed back
