"""Well-formedness rules for scene graphs, each reported with the node it concerns.

A tabletop graph is well formed when ids are unique, labels and relations are known,
every movable object has exactly one placement (`on`, `in`, `under`, `nextto`),
placements exist and suit the relation (`on` needs a surface, `in` a container,
`under` furniture: a fixed surface, `nextto` anything but a room), no capacity is
exceeded (only `on` and `in` count) and there is no cycle. `inroom` puts furniture (a
fixed object) in a room, at most one; a node's state keys need the kind's role
(`open`: openable, `toggled_on`: toggleable). A partial graph (a goal listing only
some edges) skips the completeness rule. docs/worlds.md, "Household worlds", says what
each relation means.
"""

from __future__ import annotations

import difflib
import json
import unicodedata
from collections import Counter

from pydantic import BaseModel

from verigraph.budget import checkpoint
from verigraph.errors import DictionaryError
from verigraph.graph.cycles import find_single_support_cycle, find_support_cycle
from verigraph.graph.dictionary import (
    KIND_KEYS,
    ROOM_RELATION,
    STATE_ROLES,
    SUPPORT_RELATIONS,
    Dictionary,
    ObjectProperties,
    builtin_dictionary,
    canonical_token,
    kind_token,
    open_label_properties,
    properties_text,
    union_dictionary,
)
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.reporting import readings_line

# Spelling suggestions cost a fuzzy match each; past this many unknown labels the fix
# names a few known labels instead, so a large bad graph is refused in linear time.
MAX_SPELLING_SUGGESTIONS = 20
# A known label this close in spelling (difflib ratio) is offered as a likely typo; less
# close ones are not offered (`apple` is not a misspelt `table`): the known labels of
# the node's role are.
SPELLING_CUTOFF = 0.75
__all__ = ["GraphProblem", "check_and_resolve", "check_well_formed",
           "find_single_support_cycle",
           "find_support_cycle", "label_readings", "open_labels", "readings_line",
           "resolve_properties"]


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
    roles: _GraphRoles | None = None
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
            except DictionaryError as exc:  # a role of the wrong type, a size out of bounds
                problems.append(_attribute_problem(node.id, i, exc))
                continue
            if declared is not None:  # the client's own kind (`widget_2` is a widget)
                resolved.setdefault(node.id, (kind_token(node.label), declared))
                continue
            unknown += 1
            roles = roles or _GraphRoles(graph, dictionary)
            problems.append(GraphProblem(
                rule="unknown_label", node=node.id, field=f"nodes[{i}].label",
                message=f"node '{node.id}' has label '{node.label}', which is not in the "
                        f"{dictionary.name} dictionary",
                fix=roles.fix(node, ranked=unknown <= MAX_SPELLING_SUGGESTIONS)))
            continue
        try:
            props = dictionary.objects[label]
            if node.attrs:
                props = props.overridden(node.attrs)
        except DictionaryError as exc:  # a bad override
            problems.append(_attribute_problem(node.id, i, exc))
            continue
        if node.state:
            problems.extend(_state_problems(node, i, label, props))
        resolved.setdefault(node.id, (label, props))
    return resolved


def _state_problems(node: Node, index: int, label: str, props: ObjectProperties
                    ) -> list[GraphProblem]:
    """A state key on a node whose kind lacks its role (`open` on a plate)."""
    problems = []
    for key in node.state:
        role = STATE_ROLES[key]
        if not getattr(props, role):
            problems.append(GraphProblem(
                rule="state_without_role", node=node.id, field=f"nodes[{index}].state.{key}",
                message=f"node '{node.id}' ({label}) has state '{key}', but a {label} is not "
                        f"{role}",
                fix=_state_fix(label, key, role)))
    return problems


def _state_fix(label: str, key: str, role: str) -> str:
    """Name the household dictionary when it gives `label` the role (a stove in the
    kitchen dictionary or in a scene that names none); else declare the role."""
    household = builtin_dictionary("household")
    kind = household.resolve(label)
    if kind is not None and getattr(household.objects[kind], role):
        return (f'name the household dictionary ("dictionary": "household"), whose {kind} '
                f"is {role}; or remove '{key}' from its state, or declare the role in its "
                f'attrs: {{"{role}": true}}')
    return f"remove '{key}' from its state, or declare the role in its attrs: " \
           f'{{"{role}": true}}'


