"""Household episodes: the built-in kitchen and dining room, with states to change.

Scenes and goals name the household dictionary (docs/worlds.md, "Household worlds").

The start is `kitchen_household` after a short random walk of valid actions of the
action table (doors opened or shut, the stove switched, food and dishes moved); the
goal is where a further walk ends, stated as a partial goal: the placement of every
movable object the walk moved and the state of every object it switched. Kept when the
reference solver's optimal plan is `target` actions long or close to it, and at least
one action passes a closed container or changes a state (a pure tabletop rearrangement
belongs to the kitchen suite).
"""

from __future__ import annotations

import random

from verigraph.actions.model import AnyAction, MoveAction, StateAction
from verigraph.actions.schemas import valid_actions
from verigraph.actions.validator import apply_action
from verigraph.graph.builtin_scenes import kitchen_household
from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.solver import solve
from verigraph.tasks.suite_blocks import Drawn

SOLVER_BUDGET = 20_000
START_WALK = 3
MAX_WALK = 6
TARGETS = (3, 4, 5, 4)  # optimal lengths aimed at, in turn


def _walk(state: WorldState, rng: random.Random, steps: int) -> list[AnyAction]:
    """`steps` random valid actions applied to `state`, in place (none under or next to
    something: the suite's goals are about doors, switches and where things go)."""
    done: list[AnyAction] = []
    for _ in range(steps):
        actions = [a for a in valid_actions(state)
                   if getattr(a, "relation", "on") in ("on", "in")]
        if not actions:
            break
        action = rng.choice(actions)
        apply_action(state, action)
        done.append(action)
    return done


def instruction(goal: SceneGraph) -> str:
    """`Make these hold: milk in fridge; fridge closed; stove on.`"""
    parts = [*goal.sentences(), *goal.state_sentences()]
    return "Make these hold: " + "; ".join(parts) + "."


def household_task(rng: random.Random, target: int) -> Drawn | None:
    """A household goal about `target` optimal actions away, or None for this draw."""
    start = WorldState.from_graph(kitchen_household())
    _walk(start, rng, START_WALK)
    state = start.copy()
    walked = _walk(state, rng, target + rng.randrange(MAX_WALK - target + 1))
    if not any(isinstance(a, StateAction) for a in walked):
        return None
    moved = {a.object for a in walked if isinstance(a, MoveAction)}
    switched = {(a.object, "open" if a.action in ("open", "close") else "toggled_on")
                for a in walked if isinstance(a, StateAction)}
    nodes, edges = {}, []
    for obj in sorted(moved):
        relation, target_id = state.support[obj]
        edges.append(Edge(source=obj, relation=relation, target=target_id))
        for node_id in (obj, target_id):
            nodes[node_id] = Node(id=node_id, label=state.objects[node_id].label)
    for obj, key in sorted(switched):
        node = nodes.setdefault(obj, Node(id=obj, label=state.objects[obj].label))
        node.state[key] = state.state_value(obj, key)
    goal_graph = SceneGraph(nodes=list(nodes.values()), edges=edges, dictionary="household")
    goal = Goal(graph=goal_graph, partial=True, instruction=instruction(goal_graph))
    start_graph = start.to_graph()
    result = solve(start_graph, goal, max_expansions=SOLVER_BUDGET)
    if not result.reachable or not result.optimal or len(result.plan) < 2:
        return None
    if not any(isinstance(a, StateAction) for a in result.plan):
        return None
    return Drawn(start_graph, goal, "household", len(result.plan))


__all__ = ["TARGETS", "household_task", "instruction"]
