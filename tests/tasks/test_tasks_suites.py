"""The benchmark's task suites: difficulty per group, fixed seeds, ground truths that hold."""

from __future__ import annotations

import random

import pytest

from verigraph.graph import Goal, SceneGraph, WorldState, check_goal
from verigraph.graph.translator import TranslationError, same_goal, translate
from verigraph.planning.tangram_plan import tangram_plan
from verigraph.solver import solve
from verigraph.tasks import language
from verigraph.tasks.groups import GROUPS, SUITE_VERSION, build_groups, suite_stats
from verigraph.tasks.suite_blocks import block_graph, stacking_task
from verigraph.tasks.suite_tangram import tangram_task

generator = pytest.importorskip("verigraph.sim2d.generator", reason="sim2d not installed")


@pytest.fixture(scope="module")
def groups() -> list:  # type: ignore[type-arg]
    return build_groups(GROUPS, 12, 0, ground_truth=True)


def test_every_group_needs_at_least_four_moves_on_average(groups: list) -> None:  # type: ignore[type-arg]
    for group in groups:
        stats = suite_stats(group)
        assert stats.episodes == 12, group.group
        assert stats.mean_optimal >= 4.0, (group.group, stats)
        assert min(stats.distribution) >= 2
        assert sum(stats.distribution.values()) == 12


def test_optimal_lengths_are_the_solvers_and_no_goal_holds_at_the_start(groups: list  # type: ignore[type-arg]
                                                                        ) -> None:
    for group in groups:
        for task in group.tasks[:4]:
            state = WorldState.from_graph(SceneGraph.model_validate(task.spec.load["graph"]))
            set_goal = task.spec.set_goal or {}
            goal = task.goal or Goal(graph=SceneGraph.model_validate(set_goal["graph"]),
                                      partial=bool(set_goal.get("partial")))
            assert not check_goal(state, goal).satisfied, task.task_id
            if group.group == "tangram":
                plan = tangram_plan(state, goal)
                assert plan is not None and len(plan) == task.optimal_length
            else:
                assert len(solve(state, goal).plan) == task.optimal_length, task.task_id


def test_tasks_are_fixed_by_seed_and_versioned() -> None:
    a = build_groups(("stacking", "language"), 6, 3, ground_truth=True)
    b = build_groups(("stacking", "language"), 6, 3, ground_truth=True)
    assert [t.spec for g in a for t in g.tasks] == [t.spec for g in b for t in g.tasks]
    c = build_groups(("stacking",), 6, 4, ground_truth=True)
    assert [t.spec for t in a[0].tasks] != [t.spec for t in c[0].tasks]
    assert SUITE_VERSION


def test_stacking_has_ordered_reversal_and_multi_tower_tasks_with_an_order() -> None:
    kinds = {stacking_task(random.Random(i), i).kind for i in range(3)}
    assert kinds == {"ordered", "reversal", "multi_tower"}
    ordered = stacking_task(random.Random(0), 0)
    start = WorldState.from_graph(ordered.graph)
    assert all(start.support[b] == ("on", "table") for b in start.support)  # spread out
    assert ordered.optimal_length == len(start.support) - 1
    reversal = stacking_task(random.Random(1), 1)
    assert reversal.kind == "reversal" and reversal.optimal_length >= 4


def test_language_hides_the_goal_and_covers_every_category(groups: list) -> None:  # type: ignore[type-arg]
    lang = next(g for g in groups if g.group == "language")
    assert all(not t.spec.show_goal_graph for t in lang.tasks)
    assert {t.category for t in lang.tasks} == set(language.CATEGORIES)
    assert all(t.goal is not None and t.goal.partial for t in lang.tasks)


def test_translator_reads_its_grammar_and_refuses_colloquial_wording() -> None:
    towers = [["red_block", "green_block", "red_block_2"], ["blue_block", "yellow_block"]]
    graph = block_graph(towers)
    goal = translate("Put the block under the green block on top of the blue block.", graph)
    assert goal.graph is not None and goal.partial
    assert goal.graph.edge_keys() == {("red_block", "on", "blue_block", None, None)}
    every = translate("Move every block that is not red to the table.", graph)
    assert every.graph is not None
    assert {k[0] for k in every.graph.edge_keys()} == {"green_block", "blue_block",
                                                       "yellow_block"}
    with pytest.raises(TranslationError):
        translate("Take the red blocks down and set them on the table.", graph)
    made = language.instruction_for(towers, "all_of_colour", random.Random(0))
    assert made is not None
    if "Take the" not in made.text:
        assert same_goal(translate(made.text, graph), made.goal)


def test_tangram_plan_matches_the_reference_solver_on_two_pieces_out() -> None:
    # four pieces keep the reference solver's exhaustive depth-2 search short
    figure = generator.generate_scene("tangram", 5, 4).goal.graph
    drawn = tangram_task(figure, random.Random(5), 2)
    assert drawn is not None and drawn.optimal_length == 2
    result = solve(drawn.graph, drawn.goal)
    assert result.reachable and len(result.plan) == 2
