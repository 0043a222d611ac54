"""Physical processes as rows of the action table: cook, heat, freeze, cool, thaw, each
with its preconditions (a working heat or cold source under the object, or none), its
refusal and fix, one state changed; the solver plans with them optimally."""

from __future__ import annotations

import pytest

from scenes import walk_checking_valid_actions
from verigraph.actions import apply_action, validate_action, validate_plan
from verigraph.actions.parser import parse_plan
from verigraph.actions.schemas import SCHEMAS, table_constraints, valid_actions
from verigraph.graph.bddl_problem import import_problem
from verigraph.graph.goal import Goal
from verigraph.graph.state import WorldState
from verigraph.solver import solve

pytestmark = pytest.mark.fast

KITCHEN = """(define (problem cook-0) (:domain omnigibson)
  (:objects bacon.n.01_1 - bacon.n.01 stove.n.01_1 - stove.n.01
            frying_pan.n.01_1 - frying_pan.n.01 electric_refrigerator.n.01_1 -
            electric_refrigerator.n.01 strawberry.n.01_1 - strawberry.n.01
            countertop.n.01_1 - countertop.n.01 floor.n.01_1 - floor.n.01)
  (:init (ontop bacon.n.01_1 countertop.n.01_1) (ontop frying_pan.n.01_1 countertop.n.01_1)
         (inside strawberry.n.01_1 electric_refrigerator.n.01_1)
         (open electric_refrigerator.n.01_1) (frozen strawberry.n.01_1)
         (inroom stove.n.01_1 kitchen) (inroom countertop.n.01_1 kitchen)
         (inroom electric_refrigerator.n.01_1 kitchen) (inroom floor.n.01_1 kitchen))
  (:goal (cooked ?bacon.n.01_1)))"""


@pytest.fixture(scope="module")
def scene() -> object:
    return import_problem(KITCHEN).scene_graph()


def refusal(scene: object, plan: str) -> tuple[str, str, str]:
    report = validate_plan(scene, plan)  # type: ignore[arg-type]
    assert not report["plan_valid"]
    v = report["violations"][0]
    return v["constraint"], v["message"], v["suggestion"]


def test_the_processes_are_rows_of_the_one_table() -> None:
    for name in ("cook", "heat", "freeze", "cool", "thaw"):
        assert SCHEMAS[name].household
    ids = table_constraints(household=True)
    assert {"no_heat_source", "heat_source_off", "still_heated", "still_cold"} <= set(ids)
    assert "no_heat_source" not in table_constraints(household=False)


def test_valid_actions_list_the_processes_a_scene_allows(scene: object) -> None:
    state = WorldState.from_graph(scene)  # type: ignore[arg-type]
    for action in parse_plan("toggle_on(stove_1)\nmove(bacon_1, on, stove_1)"):
        assert validate_action(state, action) is None
        apply_action(state, action)
    assert "cook(bacon_1)" in {a.text() for a in valid_actions(state)}
    for seed in range(3):
        assert walk_checking_valid_actions(state.copy(), seed, 8) > 0


def test_cook_needs_a_working_heat_source_under_the_object(scene: object) -> None:
    constraint, message, fix = refusal(scene, "cook(bacon_1)")
    assert constraint == "no_heat_source" and "bacon_1" in message
    assert fix == "put it on or in a heat source first, e.g. move(bacon_1, on, stove_1)"
    constraint, message, fix = refusal(scene, "move(bacon_1, on, stove_1)\ncook(bacon_1)")
    assert constraint == "heat_source_off" and "(no state given: off)" in message
    assert fix == "toggle_on(stove_1) first"
    assert refusal(scene, "cook(stove_1)")[0] == "not_cookable"


def test_cook_through_what_carries_it_changes_one_state(scene: object) -> None:
    plan = ("move(frying_pan_1, on, stove_1)\nmove(bacon_1, in, frying_pan_1)\n"
            "toggle_on(stove_1)\ncook(bacon_1)")
    report = validate_plan(scene, plan, {"formula": "(cooked bacon_1)"})  # type: ignore[arg-type]
    assert report["valid"] and report["goal_reached"]
    node = next(n for n in report["final_graph"]["nodes"] if n["id"] == "bacon_1")
    assert node["state"].get("cooked") is True and not node["state"].get("hot", False)
    assert refusal(scene, plan + "\ncook(bacon_1)")[0] == "already_cooked"


def test_cool_and_thaw_need_the_source_gone(scene: object) -> None:
    on_stove = "move(bacon_1, on, stove_1)\ntoggle_on(stove_1)\nheat(bacon_1)\n"
    assert refusal(scene, on_stove + "cool(bacon_1)")[0] == "still_heated"
    report = validate_plan(scene, on_stove + "toggle_off(stove_1)\ncool(bacon_1)",  # type: ignore[arg-type]
                           {"formula": "(not (hot bacon_1))"})
    assert report["valid"]
    constraint, _, fix = refusal(scene, "thaw(strawberry_1)")
    assert constraint == "still_cold" and fix == "move strawberry_1 off fridge_1"
    assert validate_plan(scene, "move(strawberry_1, on, countertop_1)\nthaw(strawberry_1)"  # type: ignore[arg-type]
                         )["plan_valid"]
    assert refusal(scene, "freeze(strawberry_1)")[0] == "already_frozen"


def test_the_solver_plans_processes_optimally(scene: object) -> None:
    state = WorldState.from_graph(scene)  # type: ignore[arg-type]
    result = solve(state, Goal(formula="(and (cooked bacon_1) (not (frozen strawberry_1)))"))
    assert result.reachable and result.optimal
    texts = [a.text() for a in result.plan]
    assert len(texts) == 5
    assert {"toggle_on(stove_1)", "cook(bacon_1)", "thaw(strawberry_1)"} <= set(texts)
