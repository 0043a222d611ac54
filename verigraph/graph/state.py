"""WorldState: the indexed, mutable form of a scene graph that the validator works on.

`SceneGraph` is the boundary format (JSON, pydantic); `WorldState` is what actions are
checked against and applied to. It indexes each object's support and what each object
carries, so every constraint check costs O(degree) rather than O(graph). Back at the
boundary (`to_graph`), the nodes and edges go to pydantic-core as plain data and are
validated in one call, rather than one model at a time.
"""

from __future__ import annotations

import operator
from dataclasses import dataclass
from typing import Any

from verigraph.errors import MalformedGraphError
from verigraph.graph.bulk import collector_paused
from verigraph.graph.dictionary import (
    PLACEMENT_RELATIONS,
    ROOM_RELATION,
    SUPPORT_RELATIONS,
    Dictionary,
    ObjectProperties,
    load_dictionary,
    state_value,
)
from verigraph.graph.model import Edge, SceneGraph, edge_order
from verigraph.graph.support import SupportIndex
from verigraph.graph.wellformed import check_and_resolve, open_labels

_object_id = operator.attrgetter("id")  # the canonical order of a graph's nodes
_first = operator.itemgetter(0)

Side = tuple[str, int]


@dataclass(slots=True)
class ObjectInfo:
    """One object with its canonical label and resolved properties."""

    id: str
    label: str
    props: ObjectProperties
    attrs: dict[str, object]


