"""The household dictionary: built on the kitchen and the tableware (`extends`), named
by household scenes only; the kitchen and the union of built-ins stay the paper's."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from verigraph.actions import validate_plan
from verigraph.graph import SceneGraph, WorldState
from verigraph.graph.dictionary import (
    BUILTIN_DICTIONARIES,
    HOUSEHOLD_RELATIONS,
    UNION_DICTIONARIES,
    builtin_dictionary,
    builtin_homes,
    load_dictionary,
    parse_inline,
    union_dictionary,
    wrong_dictionary_advice,
)
from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, Node
from verigraph.graph.wellformed import check_well_formed
from verigraph.solver.table_search import needs_table_search

pytestmark = pytest.mark.fast

STORAGE = Path("tests/data/llm_trials/round3/t08_storage/start.json")


def test_the_household_is_the_kitchen_and_tableware_plus_states_rooms_and_relations() -> None:
    household, kitchen = builtin_dictionary("household"), builtin_dictionary("kitchen")
    tableware = builtin_dictionary("tableware")
    assert household.relations == HOUSEHOLD_RELATIONS
    for label, props in {**tableware.objects, **kitchen.objects}.items():
        if label != "stove":  # a word both know is the kitchen's, as in the union
            assert household.objects[label] == props, label
    assert household.objects["stove"].toggleable
    assert household.objects["stove"].model_copy(update={"toggleable": False}) == \
        kitchen.objects["stove"]
    assert household.objects["fridge"].openable and household.objects["kitchen"].room
    assert household.ambiguous == {}


def test_the_kitchen_and_the_union_are_the_paper_worlds() -> None:
    kitchen = builtin_dictionary("kitchen")
    assert kitchen.relations == ("on", "in")
    assert not any(p.openable or p.toggleable or p.room for p in kitchen.objects.values())
    assert "household" in BUILTIN_DICTIONARIES and "household" not in UNION_DICTIONARIES
    union = union_dictionary()
    assert union.relations == ("on", "in", "touches") and load_dictionary("all") is union
    for word in ("fridge", "drawer", "box", "kitchen", "milk"):
        assert union.resolve(word) is None, word
    assert builtin_homes("pan") == ["kitchen"] and builtin_homes("fridge") == ["household"]


def test_a_household_label_in_the_kitchen_is_sent_to_the_household_by_name() -> None:
    advice = wrong_dictionary_advice(["fridge"], "kitchen", ["fridge", "counter"])
    assert advice is not None
    message, fix, covered = advice
    assert message == "`fridge` is in the household dictionary; use it"
    assert fix == 'set "dictionary": "household"' and covered == ["fridge"]


def test_a_user_dictionary_extends_the_household() -> None:
    spec = parse_inline({"extends": "household", "objects": {"safe": {
        "movable": False, "container": True, "capacity": 2, "openable": True}}})
    built = load_dictionary(spec)
    assert built.relations == HOUSEHOLD_RELATIONS
    assert built.objects["fridge"].openable and built.objects["safe"].openable
    graph = SceneGraph.model_validate({
        "nodes": [{"id": "safe", "label": "safe", "state": {"open": False}},
                  {"id": "milk", "label": "milk"}, {"id": "counter", "label": "counter"}],
        "edges": [{"source": "milk", "relation": "on", "target": "counter"}],
        "dictionary": spec.model_dump(mode="json", exclude_none=True)})
    report = validate_plan(graph, "move(milk, in, safe)")
    assert report["violations"][0]["constraint"] == "container_closed"


def test_a_state_the_kind_lacks_outside_the_household_names_the_household() -> None:
    for dictionary in ("kitchen", None):
        graph = SceneGraph.model_validate({
            "nodes": [{"id": "s", "label": "stove", "state": {"toggled_on": True}}],
            "edges": [], "dictionary": dictionary})
        (problem,) = check_well_formed(graph, load_dictionary(dictionary))
        assert problem.rule == "state_without_role"
        assert problem.fix.startswith('name the household dictionary ("dictionary": '
                                      '"household"), whose stove is toggleable')
    plate = SceneGraph.model_validate({
        "nodes": [{"id": "p", "label": "plate", "state": {"open": True}}], "edges": [],
        "dictionary": "household"})
    problem = next(p for p in check_well_formed(plate, load_dictionary("household"))
                   if p.rule == "state_without_role")
    assert "household" not in problem.fix and '{"openable": true}' in problem.fix


def test_a_drawer_without_a_dictionary_is_not_closed() -> None:
    graph = SceneGraph.model_validate({
        "nodes": [{"id": "t", "label": "table"}, {"id": "d", "label": "drawer",
                                                   "attrs": {"container": True}},
                  {"id": "c", "label": "cup"}],
        "edges": [{"source": "c", "relation": "on", "target": "t"},
                  {"source": "d", "relation": "on", "target": "t"}]})
    assert validate_plan(graph, "move(c, in, d)")["valid"]


def test_only_household_scenes_go_to_the_table_search() -> None:
    data = json.loads(STORAGE.read_text())
    storage = SceneGraph.model_validate(data)
    goal = Goal(graph=SceneGraph(nodes=[], edges=[]), partial=True)
    assert not needs_table_search(WorldState.from_graph(storage), goal)
    # the same puzzle in the household dictionary: under/nextto allowed, boxes openable
    household = storage.model_copy(update={"dictionary": "household"})
    assert needs_table_search(WorldState.from_graph(household), goal)
    # a household tabletop without openables or states stays on on/in
    shelf = SceneGraph(nodes=[Node(id="s", label="shelf"), Node(id="c", label="cup"),
                              Node(id="p", label="plate")],
                       edges=[Edge(source="c", relation="on", target="s"),
                              Edge(source="p", relation="on", target="s")],
                       dictionary="household")
    assert not needs_table_search(WorldState.from_graph(shelf), goal)
    with_lamp = shelf.model_copy(update={"nodes": [*shelf.nodes, Node(id="l", label="lamp")],
                                         "edges": [*shelf.edges, Edge(
                                             source="l", relation="on", target="s")]})
    assert needs_table_search(WorldState.from_graph(with_lamp), goal)
