"""Kitchen reference-image episodes: a generated kitchen and a goal several moves away.

The start scene is the sim2d generator's kitchen for the draw; the goal is reached by a
random walk of valid moves that also have room in the simulator (so `--simulate` can
carry it out), continued until the reference solver needs `target` moves and at least
one object that must move is not clear at the start (something has to be cleared first).
"""

from __future__ import annotations

import random

from verigraph.actions.validator import apply_action
from verigraph.graph.goal import Goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.solver import solve
from verigraph.tasks.suite_blocks import Drawn

SOLVER_BUDGET = 40_000
MAX_WALK = 14
INSTRUCTION = "Rearrange the scene so that it looks like the reference image."


def misplaced_not_clear(start: WorldState, goal: SceneGraph) -> bool:
    """An object whose support must change carries something at the start."""
    wanted = {e.source: (e.relation, e.target) for e in goal.edges}
    return any(start.support.get(o) != w and not start.is_clear(o) for o, w in wanted.items())


def kitchen_goal(graph: SceneGraph, rng: random.Random, target: int) -> Drawn | None:
    """A goal `target` optimal moves away that needs clearing, or None for this scene."""
    from verigraph.sim2d.generator import valid_moves
    from verigraph.sim2d.room import room_violation

    start = WorldState.from_graph(graph)
    state = start.copy()
    best: Drawn | None = None
    for _ in range(MAX_WALK):
        moves = [m for m in valid_moves(state) if room_violation(state, m) is None]
        if not moves:
            break
        apply_action(state, rng.choice(moves))
        goal_graph = state.to_graph()
        if goal_graph.edge_keys() == graph.edge_keys() \
                or not misplaced_not_clear(start, goal_graph):
            continue
        goal = Goal(graph=goal_graph, instruction=INSTRUCTION)
        result = solve(start, goal, max_expansions=SOLVER_BUDGET)
        if not result.reachable:
            continue
        length = len(result.plan)
        if length >= 3 and (best is None or abs(length - target) < abs(best.optimal_length
                                                                       - target)):
            best = Drawn(graph, goal, "rearrange", length)
        if length >= target:
            break
    return best
