"""The `noisy` planner: the reference solver with seeded mistakes of the kinds LLMs make.

An offline stand-in for an imperfect LLM, so the value of feedback and of the threshold
t can be measured reproducibly. It plans towards the goal its prompt shows (language
tasks: the rule-based translator's goal; it is never handed the privileged goal) and then
spoils the proposal. Mistakes are drawn without asking the verifier, so some are
refused and some are valid but useless (or harmful: they undo progress), like a real
model's. Parameters (`NoiseProfile`):

- `action_error` (`--noise`, default 0.3): per proposed action, the chance that it is
  replaced by a mistake of one of the enabled `kinds`:
  - `random_move`: a move (tangram: an align) drawn at random from the scene's objects;
  - `non_clear`: move an object that carries something (forgets to clear it first);
  - `hallucinated`: an object that is not in the scene;
  - `wrong_relation`: the planned move with `in`/`on` flipped (tangram: a side the
    piece does not have);
  - `skip_step`: the planned action is left out (the rest may then fail);
  so the more actions per call (k), the more mistakes per call.
- `malformed` (default action_error / 5): per call, an unreadable answer.
- `premature_done` (default action_error / 5): per call, `done` while its goal does
  not hold.
- `repeat` (default 0.5): after a refusal, the chance that the refused action is
  proposed again first (models often repeat a rejected step).
"""

from __future__ import annotations

import random
from typing import Literal, get_args

from pydantic import BaseModel, ConfigDict, Field

from verigraph.actions.model import AlignAction, AnyAction, DoneAction, MoveAction
from verigraph.graph.dictionary import SUPPORT_RELATIONS
from verigraph.graph.state import WorldState
from verigraph.planning.goal_reader import GoalReader
from verigraph.planning.models import PlannerReply, PlannerRequest
from verigraph.planning.oracle import chunk, reference_plan
from verigraph.planning.parsing import refused_action

MistakeKind = Literal["random_move", "non_clear", "hallucinated", "wrong_relation",
                      "skip_step"]
MISTAKE_KINDS: tuple[MistakeKind, ...] = get_args(MistakeKind)
GARBAGE = ('{"actions": [{"action": "move", "object": ', "Sure! Here is the plan:\nmove(",
           '{"plan": "stack them"}')