class _GraphRoles:
    """What the graph says an unknown label's node does (what rests on or in it, whether
    it rests on something), for a refusal that helps by meaning: the node's own
    declaration with that role, and known labels of the same role (not of similar
    spelling only: `apple` is not a misspelt `table`). Built once per graph, on the
    first unknown label."""

    def __init__(self, graph: SceneGraph, dictionary: Dictionary) -> None:
        self.dictionary = dictionary
        self.held: dict[str, dict[str, list[str]]] = {}
        self.supported: dict[str, str] = {}
        for edge in graph.edges:
            if edge.relation in SUPPORT_RELATIONS:
                self.held.setdefault(edge.target, {}).setdefault(edge.relation, []).append(
                    edge.source)
                self.supported.setdefault(edge.source, edge.target)
        self.groups: dict[str, list[str]] = {}
        for label, props in dictionary.objects.items():
            if props.sides is not None:
                continue
            self.groups.setdefault(_role_name(props), []).append(label)

    def fix(self, node: Node, *, ranked: bool) -> str:
        """`declare it: {"id": ..., "attrs": {...}} (why), or use a built-in container
        such as bowl, pot, cup`; a close misspelling first when there is one."""
        held = self.held.get(node.id, {})
        movable = node.id in self.supported or not held
        attrs: dict[str, object] = {"movable": movable}
        if "on" in held:
            attrs["surface"] = True
        if "in" in held:
            attrs["container"] = True
        count = sum(len(v) for v in held.values())
        if held and movable:
            attrs["capacity"] = count
        if held:
            parts = []
            for relation, names in held.items():
                what = ", ".join(names[:3]) + (f" and {len(names) - 3} more"
                                               if len(names) > 3 else "")
                parts.append(f"{what} {'is' if len(names) == 1 else 'are'} {relation} it")
            why = " and ".join(parts) + " here"
        elif node.id in self.supported:
            why = f"it rests on {self.supported[node.id]} and holds nothing here"
        else:
            why = "nothing rests on it here"
        declare = json.dumps({"id": node.id, "label": node.label, "attrs": attrs})
        role = _role_name(ObjectProperties(movable=movable, surface="on" in held,
                                           container="in" in held))
        group = self.groups.get(role) or self.dictionary.names
        if ranked:
            token = canonical_token(node.label)
            group = sorted(group, key=lambda g: -difflib.SequenceMatcher(
                None, token, g).ratio())
        text = (f"declare it: {declare} ({why}; surface: true if things rest on it, "
                "container: true if they go in it, capacity: how many at once)")
        if group:
            text += f", or use a built-in {role} such as {', '.join(group[:3])}"
        near = [n for n in self.dictionary.nearest(node.label)
                if difflib.SequenceMatcher(None, canonical_token(node.label), n).ratio()
                >= SPELLING_CUTOFF] if ranked else []
        looks = confusable_of(node.label, self.dictionary)
        if looks:
            text = f"write {looks[0]} (your label {looks[1]}), or " + text
        elif near:
            text = f"use a known label such as {', '.join(near)} (close in spelling), or " \
                   + text
        return text


def _role_name(props: ObjectProperties) -> str:
    mobility = "movable" if props.movable else "fixed"
    if props.container:
        return f"{mobility} container"
    if props.surface:
        return f"{mobility} surface"
    return f"{mobility} object"


# Letters of other scripts that look like Latin ones (after lower-casing): enough to
# catch a label typed or pasted with a Cyrillic or Greek look-alike (`cuр` for `cup`).
_LOOKALIKES = str.maketrans({
    "а": "a", "в": "b", "е": "e", "ё": "e", "з": "3", "і": "i", "ї": "i", "ј": "j",
    "к": "k", "м": "m", "н": "h", "о": "o", "р": "p", "с": "c", "т": "t", "у": "y",
    "х": "x", "ѕ": "s", "ԁ": "d", "ԛ": "q", "ԝ": "w", "һ": "h", "ь": "b", "ɡ": "g",
    "α": "a", "β": "b", "γ": "y", "ε": "e", "η": "n", "ι": "i", "κ": "k", "μ": "u",
    "ν": "v", "ο": "o", "ρ": "p", "τ": "t", "υ": "u", "χ": "x", "ω": "w", "ς": "c",
    "ı": "i", "ℓ": "l",
})


