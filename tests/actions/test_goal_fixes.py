"""Fixes ranked by the goal: with the goal's placements a refusal's fix keeps the goal
edges that hold and moves a blocker where the goal wants it; without them, as before."""

import pytest
from test_constraints import align, kitchen_table, move, tangram
from test_processes import KITCHEN

from verigraph.actions import validate_action, validate_plan
from verigraph.actions.parser import parse_plan
from verigraph.actions.validator import all_violations, apply_action
from verigraph.graph.bddl_problem import import_problem
from verigraph.graph.builtin_scenes import kitchen_household, kitchen_household_goal
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
    assert wanted_placements(formula) == {("cup", "on", "plate"), ("mug", "in", "bowl"),
                                          ("spoon", "not in", "bowl")}  # a place forbidden


def test_the_other_target_offered_is_the_goals_when_it_takes_the_object():
    wanted = frozenset({("cup", "on", "plate"), ("mug", "on", "plate"), ("book", "in", "bowl")})
    v = validate_action(full_plate(), move("book", "on", "plate"), wanted=wanted)
    assert v is not None and v.suggestion == "the goal keeps mug and cup there: choose " \
        "another target, e.g. move(book, in, bowl) (where the goal wants it)"


# -- every other fix producer: states, closed containers, kinds, cycles, tangram, processes
HOUSEHOLD_GOAL = kitchen_household_goal()  # milk in fridge, fridge closed, pot on stove on


def household() -> WorldState:
    return WorldState.from_graph(kitchen_household())


def test_the_goals_states_and_sided_contacts_are_wanted_too():
    wanted = wanted_placements(HOUSEHOLD_GOAL)
    assert {("fridge", "open", "false"), ("stove", "toggled_on", "true"),
            ("milk", "in", "fridge")} <= wanted
    assert wanted_placements(Goal(formula="(and (not (open fridge)) (toggled_on stove))")) \
        == {("fridge", "open", "false"), ("stove", "toggled_on", "true")}
    tangram_goal = Goal.parse({"nodes": [{"id": "square", "label": "square"},
                                         {"id": "medium_triangle", "label": "medium_triangle"}],
                               "edges": [{"source": "square", "relation": "touches",
                                          "target": "medium_triangle", "source_side": 1,
                                          "target_side": 1}],
                               "partial": True, "dictionary": "tangram"})
    assert ("square[1]", "touches", "medium_triangle[1]") in wanted_placements(tangram_goal)


def test_a_closed_container_is_opened_and_closed_again_when_the_goal_wants_it_closed():
    state = household()
    action = parse_plan("move(milk, in, fridge)")[0]
    blind = validate_action(state, action)
    assert blind is not None and blind.suggestion == \
        "open(fridge) first, then move(milk, in, fridge)"
    v = validate_action(state, action, wanted=wanted_placements(HOUSEHOLD_GOAL))
    assert v is not None and v.suggestion == "open(fridge) first, then move(milk, in, " \
        "fridge), then close(fridge) (the goal wants it closed)"
    assert validate_plan(kitchen_household(), "open(fridge)\nmove(milk, in, fridge)\n"
                         "close(fridge)")["plan_valid"]


def test_taking_an_object_off_a_goal_edge_out_of_a_closed_container_is_said():
    state = household()
    v = validate_action(state, parse_plan("move(bread, on, counter)")[0],
                        wanted=frozenset({("bread", "in", "cabinet")}))
    assert v is not None and v.constraint == "container_closed"
    assert v.suggestion.endswith("; but the goal keeps bread in cabinet: this move undoes "
                                 "it, so drop it unless it clears the way")


def test_an_already_reached_state_the_goal_wants_is_not_undone():
    state = household()
    blind = validate_action(state, parse_plan("close(fridge)")[0])
    assert blind is not None and "open(fridge) would make it open" in blind.suggestion
    v = validate_action(state, parse_plan("close(fridge)")[0],
                        wanted=wanted_placements(HOUSEHOLD_GOAL))
    assert v is not None and v.suggestion == "drop this action (the goal wants fridge closed)"


def test_a_wrong_kind_of_target_is_fixed_toward_the_goal():
    wanted = frozenset({("fork", "in", "bowl")})
    wrong = validate_action(kitchen_table(), move("fork", "in", "book"), wanted=wanted)
    assert wrong is not None and wrong.constraint == "target_not_container"
    assert wrong.suggestion == "use move(fork, on, book)"  # the other relation fits first
    state = kitchen_table()
    state.set_support("fork", "on", "desk")
    onto = validate_action(state, move("fork", "on", "mug"), wanted=wanted)
    assert onto is not None and onto.suggestion == "use move(fork, in, mug)"
    state.set_support("spoon", "on", "desk")
    same = validate_action(state, move("fork", "in", "fork"), wanted=wanted)
    assert same is not None and same.suggestion == \
        "choose a different target, e.g. move(fork, in, bowl) (where the goal wants it)"
    assert validate_action(state, move("fork", "in", "bowl")) is None


