"""A scene under the wrong built-in dictionary is told which one knows its labels."""

from __future__ import annotations

from typing import Any

import pytest

from verigraph.errors import VeriGraphError
from verigraph.graph.dictionary import wrong_dictionary_advice
from verigraph.tools import Toolbox

pytestmark = pytest.mark.fast


def kitchen_table(*extra: dict[str, str]) -> dict[str, Any]:
    nodes = [{"id": "table", "label": "table"}, {"id": "tray", "label": "tray"},
             {"id": "plate_1", "label": "plate"}, {"id": "cup_2", "label": "mug"},
             {"id": "shelf", "label": "shelf"}, *extra]
    edges = [{"source": "tray", "relation": "on", "target": "table"},
             {"source": "plate_1", "relation": "on", "target": "tray"},
             {"source": "cup_2", "relation": "on", "target": "table"}]
    return {"dictionary": "kitchen", "nodes": nodes, "edges": edges}


def load_error(graph: dict[str, Any]) -> str:
    with pytest.raises(VeriGraphError) as err:
        Toolbox().call("load_scene", {"graph": graph})
    return str(err.value)


def test_labels_of_another_dictionary_name_it_instead_of_spellings() -> None:
    message = load_error(kitchen_table())
    assert ("`table`, `tray`, `plate` and `mug` are in the tableware dictionary; use it, or "
            "omit `dictionary` to use all built-ins") in message
    assert 'set "dictionary": "tableware"' in message
    assert "spoon" not in message and "kettle" not in message  # no spelling guesses
    assert "breaks 1 rule" in message


def test_a_scene_that_needs_two_dictionaries_is_told_to_omit_it() -> None:
    graph = kitchen_table({"id": "pan", "label": "pan"})
    graph["edges"].append({"source": "pan", "relation": "on", "target": "shelf"})
    message = load_error(graph)
    assert "not in the kitchen dictionary" in message and "in tableware" in message
    assert "omit `dictionary` to use all built-ins" in message and "use it" not in message


def test_misspellings_still_get_the_nearest_names() -> None:
    graph = kitchen_table()
    graph["nodes"][4]["label"] = "shelff"
    message = load_error(graph)
    assert "'shelff', which is not in the kitchen dictionary" in message
    assert "such as shelf" in message
    assert wrong_dictionary_advice(["shelff"], "kitchen", ["shelff"]) is None


def test_the_fixed_scene_loads() -> None:
    graph = kitchen_table()
    graph["dictionary"] = "tableware"
    state = Toolbox().call("load_scene", {"graph": graph})
    assert len(state.model_dump()["graph"]["nodes"]) == 5


def test_a_submitted_graph_gets_the_same_advice() -> None:
    graph = kitchen_table()
    out = Toolbox().call("submit_scene_graph", {"graph": graph})
    dumped = out.model_dump()
    assert dumped["accepted"] is False
    fields = [p["field"] for p in dumped["problems"]]
    assert fields == ["dictionary"]
    assert "in the tableware dictionary; use it" in dumped["problems"][0]["message"]
    retried = Toolbox().call("submit_scene_graph", {"graph": graph, "dictionary": "tableware"})
    assert retried.model_dump()["accepted"] is True
