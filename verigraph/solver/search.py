"""Reference solver: optimal A* over graph edits, an anytime mode, and a hard budget.

Every solve runs under a `SearchBudget` (wall clock, memory growth, expansions); running out
is an answer (`status="budget_exhausted"` with the numbers), never a crash. Optimal
mode is A* with the misplaced-objects bound (see `encoding`); a household world (openable
containers, states in the goal, `under`/`nextto`) is searched over the action table
instead (`table_search`, optimal, every action one step). Anytime mode first takes
the polynomial strategy's plan (`strategy`), then refines it with weighted A* (w = 2,
then 1.5) and finally A* (w = 1), each pruned by the best length so far; the result
carries the lower bound it proved: the heuristic at the start, raised to the smallest
f-value A* left open when it stopped. A search the budget stops before any plan is found
still returns that bound (`lower_bound`: every plan needs at least that many moves).
Tangram goals are solved by breadth-first search: goal-directed first (`solver.tangram`),
then over every align to depth 2. Before any search, a goal formula that no state
satisfies at all (`satisfiable`) is said unreachable, with the parts that cannot hold.
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Callable

from verigraph.actions.model import AlignAction, AnyAction
from verigraph.actions.validator import apply_action, validate_action
from verigraph.graph.formula import parse_formula
from verigraph.graph.formula_eval import Facts, check_names, facts_of, holds
from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.solver.budget import (
    DEFAULT_MAX_EXPANSIONS,
    DEFAULT_MEMORY_LIMIT_MB,
    DEFAULT_TIME_LIMIT_S,
    SearchBudget,
    SearchBudgetSpent,
)
from verigraph.solver.encoding import (
    RELATIONS,
    Codes,
    Move,
    SearchProblem,
    goal_codes,
    misplaced_heuristic,
    stack_heuristic,
)
from verigraph.solver.formula_bound import formula_bound, formula_needs_table
from verigraph.solver.result import SolveResult, static_reason
from verigraph.solver.satisfiable import unsatisfiable_reason
from verigraph.solver.table_search import needs_table_search, table_astar
from verigraph.solver.tangram import tangram_plan

__all__ = ["DEFAULT_MAX_EXPANSIONS", "SolveResult", "solve"]


def solve(scene: SceneGraph | WorldState, goal: Goal | SceneGraph | str, *,
          max_expansions: int = DEFAULT_MAX_EXPANSIONS,
          time_limit: float = DEFAULT_TIME_LIMIT_S,
          memory_limit_mb: float = DEFAULT_MEMORY_LIMIT_MB,
          anytime: bool = False) -> SolveResult:
    """A plan from `scene` to `goal` within the budget, or a clear reason why there is none.

    >>> from verigraph.graph.builtin_scenes import cup_on_book, cup_on_book_goal
    >>> [a.text() for a in solve(cup_on_book(), cup_on_book_goal()).plan]
    ['move(cup, on, desk)', 'move(book, on, shelf)']
    """
    budget = SearchBudget(time_limit_s=time_limit, memory_limit_mb=memory_limit_mb,
                    max_expansions=max_expansions)
    try:
        return _finish(_solve(scene, goal, budget, anytime), budget)
    except SearchBudgetSpent as exc:
        return _finish(SolveResult(reachable=None, status="budget_exhausted", reason=str(exc),
                                   expanded=budget.expansions), budget)
    except MemoryError:
        return _finish(SolveResult(reachable=None, status="budget_exhausted",
                                   expanded=budget.expansions,
                                   reason=budget.reason("out of memory")), budget)


def _finish(result: SolveResult, budget: SearchBudget) -> SolveResult:
    result.elapsed_s = round(budget.elapsed(), 3)
    result.memory_mb = round(max(budget.peak_mb, budget.used_mb()), 1)
    return result


def _solve(scene: SceneGraph | WorldState, goal: Goal | SceneGraph | str, budget: SearchBudget,
           anytime: bool) -> SolveResult:
    state = scene.copy() if isinstance(scene, WorldState) else WorldState.from_graph(scene)
    goal_model = Goal.parse(goal)
    if goal_model.formula is not None:  # ids and kinds the scene lacks: bad input, said so
        check_names(parse_formula(goal_model.formula), facts_of(state))
    if check_goal(state, goal_model).satisfied:
        return SolveResult(reachable=True, plan=[], optimal=True, lower_bound=0)
    reason = static_reason(state, goal_model)
    if reason:
        return SolveResult(reachable=False, status="unreachable", reason=reason)
    if state.contacts or any(o.props.sides for o in state.objects.values()):
        return _solve_tangram(state, goal_model, budget)
    if goal_model.formula is not None:  # a goal no state satisfies: said before search
        reason = unsatisfiable_reason(state, parse_formula(goal_model.formula), budget)
        if reason:
            return SolveResult(reachable=False, status="unreachable", reason=reason)
    if needs_table_search(state, goal_model) or formula_needs_table(goal_model) \
            or (anytime and goal_model.formula is not None):
        # anytime over a formula: the table's greedy best-first search, guided by every
        # requirement of the formula, finds a plan where the encoded weighted A* stalls
        return _solve_table(state, goal_model, budget, anytime)
    problem = SearchProblem(state)
    wanted = goal_codes(problem, goal_model.graph) if goal_model.graph is not None else {}
    h_graph = misplaced_heuristic(problem, wanted)
    h_stack = stack_heuristic(problem) if goal_model.predicate == "single_stack" else None
    formula = parse_formula(goal_model.formula) if goal_model.formula is not None else None
    facts_at = _facts_at(problem, state) if formula is not None else None
    rest = goal_model.model_copy(update={"formula": None})
    rest_checked = rest.graph is not None or rest.predicate is not None

    def h(codes: Codes) -> int:
        value = h_graph(codes) if wanted else 0
        if h_stack:
            value = max(value, h_stack(codes))
        if formula is not None and facts_at is not None:
            value = max(value, formula_bound(formula, facts_at(codes)))
        return value

    def is_goal(codes: Codes) -> bool:
        if wanted and any(codes[k] != c for k, c in wanted.items()):
            return False
        if formula is not None and facts_at is not None \
                and not holds(formula, facts_at(codes)):
            return False
        return not rest_checked or _decoded_goal_check(problem, state, codes, rest)

    if not anytime:
        proof = {"floor": h(problem.start)}
        try:
            found, plan = _astar(problem, h, is_goal, budget, weight=1.0, bound=math.inf,
                                 proof=proof)
        except SearchBudgetSpent as exc:  # no plan, but the bound A* proved holds
            return SolveResult(reachable=None, status="budget_exhausted", reason=str(exc),
                               expanded=budget.expansions, lower_bound=proof["floor"])
        return _searched(found, plan, budget, "moves")
    return _anytime(problem, wanted, h, is_goal, budget)


def _searched(found: bool, plan: list[AnyAction], budget: SearchBudget, what: str
              ) -> SolveResult:
    """A search that ran to its end: the optimal plan, or unreachable (every reachable
    state searched)."""
    if found:
        return SolveResult(reachable=True, plan=plan, expanded=budget.expansions,
                           optimal=True, lower_bound=len(plan))
    return SolveResult(reachable=False, status="unreachable", expanded=budget.expansions,
                       reason=f"no sequence of valid {what} reaches the goal "
                              f"(all {budget.expansions} reachable states searched)")


def _anytime(problem: SearchProblem, wanted: dict[int, int], h: Callable[[Codes], int],
             is_goal: Callable[[Codes], bool], budget: SearchBudget) -> SolveResult:
    from verigraph.solver.strategy import greedy_plan

    lower = h(problem.start)
    best: list[AnyAction] | None = None
    moves = greedy_plan(problem, wanted, budget) if wanted else None
    if moves is not None and is_goal(_replay(problem, moves)):
        best = [problem.action(m) for m in moves]
    first_plan_s = round(budget.elapsed(), 3) if best is not None else None
    proof = {"floor": lower}  # the f-floor of the w = 1 run, kept if the budget stops it
    try:
        for weight in (2.0, 1.5, 1.0):
            if best is not None and len(best) <= lower:
                break
            bound = math.inf if best is None else len(best)
            found, plan = _astar(problem, h, is_goal, budget, weight, bound,
                                    proof if weight == 1.0 else None)
            if found:
                best = plan
                first_plan_s = first_plan_s or round(budget.elapsed(), 3)
            if weight == 1.0:
                if best is None:
                    return SolveResult(reachable=False, status="unreachable",
                                       expanded=budget.expansions,
                                       reason="no sequence of valid moves reaches the goal")
                lower = len(best)  # A* finished: nothing shorter exists
    except SearchBudgetSpent as exc:
        lower = max(lower, proof["floor"])
        if best is None:
            return SolveResult(reachable=None, status="budget_exhausted", reason=str(exc),
                               expanded=budget.expansions, lower_bound=lower)
        return SolveResult(reachable=True, plan=best, expanded=budget.expansions,
                           optimal=len(best) <= lower, lower_bound=lower,
                           first_plan_s=first_plan_s, reason=f"refinement stopped: {exc}")
    assert best is not None
    return SolveResult(reachable=True, plan=best, expanded=budget.expansions,
                       optimal=len(best) <= lower, lower_bound=lower, first_plan_s=first_plan_s)


def _replay(problem: SearchProblem, moves: list[Move]) -> Codes:
    codes = list(problem.start)
    for i, r, j in moves:
        codes[problem.slot[i]] = j * 2 + r
    return tuple(codes)


def _facts_at(problem: SearchProblem, state: WorldState) -> Callable[[Codes], Facts]:
    """The facts of an encoded state for a goal formula: the start's objects, states and
    the edges of fixed objects, with each movable object where the codes put it."""
    base = facts_of(state)
    moving = {problem.ids[i] for i in problem.movable}
    kept = [edge for edge in base.edges if edge[1] not in moving]
    ids, movable = problem.ids, problem.movable

    def facts(codes: Codes) -> Facts:
        return base.with_edges([*kept, *((RELATIONS[c & 1], ids[movable[k]], ids[c >> 1])
                                         for k, c in enumerate(codes))])

    return facts


def _decoded_goal_check(problem: SearchProblem, state: WorldState, codes: Codes,
                        goal: Goal) -> bool:
    trial = state.copy()
    for k, i in enumerate(problem.movable):
        code = codes[k]
        trial.set_support(problem.ids[i], RELATIONS[code & 1], problem.ids[code >> 1])
    return check_goal(trial, goal).satisfied


def _astar(problem: SearchProblem, h: Callable[[Codes], int], is_goal: Callable[[Codes], bool],
           budget: SearchBudget, weight: float, bound: float,
           proof: dict[str, int] | None = None) -> tuple[bool, list[AnyAction]]:
    """(found, plan): a plan shorter than `bound`, if there is one.

    With `proof`, the largest f popped so far (the f-floor, a proven lower bound for
    w = 1) is written there as the search goes, so a budget stop still leaves it behind.
    """
    start = problem.start
    counter = itertools.count()
    frontier: list[tuple[float, int, int, Codes]] = [(weight * h(start), 0, next(counter),
                                                      start)]
    parent: dict[Codes, tuple[Codes, Move] | None] = {start: None}
    best_g = {start: 0}
    floor = 0
    while frontier:
        f, neg_g, _, codes = heapq.heappop(frontier)
        g = -neg_g
        if g > best_g.get(codes, math.inf):
            continue
        if f > floor:
            floor = int(f)
            if proof is not None:
                proof["floor"] = floor
        if is_goal(codes):
            moves = []
            node: Codes | None = codes
            while node is not None and parent[node] is not None:
                prev, move = parent[node]  # type: ignore[misc]
                moves.append(problem.action(move))
                node = prev
            return True, list(reversed(moves))
        budget.expansions += 1
        budget.check()
        for nxt, move in problem.successors(codes, budget):
            ng = g + 1
            if ng < best_g.get(nxt, math.inf):
                hn = h(nxt)
                if ng + hn >= bound:
                    continue  # cannot beat the plan we already have
                best_g[nxt] = ng
                parent[nxt] = (codes, move)
                # Ties broken towards deeper nodes: fewer expansions, still optimal.
                heapq.heappush(frontier, (ng + weight * hn, -ng, next(counter), nxt))
    return False, []


def _solve_table(state: WorldState, goal: Goal, budget: SearchBudget,
                 anytime: bool = False) -> SolveResult:
    """A household world: optimal A* over the action table; anytime: greedy best-first
    search first (a plan soonest, its detours dropped by `table_search.without_detours`,
    its length not proven optimal), then A* over what
    budget is left, pruned by that plan's length (a shorter plan found replaces it; A*
    that finishes proves the one kept optimal; its bound is kept if it stops)."""
    proof = {"floor": 0}
    first: list[AnyAction] | None = None
    try:
        if anytime:
            found, plan = table_astar(state, goal, budget, weight=math.inf)
            if not found:
                return _searched(found, plan, budget, "actions")
            first = plan
        found, plan = table_astar(state, goal, budget, proof=proof,
                                  bound=math.inf if first is None else len(first))
    except SearchBudgetSpent as exc:
        if first is not None:
            return SolveResult(reachable=True, plan=first, expanded=budget.expansions,
                               optimal=len(first) <= proof["floor"],
                               lower_bound=proof["floor"], reason=f"refinement stopped: {exc}")
        return SolveResult(reachable=None, status="budget_exhausted", reason=str(exc),
                           expanded=budget.expansions, lower_bound=proof["floor"])
    if first is not None and not found:  # nothing shorter than the first plan exists
        return SolveResult(reachable=True, plan=first, expanded=budget.expansions,
                           optimal=True, lower_bound=len(first))
    return _searched(found, plan, budget, "actions")


def _solve_tangram(state: WorldState, goal: Goal, budget: SearchBudget,
                   max_depth: int = 2) -> SolveResult:
    """Goal-directed breadth-first search first (`solver.tangram`: only aligns that make
    a missing goal contact, to any depth the budget allows); optimal when its plan is
    as long as the goal contacts missing (each align adds one). Otherwise breadth-first
    search over every align to depth 2, which also finds plans that first move a piece
    out of the way."""
    def step() -> None:
        budget.expansions += 1
        budget.check()

    bound = len(check_goal(state, goal).missing_edges)
    if goal.graph is not None:
        aligns = tangram_plan(state, goal, step=step)
        if aligns is not None:
            return SolveResult(reachable=True, plan=list(aligns), expanded=budget.expansions,
                               optimal=len(aligns) <= bound, lower_bound=bound or None)
    pieces = [o.id for o in state.objects.values() if o.props.sides and o.props.movable]
    layer: list[tuple[WorldState, list[AnyAction]]] = [(state, [])]
    for _ in range(max_depth):
        next_layer = []
        for current, plan in layer:
            for p, q in itertools.permutations(pieces, 2):
                for s in range(current.side_count(p) or 0):
                    for t in range(current.side_count(q) or 0):
                        action = AlignAction(object=p, side=s, target=q, target_side=t)
                        if validate_action(current, action) is not None:
                            continue
                        step()
                        trial = current.copy()
                        apply_action(trial, action)
                        if check_goal(trial, goal).satisfied:  # breadth first: shortest
                            return SolveResult(reachable=True, plan=[*plan, action],
                                               expanded=budget.expansions, optimal=True,
                                               lower_bound=len(plan) + 1)
                        next_layer.append((trial, [*plan, action]))
        layer = next_layer
    return SolveResult(reachable=None, status="budget_exhausted", expanded=budget.expansions,
                       reason=f"no goal-directed align plan, and no sequence of at most "
                              f"{max_depth} align actions, reaches the goal")
