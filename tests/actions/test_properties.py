"""Property tests: rejected actions change nothing, valid ones keep graphs well formed,
solver plans validate and are optimal against brute force."""

from collections import deque

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from scenes import random_blocks, random_tableware, raw_move, scene_and_seed
from verigraph.actions import MoveAction, apply_action, validate_action, validate_plan
from verigraph.graph import Goal, WorldState, check_well_formed
from verigraph.solver import solve
from verigraph.solver.budget import SearchBudget
from verigraph.solver.encoding import SearchProblem
from verigraph.solver.search import _decoded_goal_check

pytestmark = pytest.mark.fast

SETTINGS = settings(max_examples=150, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])


@SETTINGS
@given(data=st.data())
def test_rejected_action_leaves_graph_byte_identical(data):
    g = data.draw(scene_and_seed())
    state = WorldState.from_graph(g)
    for _ in range(6):
        action = MoveAction(**data.draw(raw_move(g)))
        before = state.to_graph().model_dump_json()
        violation = validate_action(state, action)
        if violation is None:
            apply_action(state, action)
        else:
            assert state.to_graph().model_dump_json() == before


@SETTINGS
@given(data=st.data())
def test_valid_actions_keep_the_graph_well_formed(data):
    g = data.draw(scene_and_seed())
    state = WorldState.from_graph(g)
    for _ in range(8):
        action = MoveAction(**data.draw(raw_move(g)))
        if validate_action(state, action) is None:
            apply_action(state, action)
            assert check_well_formed(state.to_graph(), state.dictionary) == []


@settings(max_examples=60, deadline=None)
@given(n=st.integers(1, 7), seed=st.integers(0, 10_000), kind=st.sampled_from(
    ["blocks", "tableware"]))
def test_solver_plans_validate_and_reach_the_goal(n, seed, kind):
    make = random_blocks if kind == "blocks" else random_tableware
    start, goal_graph = make(n, seed), make(n, seed + 1)
    goal = Goal(graph=goal_graph)
    result = solve(start, goal)
    if result.reachable:
        report = validate_plan(start, result.plan or "done", goal)
        assert report["valid"] and report["goal_reached"]
    else:
        assert result.reason


def brute_force_length(start, goal, limit=8):
    """Breadth-first search over the same encoding: the true optimum."""
    state = WorldState.from_graph(start)
    problem = SearchProblem(state)
    budget = SearchBudget(time_limit_s=600, memory_limit_mb=4096, max_expansions=10**9)
    frontier = deque([(problem.start, 0)])
    seen = {problem.start}
    while frontier:
        codes, depth = frontier.popleft()
        if _decoded_goal_check(problem, state, codes, goal):
            return depth
        if depth == limit:
            continue
        for nxt, _ in problem.successors(codes, budget):
            if nxt not in seen:
                seen.add(nxt)
                frontier.append((nxt, depth + 1))
    return None


@settings(max_examples=40, deadline=None)
@given(n=st.integers(2, 5), seed=st.integers(0, 10_000), kind=st.sampled_from(
    ["blocks", "tableware", "stack"]))
def test_solver_is_optimal_against_brute_force(n, seed, kind):
    if kind == "stack":
        start, goal = random_blocks(n, seed), Goal(predicate="single_stack")
    else:
        make = random_blocks if kind == "blocks" else random_tableware
        start, goal = make(n, seed), Goal(graph=make(n, seed + 7))
    result = solve(start, goal)
    expected = brute_force_length(start, goal)
    if expected is None:
        assert result.reachable is False
    else:
        assert result.reachable and len(result.plan) == expected
