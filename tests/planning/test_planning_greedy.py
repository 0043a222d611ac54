"""The greedy feedback-driven baseline and the rule-based language planner."""

from __future__ import annotations

import pytest

from verigraph.actions import DoneAction, MoveAction, validate_action
from verigraph.agent import LoopConfig, run_episode
from verigraph.graph import Goal, WorldState
from verigraph.planning import InProcessTools, PlannerRequest
from verigraph.planning.greedy import GreedyPlanner, goal_moves
from verigraph.planning.models import Feedback
from verigraph.planning.rule_based import RuleBasedPlanner
from verigraph.tasks.suite_blocks import block_graph
from verigraph.tasks.task import EpisodeSpec

pytestmark = pytest.mark.fast

TOWER = [["red_block", "green_block", "blue_block"]]  # red at the bottom
REVERSED = Goal(graph=block_graph([["blue_block", "green_block", "red_block"]]))


def request(goal: Goal | None, feedback: Feedback | None = None, history: list[str] | None = None,
            k: int | None = 3, instruction: str | None = None) -> PlannerRequest:
    return PlannerRequest(mode="iterative" if k else "direct", iteration=1,
                          graph=block_graph(TOWER), goal=goal, k=k, prompt="",
                          feedback=feedback, history=history or [], instruction=instruction)


def test_greedy_moves_each_misplaced_object_straight_to_its_goal_place() -> None:
    moves = goal_moves(WorldState.from_graph(block_graph(TOWER)), REVERSED)
    assert {m.text() for m in moves} == {"move(red_block, on, green_block)",
                                         "move(green_block, on, blue_block)",
                                         "move(blue_block, on, table)"}
    direct = GreedyPlanner(seed=0).propose(request(REVERSED, k=None)).actions
    assert isinstance(direct[-1], DoneAction) and len(direct) == 4


def test_full_feedback_repair_puts_the_suggested_fix_before_the_refused_action() -> None:
    state = WorldState.from_graph(block_graph(TOWER))
    refused = MoveAction(object="green_block", target="blue_block")
    violation = validate_action(state, refused)
    assert violation is not None and violation.constraint == "would_create_cycle"
    reply = GreedyPlanner(seed=0).propose(request(REVERSED, Feedback(
        kind="violation", text=violation.text(), violation=violation)))
    assert [a.text() for a in reply.actions] == ["move(blue_block, on, table)",
                                                 "move(green_block, on, blue_block)"]


def test_constraint_only_repair_finds_the_refused_action_in_its_own_proposal() -> None:
    planner = GreedyPlanner(seed=0)
    first = planner.propose(request(REVERSED, history=[]))
    refused = next(a for a in first.actions if isinstance(a, MoveAction)
                   and a.object != "blue_block")
    planner.last = [refused]
    reply = planner.propose(request(REVERSED, Feedback(
        kind="violation", text="[object_not_clear] an action was refused")))
    above = {"red_block": "green_block", "green_block": "blue_block"}[refused.object]
    assert reply.actions[0] == MoveAction(object=above, target="table")
    assert reply.actions[1] == refused


def test_full_feedback_beats_no_feedback_on_stacking_tasks() -> None:
    from verigraph.tasks.groups import build_groups

    pytest.importorskip("verigraph.sim2d.generator")
    tasks = build_groups(("stacking",), 9, 0, ground_truth=True)[0].tasks
    env = InProcessTools()
    rate = {}
    for mode in ("full", "none"):
        wins = sum(run_episode(env, GreedyPlanner(seed=i), t.spec,
                               LoopConfig(feedback=mode, max_iterations=30)).success
                   for i, t in enumerate(tasks))
        rate[mode] = wins / len(tasks)
    assert rate["full"] >= rate["none"] + 0.3, rate


def test_rule_based_planner_plans_the_translated_goal_and_says_when_it_cannot() -> None:
    env = InProcessTools()
    graph = block_graph([["red_block", "green_block"], ["blue_block"]])
    spec = EpisodeSpec(load={"graph": graph.model_dump(mode="json")}, show_goal_graph=False,
                       set_goal={"graph": block_graph([["blue_block", "red_block"],
                                                       ["green_block"]]).model_dump(
                           mode="json"), "partial": True,
                                 "instruction": "Put the block under the green block on the "
                                                "blue block."})
    trace = run_episode(env, RuleBasedPlanner(), spec)
    assert trace.success and trace.actions_executed == 2
    lost = RuleBasedPlanner().propose(request(None, instruction="Sort out the mess, please."))
    assert lost.actions == [DoneAction()]
    assert lost.note is not None and "not understood" in lost.note
