"""Reference solver: unreachable goals explained, scale to 12+ objects, tangram."""

import pytest

from scenes import graph, random_blocks
from verigraph.actions import validate_plan
from verigraph.graph import Edge, Goal, Node, SceneGraph
from verigraph.graph.builtin_scenes import cup_on_book, cup_on_book_goal, three_blocks
from verigraph.solver import solve

pytestmark = pytest.mark.fast


def test_papers_example():
    result = solve(cup_on_book(), cup_on_book_goal())
    assert [a.text() for a in result.plan] == ["move(cup, on, desk)", "move(book, on, shelf)"]
    assert result.optimal


def test_already_satisfied_goal_has_empty_plan():
    assert solve(three_blocks(), Goal(graph=three_blocks())).plan == []


def test_reversing_a_tower_of_twelve():
    ids = [f"b{i}" for i in range(12)]
    up = [(ids[0], "on", "table")] + [(ids[i], "on", ids[i - 1]) for i in range(1, 12)]
    down = [(ids[11], "on", "table")] + [(ids[i], "on", ids[i + 1]) for i in range(11)]
    nodes = [("table", "table")] + [(b, "block") for b in ids]
    result = solve(graph("blocks", nodes, up), Goal(graph=graph("blocks", nodes, down)))
    assert len(result.plan) == 12  # the top block can go straight to the table, then 11 more
    assert validate_plan(graph("blocks", nodes, up), result.plan,
                         Goal(graph=graph("blocks", nodes, down)))["valid"]


def test_twelve_random_blocks_to_a_random_arrangement():
    for seed in range(5):
        start, goal = random_blocks(12, seed), Goal(graph=random_blocks(12, seed + 50))
        result = solve(start, goal)
        assert result.reachable and validate_plan(start, result.plan, goal)["valid"]


def test_conflicting_capacity_is_unreachable_with_a_reason():
    nodes = [("table", "table"), ("cup", "cup"), ("spoon", "spoon"), ("fork", "fork")]
    start = graph("tableware", nodes, [("cup", "on", "table"), ("spoon", "on", "table"),
                                       ("fork", "on", "table")])
    goal = Goal(graph=graph("tableware", nodes, [("cup", "on", "table"),
                                                 ("spoon", "in", "cup"), ("fork", "in", "cup")]))
    result = solve(start, goal)
    assert result.reachable is False and "capacity" in result.reason


def test_goal_with_unknown_object_is_unreachable():
    goal = Goal(graph=SceneGraph(nodes=[Node(id="lamp", label="book")], edges=[]), partial=True)
    result = solve(cup_on_book(), goal)
    assert result.reachable is False and "lamp" in result.reason


def test_moving_a_fixed_object_is_unreachable():
    goal = Goal(graph=graph("tableware", [("desk", "desk"), ("shelf", "shelf")],
                            [("desk", "on", "shelf")]), partial=True)
    result = solve(cup_on_book(), goal)
    assert result.reachable is False and "fixed" in result.reason


def test_tangram_single_align():
    pieces = ["square", "parallelogram", "medium_triangle"]
    nodes = [Node(id=p, label=p) for p in pieces]
    start = SceneGraph(nodes=nodes, edges=[Edge(source="square", relation="touches",
                                                target="parallelogram", source_side=0,
                                                target_side=0)], dictionary="tangram")
    goal_edges = [*start.edges, Edge(source="medium_triangle", relation="touches",
                                     target="square", source_side=1, target_side=2)]
    goal = Goal(graph=SceneGraph(nodes=nodes, edges=goal_edges, dictionary="tangram"))
    result = solve(start, goal)
    assert result.reachable and len(result.plan) == 1
    assert validate_plan(start, result.plan, goal)["valid"]
