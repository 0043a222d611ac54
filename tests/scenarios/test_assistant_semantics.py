"""Small semantics said where a model reads them: done and k, a done-only call, what
render_scene's image is, and a fixed surface's unlimited capacity."""

from __future__ import annotations

import pytest
from mcp import Client
from mcp_helpers import (  # noqa: F401 - in_process_client: the client fixture
    in_process_client,
    structured,
    text,
)

pytestmark = [pytest.mark.fast, pytest.mark.anyio]


async def load(client: Client, **args: object) -> str:
    return str(structured(await client.call_tool("load_scene", {"scene_id": "cup_on_book",
                                                                **args}))["episode_id"])


async def test_done_does_not_count_toward_k_and_says_so(client: Client) -> None:
    eid = await load(client, k=1)
    tools = {t.name: t for t in (await client.list_tools()).tools}
    assert "done not counted" in (tools["execute_actions"].description or "")
    state = await client.call_tool("get_state", {"episode_id": eid})
    assert "k=1 actions per execute_actions call (done not counted)" in text(state)
    out = await client.call_tool("execute_actions", {
        "episode_id": eid, "actions": ["move(cup, on, desk)", "done"]})
    assert structured(out)["done"] and text(out).startswith("executed 1: move(cup, on, desk)")


async def test_a_done_only_call_answers_clearly(client: Client) -> None:
    eid = await load(client)
    out = await client.call_tool("execute_actions", {"episode_id": eid, "actions": ["done"]})
    said = text(out)
    assert said.startswith("no action to execute: done received")
    assert "executed 0" not in said and "nothing;" not in said
    assert "end token received: call end_episode" in said


async def test_render_scene_says_a_diagram_is_not_a_picture(client: Client) -> None:
    drawn = await client.call_tool("render_scene", {"episode_id": await load(client)})
    assert [c.type for c in drawn.content] == ["image", "text"]
    assert "a DIAGRAM of the current scene's graph" in text(drawn)
    assert "simulate=true" in text(drawn)
    simulated = await client.call_tool("render_scene",
                                       {"episode_id": await load(client, simulate=True)})
    assert text(simulated).strip() == "the 2D simulator's picture of the current scene"
    tools = {t.name: t for t in (await client.list_tools()).tools}
    assert "diagram of the graph (pictures need simulate=true)" in (
        tools["render_scene"].description or "")


async def test_a_fixed_surface_says_its_capacity_is_unlimited(client: Client) -> None:
    loaded = await client.call_tool("load_scene", {"scene_id": "three_blocks"})
    assert "table (table: fixed surface, capacity unlimited)" in text(loaded)
    assert "capacity 1" in text(loaded)
