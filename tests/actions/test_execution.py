"""execute_until_violation, goal checks and predicates (docs/design.md section 6)."""

import pytest

from scenes import graph
from verigraph.actions import MoveAction, execute_until_violation, parse_plan, validate_plan
from verigraph.actions.model import AlignAction, DoneAction
from verigraph.graph import Edge, Goal, Node, SceneGraph, WorldState, check_goal
from verigraph.graph.builtin_scenes import cup_on_book, cup_on_book_goal, three_blocks
from verigraph.reporting import report_text

pytestmark = pytest.mark.fast


def test_paper_example_first_move_rejected_then_corrected_plan_passes():
    scene = cup_on_book()
    bad = execute_until_violation(parse_plan("move(book, on, shelf)\nmove(cup, on, desk)"),
                                  scene)
    assert bad.executed == [] and bad.violation.constraint == "object_not_clear"
    assert bad.violation.blocking == ["cup"] and "move cup" in bad.violation.suggestion
    assert bad.graph == scene.canonical()
    fixed = validate_plan(scene, "move(cup, on, desk)\nmove(book, on, shelf)\ndone",
                          cup_on_book_goal())
    assert fixed["valid"] and fixed["goal_reached"] and fixed["done"]


def test_valid_prefix_stays_applied_and_input_is_untouched():
    scene = cup_on_book()
    before = scene.model_dump_json()
    actions = parse_plan("move(cup, on, desk)\nmove(book, on, cup)\nmove(book, on, shelf)")
    result = execute_until_violation(actions, scene)
    assert [a.text() for a in result.executed] == ["move(cup, on, desk)"]
    assert result.violation.step == 2 and result.violation.constraint == "target_not_surface"
    assert Edge(source="cup", relation="on", target="desk") in result.graph.edges
    assert scene.model_dump_json() == before


def test_done_stops_execution():
    result = execute_until_violation([MoveAction(object="cup", target="desk"), DoneAction(),
                                      MoveAction(object="book", target="shelf")], cup_on_book())
    assert result.done and len(result.executed) == 1


def test_world_state_input_is_copied():
    state = WorldState.from_graph(cup_on_book())
    execute_until_violation([MoveAction(object="cup", target="desk")], state)
    assert state.support["cup"] == ("on", "book")


def test_goal_diff_lists_missing_and_extra_edges_and_nodes():
    state = WorldState.from_graph(cup_on_book())
    goal = cup_on_book_goal()
    d = check_goal(state, goal)
    assert not d.satisfied
    assert d.missing_edges == ["book on shelf", "cup on desk"]
    assert d.extra_edges == ["book on desk", "cup on book"]
    bigger = goal.graph.model_copy(update={"nodes": [*goal.graph.nodes,
                                                     Node(id="lamp", label="book")]})
    d2 = check_goal(state, Goal(graph=bigger))
    assert d2.missing_nodes == ["lamp"]


def test_partial_goal_only_needs_listed_edges():
    state = WorldState.from_graph(cup_on_book())
    partial = Goal(graph=SceneGraph(nodes=[Node(id="cup", label="cup"),
                                           Node(id="book", label="book")],
                                    edges=[Edge(source="cup", relation="on", target="book")]),
                   partial=True)
    assert check_goal(state, partial).satisfied
    assert not check_goal(state, partial.model_copy(update={"partial": False})).satisfied


def test_goal_parse_accepts_graphs_with_partial_flag_and_predicates():
    g = Goal.parse({"nodes": [{"id": "cup", "label": "cup"}], "edges": [], "partial": True})
    assert g.partial and g.graph is not None
    assert Goal.parse("single_stack").predicate == "single_stack"


def test_single_stack_predicate():
    state = WorldState.from_graph(three_blocks())
    d = check_goal(state, Goal(predicate="single_stack"))
    assert not d.satisfied and "green_block" in d.detail
    state.set_support("green_block", "on", "red_block")
    assert check_goal(state, Goal(predicate="single_stack")).satisfied


def test_single_stack_rejects_a_branching_pile():
    state = WorldState.from_graph(graph(
        "tableware", [("table", "table"), ("plate", "plate"), ("cup", "cup"), ("mug", "mug")],
        [("plate", "on", "table"), ("cup", "on", "plate"), ("mug", "on", "plate")]))
    assert not check_goal(state, Goal(predicate="single_stack")).satisfied


def tangram_pair(square_side: int, para_side: int) -> SceneGraph:
    return SceneGraph(nodes=[Node(id="square", label="square"),
                             Node(id="parallelogram", label="parallelogram")],
                      edges=[Edge(source="square", relation="touches", target="parallelogram",
                                  source_side=square_side, target_side=para_side)],
                      dictionary="tangram")


def test_tangram_goal_matches_up_to_piece_symmetry():
    goal = Goal(graph=tangram_pair(0, 0))
    # The square has 4-fold symmetry: any of its sides is equivalent.
    assert check_goal(WorldState.from_graph(tangram_pair(2, 0)), goal).satisfied
    # The parallelogram has 2-fold symmetry: side 2 matches side 0, side 1 does not.
    assert check_goal(WorldState.from_graph(tangram_pair(3, 2)), goal).satisfied
    assert not check_goal(WorldState.from_graph(tangram_pair(0, 1)), goal).satisfied


def test_align_replaces_the_moved_pieces_contacts():
    result = execute_until_violation(
        [AlignAction(object="square", side=1, target="parallelogram", target_side=3)],
        tangram_pair(0, 0))
    assert result.violation is None
    assert [e.sentence() for e in result.graph.edges] == ["square[1] touches parallelogram[3]"]


def test_all_errors_lists_every_problem():
    report = validate_plan(cup_on_book(), "move(book, shelf)\nmove(cup, sofa)\n"
                           "move(cup, desk)\nmove(book, shelf)", all_errors=True)
    assert [v["constraint"] for v in report["violations"]] == ["object_not_clear",
                                                             "unknown_object"]
    assert [s["ok"] for s in report["steps"]] == [False, False, True, True]
    first = validate_plan(cup_on_book(), "move(book, shelf)\nmove(cup, sofa)\nmove(cup, desk)")
    assert len(first["steps"]) == 1 and first["not_checked"] == 2
    assert "2 later action(s) not checked" in report_text(first)
