"""Every violation is in the text a model reads, and every fix covers every blocker.

validate_action lists every constraint an action breaks (a covered board moved onto a
pot breaks object_not_clear and target_not_surface); validate_plan with all_errors
writes the per-step report into the text, bounded: the first 20 steps and every
failure, then a count.
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
from verigraph.actions.parser import parse_plan
from verigraph.actions.report import validate_plan
from verigraph.actions.validator import all_violations
from verigraph.graph.io import scene_from_data
from verigraph.graph.state import WorldState
from verigraph.reporting import report_text

pytestmark = [pytest.mark.fast, pytest.mark.anyio]


async def test_validate_action_text_names_every_failed_constraint(client: Client) -> None:
    loaded = structured(await client.call_tool("load_scene", {"graph": start("image_kitchen_1")}))
    check = await client.call_tool("validate_action", {"episode_id": loaded["episode_id"],
                                                       "action": "move(cutting_board, on, pot)"})
    said = text(check)
    assert said.startswith("INVALID move(cutting_board, on, pot): breaks 2 constraints")
    assert "[object_not_clear] cannot move cutting_board" in said
    assert "[target_not_surface] pot (pot) is not a surface" in said
    assert "use move(cutting_board, in, pot)" in said
    out = structured(check)
    assert [v["constraint"] for v in out["violations"]] == ["object_not_clear",
                                                           "target_not_surface"]
    assert out["violation"]["constraint"] == "object_not_clear"  # the one execution stops at


async def test_validate_plan_all_errors_puts_the_per_step_report_in_the_text(
        client: Client) -> None:
    plan = "move(pot, on, shelf)\nmove(pan, on, shelf)\nmove(kettle, on, stove)\n" \
           "move(cutting_board, on, stove)\ndone"
    report = await client.call_tool("validate_plan", {"graph": start("lang_kitchen_clear"),
                                                      "plan": plan, "all_errors": True})
    said = text(report)
    assert said.splitlines()[0].startswith("INVALID: 4 step(s) checked, 2 violation(s)")
    assert re.search(r"^\s*1 FAIL\s+move\(pot, on, shelf\): \[object_not_clear\]", said, re.M)
    assert re.search(r"^\s*2 ok\s+move\(pan, on, shelf\)   -pan on \w+, \+pan on shelf$", said,
                     re.M)
    assert re.search(r"^\s*4 FAIL\s+move\(cutting_board, on, stove\): \[target_full\] stove",
                     said, re.M)
    assert "more violation" not in said
    assert len(structured(report)["violations"]) == 2


async def test_a_long_report_shows_twenty_steps_every_failure_and_counts_the_rest(
        client: Client) -> None:
    shuffle = ["move(red_block, on, table)", "move(red_block, on, green_block)"]
    plan = [shuffle[i % 2] for i in range(80)]
    plan[50] = "move(table, on, red_block)"  # a fixed object: not_movable
    plan[70] = "move(ghost, on, table)"  # unknown_object
    report = await client.call_tool("validate_plan", {"scene_id": "three_blocks",
                                                      "plan": plan, "all_errors": True})
    said = text(report)
    assert "51 FAIL  move(table, on, red_block): [not_movable]" in said
    assert "71 FAIL  move(ghost, on, table): [unknown_object]" in said
    steps = structured(report)["steps"]
    shown_ok = [int(n) for n in re.findall(r"^\s*(\d+) ok ", said, re.M)]
    assert shown_ok == [s["step"] for s in steps if s["ok"] and s["step"] <= 20]
    failed = [s["step"] for s in steps if not s["ok"]]
    assert [int(n) for n in re.findall(r"^\s*(\d+) FAIL ", said, re.M)] == failed
    later_ok = sum(1 for s in steps if s["ok"] and s["step"] > 20)
    assert f"... and {later_ok} more accepted step(s) after step 20" in said
    assert len(said) < 4000


async def test_a_report_that_stops_says_how_many_actions_it_did_not_check(
        client: Client) -> None:
    report = await client.call_tool("validate_plan", {
        "scene_id": "cup_on_book", "plan": "move(book, on, shelf)\nmove(cup, on, desk)"})
    said = text(report)
    assert "1 FAIL  move(book, on, shelf): [object_not_clear]" in said
    assert "1 later action(s) not checked" in said and "all_errors=true" in said


async def test_the_suggestion_moves_every_blocker(client: Client) -> None:
    report = await client.call_tool("validate_plan", {
        "graph": start("check_plan"), "plan": "move(cutting_board, on, shelf)"})
    assert ("Suggestion: move knife, spoon and lid somewhere else first, e.g. "
            "move(knife, on, counter), move(spoon, on, counter), move(lid, on, counter)"
            ) in text(report)
    assert structured(report)["violations"][0]["blocking"] == ["knife", "spoon", "lid"]


def test_the_suggested_moves_are_valid_in_sequence_and_respect_capacity() -> None:
    """A shelf of capacity 1 takes one blocker; the next one is sent elsewhere."""
    scene = scene_from_data({"dictionary": "kitchen", "nodes": [
        {"id": "shelf", "label": "shelf", "attrs": {"capacity": 1}},
        {"id": "stove", "label": "stove"}, {"id": "counter", "label": "counter"},
        {"id": "cutting_board", "label": "cutting_board"}, {"id": "knife", "label": "knife"},
        {"id": "spoon", "label": "spoon"}, {"id": "lid", "label": "lid"},
        {"id": "pot", "label": "pot"}],
        "edges": [{"source": "cutting_board", "relation": "on", "target": "counter"},
                  {"source": "pot", "relation": "on", "target": "stove"},
                  {"source": "knife", "relation": "on", "target": "cutting_board"},
                  {"source": "spoon", "relation": "on", "target": "cutting_board"},
                  {"source": "lid", "relation": "on", "target": "cutting_board"}]})
    state = WorldState.from_graph(scene)
    found = all_violations(state, parse_plan("move(cutting_board, on, pot)")[0])
    clear = next(v for v in found if v.constraint == "object_not_clear")
    hinted = re.findall(r"move\([^)]*\)", clear.suggestion)
    assert len(hinted) == 3 and sum("shelf" in h for h in hinted) <= 1
    after = validate_plan(scene, "\n".join(hinted))
    assert after["plan_valid"], report_text(after)
