"""The `greedy` planner: goal-directed, no lookahead, recovers only through feedback.

A baseline that is not the solver, built to measure what the verifier's feedback is
worth. Each call it moves every misplaced object straight to its goal place (tangram:
aligns each missing goal contact), in a fresh seeded random order, and never simulates
its own plan, so it does not know that a block must be cleared first or that a target
is full. What it learns of a refusal depends on the loop's feedback mode:

- `full`: the verifier's violation (constraint, blocking objects, suggestion). It puts
  the suggested fix (`move(cup, on, desk)` in the suggestion; else the first blocking
  object onto a fixed surface) before the refused action and tries again.
- `constraint`: only "[object_not_clear] an action was refused". It finds the refused
  action in its own previous proposal (the first one the history does not show),
  looks up in the graph what is on the object (or the target), and moves that to a
  fixed surface it picks at random: no suggestion tells it where there is room.
- `none`: nothing; it just asks itself again (with a new random order).

It reads the goal its prompt shows; with only an instruction it uses the rule-based
translator. Not privileged: the episode never hands it `request.privileged_goal`.
"""

from __future__ import annotations

import random
import re

from verigraph.actions.model import AlignAction, AnyAction, DoneAction, MoveAction
from verigraph.graph.goal import Goal, check_goal, towers
from verigraph.graph.state import WorldState
from verigraph.planning.goal_reader import GoalReader
from verigraph.planning.models import PlannerReply, PlannerRequest
from verigraph.planning.oracle import chunk
from verigraph.planning.parsing import refused_action

SUGGESTED = re.compile(r"move\((?P<o>[\w-]+), (?P<r>on|in), (?P<t>[\w-]+)\)")
CONSTRAINT_ONLY = re.compile(r"^\[(?P<c>[a-z_]+)\] an action was refused")
CLEARING = ("object_not_clear", "target_full", "would_create_cycle")


def goal_moves(state: WorldState, goal: Goal) -> list[AnyAction]:
    """One action per misplaced object (or missing tangram contact), straight to the goal."""
    out: list[AnyAction] = []
    if goal.graph is not None:
        aligned: set[str] = set()
        for edge in goal.graph.edges:
            if edge.relation == "touches":
                a, sa, b, sb = edge.source, edge.source_side or 0, edge.target, \
                    edge.target_side or 0
                if (b, sb) in state.contacts.get((a, sa), []):
                    continue
                # move the piece that is out of the figure (fewer contacts), once per call:
                # a second align of the same piece would undo the first
                if _contacts(state, b) < _contacts(state, a):
                    a, sa, b, sb = b, sb, a, sa
                if a not in aligned:
                    aligned.add(a)
                    out.append(AlignAction(object=a, side=sa, target=b, target_side=sb))
            elif state.support.get(edge.source) != (edge.relation, edge.target) \
                    and edge.source in state.objects:
                out.append(MoveAction(object=edge.source, relation=edge.relation,
                                      target=edge.target))
    elif goal.predicate == "single_stack":
        tallest = max(towers(state), key=len, default=[])
        if tallest:
            for obj in sorted(o.id for o in state.objects.values() if o.props.movable):
                if obj not in tallest:
                    out.append(MoveAction(object=obj, relation="on", target=tallest[-1]))
                    break
    return out


class GreedyPlanner:
    """Straight-to-goal moves in a seeded random order; repairs from feedback only."""

    name = "greedy"

    def __init__(self, seed: int = 0) -> None:
        self.rng = random.Random(seed)
        self.reader = GoalReader()
        self.last: list[AnyAction] = []
        self.history_before = 0

    def propose(self, request: PlannerRequest) -> PlannerReply:
        executed = len(request.history) - self.history_before
        self.history_before = len(request.history)
        goal, note = self.reader.read(request)
        if goal is None:
            return PlannerReply(actions=[DoneAction()], note=note)
        state = WorldState.from_graph(request.graph)
        if check_goal(state, goal).satisfied:
            return PlannerReply(actions=[DoneAction()], note=note)
        moves = goal_moves(state, goal)
        self.rng.shuffle(moves)
        # after a refusal it fixes that first and tries the refused action again
        repair = self._repair(request, state, executed)
        actions = repair or moves
        if not actions:
            return PlannerReply(actions=[DoneAction()], note=note)
        # it believes its moves finish the job, but says done only once the goal holds
        # (direct mode: the whole plan, then done)
        proposal = chunk(actions, None) if request.k is None else actions[:request.k]
        self.last = [a for a in proposal if not isinstance(a, DoneAction)]
        return PlannerReply(actions=proposal, note=note)

    def close(self) -> None:
        return None

    # -- recovery from feedback ----------------------------------------------------------
    def _repair(self, request: PlannerRequest, state: WorldState, executed: int
                ) -> list[AnyAction]:
        feedback = request.feedback
        if feedback is None or feedback.kind != "violation":
            return []
        if feedback.violation is not None:  # full feedback
            v = feedback.violation
            refused = refused_action(v.action)
            if v.constraint not in CLEARING:
                return []
            fix = SUGGESTED.search(v.suggestion)
            if fix is not None:
                first: AnyAction = MoveAction(object=fix["o"], relation=fix["r"],
                                              target=fix["t"])
            elif v.blocking:
                first = self._away(state, v.blocking[0])
            else:
                return []
            return [first, *([refused] if refused is not None else [])]
        m = CONSTRAINT_ONLY.match(feedback.text)
        if m is None or m["c"] not in CLEARING:
            return []
        if not 0 <= executed < len(self.last):
            return []
        refused = self.last[executed]
        if not isinstance(refused, MoveAction):
            return []
        if m["c"] == "would_create_cycle":
            culprit: str | None = refused.target  # it rests on the object: move it off
        else:
            loaded = refused.object if m["c"] == "object_not_clear" else refused.target
            culprit = next(iter(state.carried.get(loaded, {})), None)
        if culprit is None:
            return []
        return [self._away(state, culprit), refused]

    def _away(self, state: WorldState, obj: str) -> MoveAction:
        """`obj` onto a fixed surface picked at random (not checked for room)."""
        surfaces = [s for s in state.fixed_surfaces if s != obj] or ["table"]
        return MoveAction(object=obj, relation="on", target=self.rng.choice(sorted(surfaces)))


def _contacts(state: WorldState, piece: str) -> int:
    return sum(1 for side in state.contacts if side[0] == piece)


