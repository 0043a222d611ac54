"""Normalising and checking a scene graph written by an agent's own vision model.

Agents write `Red Block`, `on top of`, or name a support by its label instead of its
id. This module maps such spellings to canonical ids, labels and relations, records
each rename, and collects every remaining problem (well-formedness against D and R)
so the agent can fix them all in one go.
"""

from __future__ import annotations

import operator
import re
import unicodedata
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, field_validator

from verigraph.errors import DictionaryError
from verigraph.graph.dictionary import (
    Dictionary,
    canonical_token,
    kind_token,
    open_label_properties,
)
from verigraph.graph.model import ID_PATTERN, DictionaryRef, Edge, Node, SceneGraph
from verigraph.graph.wellformed import GraphProblem, check_well_formed

RELATION_SYNONYMS = {
    "on": "on", "on_top_of": "on", "onto": "on", "atop": "on", "upon": "on", "on_top": "on",
    "resting_on": "on", "sits_on": "on", "stacked_on": "on", "is_on": "on",
    "in": "in", "inside": "in", "into": "in", "within": "in", "inside_of": "in", "is_in": "in",
    "contained_in": "in",
    "touches": "touches", "touch": "touches", "touching": "touches", "adjacent_to": "touches",
}
_ID = re.compile(ID_PATTERN)


class SubmittedNode(BaseModel):
    """A node as an agent wrote it (names are normalised afterwards)."""

    model_config = ConfigDict(extra="forbid")

    id: str = Field(min_length=1, max_length=128)
    label: str = Field(min_length=1, max_length=128)
    attrs: dict[str, Any] = Field(default_factory=dict)
    # Household states (open, toggled_on), checked as on a Node; dumped only when set.
    state: dict[str, bool] = Field(default_factory=dict, exclude_if=operator.not_)

    @field_validator("state", mode="before")
    @classmethod
    def _known_states(cls, value: Any) -> Any:
        return Node._known_states(value)


class SubmittedEdge(BaseModel):
    """An edge as an agent wrote it."""

    model_config = ConfigDict(extra="forbid")

    source: str = Field(min_length=1, max_length=128)
    relation: str = Field(min_length=1, max_length=64)
    target: str = Field(min_length=1, max_length=128)
    source_side: int | None = Field(default=None, ge=0, le=64)
    target_side: int | None = Field(default=None, ge=0, le=64)


class SubmittedGraph(BaseModel):
    """A scene graph in the format of docs/design.md section 2, before normalisation."""

    model_config = ConfigDict(extra="forbid")

    nodes: list[SubmittedNode] = Field(max_length=500)
    edges: list[SubmittedEdge] = Field(default_factory=list, max_length=2000)
    dictionary: DictionaryRef = None


class Rename(BaseModel):
    """One normalisation applied to the submitted graph."""

    field: str
    before: str
    after: str
    reading: str | None = None  # a label's: box read as block (synonym, blocks dictionary)


def normalise_id(raw: str) -> str:
    """`Red Block` -> `red_block`, `tasse_é` -> `tasse_e`: ids are ASCII (they appear in
    action text and resource URIs), so accents are folded and other letters dropped."""
    folded = unicodedata.normalize("NFKD", raw).encode("ascii", "ignore").decode("ascii")
    token = canonical_token(folded).strip("_")[:128]
    return token if token and _ID.match(token) else raw


def normalise_graph(graph: SubmittedGraph, dictionary: Dictionary
                    ) -> tuple[SceneGraph, list[Rename], list[GraphProblem]]:
    """Canonical ids, labels and relations; problems the renaming itself found."""
    renames: list[Rename] = []
    problems: list[GraphProblem] = []
    id_map: dict[str, str] = {}
    nodes: list[Node] = []
    for i, raw in enumerate(graph.nodes):
        node_id = normalise_id(raw.id)
        if node_id != raw.id:
            renames.append(Rename(field=f"nodes[{i}].id", before=raw.id, after=node_id))
        if not _ID.match(node_id):
            # The reply shows a placeholder (its own schema only allows valid ids);
            # the problem names the id as it was sent.
            node_id = f"invalid_id_{i}"
            problems.append(GraphProblem(
                rule="invalid_id", node=raw.id, field=f"nodes[{i}].id",
                message=f"id {raw.id!r} has characters other than ASCII letters, digits, "
                        f"_ . - (shown as {node_id})",
                fix="use ids like cup, red_block or plate_2"))
            renames.append(Rename(field=f"nodes[{i}].id", before=raw.id, after=node_id))
        id_map.setdefault(raw.id, node_id)
        id_map.setdefault(node_id, node_id)
        label = dictionary.resolve(raw.label) or _own_label(raw)
        if label != raw.label:
            renames.append(Rename(field=f"nodes[{i}].label", before=raw.label, after=label,
                                  reading=dictionary.reading(raw.label)
                                  or f"{raw.label} read as {label} (case and spacing, your "
                                     "label)"))
        nodes.append(Node.model_construct(id=node_id, label=label, attrs=dict(raw.attrs),
                                          state=dict(raw.state)))
    by_label: dict[str, list[str]] = {}
    for node in nodes:
        by_label.setdefault(node.label, []).append(node.id)
    edges: list[Edge] = []
    for i, raw_edge in enumerate(graph.edges):
        ends = []
        for role, name in (("source", raw_edge.source), ("target", raw_edge.target)):
            resolved = _endpoint(name, id_map, by_label, dictionary)
            if resolved != name:
                renames.append(Rename(field=f"edges[{i}].{role}", before=name, after=resolved))
            ends.append(resolved)
        relation = RELATION_SYNONYMS.get(canonical_token(raw_edge.relation), raw_edge.relation)
        if relation != raw_edge.relation:
            renames.append(Rename(field=f"edges[{i}].relation", before=raw_edge.relation,
                                  after=relation))
        edges.append(Edge.model_construct(source=ends[0], relation=relation, target=ends[1],
                                          source_side=raw_edge.source_side,
                                          target_side=raw_edge.target_side))
    scene = SceneGraph.model_construct(
        nodes=nodes, edges=edges, dictionary=dictionary.reference())
    return scene, renames, problems


def _own_label(node: SubmittedNode) -> str:
    """A label no dictionary knows: in its canonical form when the attrs declare a role
    (the client's own kind), else as written (refused later with how to declare one)."""
    try:
        declared = open_label_properties(node.attrs)
    except DictionaryError:
        declared = None
    return kind_token(node.label) if declared is not None else node.label


def _endpoint(name: str, id_map: dict[str, str], by_label: dict[str, list[str]],
              dictionary: Dictionary) -> str:
    """An edge end by id, normalised id, or (when unique) by the label of one node."""
    if name in id_map:
        return id_map[name]
    token = normalise_id(name)
    if token in id_map:
        return id_map[token]
    label = dictionary.resolve(name)
    if label is not None and len(by_label.get(label, [])) == 1:
        return by_label[label][0]
    return name


def check_submission(graph: SubmittedGraph, dictionary: Dictionary
                     ) -> tuple[SceneGraph, list[Rename], list[GraphProblem]]:
    """Normalise, then check well-formedness; every problem is returned, none raised."""
    scene, renames, problems = normalise_graph(graph, dictionary)
    problems.extend(check_well_formed(scene, dictionary))
    return scene, renames, problems
