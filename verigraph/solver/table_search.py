"""Optimal search over the action table, for household worlds.

Where the integer encoding (`encoding`) cannot speak for every action (openable
containers, object states in the goal, `under`/`nextto` placements, or parking places
that only `under`/`nextto` give), the solver searches here: successors are every row
of the action table (`verigraph.actions.schemas`) bound to the candidates its
parameters' roles allow (`schemas.candidates`, `ActionSchema.arguments`: the bindings
`schemas.valid_actions` lists, the relations narrowed to those the goal needs) and
accepted by the row's compiled preconditions, applied with the row's effect. Every
action is one step. A* with the number of goal atoms (a movable object's goal
placement, a goal state) that do not hold yet, plus the opening (and, where the goal
wants it closed, the closing) of each closed container a misplaced object must leave
or enter: an action changes one placement or one state, and those opens and closes
fix no placement, so the bound is admissible, and the plan found is optimal. The
frontier holds compact keys (placements and states), a world is
rebuilt from its key when it is expanded.
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Callable, Iterator
from typing import Any

from verigraph.actions.model import AnyAction
from verigraph.actions.processes import process_needs
from verigraph.actions.schemas import SCHEMAS, ActionSchema, SetState, candidates
from verigraph.graph.dictionary import (
    PLACEMENT_RELATIONS,
    STATE_ROLES,
    SUPPORT_RELATIONS,
    THERMAL_ROLES,
)
from verigraph.graph.formula import Atom, Formula, Imply, Junction, Not, parse_formula
from verigraph.graph.formula_eval import Facts, facts_of
from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.state import WorldState
from verigraph.solver.budget import SearchBudget, SearchBudgetSpent
from verigraph.solver.formula_bound import formula_bound

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
    if goal.formula is not None and _formula_needs_table(parse_formula(goal.formula)):
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


def _formula_needs_table(formula: Formula) -> bool:
    """A formula that asks for a state (`open`, `cooked`, ...) or an `under`/`nextto`
    placement: only the table's actions reach it."""
    return any(r not in (*SUPPORT_RELATIONS, "inroom") for r in _atom_relations(formula))


def _atom_relations(formula: Formula) -> set[str]:
    """The relations and state keys a formula's atoms read."""
    found: set[str] = set()
    stack: list[Formula] = [formula]
    while stack:
        node = stack.pop()
        if isinstance(node, Atom):
            found.add(node.relation)
        elif isinstance(node, Not):
            stack.append(node.body)
        elif isinstance(node, Junction):
            stack.extend(node.parts)
        elif isinstance(node, Imply):
            stack.extend((node.condition, node.then))
        else:  # a quantifier
            stack.append(node.body)
    return found


