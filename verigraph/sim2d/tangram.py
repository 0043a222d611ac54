"""The tangram world (top view, no gravity): align pieces side to side, read contacts back.

Pieces are kinematic pymunk bodies; `align` computes the rigid motion of docs/design.md
section 2, asks the physics engine which pieces the moved piece would touch, refuses
with `overlap` (nothing moves) if it penetrates any of them, and otherwise applies it. The graph
is read from geometry: a `touches` edge for every pair of sides that are antiparallel,
collinear within a tolerance and overlap by more than a fraction of the shorter side.
"""

from __future__ import annotations

from collections import deque

import numpy as np
import pymunk

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AlignAction, MoveAction
from verigraph.graph.dictionary import InlineDictionary
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.sim2d.errors import SimError
from verigraph.sim2d.render import render_tangram
from verigraph.sim2d.tangram_geometry import (
    OVERLAP_DEPTH,
    SEPARATION,
    TPose,
    Vec,
    align_pose,
    overlap_depth,
    piece_model,
    placed,
    touching_sides,
)
from verigraph.sim2d.world import SimWorld, WorldKind


class TangramWorld(SimWorld):
    """Seven (or fewer) tangram pieces lying on a table, seen from above."""

    kind: WorldKind = "tangram"

    def __init__(self, nodes: list[Node], labels: dict[str, str], poses: dict[str, TPose],
                 dictionary_name: str | InlineDictionary | None = "tangram") -> None:
        self.nodes = [n.model_copy(deep=True) for n in nodes]
        self.labels = dict(labels)
        self.dictionary_name = dictionary_name
        self.space = pymunk.Space()
        self.bodies: dict[str, pymunk.Body] = {}
        for node in nodes:
            body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
            shape = pymunk.Poly(body, list(piece_model(labels[node.id])))
            self.space.add(body, shape)
            self.bodies[node.id] = body
            self.set_pose(node.id, poses[node.id])

    # -- state -----------------------------------------------------------------------------
    def pose(self, piece: str) -> TPose:
        b = self.bodies[piece]
        return TPose(float(b.position.x), float(b.position.y), float(b.angle))

    def vertices(self, piece: str) -> list[Vec]:
        return placed(self.labels[piece], self.pose(piece))

    def set_pose(self, piece: str, pose: TPose) -> None:
        """Put a piece at a pose (no checks: layout, generators and tests)."""
        body = self.bodies[piece]
        body.angle = pose.theta  # before the position: see physics.set_pose
        body.position = (pose.x, pose.y)
        self.space.reindex_shapes_for_body(body)

    def overlapping(self, piece: str) -> list[str]:
        """Pieces that `piece` penetrates deeper than the tolerance.

        The physics engine finds the pieces in contact; the depth of each contact is
        measured on the polygons (see overlap_depth)."""
        body = self.bodies[piece]
        mine = self.vertices(piece)
        hits = []
        for shape in body.shapes:
            for hit in self.space.shape_query(shape):
                other = next((k for k, b in self.bodies.items() if b is hit.shape.body), None)
                if other is None or other == piece or other in hits:
                    continue
                if overlap_depth(mine, self.vertices(other)) > OVERLAP_DEPTH:
                    hits.append(other)
        return hits

    # -- World protocol --------------------------------------------------------------------
    def observe(self) -> SceneGraph:
        ids = [n.id for n in self.nodes]
        verts = {p: self.vertices(p) for p in ids}
        edges = []
        for i, p in enumerate(ids):
            for q in ids[i + 1:]:
                for sp, sq in touching_sides(verts[p], verts[q]):
                    edges.append(Edge(source=p, relation="touches", target=q, source_side=sp,
                                      target_side=sq))
        return SceneGraph(nodes=[n.model_copy(deep=True) for n in self.nodes], edges=edges,
                          dictionary=self.dictionary_name).canonical()

    def perform(self, action: MoveAction | AlignAction) -> Violation | None:
        if not isinstance(action, AlignAction):
            return Violation(action=action.model_dump(), constraint="unknown_relation",
                             message="tangram pieces are placed with align, not move",
                             suggestion="use align(piece, side, target, target_side)")
        self._check(action)
        old = self.pose(action.object)
        self.set_pose(action.object, self.align_target(action))
        hits = self.overlapping(action.object)
        if hits:
            self.set_pose(action.object, old)
            return Violation(
                action=action.model_dump(), constraint="overlap",
                message=f"{action.text()} would make {action.object} overlap "
                        f"{', '.join(hits)}; nothing was moved", blocking=hits,
                suggestion=f"align {action.object} with a side that faces free space, or "
                           f"move {hits[0]} away first")
        return None

    def perform_unverified(self, action: MoveAction | AlignAction) -> SceneGraph:
        if not isinstance(action, AlignAction):
            raise SimError("tangram pieces are placed with align, not move", field="action",
                           value=action.text(), fix="use align(piece, side, target, side)")
        self._check(action)
        self.set_pose(action.object, self.align_target(action))
        return self.observe()

    def align_target(self, action: AlignAction) -> TPose:
        """The pose `align` would give the moved piece."""
        return align_pose(self.labels[action.object], action.side,
                          self.vertices(action.target), action.target_side)

    def render(self, width: int | None = None, height: int | None = None, *,
               labels: bool = False) -> np.ndarray:
        return render_tangram(self, width, height, labels=labels)

    def copy(self) -> TangramWorld:
        return TangramWorld(self.nodes, self.labels, {p: self.pose(p) for p in self.bodies},
                            self.dictionary_name)

    def _check(self, action: AlignAction) -> None:
        for role, name, side_index in (("object", action.object, action.side),
                                       ("target", action.target, action.target_side)):
            if name not in self.bodies:
                raise SimError(f"there is no piece '{name}' in the simulated scene",
                               field=role, value=name,
                               fix=f"use one of {', '.join(self.bodies)}")
            n_sides = len(piece_model(self.labels[name]))
            if not 0 <= side_index < n_sides:
                raise SimError(f"{name} has sides 0..{n_sides - 1}", field=role,
                               value=side_index, fix=f"use a side between 0 and {n_sides - 1}")
        if action.object == action.target:
            raise SimError("cannot align a piece with itself", field="target",
                           value=action.target, fix="choose another piece")