class WorldState(SupportIndex):
    """Objects, placements (`obj -> (relation, target)`), what each object has placed on,
    in, under or next to it (`carried`), object states, furniture's rooms and tangram
    contacts.

    `carried[x]` holds every placement relative to x, so `is_clear(x)` means nothing is
    on, in, under or next to it; only `on` and `in` count against x's capacity (`load`).
    """

    __slots__ = ("dictionary", "move_relations", "objects", "contacts", "_fixed_surfaces",
                 "states", "rooms", "openable", "_uncounted")

    def __init__(self, dictionary: Dictionary) -> None:
        super().__init__()
        self.dictionary = dictionary
        self.move_relations = tuple(r for r in dictionary.relations
                                    if r in PLACEMENT_RELATIONS)
        # Whether `carried` may hold placements that carry nothing (under, nextto).
        self._uncounted = len(self.move_relations) > len(
            [r for r in self.move_relations if r in SUPPORT_RELATIONS])
        self.objects: dict[str, ObjectInfo] = {}
        # Every contact of every side: a long side can touch two small pieces at once.
        self.contacts: dict[Side, list[Side]] = {}
        self._fixed_surfaces: list[str] = []
        # Object -> its state keys that are set (sparse: most objects have none).
        self.states: dict[str, dict[str, bool]] = {}
        # Furniture -> the room it stands in (never changes).
        self.rooms: dict[str, str] = {}
        # The openable objects (never changes): nothing goes in or out while one is closed.
        self.openable: frozenset[str] = frozenset()

    @classmethod
    def from_graph(cls, graph: SceneGraph, dictionary: Dictionary | str | None = None, *,
                   partial: bool = False) -> WorldState:
        """Check the graph and index it; raises MalformedGraphError listing every problem."""
        d = dictionary if isinstance(dictionary, Dictionary) else load_dictionary(
            dictionary if dictionary is not None else graph.dictionary)  # loaded once
        with collector_paused(len(graph.nodes) + len(graph.edges)):
            problems, resolved = check_and_resolve(graph, d, partial=partial)
            if problems:
                raise MalformedGraphError(problems)
            return cls(open_labels(d, resolved))._index(graph, resolved)

    def _index(self, graph: SceneGraph, resolved: dict[str, tuple[str, ObjectProperties]]
               ) -> WorldState:
        """Fill the indexes from a checked graph (one pass over nodes, one over edges)."""
        # A checked graph has unique ids and every node resolved, in node order.
        self.objects = {n.id: ObjectInfo(n.id, label, props, dict(n.attrs))
                        for n, (label, props) in zip(graph.nodes, resolved.values(),
                                                     strict=True)}
        self.states = {n.id: dict(n.state) for n in graph.nodes if n.state}
        carried: dict[str, dict[str, str]] = {node_id: {} for node_id in resolved}
        self.carried = carried
        self._fixed_surfaces = [i for i, (_, p) in resolved.items() if p.surface and not p.movable]
        self.openable = frozenset(i for i, (_, p) in resolved.items() if p.openable)
        support = self.support
        for edge in graph.edges:
            relation = edge.relation
            if relation == "touches":
                self.add_contact((edge.source, edge.source_side or 0),
                                 (edge.target, edge.target_side or 0))
            elif relation == ROOM_RELATION:
                self.rooms[edge.source] = edge.target
            else:
                support[edge.source] = (relation, edge.target)
                carried[edge.target][edge.source] = relation
        return self

    def copy(self) -> WorldState:
        """Independent copy (objects are shared: they never change)."""
        other = WorldState.__new__(WorldState)
        other.dictionary = self.dictionary
        other.move_relations = self.move_relations
        other.objects = self.objects
        other.support = dict(self.support)
        other.carried = {k: dict(v) for k, v in self.carried.items()}
        other.contacts = {k: list(v) for k, v in self.contacts.items()}
        other._fixed_surfaces = self._fixed_surfaces
        other._uncounted = self._uncounted
        other.states = {k: dict(v) for k, v in self.states.items()}
        other.rooms = self.rooms
        other.openable = self.openable
        return other

    # -- queries ---------------------------------------------------------------------------
    @property
    def fixed_surfaces(self) -> list[str]:
        return self._fixed_surfaces

    def is_clear(self, obj: str) -> bool:
        return not self.carried[obj]

    def has_room(self, target: str) -> bool:
        cap = self.objects[target].props.capacity
        if cap is None:
            return True
        held = self.carried[target]
        return len(held) < cap or (self._uncounted and self.load(target) < cap)

    def load(self, target: str) -> int:
        """How many objects are on or in `target` (what counts against its capacity)."""
        held = self.carried[target]
        if not self._uncounted:
            return len(held)
        return sum(1 for relation in held.values() if relation in SUPPORT_RELATIONS)

    def state_value(self, obj: str, key: str) -> bool:
        """`obj`'s state `key` (`open`, `toggled_on`); unset: closed, off."""
        return state_value(self.states.get(obj, {}), key)

    def set_state(self, obj: str, key: str, value: bool) -> None:
        """Set one state key of `obj` (kept explicit, so the graph shows it)."""
        self.states.setdefault(obj, {})[key] = value

    def room_of(self, obj: str) -> str | None:
        """The room `obj` is in: its own (furniture), or that of the furniture its
        placements lead down to; None when no room is known (O(stack height))."""
        room = self.rooms.get(obj)
        if room is not None or not self.rooms:
            return room
        for below in self.supports_chain(obj):
            room = self.rooms.get(below)
            if room is not None:
                return room
        return None

    def supports_chain(self, obj: str) -> list[str]:
        """Objects below `obj`, nearest first (O(stack height))."""
        chain = []
        current = self.support.get(obj)
        while current is not None:
            chain.append(current[1])
            current = self.support.get(current[1])
        return chain

    def side_count(self, obj: str) -> int | None:
        return self.objects[obj].props.sides

    # -- edits (set_support: SupportIndex) ----------------------------------------------------
    def partners(self, side: Side) -> list[Side]:
        """The sides touching a side (none, one, or several along a long side)."""
        return self.contacts.get(side, [])

    def detach_contacts(self, obj: str) -> list[Edge]:
        """Remove every tangram contact of `obj` (it is being moved); returns them."""
        removed = []
        n_sides = self.side_count(obj) or 0
        for side in range(n_sides):
            for other in self.contacts.pop((obj, side), []):
                rest = [s for s in self.contacts.get(other, []) if s != (obj, side)]
                if rest:
                    self.contacts[other] = rest
                else:
                    self.contacts.pop(other, None)
                removed.append(Edge(source=obj, relation="touches", target=other[0],
                                    source_side=side, target_side=other[1]))
        return removed

    def add_contact(self, a: Side, b: Side) -> Edge:
        for x, y in ((a, b), (b, a)):
            mine = self.contacts.setdefault(x, [])
            if y not in mine:
                mine.append(y)
        return Edge(source=a[0], relation="touches", target=b[0], source_side=a[1],
                    target_side=b[1])

    # -- export ----------------------------------------------------------------------------
    def edges(self) -> list[Edge]:
        return [Edge(source=o, relation=r, target=t) for o, (r, t) in self.support.items()] \
            + self._contact_edges() + [Edge(source=o, relation=ROOM_RELATION, target=r)
                                       for o, r in self.rooms.items()]

    def _contact_edges(self) -> list[Edge]:
        """One edge per tangram contact (each touching pair once)."""
        edges = []
        seen: set[frozenset[Side]] = set()
        for a, others in self.contacts.items():
            for b in others:
                pair = frozenset((a, b))
                if pair in seen:
                    continue
                seen.add(pair)
                edges.append(Edge(source=a[0], relation="touches", target=b[0],
                                  source_side=a[1], target_side=b[1]))
        return edges

    def to_graph(self) -> SceneGraph:
        """Back to the boundary format (canonical labels, stable order).

        The nodes and support edges go in as plain data and are validated in one call,
        the list at once (about a third of the cost of building each model on its own), into
        the same models `Node(...)` and `Edge(...)` give.
        """
        nodes = [{"id": o.id, "label": o.label, "attrs": o.attrs} for o in self.objects.values()]
        if self.states:
            states = self.states
            for node in nodes:
                if node["id"] in states:
                    node["state"] = states[node["id"]]
        edges: list[dict[str, str] | Edge] = [
            {"source": o, "relation": r, "target": t} for o, (r, t) in self.support.items()]
        edges += self._contact_edges()
        edges += [{"source": o, "relation": ROOM_RELATION, "target": r}
                  for o, r in self.rooms.items()]
        return SceneGraph.model_validate({"nodes": nodes, "edges": edges,
                                          "dictionary": self.dictionary.reference()}
                                         ).sorted_in_place()

    def graph_data(self) -> dict[str, Any]:
        """`to_graph()` as JSON-ready plain data, as `model_dump(mode="json",
        exclude_none=True)` writes it, without building or checking a model: the final
        graph of a plan report (`verigraph.reporting`), whose data this state already
        checked. Nodes and edges in the canonical order."""
        states = self.states
        nodes = []
        for o in sorted(self.objects.values(), key=_object_id):
            node: dict[str, Any] = {"id": o.id, "label": o.label, "attrs": o.attrs}
            if states.get(o.id):
                node["state"] = states[o.id]
            nodes.append(node)
        edges: list[dict[str, Any]] = [
            {"source": o, "relation": r, "target": t} for o, (r, t) in self.support.items()]
        edges += [{"source": o, "relation": ROOM_RELATION, "target": r}
                  for o, r in self.rooms.items()]
        keyed = [(edge_order(e), e.model_dump(exclude_none=True))
                 for e in self._contact_edges()]
        keyed += [((e["source"], e["relation"], e["target"], "", ""), e) for e in edges]
        keyed.sort(key=_first)
        data: dict[str, Any] = {"nodes": nodes, "edges": [e for _, e in keyed]}
        reference = self.dictionary.reference()
        if reference is not None:
            data["dictionary"] = reference if isinstance(reference, str) else \
                reference.model_dump(mode="json", exclude_none=True)
        return data
