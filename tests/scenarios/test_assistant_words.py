"""set_goal with words: the rule-based translator's reading, as a proposal to confirm.

What it understood becomes goal edges the assistant sends back (set_goal edges=...);
what it did not is named, clause by clause. Nothing is stored until then.
"""

from __future__ import annotations

import re

import pytest
from mcp import Client
from mcp_helpers import (  # noqa: F401 - in_process_client: the client fixture
    in_process_client,
    structured,
    text,
)

from llm_trials import start

pytestmark = [pytest.mark.fast, pytest.mark.anyio]


async def load(client: Client, task: str) -> str:
    return str(structured(await client.call_tool("load_scene", {"graph": start(task)}))[
        "episode_id"])


async def test_words_become_a_proposal_that_the_assistant_confirms(client: Client) -> None:
    eid = await load(client, "lang_kitchen_clear")
    words = "Kettle and cutting board on the stove, pot and pan on the shelf."
    out = await client.call_tool("set_goal", {"episode_id": eid, "instruction": words})
    said = text(out)
    assert said.startswith("goal PROPOSAL (accepted: false, nothing set")
    proposed = "cutting_board on stove; kettle on stove; pan on shelf; pot on shelf"
    assert f"proposed goal (partial): {proposed}" in said
    assert "understood: 'kettle and cutting board on the stove'" in said
    assert "understood: 'pot and pan on the shelf'" in said
    assert structured(out)["accepted"] is False and structured(out)["goal"] is None
    assert structured(await client.call_tool("get_state", {"episode_id": eid}))["goal"] is None
    confirmed = await client.call_tool("set_goal", {"episode_id": eid, "edges": proposed})
    assert structured(confirmed)["accepted"] and f"goal (partial): {proposed}" in text(confirmed)


async def test_what_the_translator_did_not_understand_is_named(client: Client) -> None:
    eid = await load(client, "lang_quantifier")
    out = await client.call_tool("set_goal", {
        "episode_id": eid,
        "instruction": "Put red_1 on green_3, then stack all the red blocks on the green "
                       "block (red_1 lowest)."})
    said = text(out)
    assert "proposed goal (partial): red_1 on green_3" in said
    assert "understood: 'put red_1 on green_3'" in said
    assert ("not understood: 'stack all the red blocks on the green block' ('the green "
            "block' does not name exactly one block)") in said
    assert "not understood: 'red_1 lowest'" in said


async def test_words_nothing_can_be_read_from_keep_the_goal_and_say_so(client: Client) -> None:
    eid = await load(client, "lang_quantifier")
    await client.call_tool("set_goal", {"episode_id": eid, "predicate": "single_stack"})
    out = await client.call_tool("set_goal", {"episode_id": eid, "instruction": "tidy up"})
    said = text(out)
    assert "nothing to propose" in said and "keeps its goal: goal: single_stack" in said
    assert "not understood: 'tidy up'" in said
    assert structured(out)["goal"]["predicate"] == "single_stack"


async def test_the_description_promises_a_proposal_not_a_goal(client: Client) -> None:
    tools = {t.name: t for t in (await client.list_tools()).tools}
    description = tools["set_goal"].description or ""
    assert "Words alone: a proposal to confirm" in description and "or words" not in description


@pytest.mark.parametrize(("words", "goal"), [
    ("Put the milk in the fridge and turn on the stove; keep the fridge closed.",
     "goal (partial): milk in fridge; fridge closed; stove on"),
    ("No cup on any plate, and put the milk on the table.",
     "goal: formula (and (on milk table) (forall (?x - cup) (not (exists (?y - plate) "
     "(ontop ?x ?y)))))"),
])
async def test_household_words_are_proposed_with_the_call_that_sets_them(
        client: Client, words: str, goal: str) -> None:
    """States and "no cup on any plate" are proposed too, and the proposal's own
    set_goal arguments, sent back as they are, set exactly the goal proposed."""
    out = await client.call_tool("load_scene", {"scene_id": "kitchen_household"})
    eid = structured(out)["episode_id"]
    said = text(await client.call_tool("set_goal", {"episode_id": eid, "instruction": words}))
    assert f"proposed {goal}" in said, said
    accept = said.split("to accept it, call set_goal with ", 1)[1].split(" (corrected")[0]
    formula = re.search(r"formula='(.*)'$", accept)
    edges = re.search(r'edges="([^"]*)", partial=true$', accept)
    assert (formula is None) != (edges is None), accept
    args = {"formula": formula.group(1)} if formula is not None else \
        {"edges": edges.group(1) if edges is not None else ""}
    set_now = await client.call_tool("set_goal", {"episode_id": eid, **args})
    assert structured(set_now)["accepted"] and goal in text(set_now), text(set_now)


async def test_a_goal_without_the_state_asked_for_ends_partial(client: Client) -> None:
    """The request in load_scene's words asks for the stove on: a goal that leaves it out
    is said to narrow the request, and the end is PARTIAL, naming it."""
    out = await client.call_tool("load_scene", {
        "scene_id": "kitchen_household",
        "instruction": "put the milk in the fridge and turn on the stove"})
    eid = structured(out)["episode_id"]
    narrowed = text(await client.call_tool("set_goal", {
        "episode_id": eid, "edges": "milk in fridge"}))
    assert "it leaves out stove on" in narrowed, narrowed
    ran = await client.call_tool("execute_actions", {
        "episode_id": eid, "actions": ["open(fridge)", "move(milk, in, fridge)", "done"]})
    assert "goal reached" in text(ran), text(ran)
    ended = text(await client.call_tool("end_episode", {"episode_id": eid}))
    assert ended.startswith("PARTIAL:") and "not done: stove on" in ended, ended


async def test_a_goal_graph_under_no_cup_on_any_plate_ends_on_what_holds(
        client: Client) -> None:
    """"No cup on any plate" asked in words, then a goal graph that moves the cup away:
    the graph cannot say the formula, so set_goal says end_episode checks it (not that
    the goal leaves it out), and it ends SUCCESS because the formula holds."""
    out = await client.call_tool("load_scene", {
        "scene_id": "kitchen_household", "instruction": "no cup on any plate"})
    eid = structured(out)["episode_id"]
    said = text(await client.call_tool("set_goal", {"episode_id": eid,
                                                    "edges": "cup on counter"}))
    assert "narrower" not in said
    assert "the request also asks (forall (?x - cup) (not (exists (?y - plate) (ontop ?x " \
           "?y)))), which a goal graph cannot say: end_episode checks it" in said, said
    await client.call_tool("execute_actions", {"episode_id": eid,
                                               "actions": ["move(cup, on, counter)", "done"]})
    ended = text(await client.call_tool("end_episode", {"episode_id": eid}))
    assert ended.startswith("SUCCESS: goal reached"), ended


async def test_a_goal_graph_that_leaves_the_cup_on_its_plate_ends_partial(
        client: Client) -> None:
    out = await client.call_tool("load_scene", {
        "scene_id": "kitchen_household",
        "instruction": "no cup on any plate, and put the milk on the table"})
    eid = structured(out)["episode_id"]
    await client.call_tool("set_goal", {"episode_id": eid, "edges": "milk on table"})
    await client.call_tool("execute_actions", {"episode_id": eid,
                                               "actions": ["move(milk, on, table)", "done"]})
    ended = text(await client.call_tool("end_episode", {"episode_id": eid}))
    assert ended.startswith("PARTIAL:") and "cup is on plate" in ended, ended
