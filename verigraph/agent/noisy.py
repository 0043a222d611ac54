"""The `noisy` planner: the oracle with seeded, injected mistakes of the kinds LLMs make.

It stands in for an imperfect LLM so the value of the verifier's feedback and of the
error threshold t can be measured offline and reproducibly. With probability `rate`
per planner call, one mistake is inserted at a random position of the proposal:

- `non_clear`: move an object that has something on or in it (object_not_clear);
- `full_target`: put an object on a target that has no room left (target_full;
  tangram: a side that already touches another piece, side_occupied);
- `hallucinated`: name an object that is not in the scene (unknown_object);
- `wrong_relation`: `in` on a non-container or `on` on a non-surface (tangram: a side
  index the piece does not have);
- `stop_early`: answer `done` before the goal holds.

A kind that is impossible in the current graph (nothing is stacked, say) falls back to
another enabled kind, so the configured rate is the rate of mistakes actually made.
The mistake is computed on the graph as it will be at its position in the proposal,
which is before one of the planned moves, so a mistake always costs something: without
feedback (direct mode) the plan fails; with it, an iteration.
"""

from __future__ import annotations

import random
from typing import Literal, get_args

from verigraph.actions.model import AlignAction, AnyAction, DoneAction, MoveAction
from verigraph.actions.validator import apply_action, validate_action
from verigraph.agent.models import PlannerReply, PlannerRequest
from verigraph.agent.oracle import chunk, reference_plan
from verigraph.graph.state import WorldState

MistakeKind = Literal["non_clear", "full_target", "hallucinated", "wrong_relation",
                      "stop_early"]
MISTAKE_KINDS: tuple[MistakeKind, ...] = get_args(MistakeKind)


class NoisyPlanner:
    """Oracle proposals with one injected mistake per call with probability `rate`."""

    def __init__(self, rate: float = 0.3, seed: int = 0,
                 kinds: tuple[MistakeKind, ...] = MISTAKE_KINDS) -> None:
        if not 0.0 <= rate <= 1.0:
            raise ValueError(f"noise rate must be between 0 and 1, got {rate}")
        unknown = [k for k in kinds if k not in MISTAKE_KINDS]
        if unknown or not kinds:
            raise ValueError(f"mistake kinds must be a non-empty subset of "
                             f"{', '.join(MISTAKE_KINDS)}; got {', '.join(kinds) or 'none'}")
        self.rate = rate
        self.kinds = tuple(kinds)
        self.rng = random.Random(seed)
        self.name = f"noisy({rate:.0%})"
        self.injected: list[MistakeKind] = []

    def propose(self, request: PlannerRequest) -> PlannerReply:
        plan, note = reference_plan(request)
        actions = chunk(plan, request.k)
        if self.rng.random() >= self.rate:
            return PlannerReply(actions=actions, note=note)
        state = WorldState.from_graph(request.graph)
        noisy, kind = self._inject(state, actions, request.k)
        if kind is None:
            return PlannerReply(actions=actions, note=note)
        self.injected.append(kind)
        return PlannerReply(actions=noisy, note=f"injected mistake: {kind}")

    def close(self) -> None:
        return None

    # -- injection ---------------------------------------------------------------------
    def _inject(self, state: WorldState, actions: list[AnyAction], k: int | None
                ) -> tuple[list[AnyAction], MistakeKind | None]:
        moves = [a for a in actions if not isinstance(a, DoneAction)]
        # Before one of the planned moves (so the mistake matters), or first when the
        # proposal is only the end token.
        last = max(len(moves) - 1, 0) if k is None else min(max(len(moves) - 1, 0), k - 1)
        position = self.rng.randint(0, last)
        at = state.copy()
        for action in moves[:position]:
            apply_action(at, action)
        upcoming = moves[position] if position < len(moves) else None
        order = list(self.kinds)
        first = self.rng.choice(order)
        order.remove(first)
        self.rng.shuffle(order)
        for kind in (first, *order):
            if kind == "stop_early":
                if moves:
                    return [*moves[:position], DoneAction()], kind
                continue
            mistake = make_mistake(kind, at, upcoming, self.rng)
            if mistake is not None:
                noisy: list[AnyAction] = [*moves[:position], mistake, *moves[position:]]
                if k is not None and len(noisy) > k:
                    return noisy[:k], kind
                return [*noisy, *[a for a in actions if isinstance(a, DoneAction)]], kind
        return actions, None


