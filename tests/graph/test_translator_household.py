"""The rule-based translator in the household world: states ("turn on the stove", "keep
the fridge closed"), `under` and `nextto` ("next to the bowl"), every object of a kind
("every cup") and "no cup on any plate" (a formula). Each reading is a trigger with its
near miss: the same words on an object without the role, or in a world without the
relation, are said not understood, with why; a reading that holds is checked by the goal
evaluator on a state where it holds and one where it does not."""

from __future__ import annotations

import pytest

from verigraph.graph.builtin_scenes import kitchen_household
from verigraph.graph.goal import check_goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.translator import TranslationError, read_instruction, translate

pytestmark = pytest.mark.fast


def house() -> SceneGraph:
    return kitchen_household()


def tabletop() -> SceneGraph:
    return SceneGraph.model_validate({
        "nodes": [{"id": "table", "label": "table"}, {"id": "cup", "label": "cup"},
                  {"id": "plate", "label": "plate"}],
        "edges": [{"source": "cup", "relation": "on", "target": "plate"},
                  {"source": "plate", "relation": "on", "target": "table"}]})


# (instruction, the goal items read: edges, then states as set_goal's edges text writes them)
TRIGGERS = [
    ("turn on the stove", ["stove on"]),
    ("turn the stove on", ["stove on"]),
    ("switch off the stove", ["stove off"]),
    ("open the fridge", ["fridge open"]),
    ("close the cabinet and the fridge", ["cabinet closed", "fridge closed"]),
    ("keep the fridge closed", ["fridge closed"]),
    ("the stove should be on", ["stove on"]),
    ("put the milk in the fridge and turn on the stove", ["milk in fridge", "stove on"]),
    ("put the milk in the fridge, put the pot on the stove and turn the stove on, and keep "
     "the fridge closed", ["milk in fridge", "pot on stove", "fridge closed", "stove on"]),
    ("put the bread next to the bowl", ["bread nextto bowl"]),
    ("put the bread beside the bowl and the cup under the table",
     ["bread nextto bowl", "cup under table"]),
    ("every cup must be in the cabinet", ["cup in cabinet"]),
    ("put all the pots in the sink", ["pot in sink"]),
]


@pytest.mark.parametrize(("words", "items"), TRIGGERS)
def test_household_words_read_as_goal_items(words: str, items: list[str]) -> None:
    reading = read_instruction(words, house())
    assert not reading.not_understood, reading.not_understood
    assert sorted([e.sentence() for e in reading.edges] + reading.state_sentences()) == \
        sorted(items)


# (instruction, on which scene, what the refusal says): the trigger's near miss.
NEAR_MISSES = [
    ("turn on the fridge", house, "fridge (fridge) is not toggleable, so it cannot be on"),
    ("open the plate", house, "plate (plate) is not openable, so it cannot be open"),
    ("put the cup under the plate", tabletop, "'under' asks for under, which this scene's "
                                              "world does not have (objects go on, in)"),
    ("put the cup next to the plate", tabletop, "'next to' asks for nextto"),
    ("no cup on any spoon", house, "no spoon in the scene"),
    ("every bowl must be on the table", tabletop, "no bowl in the scene"),
]


@pytest.mark.parametrize(("words", "scene", "why"), NEAR_MISSES)
def test_near_misses_are_not_understood_and_say_why(words: str, scene: object,
                                                    why: str) -> None:
    graph = scene()  # type: ignore[operator]
    reading = read_instruction(words, graph)
    assert not reading.asks() and len(reading.not_understood) == 1
    assert why in reading.not_understood[0][1], reading.not_understood
    with pytest.raises(TranslationError):
        translate(words, graph)


def test_states_and_edges_make_a_goal_graph_the_evaluator_checks() -> None:
    graph = house()
    goal = translate("put the milk in the fridge and turn on the stove", graph)
    assert goal.formula is None and goal.graph is not None and goal.partial
    state = WorldState.from_graph(graph)
    assert not check_goal(state, goal).satisfied
    state.set_state("fridge", "open", True)
    state.set_support("milk", "in", "fridge")
    assert check_goal(state, goal).missing_states == ["stove on"]
    state.set_state("stove", "toggled_on", True)
    assert check_goal(state, goal).satisfied


@pytest.mark.parametrize(("words", "formula"), [
    ("no cup on any plate", "(forall (?x - cup) (not (exists (?y - plate) (ontop ?x ?y))))"),
    ("no cup may stay on any plates",
     "(forall (?x - cup) (not (exists (?y - plate) (ontop ?x ?y))))"),
    ("no cup on the plate", "(forall (?x - cup) (not (ontop ?x plate)))"),
])
def test_no_kind_on_any_kind_is_a_formula_that_holds_once_they_part(words: str,
                                                                     formula: str) -> None:
    graph = house()  # the cup stands on the plate
    goal = translate(words, graph)
    assert goal.formula == formula and goal.graph is None
    state = WorldState.from_graph(graph)
    assert not check_goal(state, goal).satisfied
    state.set_support("cup", "on", "counter")
    assert check_goal(state, goal).satisfied


def test_a_formula_clause_makes_the_whole_request_one_formula() -> None:
    goal = translate("no cup on any plate; turn on the stove; put the milk on the table",
                     house())
    assert goal.formula == ("(and (on milk table) (toggled_on stove) (forall (?x - cup) "
                            "(not (exists (?y - plate) (ontop ?x ?y)))))")


def test_an_and_between_two_noun_phrases_stays_one_list() -> None:
    reading = read_instruction("put the bowl and the cup on the counter", house())
    assert [e.sentence() for e in reading.edges] == ["bowl on counter", "cup on counter"]
