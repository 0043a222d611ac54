"""The household world: states, the actions that change them, under/nextto/inroom, the
action table every checker reads, and the solver over it."""

from __future__ import annotations

import pytest

from scenes import random_blocks, random_tableware, walk_checking_valid_actions
from verigraph.actions import MoveAction, validate_action, validate_plan
from verigraph.actions.execution import execute_until_violation
from verigraph.actions.model import StateAction
from verigraph.actions.parser import parse_plan
from verigraph.actions.schemas import SCHEMAS, table_constraints, valid_actions
from verigraph.actions.validator import all_violations, apply_action
from verigraph.errors import PlanParseError
from verigraph.graph import Goal, SceneGraph, WorldState
from verigraph.graph.builtin_scenes import kitchen_household, kitchen_household_goal
from verigraph.graph.dictionary import load_dictionary
from verigraph.graph.wellformed import check_well_formed
from verigraph.reporting import edit_text
from verigraph.solver import solve

pytestmark = pytest.mark.fast


def world() -> WorldState:
    return WorldState.from_graph(kitchen_household())


@pytest.mark.parametrize("seed", range(4))
def test_valid_actions_are_every_action_the_validator_accepts(seed: int) -> None:
    for start in (kitchen_household(), random_tableware(5, seed), random_blocks(4, seed)):
        assert walk_checking_valid_actions(WorldState.from_graph(start), seed, 10) > 0


def test_valid_actions_keep_table_then_scene_order() -> None:
    # The household suite draws from this list with a seeded generator: its order is
    # the stored tasks'.
    found = [a.text() for a in valid_actions(world())]
    assert len(found) == 81
    assert found[:4] == ["move(bowl, on, plate)", "move(bowl, on, stove)",
                         "move(bowl, on, table)", "move(bowl, in, cup)"]
    assert found[-4:] == ["open(cabinet)", "open(fridge)", "toggle_on(sink)",
                          "toggle_on(stove)"]


def first(state: WorldState, text: str) -> str | None:
    violation = validate_action(state, parse_plan(text)[0])
    return None if violation is None else violation.constraint


@pytest.mark.parametrize("text,constraint", [
    ("move(milk, in, fridge)", "container_closed"),
    ("move(bread, on, counter)", "container_closed"),  # out of the closed cabinet
    ("open(plate)", "not_openable"),
    ("close(fridge)", "already_closed"),
    ("toggle_on(cup)", "not_toggleable"),
    ("toggle_off(stove)", "already_off"),
    ("move(cup, under, plate)", "target_not_furniture"),
    ("move(cup, nextto, kitchen)", "target_is_room"),
    ("move(plate, nextto, sink)", "object_not_clear"),
    ("open(ghost)", "unknown_object"),
])
def test_each_household_refusal_has_its_own_constraint(text: str, constraint: str) -> None:
    assert first(world(), text) == constraint


def test_every_refusal_names_a_fix_the_verifier_accepts() -> None:
    state = world()
    violation = validate_action(state, MoveAction(object="milk", relation="in",
                                                  target="fridge"))
    assert violation is not None and violation.suggestion.startswith("open(fridge) first")
    assert validate_action(state, StateAction(action="open", object="fridge")) is None
    plate = validate_action(state, StateAction(action="open", object="plate"))
    assert plate is not None and "open(fridge)" in plate.suggestion
    already = validate_action(state, StateAction(action="close", object="fridge"))
    assert already is not None and "no state given" not in already.message  # it is set
    nothing = WorldState.from_graph(SceneGraph.model_validate({
        "nodes": [{"id": "c", "label": "cabinet"}], "edges": [], "dictionary": "household"}))
    closed = validate_action(nothing, StateAction(action="close", object="c"))
    assert closed is not None and "(no state given: closed)" in closed.message


