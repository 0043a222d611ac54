"""Well-formedness rules for scene graphs, each reported with the node it concerns.

A tabletop graph is well formed when ids are unique, labels and relations are known,
every movable object has exactly one support, supports exist and suit the relation
(`on` needs a surface, `in` a container), no capacity is exceeded and there is no
cycle. A partial graph (a goal listing only some edges) skips the completeness rule.
"""

from __future__ import annotations

from collections import Counter

from pydantic import BaseModel

from verigraph.budget import checkpoint
from verigraph.graph.cycles import find_single_support_cycle, find_support_cycle
from verigraph.graph.dictionary import (
    Dictionary,
    ObjectProperties,
    canonical_token,
    open_label_properties,
)
from verigraph.graph.model import Edge, SceneGraph

# Spelling suggestions cost a fuzzy match each; past this many unknown labels the fix
# names a few known labels instead, so a large bad graph is refused in linear time.
MAX_SPELLING_SUGGESTIONS = 20
# How a client declares a label of its own, shown wherever an unknown label is refused.
DECLARE_EXAMPLE = ('or declare your own: {"id": "laptop", "label": "laptop", "attrs": '
                   '{"movable": true, "surface": true, "capacity": 1}}')
__all__ = ["DECLARE_EXAMPLE", "GraphProblem", "check_and_resolve", "check_well_formed",
           "find_single_support_cycle", "find_support_cycle", "label_readings", "open_labels",
           "readings_line", "resolve_properties"]


class GraphProblem(BaseModel):
    """One broken rule: which rule, which node, what is wrong and how to fix it."""

    rule: str
    node: str | None
    field: str
    message: str
    fix: str


def resolve_properties(graph: SceneGraph, dictionary: Dictionary,
                       problems: list[GraphProblem]) -> dict[str, tuple[str, ObjectProperties]]:
    """Map node id -> (canonical label, properties), recording unknown labels as problems."""
    resolved: dict[str, tuple[str, ObjectProperties]] = {}
    unknown = 0
    known: list[str] = []
    labels: dict[str, str | None] = {}  # raw label -> canonical: scenes repeat labels
    for i, node in enumerate(graph.nodes):
        if node.label in labels:
            label = labels[node.label]
        else:
            label = labels[node.label] = dictionary.resolve(node.label)
        if label is None:
            choices = dictionary.choices(node.label)
            if choices:
                problems.append(GraphProblem(
                    rule="ambiguous_label", node=node.id, field=f"nodes[{i}].label",
                    message=f"node '{node.id}' has label '{node.label}', which means "
                            f"{' or '.join(choices)} in the {dictionary.name} dictionary",
                    fix=f"write one of {', '.join(choices)}, or name the dictionary you mean"))
                continue
            try:
                declared = open_label_properties(node.attrs)
            except Exception as exc:  # DictionaryError: a role of the wrong type
                problems.append(GraphProblem(rule="bad_attribute", node=node.id,
                                             field=f"nodes[{i}].attrs", message=str(exc),
                                             fix="give roles as booleans, e.g. surface: true"))
                continue
            if declared is not None:  # the client's own kind of object
                resolved.setdefault(node.id, (canonical_token(node.label), declared))
                continue
            unknown += 1
            near = dictionary.nearest(node.label) if unknown <= MAX_SPELLING_SUGGESTIONS else []
            known = known or dictionary.names[:5]
            problems.append(GraphProblem(
                rule="unknown_label", node=node.id, field=f"nodes[{i}].label",
                message=f"node '{node.id}' has label '{node.label}', which is not in the "
                        f"{dictionary.name} dictionary",
                fix=f"use a known label such as {', '.join(near or known)}, "
                    + DECLARE_EXAMPLE))
            continue
        try:
            props = dictionary.objects[label]
            if node.attrs:
                props = props.overridden(node.attrs)
        except Exception as exc:  # DictionaryError from a bad override
            problems.append(GraphProblem(rule="bad_attribute", node=node.id,
                                         field=f"nodes[{i}].attrs", message=str(exc),
                                         fix="give property overrides their documented type"))
            continue
        resolved.setdefault(node.id, (label, props))
    return resolved


