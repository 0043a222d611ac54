"""Fewest align actions to a tangram figure, by a goal-directed breadth-first search.

An align detaches the moved piece's contacts and adds exactly one, so a useful align
creates a missing goal contact; searching only those (in either direction) keeps the
branching at twice the number of missing contacts, and breadth first keeps the plan
shortest among such plans. Since each align adds one contact, a plan needs at least as
many aligns as goal contacts are missing: a plan of that length is optimal outright.
"""

from __future__ import annotations

from collections.abc import Callable

from verigraph.actions.model import AlignAction
from verigraph.actions.validator import apply_action, validate_action
from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.state import WorldState

MAX_DEPTH = 12
MAX_NODES = 20_000

Contacts = frozenset[tuple[tuple[str, int], tuple[tuple[str, int], ...]]]


def contact_key(state: WorldState) -> Contacts:
    """The contacts of a state as a hashable value (each side's partners, in order)."""
    return frozenset((side, tuple(others)) for side, others in state.contacts.items())


def missing_contacts(state: WorldState, goal: Goal) -> list[AlignAction]:
    """Aligns that would create a goal contact that does not hold now (both directions)."""
    assert goal.graph is not None
    out = []
    for edge in goal.graph.edges:
        if edge.relation != "touches":
            continue
        a, sa, b, sb = edge.source, edge.source_side or 0, edge.target, edge.target_side or 0
        if (b, sb) in state.contacts.get((a, sa), []):
            continue
        out += [AlignAction(object=a, side=sa, target=b, target_side=sb),
                AlignAction(object=b, side=sb, target=a, target_side=sa)]
    return out


def tangram_plan(state: WorldState, goal: Goal, *, max_depth: int = MAX_DEPTH,
                 max_nodes: int = MAX_NODES, step: Callable[[], None] | None = None
                 ) -> list[AlignAction] | None:
    """A shortest goal-directed align plan, or None when none is found within the limits
    (`step` is called once per state generated: a budget's check)."""
    if check_goal(state, goal).satisfied:
        return []
    layer: list[tuple[WorldState, list[AlignAction]]] = [(state, [])]
    seen = {contact_key(state)}
    for _ in range(max_depth):
        nxt: list[tuple[WorldState, list[AlignAction]]] = []
        for current, plan in layer:
            for action in missing_contacts(current, goal):
                if validate_action(current, action) is not None:
                    continue
                if step is not None:
                    step()
                trial = current.copy()
                apply_action(trial, action)
                key = contact_key(trial)
                if key in seen:
                    continue
                seen.add(key)
                if check_goal(trial, goal).satisfied:
                    return [*plan, action]
                nxt.append((trial, [*plan, action]))
                if len(seen) > max_nodes:
                    return None
        layer = nxt
        if not layer:
            return None
    return None
