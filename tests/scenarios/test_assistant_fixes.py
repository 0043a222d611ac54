"""A violation's fix names a real place the verifier accepts, and says why it chose it.

Where no fixed surface has room, the fix goes to a fixed container, else to a movable
surface or container with room, and its text says what that place carries and why no
fixed surface was taken; where nothing has room, it says so instead of a placeholder.
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

from scenes import random_blocks, random_tableware
from verigraph.actions.model import MoveAction
from verigraph.actions.report import validate_plan
from verigraph.actions.validator import all_violations
from verigraph.graph.state import WorldState
from verigraph.reporting import report_text

pytestmark = [pytest.mark.fast, pytest.mark.anyio]
MOVE = re.compile(r"move\(([\w.-]+), (on|in), ([\w.-]+)\)")


def pantry(shelf_capacity: int = 3) -> dict[str, Any]:
    """A shelf (full at 3) with a basket, a crate and a pear; a jar in the basket."""
    return {
        "dictionary": {"extends": "all", "objects": {
            "basket": {"container": True, "capacity": 2},
            "crate": {"container": True, "capacity": 3}, "fruit": {}, "jar": {}}},
        "nodes": [{"id": "shelf", "label": "shelf", "attrs": {"capacity": shelf_capacity}},
                  {"id": "basket", "label": "basket"}, {"id": "crate", "label": "crate"},
                  {"id": "apple", "label": "fruit"}, {"id": "pear", "label": "fruit"},
                  {"id": "jam_jar", "label": "jar"}],
        "edges": [{"source": "basket", "relation": "on", "target": "shelf"},
                  {"source": "crate", "relation": "on", "target": "shelf"},
                  {"source": "pear", "relation": "on", "target": "shelf"},
                  {"source": "jam_jar", "relation": "in", "target": "basket"},
                  {"source": "apple", "relation": "in", "target": "crate"}]}


async def check(client: Client, eid: str, action: str) -> str:
    return text(await client.call_tool("validate_action", {"episode_id": eid, "action": action}))


async def test_no_free_surface_sends_the_object_to_a_container_with_room(
        client: Client) -> None:
    eid = structured(await client.call_tool("load_scene", {"graph": pantry()}))["episode_id"]
    said = await check(client, eid, "move(jam_jar, on, apple)")
    assert "<a free surface>" not in said
    assert "choose a surface or a container, e.g. move(jam_jar, in, crate) (chosen because " \
           "crate, a movable container, carries 1 of 3 and shelf is full at 3 of 3)" in said
    assert (await check(client, eid, "move(jam_jar, in, crate)")).startswith("valid: ")


async def test_a_full_target_is_emptied_by_a_clear_object_that_has_somewhere_to_go(
        client: Client) -> None:
    eid = structured(await client.call_tool("load_scene", {"graph": pantry()}))["episode_id"]
    said = await check(client, eid, "move(jam_jar, on, shelf)")
    assert "[target_full] shelf already carries 3 object(s) (basket, crate, pear)" in said
    # the basket holds the jar, so the clear pear is the one to move
    fix = MOVE.search(said.split("e.g. ")[1])
    assert fix is not None and fix.group(1) == "pear", said
    assert (await check(client, eid, fix.group(0))).startswith("valid: ")


async def test_where_nothing_has_room_the_fix_says_so(client: Client) -> None:
    scene = pantry(shelf_capacity=3)
    scene["edges"].append({"source": "apple", "relation": "in", "target": "basket"})
    scene["edges"] = [e for e in scene["edges"] if e != {"source": "apple", "relation": "in",
                                                         "target": "crate"}]
    scene["dictionary"]["objects"]["crate"]["capacity"] = 0
    eid = structured(await client.call_tool("load_scene", {"graph": scene}))["episode_id"]
    said = await check(client, eid, "move(pear, on, apple)")
    assert "<a free surface>" not in said
    assert "no place in the scene takes pear now (shelf is full at 3 of 3); free one first" \
        in said


def suggested_moves(suggestion: str) -> list[MoveAction]:
    return [MoveAction(object=o, relation=r, target=t) for o, r, t in MOVE.findall(suggestion)]


@pytest.mark.parametrize("seed", range(40))
def test_every_suggested_place_is_accepted_by_the_verifier(seed: int) -> None:
    """For each failing move of random scenes, the fix's moves pass every check that
    concerns the place (the moved object may itself still need clearing)."""
    scene = random_tableware(7, seed) if seed % 2 else random_blocks(6, seed)
    state = WorldState.from_graph(scene)
    checked = 0
    for obj in [o for o, info in state.objects.items() if info.props.movable]:
        for target in state.objects:
            for relation in state.move_relations:
                found = all_violations(state, MoveAction(object=obj, relation=relation,
                                                         target=target))
                for v in found:
                    assert "<a free surface>" not in v.suggestion
                    moves = suggested_moves(v.suggestion.split("e.g. ")[-1])
                    if v.constraint == "object_not_clear":
                        report = validate_plan(state, moves)
                        assert report["plan_valid"], (v.suggestion, report_text(report))
                        checked += 1
                    elif v.constraint in ("target_full", "target_not_surface",
                                          "target_not_container") and moves:
                        left = {w.constraint for w in all_violations(state, moves[0])}
                        assert left <= {"object_not_clear"}, (v.suggestion, left)
                        if v.constraint == "target_full":
                            assert not left, v.suggestion
                        checked += 1
    assert checked


async def test_clearing_a_tower_moves_the_top_first(client: Client) -> None:
    """Under a tower, the object on top must go before the one it rests on."""
    tower = {"dictionary": "blocks", "nodes": [
        {"id": "table", "label": "table"}, {"id": "a", "label": "block"},
        {"id": "b", "label": "block"}, {"id": "c", "label": "block"},
        {"id": "d", "label": "block"}],
        "edges": [{"source": "a", "relation": "on", "target": "table"},
                  {"source": "b", "relation": "on", "target": "a"},
                  {"source": "c", "relation": "on", "target": "b"},
                  {"source": "d", "relation": "on", "target": "table"}]}
    eid = structured(await client.call_tool("load_scene", {"graph": tower}))["episode_id"]
    said = await check(client, eid, "move(a, on, d)")
    assert "Suggestion: move b somewhere else first (what rests on it before: c), e.g. " \
           "move(c, on, table), move(b, on, table)" in said
    plan = "\n".join([*(m.group(0) for m in MOVE.finditer(said.split("e.g. ")[1])),
                      "move(a, on, d)"])
    report = await client.call_tool("validate_plan", {"episode_id": eid, "plan": plan})
    assert text(report).startswith("VALID: 3 step(s) checked"), text(report)
