"""Scene graph model: JSON/YAML/networkx round trips and canonical form."""

import json

import networkx as nx
import pytest

from verigraph.errors import InputFileError
from verigraph.graph import Edge, Node, SceneGraph, WorldState, load_scene, save_graph
from verigraph.graph.builtin_scenes import cup_on_book
from verigraph.graph.io import scene_from_data

pytestmark = pytest.mark.fast


def test_networkx_round_trip_keeps_nodes_edges_and_sides():
    g = SceneGraph(nodes=[Node(id="square", label="square", attrs={"color": "orange"}),
                          Node(id="parallelogram", label="parallelogram")],
                   edges=[Edge(source="square", relation="touches", target="parallelogram",
                               source_side=1, target_side=3)], dictionary="tangram")
    nxg = g.to_networkx()
    assert isinstance(nxg, nx.DiGraph)
    assert nxg.edges["square", "parallelogram"] == {"relation": "touches", "source_side": 1,
                                                    "target_side": 3}
    assert SceneGraph.from_networkx(nxg) == g


@pytest.mark.parametrize("suffix", [".json", ".yaml"])
def test_file_round_trip(tmp_path, suffix):
    g = cup_on_book()
    path = tmp_path / f"scene{suffix}"
    save_graph(g, path)
    assert load_scene(path) == g


def test_canonical_order_makes_equal_scenes_dump_equally():
    g = cup_on_book()
    shuffled = SceneGraph(nodes=list(reversed(g.nodes)), edges=list(reversed(g.edges)),
                          dictionary=g.dictionary)
    assert shuffled.canonical().model_dump_json() == g.canonical().model_dump_json()


def test_touches_edge_key_is_undirected():
    a = Edge(source="p", relation="touches", target="q", source_side=1, target_side=2)
    b = Edge(source="q", relation="touches", target="p", source_side=2, target_side=1)
    assert a.key() == b.key()
    on = Edge(source="p", relation="on", target="q")
    assert on.key() != Edge(source="q", relation="on", target="p").key()


def test_bad_json_names_line_and_column(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"nodes": [\n  {"id": "cup",, }\n]}')
    with pytest.raises(InputFileError) as err:
        load_scene(path)
    assert "line 2" in str(err.value) and "column" in str(err.value)


def test_bad_yaml_is_an_input_error(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text("nodes: [\n  - id: cup\n  label: : :\n")
    with pytest.raises(InputFileError, match="invalid YAML"):
        load_scene(path)


def test_wrong_shape_names_the_field():
    with pytest.raises(InputFileError) as err:
        scene_from_data({"nodes": [{"id": "cup"}], "edges": []})
    assert err.value.field == "scene.nodes.0.label"
    with pytest.raises(InputFileError, match="mapping"):
        scene_from_data(json.loads("[1, 2]"))


def test_to_graph_equals_the_graph_built_model_by_model():
    """`WorldState.to_graph` validates plain data in one call: the same graph (and fields
    set) as building each Node and Edge, blocks and tangram contacts alike."""
    tangram = SceneGraph(nodes=[Node(id="square", label="square", attrs={"color": "red"}),
                                Node(id="parallelogram", label="parallelogram"),
                                Node(id="small_triangle", label="small_triangle_1")],
                         edges=[Edge(source="square", relation="touches", target="parallelogram",
                                     source_side=1, target_side=3),
                                Edge(source="small_triangle", relation="touches",
                                     target="square", source_side=0, target_side=2)],
                         dictionary="tangram")
    for graph in (cup_on_book(), tangram):
        state = WorldState.from_graph(graph)
        built = SceneGraph(nodes=[Node(id=o.id, label=o.label, attrs=dict(o.attrs))
                                  for o in state.objects.values()], edges=state.edges(),
                           dictionary=state.dictionary.reference()).canonical()
        got = state.to_graph()
        assert got == built and got.model_dump_json() == built.model_dump_json()
        assert [n.model_fields_set for n in got.nodes] == [n.model_fields_set for n in built.nodes]
        assert [e.model_fields_set for e in got.edges] == [e.model_fields_set for e in built.edges]
