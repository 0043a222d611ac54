"""The agent's boundary types: what a planner is asked, what it answers, what a run records.

Every planner backend (solver, noisy solver, OpenAI-compatible, Anthropic) sees the same
`PlannerRequest` and returns a `PlannerReply`; the loop records one `IterationRecord`
per planner call and an `EpisodeTrace` per episode (the JSON written by `--trace`).
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction
from verigraph.graph.goal import Goal, GraphDiff
from verigraph.graph.model import SceneGraph

Mode = Literal["iterative", "direct"]
DonePolicy = Literal["verify", "trust"]
FeedbackKind = Literal["violation", "malformed", "premature_done"]
FeedbackMode = Literal["full", "constraint", "none"]
IterationVerdict = Literal["clean", "violation", "malformed", "premature_done", "end_token",
                           "planner_error"]
StopReason = Literal["end_token", "goal_reached", "threshold", "no_progress",
                     "iteration_limit", "single_shot", "planner_error"]


class Feedback(BaseModel):
    """What went wrong in the previous iteration, in the words the planner will read.

    `violation` is the verifier's own report when an action was refused; malformed model
    output and a premature end token have no constraint id, so only `text` describes them.
    """

    kind: FeedbackKind
    text: str
    violation: Violation | None = None


class PlannerRequest(BaseModel):
    """Everything a planner may use to propose the next actions.

    LLM backends read only `prompt` (the rendered MCP prompt). The offline planners read
    the structured fields, which carry exactly what the prompt shows: `goal` is the goal
    as the prompt states it (None when the prompt shows only an instruction), and
    `feedback` is what the prompt shows of the last failure. `privileged_goal` is the
    verifier's ground truth, set only for a planner that declares `privileged = True`
    (the `oracle`, a ceiling, not a competitor); every other planner receives None.
    """

    model_config = ConfigDict(extra="forbid")

    mode: Mode
    iteration: int = Field(ge=1, description="1-based planner call number")
    graph: SceneGraph = Field(description="the current scene graph")
    goal: Goal | None = Field(description="the goal as the prompt shows it (graph and/or "
                                          "predicate); None when only words are shown")
    privileged_goal: Goal | None = Field(default=None,
                                         description="the ground-truth goal; oracle only")
    instruction: str | None = None
    feedback: Feedback | None = Field(default=None, description="what failed last time")
    history: list[str] = Field(default_factory=list, description="actions executed so far")
    k: int | None = Field(description="at most k actions (iterative); None = a whole plan")
    prompt: str = Field(description="the rendered planner prompt an LLM reads")


class PlannerReply(BaseModel):
    """Proposed actions, or why none could be read from the model's answer.

    `error` set means the answer was malformed or truncated; the loop turns it into
    feedback for the next iteration instead of failing the run.
    """

    actions: list[AnyAction] = Field(default_factory=list)
    error: str | None = Field(default=None, description="malformed output, in words")
    raw: str | None = Field(default=None, description="the model's raw answer")
    llm_calls: int = Field(default=1, ge=0, description="model calls this reply cost")
    usage: dict[str, Any] | None = Field(default=None, description="token counts if known")
    note: str | None = Field(default=None, description="planner-side remark for the trace")


class IterationRecord(BaseModel):
    """One pass of Algorithm 1: proposal, verifier verdict, feedback, tau after it."""

    iteration: int
    proposed: list[str] = Field(description="actions the planner proposed (text form)")
    dropped: list[str] = Field(default_factory=list,
                               description="proposed beyond k, never sent to the verifier")
    executed: list[str] = Field(default_factory=list, description="the valid prefix applied")
    verdict: IterationVerdict
    feedback: Feedback | None = Field(default=None, description="sent to the next iteration")
    tau: int = Field(description="consecutive failed iterations after this one")
    server_tau: int | None = Field(default=None,
                                   description="tau as counted by execute_actions")
    goal_satisfied: bool | None = None
    llm_calls: int = 0
    seconds: float = 0.0
    raw_output: str | None = None
    prompt: str | None = Field(default=None, description="only with --trace-prompts")
    note: str | None = None
    goal_distance: int | None = Field(default=None,
                                      description="goal edges missing + extra edges after it")


class EpisodeTrace(BaseModel):
    """A whole episode as the agent saw it; the JSON trace file."""

    planner: str
    mode: Mode
    k: int
    threshold: int
    done_policy: DonePolicy
    transport: str
    stop_on_goal: bool = True
    feedback_mode: FeedbackMode = "full"
    episode_id: str | None = None
    task: str | None = Field(default=None, description="task id in a benchmark")
    initial_graph: SceneGraph | None = None
    goal: Goal | None = None
    instruction: str | None = None
    iterations: list[IterationRecord] = Field(default_factory=list)
    stop_reason: StopReason | None = None
    success: bool = False
    verdict: str | None = Field(default=None, description="end_episode's verdict")
    verdict_summary: str | None = None
    final_graph: SceneGraph | None = None
    goal_diff: GraphDiff | None = None
    llm_calls: int = 0
    actions_executed: int = 0
    violations_caught: int = Field(default=0, description="actions the verifier refused")
    malformed_outputs: int = 0
    premature_done: int = 0
    planner_error: str | None = Field(default=None,
                                      description="the exception that ended the episode")
    wall_time_s: float = 0.0

    def summary(self) -> str:
        head = "SUCCESS" if self.success else "FAILURE"
        return (f"{head} ({self.verdict}, stopped: {self.stop_reason}); "
                f"{self.actions_executed} action(s) executed in {len(self.iterations)} "
                f"iteration(s), {self.llm_calls} planner call(s), {self.violations_caught} "
                f"violation(s) caught, {self.malformed_outputs} malformed answer(s), "
                f"{self.wall_time_s:.2f} s")