def test_open_then_in_then_close_and_the_edits_say_so() -> None:
    report = validate_plan(kitchen_household(), "open(fridge)\nmove(milk, in, fridge)\n"
                           "close(fridge)\ntoggle_on(stove)")
    assert report["valid"]
    texts = [edit_text(s["edit"]) for s in report["steps"] if "edit" in s]
    assert texts == ["fridge: closed -> open", "-milk on counter, +milk in fridge",
                     "fridge: open -> closed", "stove: off -> on"]
    nodes = {n["id"]: n for n in report["final_graph"]["nodes"]}
    assert nodes["fridge"]["state"] == {"open": False}
    assert nodes["stove"]["state"] == {"toggled_on": True}
    # A move's edit dumps as it always did (no `states` key).
    assert "states" not in report["steps"][1]["edit"]


def test_under_and_nextto_carry_nothing_but_block_moving_their_reference() -> None:
    state = world()
    apply_action(state, MoveAction(object="bowl", relation="nextto", target="plate"))
    assert state.load("plate") == 1 and state.has_room("table")
    assert first(state, "move(plate, on, counter)") == "object_not_clear"
    apply_action(state, MoveAction(object="milk", relation="under", target="table"))
    assert state.load("table") == 1  # the plate only; the milk under it counts nothing
    assert state.room_of("milk") == "dining_room" and state.room_of("bread") == "kitchen"


def test_a_rejected_action_changes_nothing_and_full_reports_list_every_reason() -> None:
    state = world()
    before = state.to_graph()
    found = all_violations(state, MoveAction(object="plate", relation="in", target="fridge"))
    assert [v.constraint for v in found] == ["object_not_clear", "container_closed"]
    result = execute_until_violation(parse_plan("move(milk, in, fridge)"), state)
    assert result.violation is not None and state.to_graph() == before


def test_graph_rules_for_states_rooms_and_placements() -> None:
    graph = SceneGraph.model_validate({
        "nodes": [{"id": "k", "label": "kitchen"}, {"id": "t", "label": "counter"},
                  {"id": "f", "label": "fridge", "state": {"toggled_on": True}},
                  {"id": "m", "label": "milk"}, {"id": "p", "label": "plate"},
                  {"id": "b", "label": "box"}],
        "edges": [{"source": "t", "relation": "inroom", "target": "k"},
                  {"source": "m", "relation": "inroom", "target": "k"},
                  {"source": "m", "relation": "on", "target": "t"},
                  {"source": "p", "relation": "under", "target": "b"},
                  {"source": "b", "relation": "nextto", "target": "k"}],
        "dictionary": "household"})
    rules = {p.rule for p in check_well_formed(graph, load_dictionary("household"))}
    assert rules == {"state_without_role", "inroom_not_furniture", "target_not_furniture",
                     "target_is_room"}
    with pytest.raises(ValueError, match="unknown state 'opened'"):
        SceneGraph.model_validate({"nodes": [{"id": "f", "label": "fridge",
                                              "state": {"opened": True}}], "edges": []})


def test_a_scene_without_states_dumps_as_before() -> None:
    graph = SceneGraph.model_validate({"nodes": [{"id": "t", "label": "table"}], "edges": []})
    assert graph.model_dump() == {"nodes": [{"id": "t", "label": "table", "attrs": {}}],
                                  "edges": [], "dictionary": None}


def test_the_parser_reads_the_new_actions_and_refuses_bad_arity() -> None:
    actions = parse_plan("open(fridge)\nmove(box, under, table)\ntoggle_off(lamp)")
    assert [a.text() for a in actions] == ["open(fridge)", "move(box, under, table)",
                                           "toggle_off(lamp)"]
    with pytest.raises(PlanParseError, match="open takes 1 argument"):
        parse_plan("open(fridge, now)")


def test_the_table_has_a_row_per_action_and_each_precondition_an_id() -> None:
    assert list(SCHEMAS) == ["move", "open", "close", "toggle_on", "toggle_off",
                             "cook", "heat", "freeze", "cool", "thaw"]
    assert "container_closed" in table_constraints(household=True)
    assert "container_closed" not in table_constraints(household=False)
    assert table_constraints(household=False)[:3] == ["unknown_object", "unknown_relation",
                                                      "same_object"]


