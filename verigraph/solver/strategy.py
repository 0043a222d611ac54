"""A polynomial blocks-world strategy generalised to scene graphs: a plan fast, at most 2x.

Repeat until the goal graph holds:

1. constructive move: a clear object whose goal support is ready (fixed, or itself in
   place for good) and has room goes straight to its goal place;
2. otherwise clear the way: a clear object that must move anyway (misplaced or above a
   misplaced one), or one that fills a goal target's capacity, goes to a fixed surface
   (or container) with room.

In blocks world every object then moves at most twice, so the plan is at most twice the
number of objects that must move, a proven lower bound: "length L, optimal is at least B".
Capacities are respected on every move. When neither move exists (e.g. no fixed place
has room) the strategy gives up and the caller falls back to search.
"""

from __future__ import annotations

from verigraph.solver.budget import SearchBudget
from verigraph.solver.encoding import Move, SearchProblem, needs_to_move


def _parking(problem: SearchProblem, load: list[int], i: int, current: int
             ) -> tuple[int, int] | None:
    """A fixed object with room for object i (not where it is), most free room first."""
    best: tuple[float, int, int] | None = None
    for j in problem.fixed_ids:
        if j == current >> 1:
            continue
        room = problem.capacity[j] - load[j]
        if room <= 0:
            continue
        for r in problem.relations:
            if problem.accepts(j, r) and (best is None or room > best[0]):
                best = (room, j, r)
                break
    return None if best is None else (best[1], best[2])


def greedy_plan(problem: SearchProblem, wanted: dict[int, int], budget: SearchBudget
                ) -> list[Move] | None:
    """Moves that reach every wanted support, or None when the strategy is stuck.

    Only the moved object's "must move" flag can change after a move (it was clear, and
    it lands on a fixed place or a ready target), so the flags are computed once: the
    whole strategy is O(n^2) for n objects.
    """
    codes = list(problem.start)
    load = problem.loads(codes)
    needs = needs_to_move(problem, wanted, codes)
    pending = {k for k, w in wanted.items() if codes[k] != w}
    moves: list[Move] = []
    limit = 2 * len(codes) + 2 * len(wanted) + 4
    slot = problem.slot
    for _ in range(limit):
        if not pending:
            return moves
        budget.check()
        chosen: tuple[int, int, int] | None = None
        for k in pending:
            i = problem.movable[k]
            t, r = wanted[k] >> 1, wanted[k] & 1
            kt = slot.get(t)
            ready = kt is None or not needs[kt]
            if not load[i] and ready and load[t] < problem.capacity[t]:
                chosen = (k, t, r)
                break
        if chosen is None:
            full_targets = {wanted[k] >> 1 for k in pending
                            if load[wanted[k] >> 1] >= problem.capacity[wanted[k] >> 1]}
            for k, code in enumerate(codes):
                i = problem.movable[k]
                on_fixed = (code >> 1) in problem.fixed_ids
                blocks = (code >> 1) in full_targets and k not in wanted
                if load[i] or (on_fixed and not blocks) or not (needs[k] or blocks):
                    continue
                place = _parking(problem, load, i, code)
                if place is not None:
                    chosen = (k, place[0], place[1])
                    break
        if chosen is None:
            return None
        k, t, r = chosen
        load[codes[k] >> 1] -= 1
        load[t] += 1
        codes[k] = t * 2 + r
        moves.append((problem.movable[k], r, t))
        needs[k] = k in wanted and codes[k] != wanted[k]
        if needs[k]:
            pending.add(k)  # a correctly placed object cleared away must come back
        else:
            pending.discard(k)
    return None
