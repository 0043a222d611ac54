"""Optimal search over the action table, for household worlds.

Where the integer encoding (`encoding`) cannot speak for every action (openable
containers, object states in the goal, `under`/`nextto` placements, or parking places
that only `under`/`nextto` give), the solver searches here: successors are every row
of the action table (`verigraph.actions.schemas`) bound to the candidates its
parameters' roles allow and accepted by the row's compiled preconditions, applied with
the row's effect. Every action is one step. A* with the number of goal atoms (a
movable object's goal placement, a goal state) that do not hold yet, plus the opening
(and, where the goal wants it closed, the closing) of each closed container a
misplaced object must leave or enter: an action changes one placement or one state,
and those opens and closes fix no placement, so the bound is admissible, and the plan
found is optimal. The frontier holds compact keys (placements and states), a world is
rebuilt from its key when it is expanded.
"""

from __future__ import annotations

import heapq
import itertools
from collections.abc import Iterator
from typing import Any

from verigraph.actions.model import AnyAction, MoveAction, StateAction
from verigraph.actions.schemas import SCHEMAS, ActionSchema
from verigraph.graph.dictionary import PLACEMENT_RELATIONS, SUPPORT_RELATIONS
from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.state import WorldState
from verigraph.solver.budget import SearchBudget

Key = tuple[tuple[Any, ...], tuple[bool, ...]]


def needs_table_search(state: WorldState, goal: Goal) -> bool:
    """Whether the encoded on/in search could miss an action that matters.

    It could when the scene has openable objects (a closed one bars `in`), the goal
    asks for a state or an `under`/`nextto` placement, the scene has such a placement,
    or the scene is a household one (a node with a state or a toggleable kind) whose
    relations allow `under`/`nextto` and that has no fixed surface of unlimited capacity
    (then those placements may be the only free places; with one, any such parking move
    has an equally long replacement onto it, so on/in suffice). A scene of movable
    objects on surfaces and in containers, with a goal of the same, is a rearrangement
    on `on`/`in` whatever else its dictionary allows: the encoded search solves it (a
    storage puzzle's capacities are not circumvented by parking objects next to each
    other, and the search stays the fast one).
    """
    if state.openable:
        return True
    if goal.graph is not None and (
            any(n.state for n in goal.graph.nodes)
            or any(e.relation in PLACEMENT_RELATIONS and e.relation not in SUPPORT_RELATIONS
                   for e in goal.graph.edges)):
        return True
    if any(r not in SUPPORT_RELATIONS for r, _ in state.support.values()):
        return True
    household = bool(state.states) or any(info.props.toggleable
                                           for info in state.objects.values())
    if household and len(state.move_relations) > len(
            [r for r in state.move_relations if r in SUPPORT_RELATIONS]):
        return not any(state.objects[s].props.capacity is None for s in state.fixed_surfaces)
    return False


