"""What a model reads when it brings its own words: label help by meaning, the user's
declarations winning aloud, look-alike labels, goals that change what an object is, and
the built-in properties a stateless check applies."""

from __future__ import annotations

import copy
from typing import Any

import pytest
from mcp import Client
from mcp_helpers import structured, text

from verigraph.errors import VeriGraphError
from verigraph.graph.dictionary import union_dictionary
from verigraph.server import build_server
from verigraph.tools import Toolbox
from verigraph.tools.registry import TOOLS

pytestmark = [pytest.mark.fast, pytest.mark.anyio]


def refusal(tool: str, arguments: dict[str, Any]) -> str:
    with pytest.raises(VeriGraphError) as caught:
        Toolbox().call(tool, arguments)
    return str(caught.value)


FRUIT = {"nodes": [{"id": "t", "label": "table"}, {"id": "b", "label": "basket"},
                   {"id": "a", "label": "apple"}, {"id": "o", "label": "orange"}],
         "edges": [{"source": "b", "relation": "on", "target": "t"},
                   {"source": "a", "relation": "on", "target": "t"},
                   {"source": "o", "relation": "in", "target": "b"}]}


def _problem_line(message: str, node: str) -> str:
    return next(line for line in message.splitlines() if f"node '{node}'" in line)


def test_an_unknown_label_gets_help_by_meaning_with_its_own_declaration() -> None:
    message = refusal("load_scene", {"graph": FRUIT})
    apple = _problem_line(message, "a")
    basket = _problem_line(message, "b")
    # Not by spelling alone: an apple is no table, plate or spoon.
    assert "table, plate, spoon" not in apple and "close in spelling" not in apple
    assert '{"id": "a", "label": "apple", "attrs": {"movable": true}}' in apple
    assert "it rests on t and holds nothing here" in apple
    # The basket's declaration is its own (not the first unknown node's), a container.
    assert ('{"id": "b", "label": "basket", "attrs": {"movable": true, "container": true, '
            '"capacity": 1}}') in basket
    assert "o is in it here" in basket
    suggested = basket.split("built-in movable container such as ")[1].split(")")[0]
    union = union_dictionary()
    for label in suggested.split(", "):
        props = union.objects[label.strip()]
        assert props.container and props.movable, label
    # A fixed surface that carries things is declared as one.
    desk = {"nodes": [{"id": "bench", "label": "workbench"}, {"id": "c", "label": "cup"}],
            "edges": [{"source": "c", "relation": "on", "target": "bench"}]}
    line = _problem_line(refusal("load_scene", {"graph": desk}), "bench")
    assert '"attrs": {"movable": false, "surface": true}' in line
    # A misspelling still gets the near name first.
    typo = copy.deepcopy(FRUIT)
    typo["nodes"][1]["label"] = "bowll"
    assert "such as bowl (close in spelling)" in _problem_line(
        refusal("load_scene", {"graph": typo}), "b")


def test_load_scenes_description_says_how_to_declare_a_label() -> None:
    description = TOOLS["load_scene"].description
    assert "attrs" in description and '"container":true' in description


SHELF_SCENE = {"nodes": [{"id": "shelf", "label": "shelf"}, {"id": "m1", "label": "mug"},
                         {"id": "m2", "label": "mug"}, {"id": "m3", "label": "mug"},
                         {"id": "desk", "label": "desk"}],
               "edges": [{"source": "shelf", "relation": "on", "target": "desk"},
                         {"source": "m1", "relation": "on", "target": "desk"},
                         {"source": "m2", "relation": "on", "target": "desk"},
                         {"source": "m3", "relation": "on", "target": "desk"}]}
MINE = {"mug": {"container": True, "capacity": 2},
        "shelf": {"movable": False, "surface": True, "capacity": 2},
        "desk": {"movable": False, "surface": True}}


