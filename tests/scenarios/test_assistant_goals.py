"""set_goal shows the goal it set, in full; image goals show how the photo's objects were
matched to the episode's ids and how sure that is; goal edges may be written as text."""

from __future__ import annotations

import base64
from typing import Any

import pytest
from mcp import Client
from mcp.types import ImageContent
from mcp_helpers import (  # noqa: F401 - in_process_client: the client fixture
    in_process_client,
    structured,
    text,
)

from llm_trials import TRIALS, start

pytestmark = [pytest.mark.fast, pytest.mark.anyio]


def photo(task: str) -> str:
    return base64.b64encode((TRIALS / task / "goal.png").read_bytes()).decode()


async def load(client: Client, graph: dict[str, Any], **args: Any) -> str:
    return str(structured(await client.call_tool("load_scene", {"graph": graph, **args}))[
        "episode_id"])


async def test_an_image_goal_is_shown_in_full_with_its_matching(client: Client) -> None:
    eid = await load(client, start("image_kitchen_1"))
    out = await client.call_tool("set_goal", {"episode_id": eid, "image": photo("image_kitchen_1")})
    said = text(out)
    goal = structured(out)["goal"]["graph"]
    full = "; ".join(f"{e['source']} {e['relation']} {e['target']}" for e in goal["edges"])
    assert f"\ngoal: {full}\n" in said and len(goal["edges"]) == 6
    assert "photo objects -> episode ids, confidence: counter -> counter 1.00" in said
    assert "cutting_board -> cutting_board 1.00" in said
    # a board resting on a pot's rim reads as `in`: the text says so and how to correct it
    assert "check: cutting_board in pot was read as `in`" in said
    assert structured(out)["accepted"] is True


async def test_look_alike_objects_make_an_image_goal_a_proposal(client: Client) -> None:
    scene = {"dictionary": "blocks", "nodes": [
        {"id": "table", "label": "table"},
        {"id": "red_1", "label": "block", "attrs": {"color": "red"}},
        {"id": "red_2", "label": "block", "attrs": {"color": "red"}},
        {"id": "blue_1", "label": "block", "attrs": {"color": "blue"}}],
        "edges": [{"source": "red_1", "relation": "on", "target": "table"},
                  {"source": "red_2", "relation": "on", "target": "red_1"},
                  {"source": "blue_1", "relation": "on", "target": "table"}]}
    sim = await load(client, scene, simulate=True)
    await client.call_tool("execute_actions", {"episode_id": sim,
                                               "actions": ["move(red_2, on, blue_1)"]})
    picture = (await client.call_tool("render_scene", {"episode_id": sim})).content[0]
    assert isinstance(picture, ImageContent)
    eid = await load(client, scene)
    out = await client.call_tool("set_goal", {"episode_id": eid,
                                              "image": picture.data})
    said = text(out)
    assert said.startswith("goal PROPOSAL (accepted: false, nothing set")
    assert "AMBIGUOUS: could be any of red_1, red_2" in said and " 0.50 " in said
    assert structured(out)["accepted"] is False
    state = structured(await client.call_tool("get_state", {"episode_id": eid}))
    assert state["goal"] is None  # a proposal changes nothing
    edges = said.split('edges="')[1].split('"')[0]
    confirmed = await client.call_tool("set_goal", {"episode_id": eid, "edges": edges})
    assert structured(confirmed)["accepted"] and f"goal (partial): {edges}" in text(confirmed)
    # the photo is a whole goal: the accepting call says partial=false, and taken as
    # written it stores the whole goal the proposal showed
    assert f'episode_id="{eid}", edges="{edges}", partial=false' in said
    whole = await client.call_tool("set_goal", {"episode_id": eid, "edges": edges,
                                                "partial": False})
    assert structured(whole)["goal"]["partial"] is False and f"\ngoal: {edges}" in text(whole)
    assert structured(whole)["goal"]["graph"]["edges"] == structured(out)["proposal"]["graph"][
        "edges"]


async def test_goal_edges_as_text_take_their_nodes_from_the_episode(client: Client) -> None:
    eid = await load(client, start("check_plan"))
    out = await client.call_tool("set_goal", {"episode_id": eid,
                                              "edges": "cutting_board on shelf; spoon in pot"})
    said = text(out)
    assert "goal (partial): cutting_board on shelf; spoon in pot" in said
    assert "missing: cutting_board on shelf; spoon in pot" in said
    assert structured(out)["goal"]["partial"] is True


async def test_bad_goal_edges_are_refused_naming_each_problem_and_change_nothing(
        client: Client) -> None:
    eid = await load(client, start("check_plan"))
    await client.call_tool("set_goal", {"episode_id": eid, "edges": "knife on counter"})
    bad = await client.call_tool("set_goal", {"episode_id": eid,
                                              "edges": "spoon in pott; knife under counter; x"})
    said = text(bad)
    assert bad.is_error and "edges" in said
    assert "no object pott in the scene" in said
    assert "relation 'under' is not one of on, in" in said
    assert "'x' is not 'source relation target'" in said
    state = await client.call_tool("get_state", {"episode_id": eid})
    assert "goal (partial): knife on counter" in text(state)
