"""Dictionaries a client gives: bounds, hostile input, open labels, synonyms out loud.

Hostile dictionaries go through the real MCP server (in process, the SDK's client):
each is refused quickly with the field and a fix, and no episode is stored.
"""

from __future__ import annotations

import time
from typing import Any

import pytest
from mcp import Client
from mcp_helpers import structured, text
from user_worlds import inline_scene

from verigraph.errors import DictionaryError, MalformedGraphError
from verigraph.graph import SceneGraph, WorldState
from verigraph.graph.dictionary import (
    BUILTIN_DICTIONARIES,
    Dictionary,
    ObjectProperties,
    builtin_dictionary,
    canonical_token,
    merge_dictionaries,
    open_label_properties,
    parse_inline,
    union_dictionary,
)
from verigraph.graph.wellformed import check_well_formed
from verigraph.server import build_server
from verigraph.tools import Toolbox

pytestmark = [pytest.mark.fast, pytest.mark.anyio]


HOSTILE: dict[str, tuple[dict[str, Any], str, str]] = {
    # name: (dictionary, field named in the error, words of the message)
    "100,000 labels": ({"objects": {f"thing_{i}": {} for i in range(100_000)}},
                       "dictionary", "at most 200"),
    "10 MB of synonyms": ({"objects": {"laptop": {"synonyms": ["w" * 1000] * 10_000}}},
                          "dictionary", "bytes as JSON"),
    "a label with a number suffix": (
        {"extends": "tableware", "objects": {"cup_2": {"container": True, "capacity": 5}}},
        "dictionary", "label 'cup_2' ends in a number suffix"),
    "a synonym with a number suffix": (
        {"objects": {"crate": {"container": True, "synonyms": ["cup_2"]}}},
        "dictionary", "synonym of crate 'cup_2' ends in a number suffix"),
    "extends as an object": ({"extends": {"name": "tableware"}, "objects": {"laptop": {}}},
                             "dictionary.extends", "valid string (got an object)"),
    "objects as a string": ({"objects": "laptop"}, "dictionary.objects",
                            "valid dictionary (got text)"),
    "extends something unknown": ({"extends": "office", "objects": {"laptop": {}}},
                                  "dictionary.extends", "no built-in dictionary 'office'"),
    "non-string synonyms": ({"objects": {"laptop": {"synonyms": [42, None]}}},
                            "dictionary.objects.laptop.synonyms", "synonyms are words"),
    "a non-boolean role": ({"objects": {"laptop": {"surface": "yes"}}},
                           "dictionary.objects.laptop.surface", "valid boolean"),
}


@pytest.mark.parametrize("case", list(HOSTILE))
async def test_hostile_dictionaries_are_refused_quickly_and_store_nothing(case: str) -> None:
    dictionary, field, words = HOSTILE[case]
    box = Toolbox()
    async with Client(build_server(box)) as c:
        scene = inline_scene()
        scene["dictionary"] = dictionary
        for tool, arguments in (("load_scene", {"graph": scene}),
                                ("submit_scene_graph", {"graph": inline_scene(),
                                                        "dictionary": dictionary})):
            started = time.perf_counter()
            result = await c.call_tool(tool, arguments)
            elapsed = time.perf_counter() - started
            shown = text(result)
            assert result.is_error, shown
            assert f"{field}" in shown and words in shown and "fix:" in shown, shown
            assert elapsed < 5.0, f"{tool} took {elapsed:.1f} s to refuse {case}"
            assert len(shown) < 2000
    assert len(box.context.store) == 0


@pytest.mark.parametrize("case", list(HOSTILE))
def test_the_library_refuses_them_with_field_and_fix(case: str) -> None:
    dictionary, field, words = HOSTILE[case]
    with pytest.raises(DictionaryError) as caught:
        parse_inline(dictionary)
    assert caught.value.field is not None and caught.value.field.startswith(field)
    assert words in caught.value.message and caught.value.fix


def test_an_inline_dictionary_extends_a_builtin_and_marks_its_labels() -> None:
    d = parse_inline(inline_scene()["dictionary"]).build()
    assert d.name == "home_office" and d.relations == ("on", "in")
    assert {"desk", "mug", "laptop", "pen_holder", "drawer_unit"} <= set(d.objects)
    assert d.user_labels == ("laptop", "pen_holder", "drawer_unit")
    assert d.resolve("pencil cup") == "pen_holder"
    assert d.reading("pencil cup") == "pencil cup read as pen_holder (synonym, your label)"
    assert d.objects["drawer_unit"].capacity == 2 and not d.objects["drawer_unit"].movable
    standalone = parse_inline({"objects": {"laptop": {"surface": True}}}).build()
    assert standalone.names == ["laptop"] and standalone.name == "yours"


def test_open_label_defaults() -> None:
    assert open_label_properties({"color": "red"}) is None  # no role declared
    movable_surface = open_label_properties({"surface": True})
    assert movable_surface == ObjectProperties(surface=True, capacity=1)
    fixed = open_label_properties({"movable": False, "surface": True})
    assert fixed is not None and fixed.capacity is None and not fixed.movable
    assert open_label_properties({"container": True, "capacity": 4}) == ObjectProperties(
        container=True, capacity=4)
    assert open_label_properties({"movable": True}) == ObjectProperties()
    with pytest.raises(DictionaryError):
        open_label_properties({"surface": "yes please"})