@pytest.mark.parametrize("extends", [None, "tableware"])
def test_the_users_mug_and_shelf_win_and_the_text_says_what_they_replace(
        extends: str | None) -> None:
    dictionary: dict[str, Any] = {"objects": MINE}
    if extends:
        dictionary["extends"] = extends
    box = Toolbox()
    state = box.call("load_scene", {"graph": SHELF_SCENE, "dictionary": dictionary})
    shown = state.summary()
    assert "shelf (shelf: your label, fixed surface, capacity 2)" in shown
    assert "m1 (mug: your label, movable container, capacity 2)" in shown
    assert ("shelf: fixed surface, capacity 2 (yours; replaces the built-in shelf: fixed "
            "surface, capacity 3") in shown
    assert "replaces the built-in mug: movable container, capacity 1" in shown
    # The user's capacity is the one the verifier applies.
    report = box.call("validate_plan", {
        "episode_id": state.episode_id,
        "plan": "move(m1, on, shelf)\nmove(m2, on, shelf)\nmove(m3, on, shelf)"})
    assert [s.ok for s in report.steps] == [True, True, False]
    assert report.violations[0].constraint == "target_full"
    assert "its capacity is 2" in report.violations[0].message


def test_with_extends_the_bases_synonyms_of_a_replaced_label_stay_and_yours_win() -> None:
    d = Toolbox().call("load_scene", {"dictionary": {
        "extends": "tableware", "objects": {
            "mug": {"container": True, "capacity": 2},
            "crate": {"container": True, "capacity": 4, "synonyms": ["tray"]}}},
        "graph": {"nodes": [{"id": "desk", "label": "desk"},
                            {"id": "m", "label": "coffee mug"},
                            {"id": "c", "label": "tray"}],
                  "edges": [{"source": "m", "relation": "on", "target": "desk"},
                            {"source": "c", "relation": "on", "target": "desk"}]}})
    shown = d.summary()
    assert "m (mug: your label, movable container, capacity 2)" in shown
    assert "c (crate: your label, movable container, capacity 4)" in shown
    assert "replaces 'tray' as the built-in tray" in shown
    assert "tray read as crate (synonym, your label)" in shown


async def test_a_look_alike_label_is_warned_about() -> None:
    lookalike = "cu\u0440"  # Cyrillic er
    graph = {"nodes": [{"id": "table", "label": "table"},
                       {"id": "c", "label": lookalike, "attrs": {"container": True}}],
             "edges": [{"source": "c", "relation": "on", "target": "table"}]}
    async with Client(build_server(Toolbox())) as client:
        loaded = await client.call_tool("load_scene", {"graph": graph})
        readings = structured(loaded)["label_readings"]
        assert any("looks like cup" in r and "U+0440" in r for r in readings), readings
        assert "looks like cup but is another label" in text(loaded)
        checked = await client.call_tool("validate_plan", {"graph": graph, "plan": "done"})
        assert "looks like cup" in text(checked)
    undeclared = copy.deepcopy(graph)
    undeclared["nodes"][1]["attrs"] = {}
    line = _problem_line(refusal("load_scene", {"graph": undeclared}), "c")
    assert line.split("(fix: ")[1].startswith("write cup")
    # Plain ASCII labels and accents that read as themselves are not warned about.
    state = Toolbox().call("load_scene", {"graph": {
        "nodes": [{"id": "table", "label": "table"}, {"id": "c", "label": "cup"}],
        "edges": [{"source": "c", "relation": "on", "target": "table"}]}})
    assert state.label_readings == []


GOAL_SCENE = {"nodes": [{"id": "table", "label": "table"}, {"id": "plate", "label": "plate",
                                                             "attrs": {"capacity": 3}},
                        {"id": "cup", "label": "cup"}],
              "edges": [{"source": "plate", "relation": "on", "target": "table"},
                        {"source": "cup", "relation": "on", "target": "table"}]}


def test_a_goal_that_changes_what_an_object_is_is_refused_with_the_reason() -> None:
    goal = {"graph": {"nodes": [{"id": "plate", "label": "plate",
                                 "attrs": {"container": True}}, {"id": "cup", "label": "cup"}],
                      "edges": [{"source": "cup", "relation": "in", "target": "plate"}]},
            "partial": True}
    message = refusal("validate_plan", {"graph": GOAL_SCENE, "plan": "move(cup, in, plate)",
                                        "goal": goal})
    assert "goal.graph.nodes[0]" in message and "container: true" in message
    assert "could never be reached" in message and "drop attrs.container" in message
    box = Toolbox()
    episode = box.call("load_scene", {"graph": GOAL_SCENE}).episode_id
    with pytest.raises(VeriGraphError) as caught:
        box.call("set_goal", {"episode_id": episode, "graph": goal["graph"], "partial": True})
    assert "could never be reached" in str(caught.value)
    # A goal node that repeats the scene's properties, or gives none, is the object as is.
    for attrs in ({"capacity": 3}, {}):
        same = {"graph": {"nodes": [{"id": "plate", "label": "plate", "attrs": attrs},
                                    {"id": "cup", "label": "cup"}],
                          "edges": [{"source": "cup", "relation": "on", "target": "plate"}]},
                "partial": True}
        report = box.call("validate_plan", {"graph": GOAL_SCENE, "goal": same,
                                            "plan": "move(cup, on, plate)"})
        assert report.valid