class TableProblem:
    """A household scene as search states: each movable object's placement and each
    state-bearing object's states, with the goal as atoms."""

    def __init__(self, state: WorldState, goal: Goal, *, additive: bool = False) -> None:
        self.start = state
        self.additive = additive  # h from distinct requirements: a guide, not a bound
        objects = state.objects
        self.movable = sorted(o for o, info in objects.items() if info.props.movable)
        # The formula's atoms (parsed once): which states the goal reads.
        self.formula = parse_formula(goal.formula) if goal.formula is not None else None
        wanted = _atom_relations(self.formula) if self.formula is not None else set()
        if goal.graph is not None:
            wanted |= {e.relation for e in goal.graph.edges}
            wanted |= {key for n in goal.graph.nodes for key in n.state}
        # A thermal state (cooked, hot, frozen) is read by no precondition but its own
        # process's, so where the goal does not read it, an action that changes it never
        # helps: those rows are left out (plans stay optimal, the space much smaller).
        # `open` and `toggled_on` gate moves and processes, so they always count.
        self.keys = {key for key in STATE_ROLES
                     if key not in THERMAL_ROLES or key in wanted}
        self.rows = [row for row in SCHEMAS.values()
                     if not isinstance(row.effect, SetState) or row.effect.key in self.keys]
        self.stateful = sorted(
            (o, key) for o, info in objects.items()
            for key, role in STATE_ROLES.items()
            if key in self.keys and getattr(info.props, role))
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
        # A formula goal: its admissible bound (verigraph.solver.formula_bound) joins.
        # `under`/`nextto` moves only where the goal reads them or rooms: with a fixed
        # surface of unlimited capacity, a parking move by them has an equally long
        # replacement onto it (needs_table_search), so the plans stay optimal.
        unlimited = any(objects[s].props.capacity is None for s in state.fixed_surfaces)
        # Each parameter's candidates (the table's `candidates`, with those relations).
        self.pools = candidates(state, [r for r in state.move_relations
                                        if r in SUPPORT_RELATIONS or r in wanted
                                        or not unlimited or "inroom" in wanted])
        self._facts = facts_of(state) if self.formula is not None else None
        self._bounds: dict[Key, int] = {}

    def facts(self, state: WorldState) -> Facts:
        """The formula's view of a search state, built from the placements directly."""
        assert self._facts is not None
        facts = self._facts.with_edges(
            [*((r, o, t) for o, (r, t) in state.support.items()),
             *(("inroom", o, r) for o, r in state.rooms.items())])
        facts.states = state.states
        return facts

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
        if self.formula is not None:
            wrong = max(wrong, formula_bound(
                self.formula, self.facts(state),
                lambda obj, key, want: process_needs(state, obj, key, want),
                additive=self.additive))
        return wrong

    def helpful(self, state: WorldState) -> set[tuple[str, str]]:
        """The things (`("place", x)`, `("open", box)`, `("cooked", x)`, ...) the goal
        formula's requirements name on `state`: an action that changes one of them is
        helpful (greedy search tries those first). Empty without a formula."""
        things: set[tuple[str, str]] = set()
        if self.formula is not None:
            formula_bound(self.formula, self.facts(state),
                          lambda obj, key, want: process_needs(state, obj, key, want),
                          additive=True, things=things)
        return things

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

    def successors(self, state: WorldState, budget: SearchBudget,
                   evaluate: Callable[[ActionSchema, tuple[str, ...]], bool] | None = None
                   ) -> Iterator[tuple[ActionSchema, tuple[str, ...], Key, int]]:
        """(row, arguments, key, bound) of each accepted action. Each is applied to
        `state` in place, read, and undone (a copy per successor cost more than the
        search did), so `state` is unchanged when the iteration ends. With `evaluate`,
        the bound is computed only for the actions it accepts (-1 for the others: the
        bound is most of a successor's cost)."""
        made = 0
        for row in self.rows:
            for args in row.arguments(self.pools):
                if not row.accepted(state, *args):
                    continue
                made += 1
                if not made & 63:
                    budget.check(memory=True)
                before = row.apply(state, *args)
                try:
                    key = self.key(state)
                    bound = self._bounds.get(key)
                    if bound is None:
                        if evaluate is not None and not evaluate(row, args):
                            bound = -1
                        else:
                            bound = self._bounds[key] = self.h(state)
                    yield row, args, key, bound
                finally:
                    if row.name == "move":
                        if before is None:  # it had no placement before
                            state.support.pop(args[0])
                            del state.carried[args[2]][args[0]]
                        else:
                            state.set_support(args[0], before[0], before[1])
                    else:
                        state.set_state(args[0], row.effect.key,  # type: ignore[union-attr]
                                        before)


def neighbours(problem: TableProblem, state: WorldState, budget: SearchBudget
               ) -> Iterator[tuple[AnyAction, WorldState]]:
    """Each accepted action with the world after it (a copy each: for checks and tests;
    the search itself reads keys and bounds from `TableProblem.successors`)."""
    for row, args, _, _ in list(problem.successors(state, budget)):
        after = state.copy()
        row.apply(after, *args)
        yield row.action(args), after


def _changes(row: ActionSchema, args: tuple[str, ...]) -> tuple[str, str]:
    """The thing an action changes: `("place", x)` for a move, `(key, x)` for a state."""
    if isinstance(row.effect, SetState):
        key = row.effect.key
        if key == "open" and not row.effect.value:
            return "close", args[0]
        return key, args[0]
    return "place", args[0]


def _helpful_test(helpful: set[tuple[str, str]]
                  ) -> Callable[[ActionSchema, tuple[str, ...]], bool]:
    """Whether an action changes one of the things in `helpful`."""
    return lambda row, args: _changes(row, args) in helpful


# Of every HELPFUL_SHARE pops, all but one come from the helpful actions' queue.
HELPFUL_SHARE = 4


Parents = dict[Key, tuple[Key, ActionSchema, tuple[str, ...]] | None]


def _steps_to(parent: Parents, key: Key) -> list[tuple[ActionSchema, tuple[str, ...]]]:
    """The rows and arguments from the start to `key`, read back through `parent`."""
    steps = []
    node: Key | None = key
    while node is not None and (link := parent[node]) is not None:
        node, row, args = link
        steps.append((row, args))
    return list(reversed(steps))


def _plan_to(parent: Parents, key: Key) -> list[AnyAction]:
    """The actions from the start to `key`, read back through `parent`."""
    return [row.action(args) for row, args in _steps_to(parent, key)]


def without_detours(state: WorldState, goal: Goal,
                    steps: list[tuple[ActionSchema, tuple[str, ...]]],
                    budget: SearchBudget) -> list[AnyAction]:
    """The plan with every action dropped whose removal leaves each remaining action
    accepted and the goal reached (greedy action elimination, first to last, until none
    can go): a greedy search's detour (a pepper set on the fridge before it goes into a
    box in it) costs its length nothing. Quadratic in the plan's length, a replay per
    try; the budget is checked between tries, and a spent one keeps the plan as far as
    it was shortened."""
    def reaches(trial: list[tuple[ActionSchema, tuple[str, ...]]]) -> bool:
        world = state.copy()
        for row, args in trial:
            if not row.accepted(world, *args):
                return False
            row.apply(world, *args)
        return check_goal(world, goal).satisfied

    dropped = True
    try:
        while dropped:
            dropped = False
            i = 0
            while i < len(steps):
                budget.check()
                trial = steps[:i] + steps[i + 1:]
                if reaches(trial):
                    steps, dropped = trial, True
                else:
                    i += 1
    except SearchBudgetSpent:
        pass  # the plan as shortened so far: still valid, the goal still reached
    return [row.action(args) for row, args in steps]