def test_a_cycle_fix_puts_the_target_where_the_goal_wants_it_and_back_if_kept():
    state = kitchen_table()  # cup on book: move(book, on, cup) would be a cycle
    v = validate_action(state, move("book", "on", "cup"),
                        wanted=frozenset({("cup", "on", "shelf")}))
    assert v is not None and v.constraint == "would_create_cycle"
    assert v.suggestion == "first move cup off book, e.g. move(cup, on, shelf) (where the " \
                           "goal wants it)"
    kept = validate_action(state, move("book", "on", "cup"),
                           wanted=frozenset({("cup", "on", "book")}))
    assert kept is not None and kept.suggestion.endswith(
        "; later, put cup back on book (the goal keeps it there)")


def test_clearing_a_blocker_the_goal_keeps_says_to_put_it_back():
    v = validate_action(kitchen_table(), move("book", "on", "shelf"),
                        wanted=frozenset({("cup", "on", "book")}))
    assert v is not None and v.suggestion == "move cup somewhere else first, e.g. move(cup, " \
        "on, desk); after move(book, on, shelf), put cup back on book (the goal keeps it " \
        "there)"


def test_an_occupied_side_the_goal_keeps_is_not_broken_and_a_goal_contact_offered():
    state = tangram()  # large_triangle_1[1] touches large_triangle_2[1]
    wanted = frozenset({("large_triangle_1[1]", "touches", "large_triangle_2[1]"),
                        ("square[0]", "touches", "parallelogram[0]")})
    v = validate_action(state, align("square", 0, "large_triangle_2", 1), wanted=wanted)
    assert v is not None and v.constraint == "side_occupied"
    assert v.suggestion == "the goal keeps that contact: align square with another free " \
        "side, e.g. align(square, 0, parallelogram, 0) (a contact the goal wants)"
    assert "move large_triangle_1 away" not in v.suggestion
    assert validate_action(state, align("square", 0, "parallelogram", 0)) is None
    blind = validate_action(state, align("square", 0, "large_triangle_2", 1))
    assert blind is not None and blind.suggestion == \
        "align with a free side of large_triangle_2, or move large_triangle_1 away first"


def test_process_fixes_serve_the_goal():
    state = WorldState.from_graph(import_problem(KITCHEN).scene_graph())
    for action in parse_plan("move(bacon_1, on, stove_1)\ntoggle_on(stove_1)\nheat(bacon_1)"):
        assert validate_action(state, action) is None
        apply_action(state, action)
    cool = parse_plan("cool(bacon_1)")[0]
    blind = validate_action(state, cool)
    assert blind is not None and blind.constraint == "still_heated"
    assert blind.suggestion == "move bacon_1 off stove_1, or toggle_off(stove_1)"
    kept = validate_action(state, cool, wanted=frozenset({("bacon_1", "on", "stove_1")}))
    assert kept is not None and kept.suggestion == \
        "toggle_off(stove_1) (the goal keeps bacon_1 where it is), or move bacon_1 off stove_1"
    on = validate_action(state, cool, wanted=frozenset({
        ("stove_1", "toggled_on", "true"), ("bacon_1", "in", "frying_pan_1")}))
    assert on is not None and on.suggestion == \
        "move(bacon_1, in, frying_pan_1) (where the goal wants it) (the goal wants stove_1 on)"
    assert validate_action(state, parse_plan("move(bacon_1, in, frying_pan_1)")[0]) is None
    off = WorldState.from_graph(import_problem(KITCHEN).scene_graph())
    off.set_support("bacon_1", "on", "stove_1")
    cook = validate_action(off, parse_plan("cook(bacon_1)")[0],
                           wanted=frozenset({("stove_1", "toggled_on", "false")}))
    assert cook is not None and cook.suggestion == \
        "toggle_on(stove_1) first, then toggle_off(stove_1) (the goal wants it off)"


def test_an_unknown_target_is_fixed_by_the_move_the_goal_wants():
    v = validate_action(kitchen_table(), move("cup", "on", "table"),
                        wanted=frozenset({("cup", "on", "shelf")}))
    assert v is not None and v.constraint == "unknown_object"
    assert v.suggestion.startswith("e.g. move(cup, on, shelf) (where the goal wants it); or ")
    covered = validate_action(kitchen_table(), move("book", "on", "table"),
                              wanted=frozenset({("book", "on", "shelf")}))
    assert covered is not None and "move(book, on, shelf)" not in covered.suggestion


