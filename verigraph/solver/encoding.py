"""Integer encoding of a tabletop scene for fast search, and the admissible heuristics.

It is the move row of the action table (`verigraph.actions.schemas`) compiled for
on/in worlds without openable containers: a move is legal when the object is movable
and clear, the target `fits` the relation and has room (what the row's preconditions
say there); `table_search` searches worlds this cannot speak for.

States are tuples of each movable object's support code (`target_index * 2 + relation`),
so expanding a node is a few integer loops. Successors are generated lazily and the
budget is checked inside the loop: one expansion of a 1,000-object scene has a million
successors, so a per-expansion check alone would come too late.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator

from verigraph.actions.model import MoveAction
from verigraph.actions.schemas import fits
from verigraph.graph.dictionary import SUPPORT_RELATIONS
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.solver.budget import SearchBudget

RELATIONS = SUPPORT_RELATIONS  # a move's relation is coded as its index here
Codes = tuple[int, ...]
Move = tuple[int, int, int]  # (object index, relation, target index)


class SearchProblem:
    """A tabletop scene as integers: movable objects, kinds, capacities, fixed loads."""

    def __init__(self, state: WorldState) -> None:
        self.ids = list(state.objects)
        self.index = {o: i for i, o in enumerate(self.ids)}
        props = [state.objects[o].props for o in self.ids]
        self.movable = [i for i, p in enumerate(props) if p.movable]
        self.slot = {i: k for k, i in enumerate(self.movable)}
        # Which relation each object takes as a target: the move row's `fits`.
        self.takes = [tuple(fits(p, relation) for relation in RELATIONS) for p in props]
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

    def encode(self, state: WorldState) -> Codes:
        codes = []
        for i in self.movable:
            rel, target = state.support[self.ids[i]]
            codes.append(self.index[target] * 2 + RELATIONS.index(rel))
        return tuple(codes)

    def loads(self, codes: Codes | list[int]) -> list[int]:
        load = list(self.fixed_load)
        for c in codes:
            load[c >> 1] += 1
        return load

    def accepts(self, j: int, r: int) -> bool:
        return self.takes[j][r]

    def successors(self, codes: Codes, budget: SearchBudget) -> Iterator[tuple[Codes, Move]]:
        load = self.loads(codes)
        n = len(self.ids)
        every = max(16, 200_000 // max(1, len(codes)))
        made = 0
        for k, i in enumerate(self.movable):
            if load[i]:
                continue  # something is on or in i
            current = codes[k]
            for j in range(n):
                if j == i:
                    continue
                for r in self.relations:
                    if not self.accepts(j, r):
                        continue
                    code = j * 2 + r
                    if code == current:
                        continue
                    room = load[j] - (1 if current >> 1 == j else 0)
                    if room >= self.capacity[j]:
                        continue
                    made += 1
                    if made % every == 0:
                        budget.check(memory=True)
                    yield codes[:k] + (code,) + codes[k + 1:], (i, r, j)

    def action(self, move: Move) -> MoveAction:
        i, r, j = move
        return MoveAction(object=self.ids[i], relation=RELATIONS[r], target=self.ids[j])


def goal_codes(problem: SearchProblem, goal_graph: SceneGraph) -> dict[int, int]:
    """Wanted support code per movable slot, from the goal graph's on/in edges."""
    wanted: dict[int, int] = {}
    for e in goal_graph.edges:
        if e.relation in RELATIONS and e.source in problem.index:
            k = problem.slot.get(problem.index[e.source])
            if k is not None:
                wanted[k] = problem.index[e.target] * 2 + RELATIONS.index(e.relation)
    return wanted


def needs_to_move(problem: SearchProblem, wanted: dict[int, int], codes: Codes | list[int],
                  *, goal_only: bool = False) -> list[bool]:
    """Per slot: the object must move at least once (misplaced, or above one that must).

    With `goal_only`, only objects with a goal position count (the classic admissible
    blocks-world bound). Iterative: towers of any height, no recursion limit.
    """
    memo: list[bool | None] = [None] * len(codes)
    slot = problem.slot
    for start in range(len(codes)):
        path: list[int] = []
        cur: int | None = start
        result = False
        while cur is not None:
            known = memo[cur]
            if known is not None:
                result = known
                break
            path.append(cur)
            w = wanted.get(cur)
            if w is not None and codes[cur] != w:
                result = True
                break
            if len(path) > len(codes):
                break  # cycle guard; encoded states are acyclic
            cur = slot.get(codes[cur] >> 1)
        for k in path:
            memo[k] = result
    return [bool(m) and (not goal_only or k in wanted) for k, m in enumerate(memo)]


def misplaced_heuristic(problem: SearchProblem, wanted: dict[int, int]) -> Callable[[Codes], int]:
    """Objects with a goal position that must move at least once: admissible, consistent."""
    def h(codes: Codes) -> int:
        return sum(needs_to_move(problem, wanted, codes, goal_only=True))
    return h


def stack_heuristic(problem: SearchProblem) -> Callable[[Codes], int]:
    """single_stack: every object outside the deepest chain standing on a fixed object."""
    def h(codes: Codes) -> int:
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
