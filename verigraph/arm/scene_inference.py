"""Locations -> scene graph: which object rests on or in which, read from geometry.

This closes the loop the paper left open: after a motion the adapter locates the
objects again and rebuilds the support edges from where they really are. An object
whose support cannot be explained (in the gripper, fallen, hidden, or resting on
something the dictionary says cannot carry it) gets no edge: the partial graph is an
honest "unknown", and the goal check reports it missing.
"""

from __future__ import annotations

from pydantic import BaseModel, Field

from verigraph.arm.models import ObjectLocation
from verigraph.graph.dictionary import Dictionary, ObjectProperties
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.wellformed import check_well_formed, resolve_properties


class InferenceTolerances(BaseModel):
    """How far geometry may be off and still count as `on` / `in`."""

    z_gap_m: float = Field(default=0.02, gt=0,
                           description="|object bottom - support top| for `on`")
    xy_margin_m: float = Field(default=0.015, ge=0,
                               description="how far outside the support's footprint the "
                                           "object's centre may be")


def _support(obj: ObjectLocation, other: ObjectLocation, props: ObjectProperties,
             tol: InferenceTolerances) -> tuple[str, float] | None:
    """(relation, score) if `other` can be what holds `obj`; lower score = better."""
    if not other.footprint_contains(obj.centre[0], obj.centre[1], tol.xy_margin_m):
        return None
    fits = max(obj.size[0], obj.size[1]) <= min(other.size[0], other.size[1]) + tol.xy_margin_m
    if props.container and fits and \
            other.bottom_z - tol.z_gap_m <= obj.bottom_z < other.top_z - 0.005:
        return "in", -1.0  # inside a container beats resting near a surface
    gap = abs(obj.bottom_z - other.top_z)
    if props.surface and gap <= tol.z_gap_m:
        return "on", gap
    return None


def infer_graph(graph: SceneGraph, dictionary: Dictionary,
                locations: dict[str, ObjectLocation],
                tolerances: InferenceTolerances | None = None) -> SceneGraph:
    """The graph's nodes with support edges rebuilt from `locations`.

    Edges that would make the graph malformed under `dictionary` are dropped (their
    object is then reported without a support), so the result always indexes.
    """
    tol = tolerances or InferenceTolerances()
    props = {node_id: p for node_id, (_, p) in resolve_properties(graph, dictionary, []).items()}
    edges: list[Edge] = []
    for node in graph.nodes:
        obj = locations.get(node.id)
        if obj is None or node.id not in props or not props[node.id].movable:
            continue
        best: tuple[float, str, str] | None = None
        for other_id, other in locations.items():
            if other_id == node.id or other_id not in props:
                continue
            found = _support(obj, other, props[other_id], tol)
            if found is not None and (best is None or found[1] < best[0]):
                best = (found[1], found[0], other_id)
        if best is not None:
            edges.append(Edge(source=node.id, relation=best[1], target=best[2]))
    inferred = SceneGraph(nodes=list(graph.nodes), edges=edges, dictionary=graph.dictionary)
    for _ in range(len(edges) + 1):
        problems = check_well_formed(inferred, dictionary, partial=True)
        if not problems:
            break
        # An over-full support loses everything on it; any other problem loses the
        # offending object's own support edge.
        full = {p.node for p in problems if p.rule == "over_capacity"}
        misfit = {p.node for p in problems if p.rule != "over_capacity"}
        inferred = inferred.model_copy(update={"edges": [
            e for e in inferred.edges if e.target not in full and e.source not in misfit]})
    return inferred
