"""Block-world episodes: ordered stacking, tower reversal, multi-tower rearrangement, and
reference-image goals that need clearing.

Scenes are drawn here rather than taken from the sim2d generator so that the difficulty
is a property of the task, not of the seed: a stacking task names its kind and its block
count, and its optimal length follows from them (ordered stacking from blocks spread on
the table: n - 1 moves; reversing a tower of n: n moves; rearranging towers: whatever
the reference solver says, at least 3). The goal is a full goal graph with the order
spelled out, so "any single tower" no longer counts.
"""

from __future__ import annotations

import random
from dataclasses import dataclass

from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.solver import solve

COLOURS = ("red", "blue", "green", "yellow", "purple", "orange", "cyan", "pink")
SOLVER_BUDGET = 60_000

Towers = list[list[str]]  # bottom first


@dataclass(frozen=True)
class Drawn:
    """One drawn task: start graph, goal, its wording, kind and optimal plan length."""

    graph: SceneGraph
    goal: Goal
    kind: str
    optimal_length: int


def block_graph(towers: Towers, colours: dict[str, str] | None = None) -> SceneGraph:
    """Towers of blocks (bottom first) on one table; `colours` maps ids to colour attrs."""
    colours = colours or {}
    nodes = [Node(id="table", label="table")]
    edges = []
    for tower in towers:
        below = "table"
        for block in tower:
            nodes.append(Node(id=block, label="block",
                              attrs={"color": colours.get(block, block.split("_")[0])}))
            edges.append(Edge(source=block, relation="on", target=below))
            below = block
    return SceneGraph(nodes=nodes, edges=edges, dictionary="blocks")


def random_towers(rng: random.Random, blocks: list[str], n_towers: int) -> Towers:
    """Blocks split at random into `n_towers` non-empty towers, in random order."""
    order = rng.sample(blocks, len(blocks))
    cuts = sorted(rng.sample(range(1, len(order)), n_towers - 1)) if n_towers > 1 else []
    bounds = [0, *cuts, len(order)]
    return [order[a:b] for a, b in zip(bounds, bounds[1:], strict=False)]


def optimal_length(graph: SceneGraph, goal: Goal) -> int | None:
    result = solve(WorldState.from_graph(graph), goal, max_expansions=SOLVER_BUDGET)
    return len(result.plan) if result.reachable else None


def needs_clearing(start: Towers, goal: Towers) -> bool:
    """Some block that must move has another block on it at the start."""
    below_start = {b: (t[i - 1] if i else "table") for t in start for i, b in enumerate(t)}
    below_goal = {b: (t[i - 1] if i else "table") for t in goal for i, b in enumerate(t)}
    return any(below_start[b] != below_goal[b] for tower in start for b in tower[:-1])


def _tower_words(tower: list[str]) -> str:
    return ", ".join(b.removesuffix("_block") for b in tower)


def _goal(towers: Towers, instruction: str) -> Goal:
    return Goal(graph=block_graph(towers), instruction=instruction)


def stacking_task(rng: random.Random, index: int) -> Drawn:
    """Kinds in turn: ordered stack from spread blocks, reversal, multi-tower rearrangement."""
    kind = ("ordered", "reversal", "multi_tower")[index % 3]
    if kind == "ordered":
        n = rng.randint(4, 8)
        blocks = [f"{c}_block" for c in rng.sample(COLOURS, n)]
        tower = rng.sample(blocks, n)
        start = [[b] for b in blocks]
        goal = _goal([tower], "Stack all the blocks into one tower, from the bottom up: "
                              f"{_tower_words(tower)}.")
        return Drawn(block_graph(start), goal, kind, n - 1)
    if kind == "reversal":
        n = rng.randint(4, 7)
        tower = [f"{c}_block" for c in rng.sample(COLOURS, n)]
        others = [f"{c}_block" for c in COLOURS if f"{c}_block" not in tower][:rng.randint(0, 1)]
        goal = _goal([list(reversed(tower)), *[[o] for o in others]],
                     "Turn the tower upside down: from the bottom up it should read "
                     f"{_tower_words(list(reversed(tower)))}.")
        graph = block_graph([tower, *[[o] for o in others]])
        return Drawn(graph, goal, kind, n)
    while True:
        n = rng.randint(5, 8)
        blocks = [f"{c}_block" for c in rng.sample(COLOURS, n)]
        start = random_towers(rng, blocks, rng.randint(2, 3))
        target = random_towers(rng, blocks, rng.randint(2, 3))
        words = "; ".join(_tower_words(t) for t in target)
        goal = _goal(target, f"Rebuild the blocks as {len(target)} towers, each from the "
                             f"bottom up: {words}.")
        length = optimal_length(block_graph(start), goal)
        if length is not None and length >= 4 and needs_clearing(start, target):
            return Drawn(block_graph(start), goal, kind, length)


def reference_blocks_task(rng: random.Random, min_length: int = 3) -> Drawn:
    """Towers to other towers, at least `min_length` moves and a block to clear first."""
    while True:
        n = rng.randint(5, 7)
        blocks = [f"{c}_block" for c in rng.sample(COLOURS, n)]
        start = random_towers(rng, blocks, rng.randint(2, 3))
        target = random_towers(rng, blocks, rng.randint(1, 3))
        goal = _goal(target, "Rearrange the blocks so that the scene looks like the "
                             "reference image.")
        length = optimal_length(block_graph(start), goal)
        if length is not None and length >= min_length and needs_clearing(start, target):
            return Drawn(block_graph(start), goal, "rearrange", length)
