"""The move row's compiled fast path accepts exactly the moves its preconditions accept one
by one,
and the report built from compact records equals the one built step by step."""

from __future__ import annotations

import random

import pytest

from scenes import random_blocks, random_tableware
from verigraph.actions import MoveAction, ValidationReport, validate_plan
from verigraph.actions.schemas import MOVE
from verigraph.actions.validator import apply_action, validate_action
from verigraph.graph import Goal, WorldState
from verigraph.graph.goal import wanted_placements

pytestmark = pytest.mark.fast


def test_the_compiled_move_row_agrees_with_its_preconditions_on_random_moves():
    rng = random.Random(4)
    outcomes = {True: 0, False: 0}
    for case in range(300):
        graph = random_blocks(6, case) if case % 2 else random_tableware(5, case)
        state = WorldState.from_graph(graph)
        ids = [*state.objects, "ghost"]
        for _ in range(10):
            a = MoveAction(object=rng.choice(ids), relation=rng.choice(["on", "in", "under"]),
                           target=rng.choice(ids))
            fast = MOVE.accepted(state, a.object, a.relation, a.target)
            one_by_one = all(p.holds(state, a.object, a.relation, a.target)
                             for p in MOVE.preconditions)
            assert fast == one_by_one == (validate_action(state, a) is None), a
            outcomes[fast] += 1
            if fast:
                apply_action(state, a)
    assert outcomes[True] > 100 and outcomes[False] > 100


def test_report_from_records_matches_step_by_step_edits():
    rng = random.Random(9)
    for case in range(40):
        start = random_blocks(5, case)
        ids = [n.id for n in start.nodes]
        plan = [MoveAction(object=rng.choice(ids), target=rng.choice(ids)) for _ in range(6)]
        goal = Goal(graph=random_blocks(5, case + 1))
        report = validate_plan(start, plan, goal, all_errors=True)
        state = WorldState.from_graph(start)
        for step, action in zip(report["steps"], plan, strict=True):
            violation = validate_action(state, action, step["step"],
                                        wanted=wanted_placements(goal))  # fixes serve the goal
            assert step["ok"] == (violation is None)
            if violation is None:
                edit = apply_action(state, action)
                assert step["edit"] == edit.model_dump(mode="json", exclude_none=True)
                assert step["action"] == action.model_dump() and step["text"] == action.text()
            else:
                assert step["violation"] == violation.model_dump(mode="json", exclude_none=True)
        assert report["final_graph"] == state.to_graph().model_dump(mode="json",
                                                                    exclude_none=True)
        # the plain form is the model's own: it validates into it and dumps back the same
        model = ValidationReport.model_validate(report)
        assert model.model_dump(mode="json", exclude_none=True) == report