def open_labels(dictionary: Dictionary, resolved: dict[str, tuple[str, ObjectProperties]]
                ) -> Dictionary:
    """`dictionary` plus the labels nodes declared in their attrs (the first node's role
    gives a label's entry; every node keeps its own properties all the same)."""
    objects = dictionary.objects
    found: dict[str, ObjectProperties] = {}
    for label, props in resolved.values():
        if label not in objects and label not in found:
            found[label] = props
    return dictionary.with_open_labels(found) if found else dictionary


MAX_READINGS = 40


def label_readings(graph: SceneGraph | None, dictionary: Dictionary,
                   *more: SceneGraph | None) -> list[str]:
    """Every label not written as its canonical name, once per spelling, over the graphs
    given (a scene and its goal; None skipped): `box read as block (synonym, blocks
    dictionary)`. `dictionary` includes the graph's own labels (WorldState.dictionary),
    so those read as `your label`."""
    readings: dict[str, str | None] = {}
    for written in (graph, *more):
        for node in written.nodes if written is not None else ():
            if node.label not in readings:
                readings[node.label] = dictionary.reading(node.label)
    found = [text for text in readings.values() if text]
    if len(found) > MAX_READINGS:
        found = [*found[:MAX_READINGS], f"... and {len(found) - MAX_READINGS} more"]
    return found


def readings_line(readings: list[str]) -> str:
    """`labels read: box read as block (synonym, blocks dictionary)`: every label the
    client wrote that was taken as another name (never silent); empty when none."""
    return "labels read: " + "; ".join(readings) if readings else ""


def check_well_formed(graph: SceneGraph, dictionary: Dictionary, *,
                      partial: bool = False) -> list[GraphProblem]:
    """Every rule the graph breaks (empty list = well formed). Runs in O(nodes + edges)."""
    return check_and_resolve(graph, dictionary, partial=partial)[0]


def check_and_resolve(graph: SceneGraph, dictionary: Dictionary, *, partial: bool = False
                      ) -> tuple[list[GraphProblem], dict[str, tuple[str, ObjectProperties]]]:
    """check_well_formed plus each node's (canonical label, properties), resolved once.

    Written for 100,000-node graphs: plain dicts in the loops, messages built only for
    the rules a graph breaks, and the cycle search on the one-support-per-object map
    whenever no object has two supports (the rule that is already a problem otherwise).
    """
    problems: list[GraphProblem] = []
    id_list = [n.id for n in graph.nodes]
    ids = set(id_list)
    if len(ids) != len(id_list):
        for node_id, count in Counter(id_list).items():
            if count > 1:
                problems.append(GraphProblem(
                    rule="duplicate_id", node=node_id, field="nodes",
                    message=f"node id '{node_id}' is used {count} times",
                    fix=f"give each object its own id, e.g. {node_id}_2"))
    resolved = resolve_properties(graph, dictionary, problems)
    below: dict[str, str] = {}  # object -> its (first) support
    more_below: dict[str, list[str]] = {}  # objects with several supports -> all of them
    relations = dictionary.relations
    resolved_get = resolved.get
    for i, edge in enumerate(graph.edges):
        if not i & 4095:
            checkpoint()
        relation, source, target_id = edge.relation, edge.source, edge.target
        if relation not in relations:
            problems.append(GraphProblem(
                rule="unknown_relation", node=edge.source, field=f"edges[{i}].relation",
                message=f"relation '{edge.relation}' ({edge.sentence()}) is not in R = "
                        f"{{{', '.join(dictionary.relations)}}}",
                fix=f"use one of {', '.join(dictionary.relations)}"))
            continue
        if source not in ids or target_id not in ids:
            missing = [x for x in (source, target_id) if x not in ids]
            problems.append(GraphProblem(
                rule="dangling_edge", node=missing[0], field=f"edges[{i}]",
                message=f"edge '{edge.sentence()}' names '{missing[0]}', which is not a node",
                fix=f"add a node with id '{missing[0]}' or remove the edge"))
            continue
        if source == target_id:
            problems.append(GraphProblem(
                rule="self_loop", node=edge.source, field=f"edges[{i}]",
                message=f"edge '{edge.sentence()}' relates '{edge.source}' to itself",
                fix="remove the edge"))
            continue
        if relation == "touches":
            problems.extend(_check_sides(edge, f"edges[{i}]", resolved))
            continue
        if source in below:
            more_below.setdefault(source, [below[source]]).append(target_id)
        else:
            below[source] = target_id
        target = resolved_get(target_id)
        if target is None:
            continue
        props = target[1]
        if relation == "on":
            if not props.surface:
                problems.append(GraphProblem(
                    rule="target_not_surface", node=edge.target, field=f"edges[{i}]",
                    message=f"'{edge.sentence()}': {edge.target} ({target[0]}) is not a "
                            "surface",
                    fix=f"use '{edge.source} in {edge.target}'" if props.container else
                        f"put {edge.source} on a surface"))
        elif relation == "in" and not props.container:
            problems.append(GraphProblem(
                rule="target_not_container", node=edge.target, field=f"edges[{i}]",
                message=f"'{edge.sentence()}': {edge.target} ({target[0]}) is not a container",
                fix=f"use '{edge.source} on {edge.target}'" if props.surface else
                    f"put {edge.source} in a container"))
    problems += _node_problems(resolved, below, more_below, partial)
    if more_below:
        cycle = find_support_cycle({k: more_below.get(k) or [v] for k, v in below.items()})
    else:
        cycle = find_single_support_cycle(below)
    if cycle:
        first = cycle[0]
        problems.append(GraphProblem(
            rule="cycle", node=first, field="edges",
            message=f"support edges form a cycle: {' -> '.join([*cycle, first])}",
            fix=f"remove one edge of the cycle, e.g. the one from '{first}'"))
    return problems, resolved