def _movable(state: WorldState) -> list[str]:
    return [o.id for o in state.objects.values() if o.props.movable and not o.props.sides]


def _pieces(state: WorldState) -> list[str]:
    return [o.id for o in state.objects.values() if o.props.sides and o.props.movable]


def make_mistake(kind: MistakeKind, state: WorldState, upcoming: AnyAction | None,
                 rng: random.Random) -> MoveAction | AlignAction | None:
    """One wrong action of `kind` that the verifier must refuse, or None if impossible."""
    action: MoveAction | AlignAction | None
    if _pieces(state):
        action = _tangram_mistake(kind, state, rng)
    else:
        action = _tabletop_mistake(kind, state, upcoming, rng)
    if action is None or validate_action(state, action) is None:
        return None  # harmless after all: not a mistake the verifier can show
    return action


def _tabletop_mistake(kind: MistakeKind, state: WorldState, upcoming: AnyAction | None,
                      rng: random.Random) -> MoveAction | None:
    movable = _movable(state)
    if not movable:
        return None
    clear = [o for o in movable if state.is_clear(o)]
    if kind == "non_clear":
        loaded = [o for o in movable if not state.is_clear(o)]
        if not loaded:
            return None
        obj = rng.choice(loaded)
        below = state.support.get(obj, ("", ""))[1]
        above = {o for o in state.objects if obj in state.supports_chain(o)}
        targets = [t for t in state.objects if t not in above | {obj, below}
                   and state.objects[t].props.surface and state.has_room(t)]
        if not targets:
            return None
        return MoveAction(object=obj, relation="on", target=rng.choice(targets))
    if kind == "full_target":
        full = [o for o in state.objects if not state.has_room(o)
                and (state.objects[o].props.surface or state.objects[o].props.container)]
        rng.shuffle(full)
        for target in full:
            candidates = [o for o in clear if o != target and o not in state.carried[target]]
            if candidates:
                relation = "on" if state.objects[target].props.surface else "in"
                return MoveAction(object=rng.choice(candidates), relation=relation,
                                  target=target)
        return None
    if kind == "hallucinated":
        return MoveAction(object=_invented_name(state, rng), relation="on",
                          target=rng.choice(list(state.objects)))
    if kind == "wrong_relation":
        if isinstance(upcoming, MoveAction):
            flipped = "in" if upcoming.relation == "on" else "on"
            return MoveAction(object=upcoming.object, relation=flipped, target=upcoming.target)
        for _ in range(10):
            obj = rng.choice(clear or movable)
            target = rng.choice([o for o in state.objects if o != obj])
            t = state.objects[target].props
            if not t.container:
                return MoveAction(object=obj, relation="in", target=target)
            if not t.surface:
                return MoveAction(object=obj, relation="on", target=target)
        return None
    return None


def _tangram_mistake(kind: MistakeKind, state: WorldState, rng: random.Random
                     ) -> AlignAction | None:
    pieces = _pieces(state)
    if len(pieces) < 2:
        return None
    obj, target = rng.sample(pieces, 2)
    n_obj = state.side_count(obj) or 3
    n_target = state.side_count(target) or 3
    if kind == "full_target":
        taken = [(side, others[0]) for side, others in state.contacts.items()
                 if side[0] in pieces and others]
        rng.shuffle(taken)
        for (piece, side), (other, _) in taken:
            movers = [p for p in pieces if p not in (piece, other)]
            if movers:
                mover = rng.choice(movers)
                return AlignAction(object=mover, side=0, target=piece, target_side=side)
        return None
    if kind == "hallucinated":
        return AlignAction(object=_invented_name(state, rng), side=0, target=target,
                           target_side=0)
    if kind == "wrong_relation":
        return AlignAction(object=obj, side=n_obj + rng.randint(0, 2), target=target,
                           target_side=rng.randrange(n_target))
    return None  # non_clear has no tangram counterpart


def _invented_name(state: WorldState, rng: random.Random) -> str:
    """A plausible object name that is not in the scene (a colour or a number off)."""
    base = rng.choice(sorted(state.objects))
    options = [f"{base}_2", f"{base}_3", "purple_block", "blue_mug", "small_triangle_3",
               "big_plate", "spoon_2"]
    return next(o for o in rng.sample(options, len(options)) if o not in state.objects)