class TableProblem:
    """A household scene as search states: each movable object's placement and each
    state-bearing object's states, with the goal as atoms."""

    def __init__(self, state: WorldState, goal: Goal) -> None:
        self.start = state
        objects = state.objects
        self.movable = sorted(o for o, info in objects.items() if info.props.movable)
        self.stateful = sorted(
            (o, key) for o, info in objects.items()
            for key, role in (("open", "openable"), ("toggled_on", "toggleable"))
            if getattr(info.props, role))
        self.candidates: dict[str, list[str]] = {
            role: sorted(o for o, info in objects.items() if getattr(info.props, role))
            for role in ("movable", "openable", "toggleable")}
        self.every = sorted(objects)
        self.placements: dict[str, tuple[str, str]] = {}
        self.states: dict[tuple[str, str], bool] = {}
        if goal.graph is not None:
            for e in goal.graph.edges:
                if e.relation in PLACEMENT_RELATIONS and e.source in objects and \
                        objects[e.source].props.movable:
                    self.placements[e.source] = (e.relation, e.target)
            for n in goal.graph.nodes:
                for key, value in n.state.items():
                    self.states[(n.id, key)] = value

    def key(self, state: WorldState) -> Key:
        support = state.support
        return (tuple(support.get(o) for o in self.movable),
                tuple(state.state_value(o, k) for o, k in self.stateful))

    def h(self, state: WorldState) -> int:
        """A lower bound on the actions still needed: goal atoms that do not hold, and
        the opens and closes of closed containers misplaced objects must pass."""
        support = state.support
        wrong = sum(state.state_value(o, k) != v for (o, k), v in self.states.items())
        passed: set[str] = set()
        openable = state.openable
        for o, p in self.placements.items():
            now = support.get(o)
            if now == p:
                continue
            wrong += 1
            for relation, box in (now or ("", ""), p):
                if relation == "in" and box in openable and \
                        not state.state_value(box, "open"):
                    passed.add(box)
        for box in passed:
            wanted = self.states.get((box, "open"))
            if wanted is None:
                wrong += 1  # open it
            elif wanted is False:
                wrong += 2  # open it, close it again
            # wanted open: that atom counts the opening already
        return wrong

    def world(self, key: Key) -> WorldState:
        """The world of a search key: the start with its placements and states."""
        state = self.start.copy()
        for o, placed in zip(self.movable, key[0], strict=True):
            if placed is not None and state.support.get(o) != placed:
                state.set_support(o, placed[0], placed[1])
        for (o, k), value in zip(self.stateful, key[1], strict=True):
            if state.state_value(o, k) != value:
                state.set_state(o, k, value)
        return state

    def _bindings(self, row: ActionSchema, state: WorldState) -> Iterator[tuple[str, ...]]:
        pools = []
        for p in row.parameters:
            if p.role == "relation":
                pools.append(list(state.move_relations))
            elif p.role is None:
                pools.append(self.every)
            else:
                pools.append(self.candidates[p.role])
        return itertools.product(*pools)

    def successors(self, state: WorldState, budget: SearchBudget
                   ) -> Iterator[tuple[AnyAction, WorldState]]:
        for row in SCHEMAS.values():
            for args in self._bindings(row, state):
                if not row.accepted(state, *args):
                    continue
                budget.check(memory=True)
                nxt = state.copy()
                row.apply(nxt, *args)
                yield _action(row, args), nxt


def valid_actions(state: WorldState) -> list[AnyAction]:
    """Every action of the table the verifier accepts on `state` now (scene order)."""
    problem = TableProblem(state, Goal(predicate="single_stack"))
    found = []
    for row in SCHEMAS.values():
        for args in problem._bindings(row, state):
            if row.accepted(state, *args):
                found.append(_action(row, args))
    return found


def _action(row: ActionSchema, args: tuple[str, ...]) -> AnyAction:
    if row.name == "move":
        return MoveAction(object=args[0], relation=args[1], target=args[2])
    return StateAction(action=row.name, object=args[0])  # type: ignore[arg-type]


def table_astar(state: WorldState, goal: Goal, budget: SearchBudget
                ) -> tuple[bool, list[AnyAction]]:
    """(found, plan): an optimal plan over the table's actions, every action one step."""
    problem = TableProblem(state, goal)
    counter = itertools.count()
    start_key = problem.key(state)
    frontier: list[tuple[int, int, int, Key]] = [(problem.h(state), 0, next(counter), start_key)]
    parent: dict[Key, tuple[Key, AnyAction] | None] = {start_key: None}
    best_g = {start_key: 0}
    while frontier:
        _, neg_g, _, key = heapq.heappop(frontier)
        g = -neg_g
        if g > best_g.get(key, g):
            continue
        current = problem.world(key)
        if problem.h(current) == 0 and check_goal(current, goal).satisfied:
            plan: list[AnyAction] = []
            node: Key | None = key
            while node is not None and parent[node] is not None:
                prev, action = parent[node]  # type: ignore[misc]
                plan.append(action)
                node = prev
            return True, list(reversed(plan))
        budget.expansions += 1
        budget.check()
        for action, nxt in problem.successors(current, budget):
            nkey = problem.key(nxt)
            ng = g + 1
            if ng < best_g.get(nkey, ng + 1):
                best_g[nkey] = ng
                parent[nkey] = (key, action)
                # Ties broken towards deeper nodes: fewer expansions, still optimal.
                heapq.heappush(frontier, (ng + problem.h(nxt), -ng, next(counter), nkey))
    return False, []
