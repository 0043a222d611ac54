"""Tangram episodes with two or three pieces out of the target figure.

The figure is the sim2d generator's target for the draw (its contacts form a tree). The
start takes 2 or 3 pieces out by peeling leaves one after the other (so a piece taken
out may be the one an earlier piece was attached to), which leaves the rest of the
figure connected. Putting them back needs one align per piece in the reverse order; the
goal-directed search in `verigraph.planning.tangram_plan` confirms the optimal length.

These episodes are symbolic: the simulator lays out the generator's own perturbation
only, so with `--simulate` the tangram group still runs on graphs (the report says so).
"""

from __future__ import annotations

import random

from verigraph.graph.goal import Goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.planning.tangram_plan import tangram_plan
from verigraph.tasks.suite_blocks import Drawn


def peelable(edges: set[tuple[str, str]]) -> list[str]:
    """The pieces that touch one other only (sorted), which can come out of the figure
    and leave it connected; [] when two pieces or fewer are left."""
    degree: dict[str, int] = {}
    for a, b in edges:
        degree[a] = degree.get(a, 0) + 1
        degree[b] = degree.get(b, 0) + 1
    return [] if len(degree) <= 2 else sorted(p for p, d in degree.items() if d == 1)


def _peel(figure: SceneGraph, rng: random.Random, count: int) -> list[str]:
    edges = {(e.source, e.target) for e in figure.edges if e.relation == "touches"}
    out: list[str] = []
    for _ in range(count):
        leaves = peelable(edges)
        if not leaves:
            break
        piece = rng.choice(leaves)
        out.append(piece)
        edges = {(a, b) for a, b in edges if piece not in (a, b)}
    return out


def tangram_task(figure: SceneGraph, rng: random.Random, pieces_out: int) -> Drawn | None:
    """`pieces_out` pieces taken out of `figure`, or None if the figure is too small."""
    removed = _peel(figure, rng, pieces_out)
    if len(removed) < pieces_out:
        return None
    start = SceneGraph(nodes=list(figure.nodes),
                       edges=[e for e in figure.edges
                              if e.source not in removed and e.target not in removed],
                       dictionary=figure.dictionary)
    put_back = put_back_goal(figure, start, removed)
    if put_back is None:
        return None
    goal, length = put_back
    return Drawn(start, goal, f"{pieces_out}_pieces_out", length)


def put_back_goal(figure: SceneGraph, start: SceneGraph, removed: list[str]
                  ) -> tuple[Goal, int] | None:
    """The goal of putting the `removed` pieces back into `figure` from `start`, and its
    reference plan's length (None when the tangram search finds no plan)."""
    words = ", ".join(removed[::-1])
    goal = Goal(graph=figure, instruction=f"Put {words} back into the figure: make every "
                                          "contact of the target figure hold.")
    plan = tangram_plan(WorldState.from_graph(start), goal)
    return None if plan is None else (goal, len(plan))


PIECES_OUT = (5, 3, 5, 2, 5, 4)  # 2-3 piece tasks and harder ones: mean 4 moves