async def test_an_unknown_label_without_a_role_is_refused_with_how_to_declare_it() -> None:
    async with Client(build_server(Toolbox())) as c:
        graph = {"nodes": [{"id": "desk", "label": "desk"},
                           {"id": "laptop", "label": "laptop"}],
                 "edges": [{"source": "laptop", "relation": "on", "target": "desk"}]}
        refused = await c.call_tool("load_scene", {"graph": graph})
        assert refused.is_error
        assert "nodes[1].label" in text(refused)
        # The declaration is the failing node's own, with the role the graph gives it.
        assert '{"id": "laptop", "label": "laptop", "attrs": {"movable": true}}' \
            in text(refused)
        graph["nodes"][1]["attrs"] = {"surface": True}
        accepted = await c.call_tool("load_scene", {"graph": graph})
        assert "laptop (laptop: your label, movable surface, capacity 1)" in text(accepted)
        wrong_type = {"nodes": [{"id": "desk", "label": "desk"},
                                {"id": "laptop", "label": "laptop",
                                 "attrs": {"surface": "sometimes"}}],
                      "edges": [{"source": "laptop", "relation": "on", "target": "desk"}]}
        bad = await c.call_tool("load_scene", {"graph": wrong_type})
        assert bad.is_error and "nodes[1].attrs" in text(bad)


async def test_every_normalisation_is_reported_in_text_and_structure() -> None:
    async with Client(build_server(Toolbox())) as c:
        graph = {"nodes": [{"id": "table", "label": "Table Top"},
                           {"id": "a", "label": "cube"}, {"id": "b", "label": "Block"},
                           {"id": "c", "label": "block"}],
                 "edges": [{"source": "a", "relation": "on", "target": "table"},
                           {"source": "b", "relation": "on", "target": "a"},
                           {"source": "c", "relation": "on", "target": "table"}]}
        loaded = await c.call_tool("load_scene", {"graph": graph})
        readings = structured(loaded)["label_readings"]
        assert readings == ["Table Top read as table (synonym, blocks and tableware dictionary)",
                            "cube read as block (synonym, blocks dictionary)",
                            "Block read as block (case and spacing, blocks dictionary)"]
        for reading in readings:
            assert reading in text(loaded)
        submitted = structured(await c.call_tool("submit_scene_graph", {"graph": graph}))
        assert submitted["accepted"]
        assert {r["reading"] for r in submitted["normalised"] if r["reading"]} >= {
            "cube read as block (synonym, blocks dictionary)"}


async def test_box_is_no_longer_silently_a_block() -> None:
    async with Client(build_server(Toolbox())) as c:
        graph = {"nodes": [{"id": "table", "label": "table"}, {"id": "box", "label": "box"}],
                 "edges": [{"source": "box", "relation": "on", "target": "table"}]}
        refused = await c.call_tool("load_scene", {"graph": graph})
        assert refused.is_error and "'box'" in text(refused)
        graph["nodes"][1]["attrs"] = {"container": True, "capacity": 4}
        loaded = await c.call_tool("load_scene", {"graph": graph})
        assert "box (box: your label, movable container, capacity 4)" in text(loaded)


def test_no_builtin_word_names_two_kinds() -> None:
    """The review of the built-in synonym lists, kept: every word (name or synonym) means
    one kind across all built-in dictionaries, so the union `all` has no ambiguity."""
    meanings: dict[str, set[str]] = {}
    for name in BUILTIN_DICTIONARIES:
        for label, props in builtin_dictionary(name).objects.items():
            for word in (label, *props.synonyms):
                meanings.setdefault(canonical_token(word), set()).add(label)
    assert {w: k for w, k in meanings.items() if len(k) > 1} == {}
    assert union_dictionary().ambiguous == {}
    assert union_dictionary().resolve("box") is None


def test_a_word_two_dictionaries_mean_differently_is_refused_with_the_choices() -> None:
    office = Dictionary(name="office", objects={
        "desk": ObjectProperties(movable=False, surface=True),
        "crate": ObjectProperties(container=True, capacity=4, synonyms=("box",))})
    toys = Dictionary(name="toys", objects={
        "brick": ObjectProperties(surface=True, capacity=1, synonyms=("box",))})
    both = merge_dictionaries("both", [office, toys])
    assert both.ambiguous == {"box": ("crate", "brick")}
    assert both.resolve("box") is None and both.resolve("crate") == "crate"
    with pytest.raises(DictionaryError) as caught:
        both.normalise("Box")
    assert "crate or brick" in caught.value.message
    graph = SceneGraph.model_validate({
        "nodes": [{"id": "desk", "label": "desk"}, {"id": "b", "label": "box"}],
        "edges": [{"source": "b", "relation": "on", "target": "desk"}]})
    problems = check_well_formed(graph, both)
    assert [(p.rule, p.field) for p in problems] == [("ambiguous_label", "nodes[1].label")]
    assert "crate, brick" in problems[0].fix
    with pytest.raises(MalformedGraphError):
        WorldState.from_graph(graph, both)


def test_a_graph_with_an_inline_dictionary_round_trips() -> None:
    graph = SceneGraph.model_validate(inline_scene())
    state = WorldState.from_graph(graph)
    again = WorldState.from_graph(SceneGraph.model_validate_json(
        state.to_graph().model_dump_json()))
    assert again.dictionary == state.dictionary
    assert again.objects["pens"].label == "pen_holder"
    assert again.to_graph() == state.to_graph()
