"""Every constraint id: one action that triggers it and one that just misses it."""

import pytest

from scenes import graph
from verigraph.actions import AlignAction, MoveAction, validate_action
from verigraph.graph import Edge, Node, SceneGraph, WorldState

pytestmark = pytest.mark.fast


def kitchen_table() -> WorldState:
    """desk, shelf(capacity 3); book on desk, cup on book, bowl on desk with spoon in it;
    plate on shelf; mug on plate (plate capacity 2)."""
    return WorldState.from_graph(graph(
        "tableware",
        [("desk", "desk"), ("shelf", "shelf"), ("book", "book"), ("cup", "cup"),
         ("bowl", "bowl"), ("spoon", "spoon"), ("plate", "plate"), ("mug", "mug"),
         ("fork", "fork")],
        [("book", "on", "desk"), ("cup", "on", "book"), ("bowl", "on", "desk"),
         ("spoon", "in", "bowl"), ("plate", "on", "shelf"), ("mug", "on", "plate"),
         ("fork", "in", "mug")]))


def move(o, r, t):
    return MoveAction(object=o, relation=r, target=t)


CASES = [
    # (constraint, triggering action, near miss that passes this check)
    ("unknown_object", move("saucer", "on", "desk"), move("fork", "on", "desk")),
    ("unknown_object", move("fork", "on", "sofa"), move("fork", "on", "shelf")),
    ("unknown_relation", move("fork", "under", "desk"), move("fork", "in", "bowl")),
    ("same_object", move("bowl", "in", "bowl"), move("fork", "in", "bowl")),
    ("not_movable", move("desk", "on", "shelf"), move("plate", "on", "desk")),
    ("object_not_clear", move("book", "on", "shelf"), move("cup", "on", "shelf")),
    ("would_create_cycle", move("book", "on", "cup"), move("cup", "on", "desk")),
    ("already_there", move("cup", "on", "book"), move("cup", "on", "desk")),
    ("target_not_surface", move("fork", "on", "cup"), move("fork", "in", "cup")),
    ("target_not_container", move("fork", "in", "book"), move("fork", "on", "book")),
    ("target_full", move("spoon", "in", "mug"), move("spoon", "in", "cup")),
]


@pytest.mark.parametrize("constraint,bad,good", CASES, ids=[c[0] for c in CASES])
def test_constraint_triggers_and_near_miss_passes(constraint, bad, good):
    state = kitchen_table()
    violation = validate_action(state, bad, step=3)
    assert violation is not None and violation.constraint == constraint
    assert violation.step == 3 and violation.message and violation.suggestion
    assert violation.action == bad.model_dump()
    near = validate_action(state, good)
    assert near is None or near.constraint != constraint


def test_papers_example_feedback_names_the_blocker_and_a_fix():
    v = validate_action(kitchen_table(), move("book", "on", "shelf"))
    assert v.constraint == "object_not_clear" and v.blocking == ["cup"]
    assert v.message == "cannot move book: cup is on book"
    assert v.suggestion == "move cup somewhere else first, e.g. move(cup, on, desk)"


def test_target_full_names_what_fills_it_and_where_to_put_it():
    v = validate_action(kitchen_table(), move("cup", "on", "plate"))
    assert v is None  # plate carries the mug; capacity 2
    state = kitchen_table()
    state.set_support("cup", "on", "plate")
    v = validate_action(state, move("book", "on", "plate"))
    assert v.constraint == "target_full" and v.blocking == ["mug", "cup"]
    # the fork is in the mug, so the example moves the clear cup (a move that is valid now)
    assert "move(cup, on, desk)" in v.suggestion and "move(mug," not in v.suggestion


def test_target_not_surface_suggests_in_for_containers():
    v = validate_action(kitchen_table(), move("fork", "on", "cup"))
    assert v.suggestion == "use move(fork, in, cup)"


def test_unknown_object_suggests_ids_with_that_label():
    v = validate_action(kitchen_table(), move("the_cup", "on", "desk"))
    assert "cup" in v.suggestion


def test_cycle_lists_the_objects_in_between():
    state = kitchen_table()
    state.set_support("plate", "on", "book")
    state.set_support("mug", "on", "shelf")
    state.set_support("fork", "on", "desk")
    state.set_support("cup", "on", "plate")
    v = validate_action(state, move("book", "on", "cup"))
    assert v.constraint == "would_create_cycle" and v.blocking == ["cup", "plate"]


def tangram() -> WorldState:
    pieces = ["large_triangle_1", "large_triangle_2", "square", "parallelogram",
              "medium_triangle"]
    return WorldState.from_graph(SceneGraph(
        nodes=[Node(id=p, label=p) for p in pieces],
        edges=[Edge(source="large_triangle_1", relation="touches", target="large_triangle_2",
                    source_side=1, target_side=1)], dictionary="tangram"))


def align(p, s, q, t):
    return AlignAction(object=p, side=s, target=q, target_side=t)


ALIGN_CASES = [
    ("unknown_side", align("square", 4, "parallelogram", 0),
     align("square", 3, "parallelogram", 0)),
    ("unknown_side", align("medium_triangle", 0, "large_triangle_1", 3),
     align("medium_triangle", 0, "large_triangle_1", 2)),
    ("side_occupied", align("square", 0, "large_triangle_2", 1),
     align("square", 0, "large_triangle_2", 0)),
    ("already_there", align("large_triangle_1", 1, "large_triangle_2", 1),
     align("large_triangle_1", 0, "large_triangle_2", 1)),
    ("same_object", align("square", 0, "square", 1), align("square", 0, "parallelogram", 1)),
    ("unknown_object", align("triangle", 0, "square", 1),
     align("medium_triangle", 0, "square", 1)),
]


@pytest.mark.parametrize("constraint,bad,good", ALIGN_CASES, ids=[c[0] for c in ALIGN_CASES])
def test_align_constraints(constraint, bad, good):
    state = tangram()
    v = validate_action(state, bad)
    assert v is not None and v.constraint == constraint, v
    near = validate_action(state, good)
    assert near is None or near.constraint != constraint


def test_align_on_tabletop_objects_is_unknown_side():
    v = validate_action(kitchen_table(), align("cup", 0, "book", 0))
    assert v.constraint == "unknown_side" and "move(" in v.suggestion


def test_move_touches_points_to_align():
    state = WorldState.from_graph(graph(None, [("table", "table"), ("cup", "cup")],
                                        [("cup", "on", "table")]))
    v = validate_action(state, move("cup", "touches", "table"))
    assert v.constraint == "unknown_relation" and "align" in v.suggestion
