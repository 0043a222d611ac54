"""Fixes ranked by the goal: with the goal's placements a refusal's fix keeps the goal
edges that hold and moves a blocker where the goal wants it; without them, as before."""

import pytest
from test_constraints import kitchen_table, move

from verigraph.actions import validate_action
from verigraph.actions.validator import all_violations
from verigraph.graph.goal import Goal, wanted_placements
from verigraph.graph.state import WorldState

pytestmark = pytest.mark.fast


def full_plate() -> WorldState:
    """The kitchen table with the cup on the plate too: the plate (capacity 2) is full."""
    state = kitchen_table()
    state.set_support("cup", "on", "plate")
    return state


def test_without_a_goal_the_fixes_are_unchanged():
    for state, action, said in (
            (full_plate(), move("book", "on", "plate"),
             "make room on plate first (any one of mug and cup elsewhere), e.g. "
             "move(cup, on, desk), or choose another target"),
            (kitchen_table(), move("book", "on", "shelf"),
             "move cup somewhere else first, e.g. move(cup, on, desk)"),
            (kitchen_table(), move("bowl", "on", "shelf"),
             "move spoon somewhere else first, e.g. move(spoon, on, desk)")):
        assert validate_action(state, action).suggestion == said
        assert all_violations(state, action, wanted=frozenset())[0].suggestion == said


def test_a_blocker_the_goal_keeps_is_not_moved_another_one_is():
    state = full_plate()
    state.set_support("fork", "on", "desk")  # the mug is clear
    v = validate_action(state, move("book", "on", "plate"),
                        wanted=frozenset({("cup", "on", "plate")}))
    assert v is not None and v.constraint == "target_full"
    assert v.suggestion == "make room on plate first (mug elsewhere; the goal keeps cup " \
                           "there), e.g. move(mug, on, desk), or choose another target"
    assert validate_action(state, move("mug", "on", "desk")) is None


def test_when_the_goal_keeps_every_blocker_another_target_is_offered():
    state = full_plate()
    v = validate_action(state, move("book", "on", "plate"),
                        wanted=frozenset({("cup", "on", "plate"), ("mug", "on", "plate")}))
    assert v is not None and v.suggestion == \
        "the goal keeps mug and cup there: choose another target, e.g. move(book, on, shelf)"
    assert validate_action(state, move("book", "on", "shelf")) is None


def test_a_blocker_goes_where_the_goal_wants_it_when_that_move_is_valid():
    state = full_plate()
    wanted = frozenset({("cup", "in", "bowl")})
    v = validate_action(state, move("book", "on", "plate"), wanted=wanted)
    assert v is not None and "e.g. move(cup, in, bowl) (where the goal wants it)" in v.suggestion
    assert validate_action(state, move("cup", "in", "bowl")) is None
    cleared = validate_action(kitchen_table(), move("book", "on", "shelf"), wanted=wanted)
    assert cleared is not None and cleared.suggestion == \
        "move cup somewhere else first, e.g. move(cup, in, bowl) (where the goal wants it)"


def test_a_goal_place_that_is_not_valid_now_is_passed_over():
    # the plate is full (mug and cup), so the spoon cannot go there now: the usual place
    state = full_plate()
    v = validate_action(state, move("bowl", "on", "shelf"),
                        wanted=frozenset({("spoon", "on", "plate")}))
    assert v is not None and v.suggestion == \
        "move spoon somewhere else first, e.g. move(spoon, on, desk)"


def test_the_placements_a_goal_asks_for():
    edges = Goal.parse({"nodes": [{"id": "cup", "label": "cup"}, {"id": "desk", "label": "desk"}],
                        "edges": [{"source": "cup", "relation": "on", "target": "desk"}],
                        "partial": True})
    assert wanted_placements(edges) == {("cup", "on", "desk")}
    formula = Goal(formula="(and (ontop cup plate) (not (inside spoon bowl)) "
                           "(forall (?c - cup) (ontop ?c desk)) "
                           "(imply (ontop fork desk) (inside mug bowl)))")
    assert wanted_placements(formula) == {("cup", "on", "plate"), ("mug", "in", "bowl")}


def test_the_other_target_offered_is_the_goals_when_it_takes_the_object():
    wanted = frozenset({("cup", "on", "plate"), ("mug", "on", "plate"), ("book", "in", "bowl")})
    v = validate_action(full_plate(), move("book", "on", "plate"), wanted=wanted)
    assert v is not None and v.suggestion == "the goal keeps mug and cup there: choose " \
        "another target, e.g. move(book, in, bowl) (where the goal wants it)"