class NoiseProfile(BaseModel):
    """The noisy planner's error rates (see the module docstring)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    action_error: float = Field(default=0.3, ge=0.0, le=1.0)
    malformed: float | None = Field(default=None, ge=0.0, le=1.0,
                                    description="default: action_error / 5")
    premature_done: float | None = Field(default=None, ge=0.0, le=1.0,
                                         description="default: action_error / 5")
    repeat: float = Field(default=0.5, ge=0.0, le=1.0)

    def per_call(self, value: float | None) -> float:
        return self.action_error / 5 if value is None else value


class NoisyPlanner:
    """Solver proposals spoilt per action, plus malformed, repeated and premature answers."""

    def __init__(self, rate: float = 0.3, seed: int = 0,
                 kinds: tuple[MistakeKind, ...] = MISTAKE_KINDS,
                 profile: NoiseProfile | None = None) -> None:
        if not 0.0 <= rate <= 1.0:
            raise ValueError(f"noise rate must be between 0 and 1, got {rate}")
        unknown = [k for k in kinds if k not in MISTAKE_KINDS]
        if unknown or not kinds:
            raise ValueError(f"mistake kinds must be a non-empty subset of "
                             f"{', '.join(MISTAKE_KINDS)}; got {', '.join(kinds) or 'none'}")
        self.profile = profile or NoiseProfile(action_error=rate)
        self.kinds = tuple(kinds)
        self.rng = random.Random(seed)
        self.name = f"noisy({self.profile.action_error:.0%})"
        self.injected: list[str] = []
        self.reader = GoalReader()
        self.last: list[AnyAction] = []

    def propose(self, request: PlannerRequest) -> PlannerReply:
        goal, note = self.reader.read(request)
        plan, why = reference_plan(request, goal)
        note = note if goal is None else why or note
        p = self.profile
        if self.rng.random() < p.per_call(p.malformed):
            self.injected.append("malformed")
            raw = self.rng.choice(GARBAGE)
            return PlannerReply(error="the answer is not valid JSON for the action schema",
                                raw=raw, note="injected mistake: malformed")
        if plan and self.rng.random() < p.per_call(p.premature_done):
            self.injected.append("premature_done")
            return PlannerReply(actions=[DoneAction()], note="injected mistake: premature_done")
        state = WorldState.from_graph(request.graph)
        actions = chunk(plan, request.k)
        moves = [a for a in actions if not isinstance(a, DoneAction)]
        done = len(moves) < len(actions)
        spoilt: list[AnyAction] = []
        made: list[str] = []
        repeated = self._repeat(request)
        if repeated is not None:
            spoilt.append(repeated)
            made.append("repeat")
        for action in moves:
            if self.rng.random() >= p.action_error:
                spoilt.append(action)
                continue
            kind = self.rng.choice(self.kinds)
            made.append(kind)
            if kind == "skip_step":
                continue
            spoilt.append(make_mistake(kind, state, action, self.rng))
        if request.k is not None:
            spoilt = spoilt[:request.k]
        if done and len(spoilt) == len(moves) and not made:
            spoilt.append(DoneAction())
        elif done and request.k is None:
            spoilt.append(DoneAction())  # a whole plan ends with done, right or wrong
        self.injected.extend(made)
        self.last = [a for a in spoilt if not isinstance(a, DoneAction)]
        if not spoilt:
            spoilt = [DoneAction()] if not plan else [moves[0]]
        mistakes = f"injected mistake: {', '.join(made)}" if made else None
        return PlannerReply(actions=spoilt, note="; ".join(x for x in (mistakes, note) if x)
                            or None)

    def close(self) -> None:
        return None

    def _repeat(self, request: PlannerRequest) -> AnyAction | None:
        """The refused action of the last call, with probability `repeat`."""
        fb = request.feedback
        if fb is None or fb.kind != "violation" or self.rng.random() >= self.profile.repeat:
            return None
        if fb.violation is not None:
            return refused_action(fb.violation.action)
        return self.last[0] if self.last else None


def _movable(state: WorldState) -> list[str]:
    return sorted(o.id for o in state.objects.values() if o.props.movable)


def make_mistake(kind: MistakeKind, state: WorldState, planned: AnyAction,
                 rng: random.Random) -> AnyAction:
    """A wrong action of `kind` instead of `planned`, drawn without asking the verifier."""
    objects = sorted(state.objects)
    if isinstance(planned, AlignAction):
        pieces = _movable(state) or objects
        if kind == "hallucinated":
            return planned.model_copy(update={"object": invented_name(state, rng)})
        if kind == "wrong_relation":
            sides = state.side_count(planned.object) or 3
            return planned.model_copy(update={"side": sides + rng.randint(0, 2)})
        obj, target = rng.sample(pieces, 2) if len(pieces) > 1 else (pieces[0], pieces[0])
        return AlignAction(object=obj, side=rng.randrange(state.side_count(obj) or 3),
                           target=target, target_side=rng.randrange(state.side_count(target)
                                                                    or 3))
    assert isinstance(planned, MoveAction)
    if kind == "hallucinated":
        return MoveAction(object=invented_name(state, rng), relation=planned.relation,
                          target=planned.target)
    if kind == "wrong_relation":
        return planned.model_copy(update={"relation": "in" if planned.relation == "on"
                                          else "on"})
    if kind == "non_clear":
        loaded = [o for o in _movable(state) if not state.is_clear(o)]
        if loaded:
            return MoveAction(object=rng.choice(loaded), relation=planned.relation,
                              target=planned.target)
    # Tabletop mistakes: on and in only, so a kitchen's noise is what it always was.
    relations = [r for r in state.move_relations if r in SUPPORT_RELATIONS] or ("on",)
    return MoveAction(object=rng.choice(_movable(state) or objects),
                      relation=rng.choice(relations), target=rng.choice(objects))


def invented_name(state: WorldState, rng: random.Random) -> str:
    """A plausible object name that is not in the scene (a colour or a number off)."""
    base = rng.choice(sorted(state.objects))
    options = [f"{base}_2", f"{base}_3", "purple_block", "blue_mug", "small_triangle_3",
               "big_plate", "spoon_2"]
    return next(o for o in rng.sample(options, len(options)) if o not in state.objects)