async def test_validate_plan_shows_the_built_in_properties_it_applies() -> None:
    graph = {"nodes": [{"id": "desk", "label": "desk"}, {"id": "shelf", "label": "shelf"},
                       {"id": "nb", "label": "notebook"}, {"id": "c", "label": "cup",
                                                           "attrs": {"capacity": 2}}],
             "edges": [{"source": "shelf", "relation": "on", "target": "desk"},
                       {"source": "nb", "relation": "on", "target": "desk"},
                       {"source": "c", "relation": "on", "target": "desk"}]}
    async with Client(build_server(Toolbox())) as client:
        shown = text(await client.call_tool("validate_plan", {"graph": graph,
                                                              "plan": "move(nb, on, shelf)"}))
    line = next(x for x in shown.splitlines() if x.startswith("built-in properties applied"))
    assert "(dictionary: all built-ins, none named)" in line
    assert "shelf: fixed surface, capacity 3 (" in line
    assert "book: movable surface" in line  # notebook is read as book
    assert "cup: movable container, capacity 2 (tableware dictionary; capacity from c's " \
           "attrs)" in line
    assert "notebook read as book (synonym, tableware dictionary)" in shown
    # Bounded: a scene of many kinds lists a dozen, then a count (of the kinds that carry
    # something or stay put; a kind that is only movable is left out).
    kinds = union_dictionary().objects
    labels = sorted(label for label, p in kinds.items() if p.sides is None and label != "table"
                    and (p.surface or p.container or not p.movable))
    assert len(labels) > 12
    many = {"nodes": [{"id": "table", "label": "table"}]
            + [{"id": f"o{i}", "label": label} for i, label in enumerate(labels)],
            "edges": [{"source": f"o{i}", "relation": "on", "target": "table"}
                      for i, label in enumerate(labels) if kinds[label].movable]}
    report = Toolbox().call("validate_plan", {"graph": many, "plan": "done"})
    from verigraph.tools.acting import report_summary
    applied = next(x for x in report_summary(report).splitlines()
                   if x.startswith("built-in properties applied"))
    assert applied.count(" dictionary)") <= 12 and "... and" in applied
    # The client's own labels are not listed as built-in.
    own = Toolbox().call("validate_plan", {"plan": "done", "graph": {
        "nodes": [{"id": "bench", "label": "bench", "attrs": {"movable": False,
                                                             "surface": True}}],
        "edges": []}})
    assert "built-in properties applied" not in report_summary(own)


def test_a_number_suffix_never_names_a_kind_of_its_own() -> None:
    """`cup_2` reads as `cup` for built-in labels; so a declared label with a suffix is
    that kind (`Widget 2` is a widget), and a dictionary word with one is refused."""
    state = Toolbox().call("load_scene", {"graph": {
        "nodes": [{"id": "t", "label": "table"},
                  {"id": "w", "label": "Widget 2", "attrs": {"surface": True}},
                  {"id": "v", "label": "widget_3", "attrs": {"surface": True,
                                                             "capacity": 2}}],
        "edges": [{"source": "w", "relation": "on", "target": "t"},
                  {"source": "v", "relation": "on", "target": "t"}]}})
    shown = state.summary()
    assert "w (widget: your label, movable surface, capacity 1)" in shown
    assert "v (widget: your label, movable surface, capacity 2)" in shown
    assert "widget_3 read as widget (number suffix dropped, your label)" in shown
    message = refusal("load_scene", {"dictionary": {"objects": {"crate": {
        "container": True, "synonyms": ["cup_2"]}}}, "graph": {"nodes": [], "edges": []}})
    assert "synonym of crate 'cup_2' ends in a number suffix" in message


def test_solve_shows_the_built_in_properties_it_applies() -> None:
    shown = Toolbox().call("solve", {"scene_id": "cup_on_book"}).summary()
    assert "built-in properties applied (dictionary: tableware): " in shown
    assert "shelf: fixed surface, capacity 3 (tableware dictionary)" in shown
