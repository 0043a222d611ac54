"""BEHAVIOR-1K's activities from the installed `bddl` (the `household` extra): every one
imported or refused naming a predicate, and a handful of each class through the whole
path (import, solve, validate, execute on the graph executor, goal checked there).
The full table is `verigraph bench behavior` (benchmarks/results/behavior.md)."""

from __future__ import annotations

from collections import Counter

import pytest

pytest.importorskip("bddl", reason="the household extra (bddl) is not installed")

from verigraph.graph.bddl_problem import (  # noqa: E402
    SUPPORTED,
    UnsupportedActivityError,
    import_problem,
)
from verigraph.tasks.behavior import activities, activity_text, run_activity  # noqa: E402


def test_every_activity_is_imported_or_refused_naming_a_predicate() -> None:
    names = activities()
    assert len(names) == 1016
    classes: Counter[str] = Counter()
    refused: Counter[str] = Counter()
    for name in names:
        try:
            imported = import_problem(activity_text(name), activity=name)
        except UnsupportedActivityError as exc:
            assert exc.predicate and exc.predicate not in SUPPORTED
            assert name in exc.message and f"'{exc.predicate}'" in exc.message
            refused[exc.predicate] += 1
            continue
        imported.scene_graph()  # well formed, never half-loaded
        classes[imported.predicate_class] += 1
    assert classes == {"spatial": 160, "household": 71, "thermal": 31}
    assert sum(refused.values()) == 754


@pytest.mark.parametrize("activity, length", [
    ("bringing_newspaper_in", 1),               # spatial
    ("bringing_glass_to_recycling", 3),         # spatial
    ("turn_off_a_normal_school_calculator", 1),  # household: toggle_off
    ("make_toast", 6),                          # thermal: open, move in, toggle_on, cook
    ("thaw_frozen_fish", 5),                    # thermal: open the fridge, out, thaw
    ("store_vodka", 3),             # nextto beside inside: open, in, next to the first
    ("bringing_in_kindling", 3),    # next to the fireplace: on its room's floor
    ("buy_mulch", 5),               # was out of budget: the nextto bound sharpened A*
])
def test_an_activity_is_solved_validated_and_executed(activity: str, length: int) -> None:
    outcome = run_activity(activity, time_limit=20)
    assert outcome.status == "solved", outcome.reason
    assert outcome.optimal and len(outcome.plan) == length


def test_a_refused_activity_names_its_predicate() -> None:
    outcome = run_activity("adding_chemicals_to_pool")
    assert (outcome.status, outcome.predicate) == ("refused", "filled")


def test_a_goal_no_source_can_reach_is_unreachable_and_says_why() -> None:
    outcome = run_activity("make_stewed_fruit")
    assert outcome.status == "unreachable"
    assert outcome.reason is not None and "no heat source" in outcome.reason


@pytest.mark.slow  # the optimal phase spends its 10 s first
def test_a_large_pairing_goal_is_solved_by_the_anytime_search() -> None:
    outcome = run_activity("assembling_gift_baskets", time_limit=10)
    assert outcome.status == "solved", outcome.reason
    assert len(outcome.plan) == 16  # a candle, a cheese, a cookie and a bow in each basket


def test_greedy_search_crosses_a_plateau_with_helpful_actions() -> None:
    import math

    from verigraph.actions.execution import run_actions
    from verigraph.graph.goal import Goal, check_goal
    from verigraph.graph.state import WorldState
    from verigraph.solver.budget import SearchBudget
    from verigraph.solver.table_search import table_astar

    # lamb and potato out of the closed fridge, heated in the oven, on platters that
    # must first come out of the closed cabinet (was out of budget)
    imported = import_problem(activity_text("laying_out_a_feast"), activity="laying_out_a_feast")
    state = WorldState.from_graph(imported.scene_graph())
    goal = Goal(formula=imported.formula)
    found, plan = table_astar(state, goal, SearchBudget(time_limit_s=10), weight=math.inf)
    assert found and 8 <= len(plan) <= 20
    run = run_actions(state, plan)
    assert not run.violations and check_goal(state, goal).satisfied


@pytest.mark.parametrize("activity", [
    "packing_picnic_into_car",    # both baskets emptied, moved into the car, refilled
    "setting_up_silent_auction",  # things out of the carton, cards on clipboards, next to
    pytest.param("prepare_a_slow_dinner_party",  # the turkey heated before it is placed
                 marks=pytest.mark.slow),  # about 10 s
])
def test_greedy_search_plans_a_long_activity_within_its_budget(activity: str) -> None:
    import math

    from verigraph.actions.execution import run_actions
    from verigraph.graph.goal import Goal, check_goal
    from verigraph.graph.state import WorldState
    from verigraph.solver.budget import SearchBudget
    from verigraph.solver.table_search import table_astar

    # were out of budget: the guide counts what is cleared out of a mover's way, and
    # what a process needs at a source, once more (each must also come back or go on),
    # and successors by actions that are not helpful are evaluated when popped
    imported = import_problem(activity_text(activity), activity=activity)
    state = WorldState.from_graph(imported.scene_graph())
    goal = Goal(formula=imported.formula)
    found, plan = table_astar(state, goal, SearchBudget(time_limit_s=10), weight=math.inf)
    assert found and len(plan) >= 8
    run = run_actions(state, plan)
    assert not run.violations and check_goal(state, goal).satisfied


def test_the_greedy_plan_keeps_none_of_its_detours() -> None:
    """freeze_vegetables: the greedy search sets each vegetable on the fridge (a cold
    source) before boxing it in a container in the fridge; with those six moves dropped
    the plan is as long as the proven lower bound, so it is optimal at once."""
    from verigraph.graph.goal import Goal
    from verigraph.solver import solve

    imported = import_problem(activity_text("freeze_vegetables"), activity="freeze_vegetables")
    result = solve(imported.scene_graph(), Goal(formula=imported.formula), time_limit=10,
                   anytime=True)
    assert result.plan is not None and len(result.plan) == 17
    assert result.optimal and result.lower_bound == 17
    assert not any(a.text().endswith("on, fridge_1)") for a in result.plan)
