"""The goal argument of the stateless tools: edges text, a predicate's name, or a goal
graph whose nodes may be left out (the scene's are used), checked before anything runs."""

from __future__ import annotations

import pytest

from verigraph.errors import VeriGraphError
from verigraph.tools import Toolbox
from verigraph.tools.registry import TOOLS

pytestmark = pytest.mark.fast
CUP_GOAL = [{"source": "cup", "relation": "on", "target": "desk"},
            {"source": "book", "relation": "on", "target": "shelf"}]


def said(tool: str, arguments: dict[str, object]) -> str:
    return TOOLS[tool].summary(Toolbox().call(tool, arguments))


def test_a_full_goal_without_nodes_takes_them_from_the_scene() -> None:
    whole = {"graph": {"edges": CUP_GOAL}, "partial": False}  # names every object
    assert said("solve", {"scene_id": "cup_on_book", "goal": whole}).startswith(
        "plan of 2 action(s), verified, optimal")
    short = {"graph": {"edges": CUP_GOAL[:1]}, "partial": False}  # the book is not named
    with pytest.raises(VeriGraphError) as refused:
        Toolbox().call("solve", {"scene_id": "cup_on_book", "goal": short})
    assert "a full goal must list every object of the scene; missing: book" in \
        refused.value.message
    partial = {"graph": {"edges": CUP_GOAL}, "partial": True}
    assert said("solve", {"scene_id": "cup_on_book", "goal": partial}).startswith(
        "plan of 2 action(s), verified, optimal")


def test_listed_nodes_are_kept_and_the_missing_ones_added() -> None:
    goal = {"partial": True, "graph": {"nodes": [{"id": "cup", "label": "cup"}],
                                       "edges": CUP_GOAL}}
    text = said("validate_plan", {"scene_id": "cup_on_book", "goal": goal,
                                  "plan": "move(cup, on, desk)\nmove(book, on, shelf)"})
    assert text.startswith("VALID: 2 step(s) checked; goal reached")


def test_text_goals_read_as_set_goal_reads_them() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"scene_id": "cup_on_book"}).episode_id
    for goal in ("cup on desk; book on shelf", "move(cup, on, desk)\nmove(book, on, shelf)",
                 "cup on desk, book on shelf"):
        out = box.call("check_goal", {"episode_id": eid, "goal": goal})
        assert TOOLS["check_goal"].summary(out) == \
            "goal not reached: missing: book on shelf; cup on desk", goal
    with pytest.raises(VeriGraphError) as refused:
        box.call("check_goal", {"episode_id": eid, "goal": "cup onto desk"})
    assert refused.value.field == "goal"
    assert "relation 'onto' is not one of on, in" in refused.value.message
