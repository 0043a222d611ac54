"""Reference solver: an optimal (fewest moves) plan by A* over graph edits.

States are tuples of each movable object's support code (`target_index * 2 + relation`),
so expanding a node is a few integer loops. The heuristic counts objects that must move
at least once, which never overestimates:

* goal graph: an object is misplaced when its support differs from the goal or its goal
  support is itself misplaced (the classic blocks-world bound);
* `single_stack`: every object outside the deepest chain standing on a fixed object.

Tangram goals are solved by breadth-first search over `align` actions.
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Callable

from pydantic import BaseModel, Field

from verigraph.actions.model import AlignAction, AnyAction, MoveAction
from verigraph.actions.validator import apply_action, validate_action
from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import check_well_formed

RELATIONS = ("on", "in")
DEFAULT_MAX_EXPANSIONS = 200_000


class SolveResult(BaseModel):
    """A plan, or why there is none."""

    reachable: bool | None = Field(description="None when the search budget ran out first")
    plan: list[AnyAction] = Field(default_factory=list)
    reason: str | None = Field(default=None, description="why the goal cannot be reached")
    expanded: int = Field(default=0, description="search nodes expanded")
    optimal: bool = Field(default=False, description="the plan has the fewest possible moves")

    def text(self) -> str:
        if self.reachable:
            lines = [a.text() for a in self.plan] + ["done"]
            return "\n".join(lines)
        return f"# no plan: {self.reason}"


class _Problem:
    """Integer encoding of a tabletop scene for fast search."""

    def __init__(self, state: WorldState) -> None:
        self.ids = list(state.objects)
        self.index = {o: i for i, o in enumerate(self.ids)}
        props = [state.objects[o].props for o in self.ids]
        self.movable = [i for i, p in enumerate(props) if p.movable]
        self.surface = [p.surface for p in props]
        self.container = [p.container for p in props]
        self.capacity = [math.inf if p.capacity is None else p.capacity for p in props]
        allowed = set(state.dictionary.relations)
        self.relations = [r for r in (0, 1) if RELATIONS[r] in allowed]
        # Supports of fixed objects never change, but they count against capacity.
        self.fixed_load = [0] * len(self.ids)
        for obj, (_, target) in state.support.items():
            if not state.objects[obj].props.movable:
                self.fixed_load[self.index[target]] += 1
        self.start = self.encode(state)
        self.fixed_ids = set(range(len(self.ids))) - set(self.movable)

    def encode(self, state: WorldState) -> tuple[int, ...]:
        codes = []
        for i in self.movable:
            rel, target = state.support[self.ids[i]]
            codes.append(self.index[target] * 2 + RELATIONS.index(rel))
        return tuple(codes)

    def loads(self, codes: tuple[int, ...]) -> list[int]:
        load = list(self.fixed_load)
        for c in codes:
            load[c >> 1] += 1
        return load

    def successors(self, codes: tuple[int, ...]
                   ) -> list[tuple[tuple[int, ...], tuple[int, int, int]]]:
        load = self.loads(codes)
        out = []
        n = len(self.ids)
        for k, i in enumerate(self.movable):
            if load[i]:
                continue  # something is on or in i
            current = codes[k]
            for j in range(n):
                if j == i:
                    continue
                for r in self.relations:
                    if (r == 0 and not self.surface[j]) or (r == 1 and not self.container[j]):
                        continue
                    code = j * 2 + r
                    if code == current:
                        continue
                    room = load[j] - (1 if current >> 1 == j else 0)
                    if room >= self.capacity[j]:
                        continue
                    new = codes[:k] + (code,) + codes[k + 1:]
                    out.append((new, (i, r, j)))
        return out

    def action(self, move: tuple[int, int, int]) -> MoveAction:
        i, r, j = move
        return MoveAction(object=self.ids[i], relation=RELATIONS[r], target=self.ids[j])


def _graph_goal(problem: _Problem, goal_graph: SceneGraph
                ) -> tuple[dict[int, int], Callable[[tuple[int, ...]], int]]:
    """Goal support codes per movable slot and the misplaced-objects heuristic."""
    slot = {i: k for k, i in enumerate(problem.movable)}
    wanted: dict[int, int] = {}
    for e in goal_graph.edges:
        if e.relation in RELATIONS and e.source in problem.index:
            i = problem.index[e.source]
            if i in slot:
                wanted[slot[i]] = problem.index[e.target] * 2 + RELATIONS.index(e.relation)

    def h(codes: tuple[int, ...]) -> int:
        memo: dict[int, bool] = {}

        def misplaced(k: int) -> bool:
            if k in memo:
                return memo[k]
            memo[k] = False  # cycle guard; goals are acyclic
            bad = codes[k] != wanted[k]
            if not bad:
                below = codes[k] >> 1
                kb = slot.get(below)
                bad = kb is not None and kb in wanted and misplaced(kb)
            memo[k] = bad
            return bad

        return sum(1 for k in wanted if misplaced(k))

    return wanted, h


def _stack_heuristic(problem: _Problem) -> Callable[[tuple[int, ...]], int]:
    def h(codes: tuple[int, ...]) -> int:
        children: dict[int, list[int]] = {}
        for k, c in enumerate(codes):
            children.setdefault(c >> 1, []).append(problem.movable[k])
        best = 0
        stack = [(i, 1) for base in problem.fixed_ids for i in children.get(base, [])]
        while stack:
            i, depth = stack.pop()
            best = max(best, depth)
            stack.extend((c, depth + 1) for c in children.get(i, []))
        return len(codes) - best

    return h


def _static_reason(state: WorldState, goal: Goal) -> str | None:
    """Reasons a goal graph can never hold, found without search."""
    if goal.graph is None:
        return None
    g = goal.graph
    missing = [n for n in g.node_ids() if n not in state.objects]
    if missing:
        return f"the goal names objects that are not in the scene: {', '.join(missing)}"
    if not goal.partial:
        extra = [o for o in state.objects if g.node(o) is None]
        if extra:
            return f"the goal lacks objects the scene has (moves cannot remove them): " \
                   f"{', '.join(extra)}"
    problems = check_well_formed(g, state.dictionary, partial=True)
    if problems:
        return f"the goal itself breaks a rule: {problems[0].message}"
    for e in g.edges:
        if e.relation in RELATIONS and not state.objects[e.source].props.movable \
                and state.support.get(e.source) != (e.relation, e.target):
            return f"{e.source} is fixed, so '{e.sentence()}' can never be made true"
    if not goal.partial:
        for o in state.objects.values():
            if not o.props.movable and o.id in state.support and not any(
                    e.source == o.id for e in g.edges):
                return f"{o.id} is fixed on {state.support[o.id][1]}; the goal removes that edge"
    return None


def solve(scene: SceneGraph | WorldState, goal: Goal | SceneGraph | str, *,
          max_expansions: int = DEFAULT_MAX_EXPANSIONS) -> SolveResult:
    """Fewest-moves plan from `scene` to `goal`, or a clear reason why there is none.

    >>> from verigraph.graph.builtin_scenes import cup_on_book, cup_on_book_goal
    >>> [a.text() for a in solve(cup_on_book(), cup_on_book_goal()).plan]
    ['move(cup, on, desk)', 'move(book, on, shelf)']
    """
    state = scene.copy() if isinstance(scene, WorldState) else WorldState.from_graph(scene)
    goal_model = Goal.parse(goal)
    if check_goal(state, goal_model).satisfied:
        return SolveResult(reachable=True, plan=[], optimal=True)
    reason = _static_reason(state, goal_model)
    if reason:
        return SolveResult(reachable=False, reason=reason)
    if state.contacts or any(o.props.sides for o in state.objects.values()):
        return _solve_tangram(state, goal_model, max_expansions)
    problem = _Problem(state)
    if goal_model.graph is not None:
        wanted, h_graph = _graph_goal(problem, goal_model.graph)
    else:
        wanted, h_graph = {}, (lambda codes: 0)
    h_stack = _stack_heuristic(problem) if goal_model.predicate == "single_stack" else None

    def h(codes: tuple[int, ...]) -> int:
        value = h_graph(codes)
        return max(value, h_stack(codes)) if h_stack else value

    def is_goal(codes: tuple[int, ...]) -> bool:
        if wanted and any(codes[k] != c for k, c in wanted.items()):
            return False
        return _decoded_goal_check(problem, state, codes, goal_model)

    return _astar(problem, h, is_goal, max_expansions)


def _decoded_goal_check(problem: _Problem, state: WorldState, codes: tuple[int, ...],
                        goal: Goal) -> bool:
    trial = state.copy()
    for k, i in enumerate(problem.movable):
        code = codes[k]
        trial.set_support(problem.ids[i], RELATIONS[code & 1], problem.ids[code >> 1])
    return check_goal(trial, goal).satisfied


def _astar(problem: _Problem, h: Callable[[tuple[int, ...]], int],
           is_goal: Callable[[tuple[int, ...]], bool], max_expansions: int) -> SolveResult:
    start = problem.start
    counter = itertools.count()
    frontier: list[tuple[int, int, int, tuple[int, ...]]] = [(h(start), 0, next(counter), start)]
    parent: dict[tuple[int, ...], tuple[tuple[int, ...], tuple[int, int, int]] | None] = {
        start: None}
    best_g = {start: 0}
    expanded = 0
    while frontier:
        _, neg_g, _, codes = heapq.heappop(frontier)
        g = -neg_g
        if g > best_g.get(codes, math.inf):
            continue
        if is_goal(codes):
            moves = []
            node: tuple[int, ...] | None = codes
            while node is not None and parent[node] is not None:
                prev, move = parent[node]  # type: ignore[misc]
                moves.append(problem.action(move))
                node = prev
            return SolveResult(reachable=True, plan=list(reversed(moves)), expanded=expanded,
                               optimal=True)
        expanded += 1
        if expanded > max_expansions:
            return SolveResult(reachable=None, expanded=expanded,
                               reason=f"search budget of {max_expansions} expansions ran out "
                                      "before a plan was found")
        for nxt, move in problem.successors(codes):
            ng = g + 1
            if ng < best_g.get(nxt, math.inf):
                best_g[nxt] = ng
                parent[nxt] = (codes, move)
                # Ties broken towards deeper nodes: fewer expansions, still optimal.
                heapq.heappush(frontier, (ng + h(nxt), -ng, next(counter), nxt))
    return SolveResult(reachable=False, expanded=expanded,
                       reason="no sequence of valid moves reaches the goal "
                              f"(all {expanded} reachable states searched)")


def _solve_tangram(state: WorldState, goal: Goal, max_expansions: int,
                   max_depth: int = 2) -> SolveResult:
    """Breadth-first search over symbolic align actions (depth-limited)."""
    pieces = [o.id for o in state.objects.values() if o.props.sides and o.props.movable]
    layer: list[tuple[WorldState, list[AnyAction]]] = [(state, [])]
    expanded = 0
    for _ in range(max_depth):
        next_layer = []
        for current, plan in layer:
            for p, q in itertools.permutations(pieces, 2):
                for s in range(current.side_count(p) or 0):
                    for t in range(current.side_count(q) or 0):
                        action = AlignAction(object=p, side=s, target=q, target_side=t)
                        if validate_action(current, action) is not None:
                            continue
                        expanded += 1
                        trial = current.copy()
                        apply_action(trial, action)
                        if check_goal(trial, goal).satisfied:
                            return SolveResult(reachable=True, plan=[*plan, action],
                                               expanded=expanded, optimal=True)
                        next_layer.append((trial, [*plan, action]))
                        if expanded > max_expansions:
                            return SolveResult(reachable=None, expanded=expanded,
                                               reason="search budget ran out")
        layer = next_layer
    return SolveResult(reachable=None, expanded=expanded,
                       reason=f"no sequence of at most {max_depth} align actions reaches the "
                              "goal")