# Where a group is put together before it is moved to its place in the row: away from
# the groups already in the row and the pieces still waiting, so a group's contacts are
# checked against its own pieces only (a loose piece set down first never blocks it).
BUILD_Y = -10_000.0


def build_tangram(graph: SceneGraph) -> TangramWorld:
    """Lay out a tangram graph so that exactly its contacts hold.

    Pieces are placed breadth-first along the contacts, each aligned with one already
    placed neighbour and checked against all others (no overlap, exactly the contacts
    the graph lists); separate groups and loose pieces are set side by side.

    This is the one rule of a valid tangram start, for every executor: `load_scene`
    lays out a tangram graph with it whether the episode runs on sim2d or on the graph
    alone, so both accept and refuse the same starts, with the same reason.
    """
    state = WorldState.from_graph(graph)
    labels = {o.id: o.label for o in state.objects.values()}
    for obj in state.objects.values():
        if obj.props.sides is None:
            raise SimError(f"'{obj.id}' ({obj.label}) is not a tangram piece; a graph is "
                           "either tabletop or tangram", field="nodes", value=obj.id,
                           fix="use only tangram pieces with touches edges")
    wanted: dict[frozenset[tuple[str, int]], None] = {}
    for edge in graph.edges:
        wanted[frozenset({(edge.source, edge.source_side or 0),
                          (edge.target, edge.target_side or 0)})] = None
    neighbours: dict[str, list[tuple[int, str, int]]] = {p: [] for p in labels}
    for (a, sa), others in state.contacts.items():
        neighbours[a].extend((sa, b, sb) for b, sb in others)
    world = TangramWorld(list(graph.nodes), labels,
                         {p: TPose(1000.0 + 50 * i, 0.0, 0.0) for i, p in enumerate(labels)},
                         graph.dictionary)
    placed_ids: list[str] = []
    offset = 0.0
    for root in labels:
        if root in placed_ids:
            continue
        group = _place_group(world, root, neighbours, placed_ids, wanted)
        xs = [x for p in group for x, _ in world.vertices(p)]
        shift = offset - min(xs)
        for p in group:
            pose = world.pose(p)
            world.set_pose(p, TPose(pose.x + shift, pose.y - BUILD_Y, pose.theta))
        offset += max(xs) - min(xs) + SEPARATION
    observed = {frozenset({(e.source, e.source_side or 0), (e.target, e.target_side or 0)})
                for e in world.observe().edges}
    if observed != set(wanted):
        extra = sorted(" touches ".join(f"{p}[{side}]" for p, side in sorted(c))
                       for c in observed - set(wanted))
        raise SimError("the listed contacts cannot all hold without others the graph does "
                       f"not list: {'; '.join(extra) or 'geometry inconsistent'}",
                       field="edges", value=None,
                       fix="list contacts that a real tangram figure can have")
    return world


