"""How far the scene is from the goal, and what the planner is told of a failure.

Small pieces of Algorithm 1 bookkeeping that the agent's loop and the environment
(verigraph.env) share, so both tell a planner the same words:

- `goal_distance`: the number of goal edges that do not hold plus the extra edges a full
  goal graph does not allow (single_stack: the objects outside the tallest tower). The
  no-progress rule stops an episode after N iterations without a new lowest distance,
  which ends valid moves back and forth that would otherwise reset tau forever.
- `shape_feedback`: the feedback modes of the feedback ablation. `full` is the verifier's
  whole report (constraint, message, blocking objects, suggestion); `constraint` keeps
  only the constraint id; `none` tells the planner nothing (it is asked
  again as if for the first time; tau still counts the failure).
- `malformed_feedback` and `violation_feedback`: the feedback of an answer that could not
  be used and of a refused action, in the words the next prompt shows.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from verigraph.actions.feedback import Violation
from verigraph.graph.goal import Goal, check_goal, towers
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.planning.models import Feedback, FeedbackMode, PlannerReply


def goal_distance(graph: SceneGraph, goal: Goal | None) -> int | None:
    """Edges still wrong (objects outside the tower, counterexamples of the formula), or
    None without a checkable goal."""
    if goal is None:
        return None
    state = WorldState.from_graph(graph)
    diff = check_goal(state, goal)
    if diff.satisfied:
        return 0
    distance = len(diff.missing_edges) + len(diff.extra_edges) + len(diff.missing_nodes) \
        + len(diff.extra_nodes) \
        + diff.formula_count()
    if goal.predicate == "single_stack":
        movable = sum(o.props.movable for o in state.objects.values())
        tallest = max((len(t) for t in towers(state)), default=0)
        distance += movable - tallest
    return distance


class ProgressMeter:
    """Counts iterations since the distance to the goal last reached a new low."""

    def __init__(self, patience: int) -> None:
        self.patience = patience
        self.best: int | None = None
        self.stalled = 0

    def update(self, distance: int | None) -> bool:
        """Record one iteration; True when the episode should stop for lack of progress."""
        if self.patience <= 0 or distance is None:
            return False
        if self.best is None or distance < self.best:
            self.best = distance
            self.stalled = 0
            return False
        self.stalled += 1
        return self.stalled >= self.patience


def shape_feedback(feedback: Feedback | None, mode: FeedbackMode) -> Feedback | None:
    """What the planner is shown of `feedback` under the feedback ablation's `mode`."""
    if feedback is None or mode == "full":
        return feedback
    if mode == "none":
        return None
    if feedback.violation is not None:
        return Feedback(kind=feedback.kind,
                        text=f"[{feedback.violation.constraint}] an action was refused")
    return Feedback(kind=feedback.kind, text=f"[{feedback.kind}]")


def malformed_feedback(reply: PlannerReply) -> Feedback:
    reason = reply.error or "it contained no action (not even done)"
    return Feedback(kind="malformed",
                    text=f"[malformed_action] your previous answer could not be used: {reason}")


def violation_feedback(out: Mapping[str, Any]) -> Feedback:
    violation = Violation.model_validate(out["violation"])
    executed = ", ".join(out.get("executed") or []) or "none"
    skipped = ", ".join(out.get("not_executed") or []) or "none"
    return Feedback(kind="violation", violation=violation,
                    text=f"{violation.text()} (executed from your answer: {executed}; not "
                         f"executed: {skipped})")