def test_solve_is_optimal_over_the_table() -> None:
    result = solve(kitchen_household(), kitchen_household_goal())
    assert result.optimal and len(result.plan) == 5
    texts = [a.text() for a in result.plan]
    assert texts.index("open(fridge)") < texts.index("move(milk, in, fridge)") \
        < texts.index("close(fridge)")
    assert validate_plan(kitchen_household(), result.plan, kitchen_household_goal())["valid"]


def test_a_state_goal_alone_and_an_unreachable_one() -> None:
    goal = Goal.model_validate({"graph": {"nodes": [
        {"id": "cabinet", "label": "cabinet", "state": {"open": True}}], "edges": []},
        "partial": True})
    result = solve(kitchen_household(), goal)
    assert [a.text() for a in result.plan] == ["open(cabinet)"] and result.optimal
    bad = Goal.model_validate({"graph": {"nodes": [
        {"id": "plate", "label": "plate", "state": {"open": True}}], "edges": []},
        "partial": True})
    assert solve(kitchen_household(), bad).reachable is False


def test_the_pddl_export_agrees_with_the_verifier_on_household_plans() -> None:
    from verigraph.pddl import validate_strips_dict
    from verigraph.solver.pddl import domain_pddl, ground_plan, is_household, problem_pddl

    state, goal = world(), kitchen_household_goal()
    assert is_household(state, goal)
    domain, problem = domain_pddl(True), problem_pddl(state, goal)
    plans = {"solved": [a.text() for a in solve(kitchen_household(), goal).plan],
             "no open": ["move(milk, in, fridge)", "move(pot, on, stove)",
                         "toggle_on(stove)"],
             "left open": ["open(fridge)", "move(milk, in, fridge)", "move(pot, on, stove)",
                           "toggle_on(stove)"],
             "twice on": ["toggle_on(stove)", "toggle_on(stove)"]}
    for name, plan in plans.items():
        actions = parse_plan("\n".join(plan))
        ours = validate_plan(kitchen_household(), actions, goal)["valid"]
        grounded = "\n".join(f"({n} {' '.join(a)})" for n, a in ground_plan(state, actions))
        theirs = validate_strips_dict(domain, problem, grounded)["valid"]
        assert ours == theirs, name
    assert domain_pddl(False) == domain_pddl()  # the tabletop domain as it was
    with pytest.raises(Exception, match="under and nextto have no PDDL export"):
        problem_pddl(state, Goal.model_validate({"graph": {
            "nodes": [{"id": "milk", "label": "milk"}, {"id": "table", "label": "table"}],
            "edges": [{"source": "milk", "relation": "under", "target": "table"}]},
            "partial": True}))



def test_a_closed_container_holds_what_rests_on_what_is_in_it() -> None:
    """Bacon on a tray in a closed fridge stays until the fridge is opened, and nothing
    is put on that tray meanwhile; open, both moves are valid."""
    graph = SceneGraph.model_validate({
        "nodes": [{"id": "fridge", "label": "fridge"}, {"id": "counter", "label": "counter"},
                  {"id": "tray", "label": "plate"}, {"id": "bacon", "label": "cheese"},
                  {"id": "bread", "label": "bread"}],
        "edges": [{"source": "tray", "relation": "in", "target": "fridge"},
                  {"source": "bacon", "relation": "on", "target": "tray"},
                  {"source": "bread", "relation": "on", "target": "counter"}],
        "dictionary": "household"})
    state = WorldState.from_graph(graph)
    out = validate_action(state, parse_plan("move(bacon, on, counter)")[0])
    assert out is not None and out.constraint == "container_closed"
    assert out.message.startswith("cannot take bacon out of fridge")
    assert out.suggestion.startswith("open(fridge) first")
    onto = validate_action(state, parse_plan("move(bread, nextto, bacon)")[0])
    assert onto is not None and onto.constraint == "container_closed"
    assert onto.message.startswith("cannot reach bacon in fridge")
    assert validate_plan(graph, parse_plan("open(fridge)\nmove(bacon, on, counter)"))["valid"]
