"""The reward: success 1/0 by default, with optional shaping terms, each documented.

`Rubric` holds the weights; `score(rubric, outcome)` turns one step's `StepOutcome`
into a reward and its named terms (reported in `info["reward_terms"]`, so a trainer
sees why a step paid what it paid). It is a pure function of the outcome, which is
what makes the rewards checkable on hand-made cases (docs/env.md, "Reward").

Terms, per step:

- `success`: `success` weight once, on the step that ends the episode with the goal
  holding (the goal reached, or `done` accepted while it holds). Never paid twice.
- `progress`: `progress * (d_before - d_after) / d_start`, where d is the goal distance
  (verigraph.planning.progress.goal_distance: goal edges missing plus extra edges). Over an
  episode these telescope to `progress * (d_start - d_end) / d_start`, at most the
  weight, so undoing and redoing a move earns nothing.
- `refusal`: `-refusal` on a failed step: an action refused by the verifier, an answer
  that could not be parsed, or `done` while the goal does not hold.
- `efficiency`: on success only, `efficiency * min(1, optimal / moves)`: the reference
  solver's optimal length against the moves this episode executed.

The default rubric is success only: the episode return is 1.0 when the goal is reached
and 0.0 otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass

from pydantic import BaseModel, ConfigDict, Field

from verigraph.planning.models import IterationVerdict

FAILED_VERDICTS = frozenset({"violation", "malformed", "premature_done"})


class Rubric(BaseModel):
    """Weights of the reward terms (see the module docstring for each term)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    success: float = Field(default=1.0, ge=0.0, description="paid once when the goal holds "
                                                            "at the end")
    progress: float = Field(default=0.0, ge=0.0, description="weight of the goal-distance "
                                                            "shaping")
    refusal: float = Field(default=0.0, ge=0.0, description="penalty per failed step")
    efficiency: float = Field(default=0.0, ge=0.0, description="on success: optimal / moves")


@dataclass(frozen=True)
class StepOutcome:
    """What one step did, as the rubric needs it (plain data, built by the environment)."""

    verdict: IterationVerdict
    distance_before: int | None
    distance_after: int | None
    distance_start: int | None
    success: bool = False
    moves: int = 0
    optimal_length: int | None = None


def score(rubric: Rubric, outcome: StepOutcome) -> tuple[float, dict[str, float]]:
    """(reward, terms) of one step; the reward is the sum of the terms."""
    terms: dict[str, float] = {}
    if outcome.success:
        terms["success"] = rubric.success
        if rubric.efficiency and outcome.optimal_length is not None:
            ratio = 1.0 if outcome.moves <= 0 else min(1.0, outcome.optimal_length
                                                       / outcome.moves)
            terms["efficiency"] = rubric.efficiency * ratio
    if rubric.progress and outcome.distance_start and outcome.distance_before is not None \
            and outcome.distance_after is not None:
        delta = outcome.distance_before - outcome.distance_after
        if delta:
            terms["progress"] = rubric.progress * delta / outcome.distance_start
    if rubric.refusal and outcome.verdict in FAILED_VERDICTS:
        terms["refusal"] = -rubric.refusal
    return float(sum(terms.values())), terms
