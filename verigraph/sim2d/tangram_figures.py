"""Tangram target figures and their single-move perturbations, from a seed.

A figure grows piece by piece: each new piece is aligned (docs/design.md section 2: midpoints
together, normals opposite) with a free side of a piece already placed, and kept only
if it overlaps nothing and touches exactly that one side; of several such placements the
most compact is kept, so figures look like tangram figures. Every side therefore touches
at most one piece and the contacts form a tree, which is what the validator's
`side_occupied` rule and a one-step repair need. A perturbation moves one leaf piece
(a piece with a single contact) away from the figure, losing exactly that contact.
"""

from __future__ import annotations

import math
import random

from verigraph.graph.dictionary import builtin_dictionary
from verigraph.graph.model import Node
from verigraph.sim2d.errors import SimError
from verigraph.sim2d.tangram import TangramWorld
from verigraph.sim2d.tangram_geometry import (
    PIECE_NAMES,
    SEPARATION,
    TPose,
    align_pose,
    piece_model,
    touching_sides,
)

MAX_ATTEMPTS = 200
FIGURE_RESTARTS = 20
COMPACT_CHOICES = 8


def tangram_nodes(pieces: list[str]) -> list[Node]:
    d = builtin_dictionary("tangram")
    return [Node(id=p, label=p, attrs={"color": d.objects[p].color}) for p in pieces]


def _parking(i: int) -> TPose:
    return TPose(10_000.0 + 40.0 * i, 10_000.0, 0.0)


def target_figure(rng: random.Random, pieces: list[str]) -> TangramWorld:
    """A connected figure of `pieces` whose contacts form a tree."""
    for _ in range(FIGURE_RESTARTS):
        world = _try_figure(rng, pieces)
        if world is not None:
            return world
    raise SimError("could not grow a tangram figure from these pieces", field="n_objects",
                   value=len(pieces), fix="use another seed")


def _try_figure(rng: random.Random, pieces: list[str]) -> TangramWorld | None:
    order = list(pieces)
    rng.shuffle(order)
    world = TangramWorld(tangram_nodes(pieces), {p: p for p in pieces},
                         {p: _parking(i) for i, p in enumerate(pieces)})
    world.set_pose(order[0], TPose(0.0, 0.0, rng.randrange(8) * math.pi / 4))
    placed = [order[0]]
    used: set[tuple[str, int]] = set()
    for piece in order[1:]:
        options: list[tuple[float, TPose, tuple[str, int], tuple[str, int]]] = []
        for _ in range(MAX_ATTEMPTS):
            other = rng.choice(placed)
            free = [s for s in range(len(piece_model(other))) if (other, s) not in used]
            if not free:
                continue
            other_side = rng.choice(free)
            own_side = rng.randrange(len(piece_model(piece)))
            pose = align_pose(piece, own_side, world.vertices(other), other_side)
            world.set_pose(piece, pose)
            if world.overlapping(piece):
                continue
            mine = world.vertices(piece)
            touches = [(q, a, b) for q in placed for a, b in touching_sides(mine,
                                                                             world.vertices(q))]
            if touches == [(other, own_side, other_side)]:
                options.append((_spread(world, placed + [piece]), pose, (piece, own_side),
                                (other, other_side)))
                if len(options) >= COMPACT_CHOICES:
                    break
        if not options:
            return None
        # The most compact of the valid placements: figures look like tangram figures.
        _, pose, mine_side, other_side_used = min(options, key=lambda o: o[0])
        world.set_pose(piece, pose)
        used.update({mine_side, other_side_used})
        placed.append(piece)
    return world


def _spread(world: TangramWorld, pieces: list[str]) -> float:
    pts = [v for p in pieces for v in world.vertices(p)]
    cx = sum(x for x, _ in pts) / len(pts)
    cy = sum(y for _, y in pts) / len(pts)
    return max(math.hypot(x - cx, y - cy) for x, y in pts)


def perturb(rng: random.Random, target: TangramWorld) -> tuple[TangramWorld, str]:
    """A copy of the figure with one leaf piece moved away (exactly one contact lost)."""
    graph = target.observe()
    degree: dict[str, int] = {n.id: 0 for n in graph.nodes}
    for e in graph.edges:
        degree[e.source] += 1
        degree[e.target] += 1
    leaves = sorted(p for p, d in degree.items() if d == 1)
    if not leaves:
        raise SimError("the figure has no piece with a single contact", field="n_objects",
                       value=len(degree), fix="use at least two pieces")
    piece = rng.choice(leaves)
    start = target.copy()
    xs = [x for p in degree if p != piece for x, _ in start.vertices(p)]
    ys = [y for p in degree if p != piece for _, y in start.vertices(p)]
    away = TPose(max(xs) + 2 * SEPARATION + 6.0, (min(ys) + max(ys)) / 2,
                 rng.randrange(8) * math.pi / 4)
    start.set_pose(piece, away)
    return start, piece


def random_pieces(rng: random.Random, n: int | None) -> list[str]:
    if n is None or n == len(PIECE_NAMES):
        return list(PIECE_NAMES)
    if not 2 <= n <= len(PIECE_NAMES):
        raise SimError(f"a tangram scene has 2 to {len(PIECE_NAMES)} pieces, not {n}",
                       field="n_objects", value=n, fix="use a number from 2 to 7")
    return sorted(rng.sample(PIECE_NAMES, n), key=PIECE_NAMES.index)
