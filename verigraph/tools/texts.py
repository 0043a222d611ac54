"""Text forms of graphs and goals for the tools' text content.

Some clients show only a tool result's text (and some drop structured content), so the
text must be enough on its own: every object with its label and role (fixed or
movable, surface, container, capacity) and every edge, in lines a model reads easily.
"""

from __future__ import annotations

from verigraph.errors import VeriGraphError
from verigraph.graph.dictionary import (
    ROOM_RELATION,
    Dictionary,
    InlineDictionary,
    ObjectProperties,
    named_dictionary,
    open_label_properties,
    properties_text,
    state_text,
)
from verigraph.graph.goal import Goal
from verigraph.graph.model import Node, SceneGraph
from verigraph.graph.wellformed import readings_line


def _properties(node: Node, dictionary: Dictionary) -> ObjectProperties | None:
    label = dictionary.resolve(node.label)
    if label is None:  # a label of the client's own, if its attrs declare a role
        try:
            return open_label_properties(node.attrs)
        except VeriGraphError:
            return None
    try:
        return dictionary.objects[label].overridden(node.attrs)
    except VeriGraphError:
        return dictionary.objects[label]


def role(props: ObjectProperties | None) -> str:
    """`fixed surface, capacity 2`, `movable container`, `movable` ..."""
    if props is None:
        return "unknown to the dictionary"
    return properties_text(props)


def _role_and_state(node: Node, props: ObjectProperties | None) -> str:
    """`fixed container, capacity 4, openable; closed (default)`."""
    text = role(props)
    states = state_text(props, node.state) if props is not None else ""
    return f"{text}; {states}" if states else text


def _your_label(node: Node, dictionary: Dictionary) -> bool:
    """Whether the node's label is the client's own (declared inline or in its attrs)."""
    label = dictionary.resolve(node.label)
    if label is None:
        try:
            return open_label_properties(node.attrs) is not None
        except VeriGraphError:
            return False
    return label in dictionary.user_labels


def _sizes(node: Node) -> str:
    """`, width 18` for the sizes a node's attrs give (the user's numbers, shown)."""
    return "".join(f", {key} {node.attrs[key]:g}" for key in ("width", "height")
                   if isinstance(node.attrs.get(key), int | float)
                   and not isinstance(node.attrs.get(key), bool))


def objects_line(graph: SceneGraph, dictionary: str | InlineDictionary | None = None) -> str:
    """`objects: table (table: fixed surface); cup_2 (mug: movable container, capacity 1)`,
    with the sizes a node's attrs give (`plate_b (plate: ..., width 18)`)."""
    d = named_dictionary(graph.dictionary or dictionary)
    parts = [f"{n.id} ({n.label}: {'your label, ' if _your_label(n, d) else ''}"
             f"{_role_and_state(n, _properties(n, d))}{_sizes(n)})" for n in graph.nodes]
    return "objects: " + ("; ".join(parts) or "none")


def edges_line(graph: SceneGraph, prefix: str = "edges") -> str:
    """`edges: cup on table; ...`, then the states nodes have set (`; states: fridge
    closed, stove on`)."""
    states = graph.state_sentences()
    return f"{prefix}: " + ("; ".join(graph.sentences()) or "none") + (
        f"; states: {', '.join(states)}" if states else "")


def rooms_line(graph: SceneGraph) -> str:
    """`rooms: kitchen: counter, fridge, stove; dining_room: table` (the furniture of
    each room, from its `inroom` edges); empty when the graph has no rooms."""
    by_room: dict[str, list[str]] = {}
    for e in graph.edges:
        if e.relation == ROOM_RELATION:
            by_room.setdefault(e.target, []).append(e.source)
    if not by_room:
        return ""
    return "rooms: " + "; ".join(f"{room}: {', '.join(sorted(items))}"
                                 for room, items in by_room.items())


def graph_lines(graph: SceneGraph, dictionary: str | InlineDictionary | None = None) -> str:
    """Two lines: every object with label and role (and state), then every edge; a
    third with the furniture of each room when the graph has rooms."""
    rooms = rooms_line(graph)
    return f"{objects_line(graph, dictionary)}\n{edges_line(graph)}" + (
        f"\n{rooms}" if rooms else "")


def dictionary_line(name: str, user_labels: list[str], readings: list[str]) -> str:
    """`dictionary: home_office; your labels: laptop: movable surface, capacity 1`, then
    every normalisation of a label (never silent)."""
    text = f"dictionary: {name}"
    if user_labels:
        text += "; your labels: " + "; ".join(user_labels)
    if readings:
        text += "\n" + readings_line(readings)
    return text


MAX_DEFAULTS = 12


def defaults_line(graph: SceneGraph, dictionary: str | InlineDictionary | None = None) -> str:
    """The capacities taken from a built-in dictionary, not from the client: `assumed
    (built-in defaults; confirm with the user, a node's attrs win): stove holds 2, shelf
    3`; empty when every capacity is the client's own. A default is said to be one, so
    nobody takes the kitchen stove's 2 for a fact about this kitchen."""
    d = named_dictionary(graph.dictionary or dictionary)
    found: dict[str, None] = {}
    for node in graph.nodes:
        label = d.resolve(node.label)
        if label is None or label in d.user_labels or "capacity" in node.attrs:
            continue
        props = _properties(node, d)
        if props is not None and (props.surface or props.container) and \
                props.capacity is not None:
            found.setdefault(f"{label} holds {props.capacity}")
    if not found:
        return ""
    shown = list(found)[:MAX_DEFAULTS] + ([f"... and {len(found) - MAX_DEFAULTS} more"]
                                          if len(found) > MAX_DEFAULTS else [])
    return ("assumed (built-in defaults, not told by the user: confirm them with the user; a "
            "node's attrs.capacity wins): " + ", ".join(shown))


SIDES_TEXT = ("sides: numbered clockwise (seen from above) from vertex 0, side i from vertex "
              "i to i+1; vertex 0 is a triangle's right angle (sides 0 and 2 the legs, 1 "
              "the hypotenuse), the parallelogram's acute vertex that starts a long side (0 "
              "and 2 long, 1 and 3 short); a square's sides are alike")


def sides_line(graph: SceneGraph, dictionary: str | InlineDictionary | None = None) -> str:
    """How tangram sides are numbered, when the graph has pieces; empty otherwise."""
    d = named_dictionary(graph.dictionary or dictionary)
    pieces = any((p := _properties(n, d)) is not None and p.sides for n in graph.nodes)
    return SIDES_TEXT if pieces else ""


MAX_FORMULA_SHOWN = 600  # characters of a goal formula a text shows


def goal_edges_text(goal: Goal) -> str:
    """A goal graph's edges and node states as set_goal's `edges` text takes them back
    (`milk in fridge; stove on`)."""
    if goal.graph is None:
        return ""
    return "; ".join([*goal.graph.sentences(), *goal.graph.state_sentences()])


def goal_line(goal: Goal | None) -> str | None:
    """`goal (partial): cup on table`, `goal: single_stack` or `goal: formula (forall
    ...)`; None without a goal."""
    if goal is None:
        return None
    parts = []
    if goal.graph is not None:
        parts.append(goal_edges_text(goal) or "no edges")
    if goal.predicate:
        parts.append(goal.predicate)
    text = goal.formula_text()
    if text is not None:
        parts.append("formula " + (text if len(text) <= MAX_FORMULA_SHOWN
                                   else text[:MAX_FORMULA_SHOWN - 3] + "..."))
    if not parts:
        return None
    partial = " (partial)" if goal.partial and goal.graph is not None else ""
    return f"goal{partial}: " + "; ".join(parts)
