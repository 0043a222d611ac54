"""Text forms of graphs and goals for the tools' text content.

Some clients show only a tool result's text (and some drop structured content), so the
text must be enough on its own: every object with its label and role (fixed or
movable, surface, container, capacity) and every edge, in lines a model reads easily.
"""

from __future__ import annotations

from verigraph.errors import VeriGraphError
from verigraph.graph.dictionary import Dictionary, ObjectProperties, load_dictionary
from verigraph.graph.goal import Goal
from verigraph.graph.model import Node, SceneGraph
from verigraph.tools.fields import dictionary_for


def _dictionary(name: str | None) -> Dictionary:
    try:
        return dictionary_for(name)
    except VeriGraphError:  # a name the tools would have refused already; fall back
        return load_dictionary(None)


def _properties(node: Node, dictionary: Dictionary) -> ObjectProperties | None:
    label = dictionary.resolve(node.label)
    if label is None:
        return None
    try:
        return dictionary.objects[label].overridden(node.attrs)
    except VeriGraphError:
        return dictionary.objects[label]


def role(props: ObjectProperties | None) -> str:
    """`fixed surface, capacity 2`, `movable container`, `movable` ..."""
    if props is None:
        return "unknown to the dictionary"
    kinds = [k for k, on in (("surface", props.surface), ("container", props.container)) if on]
    text = " ".join(["movable" if props.movable else "fixed", *kinds])
    if kinds and props.capacity is not None:
        text += f", capacity {props.capacity}"
    return text


def objects_line(graph: SceneGraph, dictionary: str | None = None) -> str:
    """`objects: table (table: fixed surface); cup_2 (mug: movable container, capacity 1)`"""
    d = _dictionary(graph.dictionary or dictionary)
    parts = [f"{n.id} ({n.label}: {role(_properties(n, d))})" for n in graph.nodes]
    return "objects: " + ("; ".join(parts) or "none")


def edges_line(graph: SceneGraph, prefix: str = "edges") -> str:
    return f"{prefix}: " + ("; ".join(graph.sentences()) or "none")


def graph_lines(graph: SceneGraph, dictionary: str | None = None) -> str:
    """Two lines: every object with label and role, then every edge."""
    return f"{objects_line(graph, dictionary)}\n{edges_line(graph)}"


def goal_line(goal: Goal | None) -> str | None:
    """`goal (partial): cup on table` or `goal: single_stack`; None without a goal."""
    if goal is None:
        return None
    parts = []
    if goal.graph is not None:
        parts.append("; ".join(goal.graph.sentences()) or "no edges")
    if goal.predicate:
        parts.append(goal.predicate)
    if not parts:
        return None
    return f"goal{' (partial)' if goal.partial else ''}: " + "; ".join(parts)