def confusable_of(label: str, dictionary: Dictionary) -> tuple[str, str] | None:
    """(known label it looks like, the characters that differ) for a label written with
    look-alike letters of another script or with accents (`cuр`: Cyrillic `р`), when
    it is not read as that label; None otherwise. Uses NFKC, accent folding and a
    small table of Cyrillic and Greek look-alikes (`_LOOKALIKES`)."""
    token = canonical_token(label)
    if token.isascii():
        return None
    folded = unicodedata.normalize("NFKC", token).lower().translate(_LOOKALIKES)
    folded = "".join(c for c in unicodedata.normalize("NFKD", folded)
                     if not unicodedata.combining(c))
    if not folded.isascii() or folded == token:
        return None
    target = dictionary.resolve(folded) or union_dictionary().resolve(folded)
    if target is None or target == dictionary.resolve(label):
        return None
    odd = list(dict.fromkeys(c for c in label if not c.isascii()))[:3]
    names = ", ".join(f"'{c}' is {unicodedata.name(c, 'a non-Latin letter')} "
                      f"(U+{ord(c):04X})" for c in odd)
    return target, names


def _attribute_problem(node_id: str, index: int, exc: DictionaryError) -> GraphProblem:
    """A node's attrs that give a property the wrong type or a value out of its bounds."""
    where = exc.field if exc.field and exc.field.startswith("attrs") else "attrs"
    return GraphProblem(rule="bad_attribute", node=node_id, field=f"nodes[{index}].{where}",
                        message=f"node '{node_id}': {exc.message}",
                        fix=exc.fix or "give property overrides their documented type")


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
                readings[node.label] = _synonym_with_attrs(node, dictionary) or \
                    dictionary.reading(node.label) or _looks_like(node.label, dictionary)
    found = [text for text in readings.values() if text]
    if len(found) > MAX_READINGS:
        found = [*found[:MAX_READINGS], f"... and {len(found) - MAX_READINGS} more"]
    return found


def _synonym_with_attrs(node: Node, dictionary: Dictionary) -> str | None:
    """A label that is a built-in's synonym, on a node whose attrs declare a role: said
    plainly, since the node is then that built-in kind with the attrs on top (the
    built-in's other properties stay), not a kind of the client's own.

    `rack read as shelf (synonym, kitchen and tableware dictionary): rack is the built-in
    shelf with your attrs on top (container, capacity), so it is a fixed surface
    container, capacity 3; for a kind of your own, use a label no dictionary knows`."""
    reading = dictionary.reading(node.label)
    canonical = dictionary.resolve(node.label)
    if reading is None or canonical is None or "(synonym" not in reading or \
            canonical in dictionary.user_labels:
        return None
    keys = [k for k in KIND_KEYS if k in node.attrs]
    if not keys:
        return None
    try:
        props = dictionary.objects[canonical].overridden(node.attrs)
    except DictionaryError:
        return None
    return (f"{reading}: {node.label} is the built-in {canonical} with your attrs on top "
            f"({', '.join(keys)}), so it is a {properties_text(props)}; for a kind of your "
            f"own, use a label no dictionary knows (e.g. my_{canonical_token(node.label)})")


def _looks_like(label: str, dictionary: Dictionary) -> str | None:
    """`cuр looks like cup but is another label ('р' is CYRILLIC SMALL LETTER ER
    (U+0440))`: a warning, since the look-alike is read as a label of its own."""
    found = confusable_of(label, dictionary)
    if found is None:
        return None
    target, names = found
    own = dictionary.resolve(label) or canonical_token(label)
    return (f"{label} looks like {target} but is another label, read as {own} "
            f"({names}; write {target} to mean {target})")




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
    uncounted: list[str] = []  # targets of `under` and `nextto` (they carry nothing)
    rooms: dict[str, str] = {}  # furniture -> its room
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
        if relation == ROOM_RELATION:
            problems.extend(_room_problems(edge, i, resolved, rooms))
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
        elif relation == "in":
            if not props.container:
                problems.append(GraphProblem(
                    rule="target_not_container", node=edge.target, field=f"edges[{i}]",
                    message=f"'{edge.sentence()}': {edge.target} ({target[0]}) is not a "
                            "container",
                    fix=f"use '{edge.source} on {edge.target}'" if props.surface else
                        f"put {edge.source} in a container"))
        else:
            uncounted.append(target_id)
            problems.extend(_beside_problem(edge, i, target[0], props))
    problems += _node_problems(resolved, below, more_below, partial, uncounted)
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


