"""Goals for validate_plan, solve and check_goal are written as set_goal takes them.

A model that knows the scene should not repeat its node list to state a goal: goal edges
as text (`apple in basket; pear in crate`) or a goal graph without nodes take the nodes
from the scene, and an edge that names an unknown id is refused naming every such id,
source or target. set_goal's proposal from words names the exact accepting call.
"""

from __future__ import annotations

import re
from typing import Any

import pytest
from mcp import Client
from mcp_helpers import (  # noqa: F401 - in_process_client: the client fixture
    in_process_client,
    structured,
    text,
)

from llm_trials import start

pytestmark = [pytest.mark.fast, pytest.mark.anyio]

# A pantry with the user's own labels: the basket holds two things, the crate three.
PANTRY: dict[str, Any] = {
    "dictionary": {"extends": "all", "objects": {
        "basket": {"container": True, "capacity": 2}, "crate": {"container": True, "capacity": 3},
        "apple": {}, "orange": {}, "pear": {}, "jar": {}}},
    "nodes": [{"id": "shelf", "label": "shelf"}, {"id": "basket", "label": "basket"},
              {"id": "crate", "label": "crate"}, {"id": "apple", "label": "apple"},
              {"id": "orange", "label": "orange"}, {"id": "pear", "label": "pear"},
              {"id": "jam_jar", "label": "jar"}],
    "edges": [{"source": "basket", "relation": "on", "target": "shelf"},
              {"source": "crate", "relation": "on", "target": "shelf"},
              {"source": "jam_jar", "relation": "in", "target": "basket"},
              {"source": "apple", "relation": "in", "target": "crate"},
              {"source": "orange", "relation": "in", "target": "crate"},
              {"source": "pear", "relation": "on", "target": "shelf"}]}
GOAL_TEXT = "apple in basket; orange in basket; pear in crate"
GOAL_EDGES = [{"source": s, "relation": r, "target": t}
              for s, r, t in (e.split() for e in GOAL_TEXT.split("; "))]
COLLEAGUE = "move(apple, in, basket)\nmove(orange, in, basket)\nmove(pear, in, crate)"


@pytest.mark.parametrize("goal", [GOAL_TEXT, {"partial": True, "graph": {"edges": GOAL_EDGES}}],
                         ids=["edges text", "graph without nodes"])
async def test_validate_plan_takes_a_goal_without_a_node_list(client: Client,
                                                              goal: Any) -> None:
    report = await client.call_tool("validate_plan", {"graph": PANTRY, "plan": COLLEAGUE,
                                                      "goal": goal, "all_errors": True})
    said = text(report)
    assert said.startswith("INVALID: 3 step(s) checked, 1 violation(s); goal not reached: "
                           "missing: orange in basket"), said
    assert "2 FAIL  move(orange, in, basket): [target_full]" in said
    assert structured(report)["goal_reached"] is False


async def test_solve_and_check_goal_take_goal_edges_as_text(client: Client) -> None:
    plan = await client.call_tool("solve", {"graph": PANTRY, "goal": GOAL_TEXT})
    said = text(plan)
    assert said.startswith("plan of 4 action(s), verified, optimal"), said
    eid = structured(await client.call_tool("load_scene", {"graph": PANTRY}))["episode_id"]
    checked = await client.call_tool("check_goal", {"episode_id": eid, "goal": GOAL_TEXT})
    assert text(checked) == "goal not reached: missing: apple in basket; orange in basket; " \
                            "pear in crate"
    single = await client.call_tool("solve", {"scene_id": "three_blocks",
                                              "goal": "single_stack"})
    assert text(single).startswith("plan of "), text(single)


async def test_unknown_ids_in_goal_edges_are_all_named_sources_and_targets(
        client: Client) -> None:
    goal = {"partial": True, "graph": {"edges": [
        {"source": "appel", "relation": "in", "target": "baskit"},
        {"source": "pear", "relation": "in", "target": "crat"}]}}
    refused = await client.call_tool("validate_plan", {"graph": PANTRY, "plan": COLLEAGUE,
                                                       "goal": goal})
    said = text(refused)
    assert refused.is_error
    assert "goal.graph.edges[0] 'appel in baskit': no object appel or baskit in the scene " \
           "(did you mean apple, basket?)" in said
    assert "goal.graph.edges[1] 'pear in crat': no object crat in the scene (did you mean " \
           "crate?)" in said
    assert "fix: use ids from the scene: apple, basket, crate" in said
    as_text = await client.call_tool("solve", {"graph": PANTRY, "goal": "appel in basket"})
    assert as_text.is_error and "no object appel in the scene" in text(as_text)
    assert "goal: goal edges" in text(as_text)  # the argument is named


async def test_the_goal_argument_says_it_takes_edges_text(client: Client) -> None:
    tools = {t.name: t.input_schema for t in (await client.list_tools()).tools}
    goal = tools["validate_plan"]["properties"]["goal"]
    assert {"type": "string"} in goal["anyOf"]
    assert "edges text 'cup on table; spoon in pot' (partial)" in goal["description"]
    assert "nodes from the scene" in goal["description"]
    assert "a formula '(forall ...)'" in goal["description"]
    for tool in ("solve", "check_goal"):
        assert "edges or formula text too" in tools[tool]["properties"]["goal"]["description"]


async def test_a_proposal_from_words_names_the_exact_accepting_call(client: Client) -> None:
    eid = structured(await client.call_tool("load_scene", {"graph": start("lang_quantifier")}))[
        "episode_id"]
    proposal = await client.call_tool("set_goal", {"episode_id": eid,
                                                   "instruction": "put all red blocks on the "
                                                                  "table"})
    said = text(proposal)
    call = re.search(r'call set_goal with episode_id="([\w-]+)", edges="([^"]*)", '
                     r"partial=(true|false)", said)
    assert call is not None and call.group(1) == eid and call.group(3) == "true", said
    accepted = await client.call_tool("set_goal", {"episode_id": eid, "edges": call.group(2),
                                                   "partial": True})
    assert structured(accepted)["goal"] == {**structured(proposal)["proposal"],
                                            "instruction": None}


async def test_edges_with_partial_false_are_the_whole_goal(client: Client) -> None:
    eid = structured(await client.call_tool("load_scene", {"scene_id": "three_blocks"}))[
        "episode_id"]
    state = structured(await client.call_tool("get_state", {"episode_id": eid}))
    now = "; ".join(f"{e['source']} {e['relation']} {e['target']}"
                    for e in state["graph"]["edges"])
    full = await client.call_tool("set_goal", {"episode_id": eid, "edges": now,
                                               "partial": False})
    assert structured(full)["goal"]["partial"] is False
    assert text(full).startswith("goal set; goal reached") and f"\ngoal: {now}" in text(full)
    one = now.split("; ")[0]
    part = await client.call_tool("set_goal", {"episode_id": eid, "edges": one, "partial": False})
    # a whole goal must place every movable object: the others are named, nothing is set
    assert part.is_error and "has no support" in text(part)
    assert structured(await client.call_tool("get_state", {"episode_id": eid}))["goal"][
        "partial"] is False


async def test_the_instructions_say_where_goal_edges_as_text_are_taken(client: Client) -> None:
    assert client.instructions is not None
    assert "set_goal, validate_plan, check_goal and solve take goal edges as text" in \
        client.instructions
