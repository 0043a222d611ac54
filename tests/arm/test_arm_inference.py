"""Locations -> scene graph: the closed loop's reading of the world."""

from __future__ import annotations

from verigraph.arm import ObjectLocation
from verigraph.arm.scene_inference import infer_graph
from verigraph.graph.dictionary import load_dictionary
from verigraph.graph.model import Node, SceneGraph

TABLE = ObjectLocation(object_id="table", centre=(0.4, 0.0, -0.01), size=(1.0, 1.0, 0.02),
                       timestamp=0.0)


def box(object_id: str, x: float, y: float, bottom: float,
        size: tuple[float, float, float] = (0.05, 0.05, 0.05)) -> ObjectLocation:
    return ObjectLocation(object_id=object_id, centre=(x, y, bottom + size[2] / 2), size=size,
                          timestamp=0.0)


def sentences(graph: SceneGraph, dictionary: str,
              locations: list[ObjectLocation]) -> set[str]:
    inferred = infer_graph(graph, load_dictionary(dictionary),
                           {loc.object_id: loc for loc in locations})
    return {e.sentence() for e in inferred.edges}


def nodes(dictionary: str, **labels: str) -> SceneGraph:
    return SceneGraph(nodes=[Node(id="table", label="table")] + [
        Node(id=i, label=lab) for i, lab in labels.items()], dictionary=dictionary)


def test_a_stack_is_read_bottom_up() -> None:
    graph = nodes("blocks", a="block", b="block", c="block")
    assert sentences(graph, "blocks", [TABLE, box("a", 0.4, 0, 0), box("b", 0.405, 0, 0.05),
                                       box("c", 0.4, 0.1, 0)]) == {
        "a on table", "b on a", "c on table"}


def test_a_held_or_fallen_object_has_no_support() -> None:
    graph = nodes("blocks", a="block", b="block")
    assert sentences(graph, "blocks", [TABLE, box("a", 0.4, 0, 0),
                                       box("b", 0.4, 0.0, 0.2)]) == {"a on table"}
    assert sentences(graph, "blocks", [TABLE, box("a", 0.4, 0, 0),
                                       box("b", 0.46, 0.0, 0.05)]) == {"a on table"}  # off the edge


def test_a_cup_in_a_bowl_but_never_a_bowl_in_a_cup() -> None:
    graph = nodes("tableware", bowl="bowl", cup="cup")
    bowl = box("bowl", 0.4, 0, 0, (0.12, 0.12, 0.06))
    cup = box("cup", 0.4, 0.005, 0.006, (0.06, 0.06, 0.08))
    assert sentences(graph, "tableware", [TABLE, bowl, cup]) == {"bowl on table", "cup in bowl"}


def test_an_over_full_support_explains_nothing_on_it() -> None:
    graph = nodes("blocks", a="block", b="block", c="block")
    wide = box("a", 0.4, 0, 0, (0.3, 0.3, 0.05))  # one block, two on it: capacity 1
    assert sentences(graph, "blocks", [TABLE, wide, box("b", 0.35, 0, 0.05),
                                       box("c", 0.45, 0, 0.05)]) == {"a on table"}