def test_a_world_refusal_says_when_its_blocker_is_kept_by_the_goal():
    """The simulator knows no goal: its refusal's fix (move the overlapped piece away) is
    noted when the goal keeps that piece's contact."""
    from verigraph.actions.constraints import with_goal_note
    from verigraph.actions.feedback import Violation
    state = tangram()  # large_triangle_1[1] touches large_triangle_2[1]
    refusal = Violation(action=align("square", 0, "large_triangle_2", 0).model_dump(),
                        constraint="overlap", message="would overlap large_triangle_1",
                        blocking=["large_triangle_1"], suggestion="align square with a side "
                        "that faces free space, or move large_triangle_1 away first")
    noted = with_goal_note(state, refusal.model_copy(), frozenset(
        {("large_triangle_1[1]", "touches", "large_triangle_2[1]")}))
    assert noted.suggestion.endswith("; the goal keeps large_triangle_1 where it is: prefer "
                                     "another target, or put it back after")
    plain = with_goal_note(state, refusal.model_copy(), frozenset(
        {("square[0]", "touches", "parallelogram[0]")}))
    assert plain.suggestion == refusal.suggestion


def test_a_place_the_goal_forbids_is_never_offered():
    goal = Goal(formula="(and (not (on cup desk)) (not (on cup shelf)))")
    wanted = wanted_placements(goal)
    assert {("cup", "not on", "desk"), ("cup", "not on", "shelf")} <= wanted
    blind = validate_action(kitchen_table(), move("book", "on", "shelf"))
    assert blind is not None and "move(cup, on, desk)" in blind.suggestion
    v = validate_action(kitchen_table(), move("book", "on", "shelf"), wanted=wanted)
    assert v is not None and "move(cup, on, desk)" not in v.suggestion
    assert "move(cup, on, shelf)" not in v.suggestion


def test_a_place_the_goal_forbids_a_whole_kind_is_never_offered():
    """"no cup on any plate" forbids every plate to every cup: a quantified goal is read
    by kind, and the reason names the goal rather than calling a surface the target."""
    named = "(not (on cup desk)) (not (on cup shelf)) (not (in cup bowl))"
    wanted = wanted_placements(Goal(formula=f"(and {named})"))
    v = validate_action(kitchen_table(), move("book", "on", "shelf"), wanted=wanted)
    assert v is not None and "move(cup, on, plate)" in v.suggestion
    assert "the goal keeps cup off desk" in v.suggestion and "target" not in v.suggestion
    for no_plate in ("(forall (?c - cup) (forall (?p - plate) (not (on ?c ?p))))",
                     "(not (exists (?p - plate) (on cup ?p)))"):
        wanted = wanted_placements(Goal(formula=f"(and {named} {no_plate})"))
        assert ("?cup" if "forall" in no_plate else "cup", "not on", "?plate") in wanted
        v = validate_action(kitchen_table(), move("book", "on", "shelf"), wanted=wanted)
        assert v is not None and "plate" not in v.suggestion, v.suggestion
    assert not {w for w in wanted_placements(Goal(
        formula="(exists (?c - cup) (not (on ?c plate)))")) if w[0].startswith("?")}


def test_what_is_within_a_forbidden_container_is_never_offered():
    """"not in the cabinet" forbids the plate in it too: a formula's `inside` reads down
    the placements, so a cup put on that plate would be in the cabinet."""
    from verigraph.graph.model import SceneGraph
    state = WorldState.from_graph(SceneGraph.model_validate({
        "nodes": [{"id": i, "label": label, **({"state": {"open": True}} if i == "cabinet"
                                                else {})}
                  for i, label in [("kitchen", "kitchen"), ("desk", "desk"),
                                   ("shelf", "shelf"), ("cabinet", "cabinet"),
                                   ("book", "book"), ("cup", "cup"), ("plate", "plate"),
                                   ("bowl", "bowl")]],
        "edges": [{"source": s, "relation": r, "target": t} for s, r, t in [
            ("cabinet", "inroom", "kitchen"), ("book", "on", "desk"), ("cup", "on", "book"),
            ("plate", "in", "cabinet"), ("bowl", "on", "desk")]],
        "dictionary": "household"}))
    named = "(not (on cup desk)) (not (on cup shelf))"
    wanted = wanted_placements(Goal(formula=f"(and {named})"))
    v = validate_action(state, move("book", "on", "shelf"), wanted=wanted)
    assert v is not None and "move(cup, in, cabinet)" in v.suggestion, v.suggestion
    wanted = wanted_placements(Goal(formula=f"(and {named} (not (inside cup cabinet)))"))
    v = validate_action(state, move("book", "on", "shelf"), wanted=wanted)
    assert v is not None and "cabinet" not in v.suggestion and "plate" not in v.suggestion
    assert "move(cup, in, bowl)" in v.suggestion, v.suggestion