def _node_problems(resolved: dict[str, tuple[str, ObjectProperties]], below: dict[str, str],
                   more_below: dict[str, list[str]], partial: bool) -> list[GraphProblem]:
    """The per-object rules (support count, capacity), in node order.

    Only objects that may break one are visited: those with two supports, those with
    none, and those carrying more than the smallest capacity any object has; the
    candidates come from set operations, so a well-formed graph costs no Python loop.
    """
    carried = Counter(below.values())  # every support edge counts at its target
    for supports in more_below.values():
        carried.update(supports[1:])
    capacities = {id(p): p.capacity for _, p in resolved.values()
                  if p.capacity is not None and (p.surface or p.container)}
    flagged = set(more_below) | (resolved.keys() - below.keys())
    if capacities:
        least = min(capacities.values())
        flagged.update(t for t, n in carried.items() if n > least)
    problems: list[GraphProblem] = []
    if not flagged:
        return problems
    for node_id, (label, props) in resolved.items():
        if node_id not in flagged:
            continue
        if node_id in more_below:
            n_supports = len(more_below[node_id])
            problems.append(GraphProblem(
                rule="multiple_supports", node=node_id, field="edges",
                message=f"'{node_id}' rests on or in {n_supports} objects; an object has "
                        "exactly one support",
                fix=f"keep one of the edges from '{node_id}'"))
        elif node_id not in below and props.movable and not partial and props.sides is None:
            problems.append(GraphProblem(
                rule="missing_support", node=node_id, field="edges",
                message=f"movable object '{node_id}' ({label}) has no support edge",
                fix=f"add an edge such as {{source: {node_id}, relation: on, target: <surface>}}"))
        if props.capacity is not None and carried[node_id] > props.capacity and (
                props.surface or props.container):
            problems.append(GraphProblem(
                rule="over_capacity", node=node_id, field="edges",
                message=f"'{node_id}' carries {carried[node_id]} objects but its capacity is "
                        f"{props.capacity}",
                fix=f"move objects off '{node_id}' or raise attrs.capacity"))
    return problems


def _check_sides(edge: Edge, where: str, resolved: dict[str, tuple[str, ObjectProperties]]
                 ) -> list[GraphProblem]:
    problems = []
    for node_id, side, name in ((edge.source, edge.source_side, "source_side"),
                                (edge.target, edge.target_side, "target_side")):
        info = resolved.get(node_id)
        if info is None:
            continue
        n_sides = info[1].sides
        if n_sides is None:
            problems.append(GraphProblem(
                rule="unknown_side", node=node_id, field=f"{where}.relation",
                message=f"'{node_id}' ({info[0]}) is not a tangram piece and has no sides",
                fix="use 'touches' only between tangram pieces"))
        elif side is None or not 0 <= side < n_sides:
            problems.append(GraphProblem(
                rule="unknown_side", node=node_id, field=f"{where}.{name}",
                message=f"'{edge.sentence()}': {node_id} has sides 0..{n_sides - 1}, got {side}",
                fix=f"give {name} between 0 and {n_sides - 1}"))
    return problems
