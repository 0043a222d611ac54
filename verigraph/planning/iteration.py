"""One iteration of Algorithm 1 (docs/design.md section 6), driven by the environment and
the agent alike.

`Iteration.step(reply, execute, goal)` takes the planner's reply (parsed actions or a
parse error), keeps at most k moves (`split_proposal`), sends them with `execute` (the
caller's `execute_actions` call, which also updates the caller's view of the episode),
reads the goal back with `goal`, and returns an `IterationOutcome`: the verdict, the feedback for
the next prompt, tau, and the stop it calls for, if any. The verigraph.env environment
(`VeriGraphEnv.step`) and the agent's loop (`verigraph.agent.loop`) both drive it, so the
verdicts, the premature-`done` sentence and the tau rule exist once.

tau (one meaning, the glossary's): the number of consecutive failed iterations. A failed
iteration is a malformed answer, a refused action (violation) or a premature `done`; a
clean iteration or an accepted end token resets it to 0, and tau reaching t stops the
episode. The server's own counter (`execute_actions`' `tau`, kept in the trace as
`server_tau`) only sees the calls that reach it, so it counts violations alone; the
iteration stops when either reaches t (`IterationOutcome.server_threshold`), which is how the one
rule serves a caller that sends malformed answers (they never reach the server) and one
that does not.

The defaults `DEFAULT_K` and `DEFAULT_THRESHOLD` (the error threshold t, called
`threshold` everywhere but `load_scene`'s argument `t`) are the server's, defined once in
`verigraph.tools.store`; the environment, the agent's loop and the CLI's options read
them here. `MAX_ACTIONS_PER_CALL` is `execute_actions`' limit; both are read from the
tools, not restated.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, NamedTuple

from verigraph.actions.model import AnyAction, DoneAction
from verigraph.graph.goal import Goal, GraphDiff
from verigraph.graph.model import SceneGraph
from verigraph.planning.models import Feedback, IterationVerdict, PlannerReply, StopReason
from verigraph.planning.parsing import split_proposal
from verigraph.planning.progress import malformed_feedback, violation_feedback
from verigraph.planning.tool_calls import ToolEnvironment
from verigraph.tools.acting import MAX_ACTIONS_PER_CALL
from verigraph.tools.store import DEFAULT_K, DEFAULT_THRESHOLD

__all__ = ["DEFAULT_K", "DEFAULT_THRESHOLD", "MAX_ACTIONS_PER_CALL", "Execute", "GoalView",
           "Iteration", "IterationOutcome", "StateReading", "call_execute_actions", "prompt_goal",
           "read_state"]

Execute = Callable[[list[AnyAction]], Mapping[str, Any]]
"""Send actions to `execute_actions` and return its result (the caller absorbs it)."""
GoalView = Callable[[], tuple["bool | None", "GraphDiff | None"]]
"""The caller's current (goal_satisfied, goal_diff)."""


class StateReading(NamedTuple):
    """What a driver of the iteration keeps of a tool's answer (`load_scene`,
    `get_state`, `execute_actions`): the graph and the goal check."""

    graph: SceneGraph
    goal_satisfied: bool | None
    goal_diff: GraphDiff | None


def read_state(state: Mapping[str, Any]) -> StateReading:
    """The graph and the goal check of a tool's answer, as models."""
    diff = state.get("goal_diff")
    return StateReading(SceneGraph.model_validate(state["graph"]), state.get("goal_satisfied"),
                   GraphDiff.model_validate(diff) if diff else None)


def call_execute_actions(tools: ToolEnvironment, episode_id: str,
                    actions: list[AnyAction]) -> dict[str, Any]:
    """Call `execute_actions` with `actions` on the episode and return its answer."""
    return tools.call("execute_actions", {
        "episode_id": episode_id, "actions": [a.model_dump(mode="json") for a in actions]})


def prompt_goal(goal: Goal | None, show_graph: bool) -> Goal | None:
    """The goal as the prompt may show it: without its graph or formula for instruction
    tasks (only the predicate, or nothing)."""
    if goal is None or show_graph or (goal.graph is None and goal.formula is None):
        return goal
    if goal.predicate is None:
        return None
    return goal.model_copy(update={"graph": None, "formula": None})


def premature_done_feedback(diff: GraphDiff | None) -> Feedback:
    """The feedback for an end token while the goal does not hold."""
    summary = diff.summary() if diff else "goal not reached"
    return Feedback(kind="premature_done",
                    text=f"[premature_done] you answered done, but {summary}. Keep planning "
                         "towards the goal and answer done only once it holds.")


@dataclass
class IterationOutcome:
    """What one iteration came to."""

    verdict: IterationVerdict
    feedback: Feedback | None
    tau: int
    moves: list[AnyAction]
    dropped: list[AnyAction]
    out: Mapping[str, Any] = field(default_factory=dict)
    """`execute_actions`' result, empty when nothing was sent."""
    ended: bool = False
    """the end token was accepted."""
    goal_satisfied: bool | None = None
    server_threshold: bool = False
    """the server's counter reached t (`threshold_reached`)."""
    stop: StopReason | None = None
    """`end_token`, `goal_reached` or `threshold`; None to go on."""


class Iteration:
    """Algorithm 1's iteration over one episode: k, the error threshold t, tau and the
    end-token rule.

    `verify_done` refuses an end token while a checkable goal does not hold (the
    agent's `done_policy="verify"`, always on in the environment); `stop_on_goal` stops
    as soon as the goal holds.
    """

    def __init__(self, k: int | None, threshold: int, *, verify_done: bool = True,
                 stop_on_goal: bool = True) -> None:
        self.k = k
        self.threshold = threshold
        self.verify_done = verify_done
        self.stop_on_goal = stop_on_goal
        self.tau = 0

    def step(self, reply: PlannerReply, execute: Execute, goal: GoalView) -> IterationOutcome:
        """Judge one reply: execute its moves, update tau, and say whether to stop."""
        moves, done, dropped = split_proposal(reply.actions, self.k)
        outcome = IterationOutcome(verdict="clean", feedback=None, tau=self.tau, moves=moves,
                          dropped=dropped)
        if reply.error is not None or not (moves or done):
            outcome.feedback = malformed_feedback(reply)
            outcome.verdict = "malformed"
        else:
            ended = True
            if moves:
                out = execute([*moves, *([DoneAction()] if done else [])])
                outcome.out = out
                outcome.server_threshold = bool(out.get("threshold_reached"))
                if out.get("violation"):
                    outcome.feedback = violation_feedback(out)
                    outcome.verdict = "violation"
                ended = done and outcome.feedback is None
            if ended:
                satisfied, diff = goal()
                if satisfied is False and self.verify_done:
                    outcome.feedback = premature_done_feedback(diff)
                    outcome.verdict = "premature_done"
                    ended = False
                else:
                    outcome.verdict = "end_token"
            outcome.ended = ended
        self.tau = 0 if outcome.verdict in ("clean", "end_token") else self.tau + 1
        outcome.tau = self.tau
        outcome.goal_satisfied = goal()[0]
        if outcome.ended:
            outcome.stop = "end_token"
        elif self.stop_on_goal and outcome.goal_satisfied:
            outcome.stop = "goal_reached"
        elif self.tau >= self.threshold or outcome.server_threshold:
            outcome.stop = "threshold"
        return outcome
