"""set_goal with words: the rule-based translator's reading, as a proposal to confirm.

What it understood becomes goal edges the assistant sends back (set_goal edges=...);
what it did not is named, clause by clause. Nothing is stored until then.
"""

from __future__ import annotations

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
