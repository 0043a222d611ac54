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


def test_the_reports_final_graph_is_the_graphs_own_dump() -> None:
    """`WorldState.graph_data` (the report's final graph, no model built) is what
    `to_graph().model_dump(mode="json", exclude_none=True)` gives, byte for byte: states,
    rooms, tangram contacts (sides, one edge per pair, in canonical order), an inline
    dictionary, and after actions of each kind."""
    import json

    from user_worlds import inline_scene

    from verigraph.actions import parse_plan
    from verigraph.actions.model import AlignAction
    from verigraph.graph import Edge, Node, SceneGraph
    from verigraph.graph.builtin_scenes import BUILTIN_SCENES
    from verigraph.graph.io import scene_from_data

    tangram = SceneGraph(nodes=[Node(id=p, label=p) for p in ("square", "parallelogram",
                                                             "small_triangle_1")],
                         edges=[Edge(source="square", relation="touches", target="parallelogram",
                                     source_side=2, target_side=0),
                                Edge(source="small_triangle_1", relation="touches",
                                     target="square", source_side=1, target_side=3)],
                         dictionary="tangram")
    cases = [(tangram, [AlignAction(object="small_triangle_1", side=0, target="parallelogram",
                                    target_side=1)]),
             (scene_from_data(inline_scene()), [])]
    cases += [(make(), []) for make in BUILTIN_SCENES.values()]
    kitchen = BUILTIN_SCENES["kitchen_household"]()
    cases.append((kitchen, parse_plan("open(fridge)\nmove(milk, in, fridge)\ntoggle_on(stove)")))
    for scene, plan in cases:
        report = validate_plan(scene, plan)
        state = WorldState.from_graph(scene)
        for action in plan:
            apply_action(state, action)
        assert json.dumps(report["final_graph"]) == json.dumps(
            state.to_graph().model_dump(mode="json", exclude_none=True))
        assert json.dumps(state.graph_data()) == json.dumps(
            state.to_graph().model_dump(mode="json", exclude_none=True))
