"""Well-formedness: each rule reported with the node it concerns."""

import pytest

from scenes import graph
from verigraph.errors import MalformedGraphError
from verigraph.graph import Edge, Node, SceneGraph, WorldState, builtin_dictionary
from verigraph.graph.wellformed import check_well_formed

pytestmark = pytest.mark.fast

TW = builtin_dictionary("tableware")


def rules(g, partial=False):
    return {(p.rule, p.node) for p in check_well_formed(g, TW, partial=partial)}


def test_paper_example_is_well_formed():
    g = graph("tableware", [("desk", "desk"), ("book", "book"), ("cup", "cup")],
              [("book", "on", "desk"), ("cup", "on", "book")])
    assert check_well_formed(g, TW) == []


@pytest.mark.parametrize("nodes,edges,expected", [
    ([("table", "table"), ("cup", "cup"), ("cup", "cup")], [("cup", "on", "table")],
     ("duplicate_id", "cup")),
    ([("table", "table"), ("cup", "teapot")], [("cup", "on", "table")],
     ("unknown_label", "cup")),
    ([("table", "table"), ("cup", "cup")], [("cup", "under", "table")],
     ("unknown_relation", "cup")),
    ([("table", "table"), ("cup", "cup")], [("cup", "on", "desk")], ("dangling_edge", "desk")),
    ([("table", "table"), ("cup", "cup")], [("cup", "on", "cup")], ("self_loop", "cup")),
    ([("table", "table"), ("cup", "cup")], [], ("missing_support", "cup")),
    ([("table", "table"), ("plate", "plate"), ("cup", "cup")],
     [("cup", "on", "table"), ("cup", "on", "plate"), ("plate", "on", "table")],
     ("multiple_supports", "cup")),
    ([("table", "table"), ("cup", "cup"), ("spoon", "spoon")],
     [("cup", "on", "table"), ("spoon", "on", "cup")], ("target_not_surface", "cup")),
    ([("table", "table"), ("plate", "plate"), ("spoon", "spoon")],
     [("plate", "on", "table"), ("spoon", "in", "plate")], ("target_not_container", "plate")),
    ([("table", "table"), ("cup", "cup"), ("spoon", "spoon"), ("fork", "fork")],
     [("cup", "on", "table"), ("spoon", "in", "cup"), ("fork", "in", "cup")],
     ("over_capacity", "cup")),
])
def test_each_rule_names_its_node(nodes, edges, expected):
    assert expected in rules(graph("tableware", nodes, edges))


def test_cycle_is_reported():
    g = graph("tableware", [("a", "book"), ("b", "book")], [("a", "on", "b"), ("b", "on", "a")])
    found = [p for p in check_well_formed(g, TW) if p.rule == "cycle"]
    assert found and "->" in found[0].message


def test_partial_graphs_need_no_support_for_every_object():
    g = graph("tableware", [("table", "table"), ("cup", "cup")], [])
    assert rules(g, partial=True) == set()


def test_world_state_rejects_malformed_graphs_listing_all_problems():
    g = graph("tableware", [("table", "table"), ("cup", "cup"), ("cup", "cup"), ("x", "zzz")],
              [])
    with pytest.raises(MalformedGraphError) as err:
        WorldState.from_graph(g)
    assert {p.rule for p in err.value.problems} >= {"duplicate_id", "unknown_label"}
    assert "more" in str(err.value)


def test_synonym_labels_are_normalised_in_the_state():
    g = SceneGraph(nodes=[Node(id="t", label="tabletop"), Node(id="d", label="dish")],
                   edges=[Edge(source="d", relation="on", target="t")], dictionary="tableware")
    state = WorldState.from_graph(g)
    assert state.objects["d"].label == "plate"
    assert {n.label for n in state.to_graph().nodes} == {"table", "plate"}


def test_tangram_sides_are_checked():
    g = SceneGraph(nodes=[Node(id="square", label="square"),
                          Node(id="medium_triangle", label="medium_triangle")],
                   edges=[Edge(source="square", relation="touches", target="medium_triangle",
                               source_side=0, target_side=3)], dictionary="tangram")
    problems = check_well_formed(g, builtin_dictionary("tangram"))
    assert [p.rule for p in problems] == ["unknown_side"]
    assert "0..2" in problems[0].message
