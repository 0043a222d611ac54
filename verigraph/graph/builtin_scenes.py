"""Small hand-written scenes with their goals: the paper's examples, usable by id.

The simulator's generator adds many more; these are the ones documentation and tests
refer to by name.
"""

from __future__ import annotations

from collections.abc import Callable

from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, Node, SceneGraph


def _graph(dictionary: str | None, nodes: list[tuple[str, str]],
           edges: list[tuple[str, str, str]]) -> SceneGraph:
    return SceneGraph(nodes=[Node(id=i, label=lab) for i, lab in nodes],
                      edges=[Edge(source=s, relation=r, target=t) for s, r, t in edges],
                      dictionary=dictionary)


def cup_on_book() -> SceneGraph:
    """The paper's motivating example: a cup on a book on a desk, a shelf nearby."""
    return _graph("tableware", [("desk", "desk"), ("shelf", "shelf"), ("book", "book"),
                                ("cup", "cup")],
                  [("book", "on", "desk"), ("cup", "on", "book")])


def cup_on_book_goal() -> Goal:
    """Book on the shelf, cup back on the desk."""
    return Goal(graph=_graph("tableware", [("desk", "desk"), ("shelf", "shelf"),
                                           ("book", "book"), ("cup", "cup")],
                             [("book", "on", "shelf"), ("cup", "on", "desk")]),
                instruction="Put the book on the shelf.")


def three_blocks() -> SceneGraph:
    """Three blocks, an incomplete stack: red on blue, green alone."""
    return _graph("blocks", [("table", "table"), ("red_block", "block"),
                             ("blue_block", "block"), ("green_block", "block")],
                  [("blue_block", "on", "table"), ("red_block", "on", "blue_block"),
                   ("green_block", "on", "table")])


def kitchen_pan() -> SceneGraph:
    """A pan on the counter, a pot on the stove with a lid on the counter."""
    return _graph("kitchen", [("counter", "counter"), ("stove", "stove"), ("pan", "pan"),
                              ("pot", "pot"), ("spoon", "spoon"), ("lid", "lid")],
                  [("pan", "on", "counter"),
                   ("pot", "on", "stove"), ("spoon", "in", "pot"), ("lid", "on", "counter")])


def kitchen_household() -> SceneGraph:
    """A household: a kitchen (closed fridge, stove off, sink, closed cabinet, counter)
    and a dining room (table), with food and dishes, in the household dictionary
    (docs/worlds.md, Household worlds)."""
    graph = _graph("household", [
        ("kitchen", "kitchen"), ("dining_room", "dining_room"), ("counter", "counter"),
        ("fridge", "fridge"), ("stove", "stove"), ("sink", "sink"), ("cabinet", "cabinet"),
        ("table", "table"), ("milk", "milk"), ("bread", "bread"), ("pot", "pot"),
        ("plate", "plate"), ("cup", "cup"), ("bowl", "bowl")],
        [("counter", "inroom", "kitchen"), ("fridge", "inroom", "kitchen"),
         ("stove", "inroom", "kitchen"), ("sink", "inroom", "kitchen"),
         ("cabinet", "inroom", "kitchen"), ("table", "inroom", "dining_room"),
         ("milk", "on", "counter"), ("bread", "in", "cabinet"), ("pot", "in", "sink"),
         ("bowl", "on", "counter"), ("plate", "on", "table"), ("cup", "on", "plate")])
    states = {"fridge": {"open": False}, "stove": {"toggled_on": False},
              "cabinet": {"open": False}}
    for node in graph.nodes:
        node.state = dict(states.get(node.id, {}))
    return graph


def kitchen_household_goal() -> Goal:
    """The milk in the fridge, the fridge closed, the pot on the stove that is on."""
    graph = _graph("household", [("milk", "milk"), ("fridge", "fridge"), ("pot", "pot"),
                          ("stove", "stove")],
                   [("milk", "in", "fridge"), ("pot", "on", "stove")])
    for node in graph.nodes:
        node.state = {"fridge": {"open": False}, "stove": {"toggled_on": True}}.get(
            node.id, {})
    return Goal(graph=graph, partial=True,
                instruction="Put the milk in the fridge and close it; put the pot on the "
                            "stove and turn the stove on.")


BUILTIN_SCENES: dict[str, Callable[[], SceneGraph]] = {
    "cup_on_book": cup_on_book,
    "three_blocks": three_blocks,
    "kitchen_pan": kitchen_pan,
    "kitchen_household": kitchen_household,
}
BUILTIN_GOALS: dict[str, Callable[[], Goal]] = {
    "cup_on_book": cup_on_book_goal,
    "three_blocks": lambda: Goal(predicate="single_stack", instruction="Stack all blocks."),
    "kitchen_household": kitchen_household_goal,
}