def _room_problems(edge: Edge, i: int, resolved: dict[str, tuple[str, ObjectProperties]],
                   rooms: dict[str, str]) -> list[GraphProblem]:
    """`x inroom r`: r is a room, x furniture (fixed, not a room), in one room only."""
    problems = []
    source, room = resolved.get(edge.source), resolved.get(edge.target)
    if room is not None and not room[1].room:
        problems.append(GraphProblem(
            rule="target_not_room", node=edge.target, field=f"edges[{i}]",
            message=f"'{edge.sentence()}': {edge.target} ({room[0]}) is not a room",
            fix="name a room as the target of inroom (a node labelled room, kitchen, "
                "living_room, bedroom, ...)"))
    if source is not None and (source[1].movable or source[1].room):
        what = "a room" if source[1].room else "movable"
        problems.append(GraphProblem(
            rule="inroom_not_furniture", node=edge.source, field=f"edges[{i}]",
            message=f"'{edge.sentence()}': {edge.source} ({source[0]}) is {what}; only "
                    "furniture (a fixed object) stands in a room",
            fix=f"place {edge.source} on, in, under or next to furniture that is in "
                f"{edge.target}" if source[1].movable else "remove the edge"))
    if edge.source in rooms and rooms[edge.source] != edge.target:
        problems.append(GraphProblem(
            rule="multiple_rooms", node=edge.source, field=f"edges[{i}]",
            message=f"'{edge.source}' is in {rooms[edge.source]} and in {edge.target}; "
                    "furniture stands in one room",
            fix=f"keep one of the inroom edges from '{edge.source}'"))
    rooms.setdefault(edge.source, edge.target)
    return problems


def _beside_problem(edge: Edge, i: int, label: str, props: ObjectProperties
                    ) -> list[GraphProblem]:
    """`under` needs furniture (a fixed surface) above; `nextto` anything but a room."""
    if edge.relation == "under" and (props.movable or not props.surface):
        return [GraphProblem(
            rule="target_not_furniture", node=edge.target, field=f"edges[{i}]",
            message=f"'{edge.sentence()}': {edge.target} ({label}) is not furniture (a fixed "
                    "surface) for something to stand under",
            fix=f"put {edge.source} under a table, desk or counter, or on {edge.target}"
                if props.surface else f"put {edge.source} under a table, desk or counter")]
    if props.room:
        return [GraphProblem(
            rule="target_is_room", node=edge.target, field=f"edges[{i}]",
            message=f"'{edge.sentence()}': {edge.target} is a room; an object is placed by "
                    "furniture, and is in the room its furniture is in",
            fix=f"put {edge.source} on, in, under or next to furniture that is inroom "
                f"{edge.target}")]
    return []


def _node_problems(resolved: dict[str, tuple[str, ObjectProperties]], below: dict[str, str],
                   more_below: dict[str, list[str]], partial: bool,
                   uncounted: list[str]) -> list[GraphProblem]:
    """The per-object rules (support count, capacity), in node order.

    Only objects that may break one are visited: those with two supports, those with
    none, and those carrying more than the smallest capacity any object has; the
    candidates come from set operations, so a well-formed graph costs no Python loop.
    """
    carried = Counter(below.values())  # every support edge counts at its target
    for supports in more_below.values():
        carried.update(supports[1:])
    carried.subtract(uncounted)  # but `under` and `nextto` carry nothing
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
                fix=_over_capacity_fix(node_id, label, props.capacity)))
    return problems


def _over_capacity_fix(node_id: str, label: str, capacity: int) -> str:
    """Keep within the capacity; never change the model of the world to fit a request.

    A capacity is the user's (attrs) or a built-in default; either way only the user
    can say the real object holds more, so the fix asks them instead of editing it."""
    return (f"keep at most {capacity} object(s) on or in '{node_id}' (ask the user which to "
            f"leave out); {capacity} is what the scene says a {label} holds: a built-in "
            "default unless its attrs gave it, so only the user can say the real one "
            "holds more (never raise a capacity just to make a goal fit)")


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