def _place_group(world: TangramWorld, root: str,
                 neighbours: dict[str, list[tuple[int, str, int]]], placed_ids: list[str],
                 wanted: dict[frozenset[tuple[str, int]], None]) -> list[str]:
    world.set_pose(root, TPose(0.0, BUILD_Y, 0.0))
    placed_ids.append(root)
    group = [root]
    queue: deque[str] = deque([root])
    while queue:
        current = queue.popleft()
        for _, other, _ in neighbours[current]:
            if other in placed_ids:
                continue
            _place_piece(world, other, neighbours, group, wanted)
            placed_ids.append(other)
            group.append(other)
            queue.append(other)
    return group


def _place_piece(world: TangramWorld, piece: str,
                 neighbours: dict[str, list[tuple[int, str, int]]], group: list[str],
                 wanted: dict[frozenset[tuple[str, int]], None]) -> None:
    """Lay `piece` against a placed neighbour as align would; refuse, naming what went
    wrong for each listed contact tried, when none gives exactly its listed contacts."""
    reasons: list[str] = []
    for side_index, other, other_side in neighbours[piece]:
        if other not in group:
            continue
        world.set_pose(piece, align_pose(world.labels[piece], side_index, world.vertices(other),
                                     other_side))
        how = f"laid with side {side_index} against {other}[{other_side}]"
        hits = world.overlapping(piece)
        if hits:
            reasons.append(f"{how}, it overlaps {', '.join(hits)}")
            continue
        mine = world.vertices(piece)
        extra: list[str] = []
        lacking: list[str] = []
        for q in group:
            got = {frozenset({(piece, a), (q, b)})
                   for a, b in touching_sides(mine, world.vertices(q))}
            need = {c for c in wanted if any(pid == q for pid, _ in c)
                    and any(pid == piece for pid, _ in c)}
            extra += [_contact_text(c, piece) for c in got - need]
            lacking += [_contact_text(c, piece) for c in need - got]
        if not extra and not lacking:
            return
        reasons.append(how + "".join(
            (f", it would also touch {', '.join(extra)}, which the graph does not list"
             if extra else "",
             f", it cannot also touch {', '.join(lacking)} as listed" if lacking else "")))
    raise SimError(f"'{piece}' cannot lie with exactly its listed contacts: "
                   + "; ".join(reasons[:4]), field="edges", value=piece,
                   fix="list contacts that a real tangram figure can have (a side touches one "
                       "other side, and no two listed contacts pull a piece to two places)")


def _contact_text(contact: frozenset[tuple[str, int]], piece: str) -> str:
    """`side 2 to square[1]`: a contact of `piece`, its own side first."""
    (a, sa), (b, sb) = sorted(contact, key=lambda end: end[0] != piece)
    return f"side {sa} to {b}[{sb}]"
