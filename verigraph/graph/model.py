"""The scene graph G: objects as nodes, support/containment/contact relations as edges.

An edge reads as a sentence, `source relation target` ("cup on book"): the target
supports or contains the source. Tangram contacts carry the side index on each piece.
"""

from __future__ import annotations

import operator
from typing import TYPE_CHECKING, Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, WithJsonSchema, field_validator
from pydantic_core import PydanticCustomError

from verigraph.graph.dictionary import STATE_ROLES, InlineDictionary, inline_or_name
from verigraph.reporting import STATE_WORDS

if TYPE_CHECKING:  # networkx loads only where a graph is converted (fast CLI start-up)
    import networkx as nx

ID_PATTERN = r"^[A-Za-z0-9_][A-Za-z0-9_.\-]*$"
# A built-in dictionary's name, or the client's own (published as a plain object: the
# full model is validated all the same, and its schema would repeat in every tool).
DictionaryRef = Annotated[str | InlineDictionary | None, BeforeValidator(inline_or_name),
                          WithJsonSchema({"type": ["string", "object", "null"]})]


class Node(BaseModel):
    """One object in the scene: a unique id and a label from the dictionary D."""

    model_config = ConfigDict(extra="forbid")

    id: str = Field(min_length=1, max_length=128, pattern=ID_PATTERN,
                    description="unique, e.g. plate_2")
    label: str = Field(min_length=1, max_length=128, description="a name from the dictionary D")
    attrs: dict[str, Any] = Field(default_factory=dict,
                                  description="colour; overrides (capacity, movable)")
    # Serialised only when set, so a scene without states dumps as it always did.
    state: Annotated[dict[str, bool], WithJsonSchema({"type": "object"})] = Field(
        default_factory=dict, exclude_if=operator.not_,
        description="open, toggled_on: true/false; missing = closed, off")

    @field_validator("state", mode="before")
    @classmethod
    def _known_states(cls, value: Any) -> Any:
        """Only the state keys there are, each a JSON boolean (refused with the fix)."""
        if not isinstance(value, dict):
            return value
        for key, on in value.items():
            if key not in STATE_ROLES:
                reason = (f"unknown state '{str(key)[:32]}' (fix: use "
                          f"{' or '.join(STATE_ROLES)}, e.g. {{\"open\": false}})")
            elif not isinstance(on, bool):
                reason = (f"state '{key}' must be true or false, got {str(on)[:32]!r} "
                          f"(fix: write {{\"{key}\": true}})")
            else:
                continue
            raise PydanticCustomError("node_state", "{reason}", {"reason": reason})
        return value


class Edge(BaseModel):
    """`source relation target`; the target supports, contains or touches the source."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    source: str = Field(min_length=1, max_length=128)
    relation: str = Field(min_length=1, max_length=32)
    target: str = Field(min_length=1, max_length=128)
    source_side: int | None = Field(default=None, ge=0, description="tangram: side of source")
    target_side: int | None = Field(default=None, ge=0, description="tangram: side of target")

    def sentence(self) -> str:
        if self.relation == "touches":
            return f"{self.source}[{self.source_side}] touches {self.target}[{self.target_side}]"
        return f"{self.source} {self.relation} {self.target}"

    def key(self) -> tuple[str, str, str, int | None, int | None]:
        """Identity of the edge; tangram contacts are undirected, so they are sorted."""
        if self.relation == "touches" and (self.target, self.target_side or 0) < (
                self.source, self.source_side or 0):
            return (self.target, "touches", self.source, self.target_side, self.source_side)
        return (self.source, self.relation, self.target, self.source_side, self.target_side)


_node_order = operator.attrgetter("id")  # the sort key of a graph's nodes


def edge_order(e: Edge) -> tuple[str, str, str, str, str]:
    """The sort key of `SceneGraph.canonical`: the edge's key, a missing side as ''."""
    source, relation, target, source_side, target_side = e.key()
    return (source, relation, target, "" if source_side is None else str(source_side),
            "" if target_side is None else str(target_side))


class SceneGraph(BaseModel):
    """A scene as JSON (docs/design.md section 2). Checked by `check_well_formed` before use."""

    model_config = ConfigDict(extra="forbid")

    nodes: list[Node] = Field(default_factory=list)
    edges: list[Edge] = Field(default_factory=list)
    dictionary: DictionaryRef = Field(
        default=None, description="dictionary D; none = all built-ins")

    def node(self, node_id: str) -> Node | None:
        return next((n for n in self.nodes if n.id == node_id), None)

    def node_ids(self) -> list[str]:
        return [n.id for n in self.nodes]

    def stateless_nodes(self) -> list[Node]:
        """The nodes without their states: a goal built on a scene's nodes asks only for
        the edges (and states) it lists, not for every state the scene has now."""
        return [n.model_copy(update={"state": {}}) if n.state else n for n in self.nodes]

    def edge_keys(self) -> set[tuple[str, str, str, int | None, int | None]]:
        return {e.key() for e in self.edges}

    def sentences(self) -> list[str]:
        return [e.sentence() for e in self.edges]

    def state_sentences(self) -> list[str]:
        """The states the nodes set, one sentence each: `fridge closed`, `stove on`."""
        return [f"{n.id} {STATE_WORDS[key][value]}" for n in self.nodes
                for key, value in n.state.items()]

    def canonical(self) -> SceneGraph:
        """Same graph with nodes and edges in a stable order: equal scenes dump equally."""
        return SceneGraph(nodes=sorted(self.nodes, key=_node_order),
                          edges=sorted(self.edges, key=edge_order),
                          dictionary=self.dictionary)

    def sorted_in_place(self) -> SceneGraph:
        """This graph, its lists put in `canonical`'s order: for a graph just built that
        no one else holds yet, the same result without building and checking a second."""
        self.nodes.sort(key=_node_order)
        self.edges.sort(key=edge_order)
        return self

    def to_networkx(self) -> nx.DiGraph:
        """Directed graph with node attributes `label`, `attrs` and edge attribute `relation`.

        Tangram contacts become one directed edge per contact (source -> target) with
        `source_side` and `target_side` attributes.
        """
        import networkx as nx

        g = nx.DiGraph(dictionary=self.dictionary)
        for n in self.nodes:
            g.add_node(n.id, label=n.label, attrs=dict(n.attrs), state=dict(n.state))
        for e in self.edges:
            data: dict[str, Any] = {"relation": e.relation}
            if e.source_side is not None:
                data["source_side"] = e.source_side
            if e.target_side is not None:
                data["target_side"] = e.target_side
            g.add_edge(e.source, e.target, **data)
        return g

    @classmethod
    def from_networkx(cls, g: nx.DiGraph) -> SceneGraph:
        """Inverse of `to_networkx`; a missing `label` falls back to the node id."""
        nodes = [Node(id=str(n), label=str(d.get("label", n)), attrs=dict(d.get("attrs", {})),
                      state=dict(d.get("state", {})))
                 for n, d in g.nodes(data=True)]
        edges = [Edge(source=str(u), target=str(v), relation=str(d.get("relation", "on")),
                      source_side=d.get("source_side"), target_side=d.get("target_side"))
                 for u, v, d in g.edges(data=True)]
        return cls(nodes=nodes, edges=edges, dictionary=g.graph.get("dictionary"))
