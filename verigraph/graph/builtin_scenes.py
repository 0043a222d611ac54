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


BUILTIN_SCENES: dict[str, Callable[[], SceneGraph]] = {
    "cup_on_book": cup_on_book,
    "three_blocks": three_blocks,
    "kitchen_pan": kitchen_pan,
}
BUILTIN_GOALS: dict[str, Callable[[], Goal]] = {
    "cup_on_book": cup_on_book_goal,
    "three_blocks": lambda: Goal(predicate="single_stack", instruction="Stack all blocks."),
}