def _greedy(problem: TableProblem, state: WorldState, goal: Goal, budget: SearchBudget
            ) -> tuple[bool, list[AnyAction]]:
    """Greedy best-first search with helpful actions: two queues, both ordered by the
    guide (fewest requirements left, shallower on ties), one holding every successor,
    the other only those reached by a helpful action (one that changes a thing the
    requirements name: `TableProblem.helpful`); they are popped in turn, so a plateau
    where the guide does not move (emptying a container before it moves) is crossed
    by the actions that matter first. Evaluation is deferred for the others: a
    successor by an action that is not helpful is queued under its parent's guide and
    evaluated only when popped (with hundreds of moves per state, evaluating each one
    cost nearly all the time, so long plans ran out of budget). A plan soonest, not
    proven optimal."""
    counter = itertools.count()
    start_key = problem.key(state)
    queues: tuple[list[tuple[int, int, int, Key]], ...] = (
        [(problem.h(state), 0, next(counter), start_key)], [])
    parent: Parents = {start_key: None}
    expanded: set[Key] = set()
    pops = 0
    while queues[0] or queues[1]:
        pops += 1
        turn = 1 if queues[1] and (pops % HELPFUL_SHARE or not queues[0]) else 0
        _, g, _, key = heapq.heappop(queues[turn])
        if key in expanded:
            continue
        expanded.add(key)
        current = problem.world(key)
        own = problem._bounds.get(key)
        if own is None:
            own = problem._bounds[key] = problem.h(current)
        if own == 0 and check_goal(current, goal).satisfied:
            return True, without_detours(state, goal, _steps_to(parent, key), budget)
        budget.expansions += 1
        budget.check()
        is_helpful = _helpful_test(problem.helpful(current))
        for row, args, nkey, nh in problem.successors(current, budget, is_helpful):
            if nkey in parent:
                continue
            parent[nkey] = (key, row, args)
            entry = (own if nh < 0 else nh, g + 1, next(counter), nkey)
            heapq.heappush(queues[0], entry)
            if nh >= 0 and is_helpful(row, args):
                heapq.heappush(queues[1], entry)
    return False, []


def table_astar(state: WorldState, goal: Goal, budget: SearchBudget, *, weight: float = 1.0,
                proof: dict[str, int] | None = None, bound: float = math.inf
                ) -> tuple[bool, list[AnyAction]]:
    """(found, plan): an optimal plan over the table's actions, every action one step.

    With `weight` > 1, weighted A* (f = g + weight * h, h counting every distinct
    requirement of the formula rather than a bound): a plan sooner, not proven optimal;
    with `weight` infinite, greedy best-first search (the node with the fewest
    requirements left first, shallower on ties): a plan soonest, often longer.
    `bound`: only plans shorter than it are sought (a node whose g + h reaches it is
    dropped; h is then the admissible bound, weight 1).
    `proof["floor"]` is raised, for weight 1, to the smallest f still open (every plan
    needs at least that many actions), so a search the budget stops keeps its bound."""
    problem = TableProblem(state, goal, additive=weight > 1.0)
    greedy = math.isinf(weight)
    if greedy:
        return _greedy(problem, state, goal, budget)
    counter = itertools.count()
    start_key = problem.key(state)
    start_h = problem.h(state)
    frontier: list[tuple[float, int, int, Key]] = [(weight * start_h, 0, next(counter),
                                                    start_key)]
    parent: Parents = {start_key: None}
    best_g = {start_key: 0}
    if proof is not None:
        proof["floor"] = max(proof.get("floor", 0), start_h)
    while frontier:
        f, neg_g, _, key = heapq.heappop(frontier)
        g = -neg_g
        if g > best_g.get(key, g):
            continue
        if proof is not None and weight == 1.0:
            proof["floor"] = max(proof["floor"], int(f))
        current = problem.world(key)
        if problem.h(current) == 0 and check_goal(current, goal).satisfied:
            return True, _plan_to(parent, key)
        budget.expansions += 1
        budget.check()
        for row, args, nkey, nh in problem.successors(current, budget):
            ng = g + 1
            if ng < best_g.get(nkey, ng + 1):
                if ng + nh >= bound:
                    continue  # cannot beat the plan already found
                best_g[nkey] = ng
                parent[nkey] = (key, row, args)
                # Ties broken towards deeper nodes: fewer expansions, still optimal.
                heapq.heappush(frontier, (ng + weight * nh, -ng, next(counter), nkey))
    return False, []
