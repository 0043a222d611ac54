"""The cyclic collector pause around large graph builds: taken only for large graphs,
shared by concurrent builds, and always given back."""

from __future__ import annotations

import gc
import json
import threading

import pytest

from verigraph.errors import InputFileError, MalformedGraphError
from verigraph.graph import Edge, Node, SceneGraph, WorldState
from verigraph.graph.bulk import LARGE_GRAPH_ITEMS, collector_paused, graph_items
from verigraph.graph.io import scene_from_data, scene_from_json

pytestmark = pytest.mark.fast


def test_small_builds_leave_the_collector_alone() -> None:
    assert gc.isenabled()
    with collector_paused(LARGE_GRAPH_ITEMS - 1):
        assert gc.isenabled()


def test_large_builds_pause_it_and_give_it_back_even_on_error() -> None:
    with pytest.raises(RuntimeError), collector_paused(LARGE_GRAPH_ITEMS):
        assert not gc.isenabled()
        raise RuntimeError("the build failed")
    assert gc.isenabled()


def test_a_collector_paused_by_someone_else_stays_paused() -> None:
    gc.disable()
    try:
        with collector_paused(LARGE_GRAPH_ITEMS):
            pass
        assert not gc.isenabled()
    finally:
        gc.enable()


def test_overlapping_builds_on_threads_resume_only_after_the_last() -> None:
    first_in, second_in, first_out = threading.Event(), threading.Event(), threading.Event()
    seen: list[bool] = []

    def first() -> None:
        with collector_paused(LARGE_GRAPH_ITEMS):
            first_in.set()
            second_in.wait(10)
        first_out.set()

    def second() -> None:
        first_in.wait(10)
        with collector_paused(LARGE_GRAPH_ITEMS):
            second_in.set()
            first_out.wait(10)
            seen.append(gc.isenabled())  # the first build ended, this one still runs

    threads = [threading.Thread(target=first), threading.Thread(target=second)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(10)
    assert seen == [False]
    assert gc.isenabled()


def test_graph_items_counts_nodes_and_edges_also_of_a_goal() -> None:
    graph = {"nodes": [{}] * 3, "edges": [{}] * 2}
    assert graph_items(graph) == 5
    assert graph_items({"graph": graph, "partial": True}) == 5
    assert graph_items("cup_on_book") == 0


def test_a_refused_large_graph_gives_the_collector_back() -> None:
    n = LARGE_GRAPH_ITEMS
    nodes = [Node(id="table", label="table")] + [Node(id=f"b{i}", label="block")
                                                 for i in range(n)]
    edges = [Edge(source=f"b{i}", relation="on", target=f"b{i - 1}" if i else "table")
             for i in range(1, n)]  # b0 has no support
    with pytest.raises(MalformedGraphError):
        WorldState.from_graph(SceneGraph(nodes=nodes, edges=edges, dictionary="blocks"))
    assert gc.isenabled()
    data = {"nodes": [{"id": f"n{i}", "label": "block"} for i in range(n)], "edges": []}
    assert len(scene_from_data(data).nodes) == n and gc.isenabled()


def test_scene_from_json_reads_what_model_validate_reads_and_names_bad_fields() -> None:
    data = {"nodes": [{"id": "table", "label": "table"}] + [
        {"id": f"b{i}", "label": "block"} for i in range(LARGE_GRAPH_ITEMS)],
        "edges": [{"source": "b0", "relation": "on", "target": "table"}],
        "dictionary": "blocks"}
    text = json.dumps(data)
    assert scene_from_json(text) == SceneGraph.model_validate(data)
    assert scene_from_json(text.encode()) == SceneGraph.model_validate(data)
    assert gc.isenabled()
    data["nodes"][3]["id"] = "no spaces"
    with pytest.raises(InputFileError) as bad:
        scene_from_json(json.dumps(data))
    assert bad.value.field == "scene.nodes.3.id"
    assert gc.isenabled()
