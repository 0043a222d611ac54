"""solve's last line: the execute_actions call that runs its plan in the episode."""

from __future__ import annotations

import pytest

from verigraph.tools import Toolbox
from verigraph.tools.solving import run_hint

pytestmark = pytest.mark.fast


@pytest.mark.parametrize(("length", "k", "mode", "said"), [
    (0, 3, None, None),
    (3, 3, None, "to run it: execute_actions with these actions, one call"),
    (19, 3, None, "to run it in one call: execute_actions with these actions and "
                  "whole_plan=true (checked first, then run step by step; k=3 per call "
                  "otherwise, 7 calls)"),
    (19, 3, "sim", "to run it in one call: execute_actions with these actions and "
                   "whole_plan=true (checked first, then run step by step; k=3 per call "
                   "otherwise, 7 calls)"),
    (19, 3, "real", "to run it: execute_actions in 7 calls of at most k=3 actions, in this "
                    "order (each call's result before the next)"),
    (51, 5, None, "to run it: execute_actions in 11 calls of at most k=5 actions, in this "
                  "order (each call's result before the next)"),
])
def test_solve_says_how_execute_actions_runs_its_plan(length: int, k: int, mode: str | None,
                                                      said: str | None) -> None:
    """A plan over k goes whole in one call (checked first), except on a real arm, where
    the user approves each call of at most k, or beyond whole_plan's limit."""
    assert run_hint(length, k, mode) == said


def test_an_episode_plan_says_its_call_and_a_graph_plan_none() -> None:
    box = Toolbox()
    episode = box.call("load_scene", {"scene_id": "three_blocks"}).episode_id
    goal = box.call("get_state", {"episode_id": episode}).goal
    assert goal is not None
    solved = box.call("solve", {"episode_id": episode})
    assert solved.run_with == run_hint(solved.length, 3, None) and solved.length > 0
    assert solved.summary().endswith("\n" + solved.run_with)
    graph = box.call("get_state", {"episode_id": episode}).graph
    alone = box.call("solve", {"graph": graph.model_dump(), "goal": goal.model_dump()})
    assert alone.run_with is None and "to run it" not in alone.summary()
