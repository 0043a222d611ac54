"""Verifier tools: validate_action, execute_actions, check_goal, validate_plan.

execute_actions is Algorithm 1's inner step on an episode: validate and apply each
action until the first violation (in the simulator too when one is attached), keep the
valid prefix, and count tau, the consecutive failed calls. Everything is computed on
a copy and committed at the end, so bad input leaves the episode exactly as it was.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field, model_validator

from verigraph.actions.executor import execute_in_world
from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction, DoneAction
from verigraph.actions.parser import parse_plan
from verigraph.actions.report import ValidationReport
from verigraph.actions.report import validate_plan as core_validate_plan
from verigraph.actions.validator import GraphEdit, apply_action
from verigraph.actions.validator import validate_action as core_check
from verigraph.errors import PlanParseError
from verigraph.graph.goal import Goal, GraphDiff
from verigraph.graph.goal import check_goal as core_check_goal
from verigraph.graph.model import SceneGraph
from verigraph.tools.context import ToolContext
from verigraph.tools.errors import EpisodeStateError, ToolArgumentError
from verigraph.tools.fields import (
    ActionInput,
    BoundedGoal,
    BoundedGraph,
    EpisodeId,
    RequestId,
    SceneId,
    count_moves,
    parse_actions,
)
from verigraph.tools.goals import check_goal_against
from verigraph.tools.loading import stateless_source
from verigraph.tools.store import TraceEntry
from verigraph.tools.texts import edges_line

MAX_ACTIONS_PER_CALL = 50
MAX_PLAN_ACTIONS = 1000
# A text plan of MAX_PLAN_ACTIONS lines with room for comments; longer text is refused
# before it is split into lines and parsed.
MAX_PLAN_CHARS = 400_000
PlanText = Annotated[str, Field(max_length=MAX_PLAN_CHARS)]
PlanList = Annotated[list[ActionInput], Field(max_length=MAX_PLAN_ACTIONS)]


# -- validate_action ------------------------------------------------------------------------
class ValidateActionInput(BaseModel):
    """One action to check against the episode's current graph."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId
    action: ActionInput = Field(description="an action as JSON or text")


class ActionCheck(BaseModel):
    """Whether the action is allowed now, why not, and what it would change."""

    ok: bool
    action: str = Field(description="the action in text form")
    violation: Violation | None = None
    would_change: GraphEdit | None = Field(default=None,
                                           description="edges it would remove and add")
    goal_satisfied_after: bool | None = Field(
        default=None, description="whether the goal would hold right after it")

    def summary(self) -> str:
        if self.violation is not None:
            return f"INVALID {self.action}: {self.violation.text()}"
        change = f" ({self.would_change.text()})" if self.would_change else ""
        goal = " - goal would be reached" if self.goal_satisfied_after else ""
        return f"valid: {self.action}{change}{goal}"


def validate_action(ctx: ToolContext, params: ValidateActionInput) -> ActionCheck:
    """Check one action; the episode is never modified."""
    actions = parse_actions([params.action], field="action", indexed=False)
    if len(actions) != 1:
        raise ToolArgumentError(f"expected one action, got {len(actions)}", field="action",
                                value=len(actions), fix="validate one action at a time, or "
                                "use validate_plan for a sequence")
    action = actions[0]
    with ctx.store.use(params.episode_id) as episode:
        state = episode.require_state()
        if isinstance(action, DoneAction):
            return ActionCheck(ok=True, action="done")
        violation = core_check(state, action)
        if violation is not None:
            return ActionCheck(ok=False, action=action.text(), violation=violation)
        after = state.copy()
        edit = apply_action(after, action)
        reached = core_check_goal(after, episode.goal).satisfied if episode.goal else None
        return ActionCheck(ok=True, action=action.text(), would_change=edit,
                           goal_satisfied_after=reached)


# -- execute_actions ------------------------------------------------------------------------
class ExecuteActionsInput(BaseModel):
    """At most k actions (plus optionally the end token) to execute in order."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId
    actions: list[ActionInput] = Field(
        min_length=1, max_length=MAX_ACTIONS_PER_CALL,
        description="JSON actions or text (a text item may hold several lines)")
    request_id: RequestId | None = Field(
        default=None, description="a retry with the same id returns the first "
                                  "result, not a second run")
    expected_calls: int | None = Field(
        default=None, ge=0, description="run only after this many "
                                        "execute_actions calls")


class ExecutionOutput(BaseModel):
    """Result of one Algorithm-1 iteration on the episode."""

    episode_id: str
    ok: bool = Field(description="every action ran (no violation)")
    executed: list[str] = Field(description="the valid prefix that was applied")
    not_executed: list[str] = Field(description="the failing action and everything after it")
    violation: Violation | None = None
    edits: list[GraphEdit]
    graph: SceneGraph = Field(description="current graph after this call")
    tau: int
    t: int
    threshold_reached: bool = Field(description="tau reached t: the episode should end")
    done: bool = Field(description="the end token was reached")
    goal_satisfied: bool | None
    goal_diff: GraphDiff | None

    def summary(self) -> str:
        parts = [f"executed {len(self.executed)}: {', '.join(self.executed) or 'nothing'}"]
        if self.violation is not None:
            parts.append(f"stopped: {self.violation.text()}")
        if self.goal_diff is not None:
            parts.append(self.goal_diff.summary())
        parts.append(f"tau={self.tau}/{self.t}")
        if self.threshold_reached:
            parts.append("threshold reached: call end_episode")
        elif self.done:
            parts.append("end token received: call end_episode for the verdict")
        return "; ".join(parts) + "\n" + edges_line(self.graph, "graph now")


def execute_actions(ctx: ToolContext, params: ExecuteActionsInput) -> ExecutionOutput:
    """execute_until_violation on the episode, updating tau; bad input changes nothing.

    With a request_id the call is idempotent: its result is recorded with the episode,
    and a retry returns that record instead of running the actions a second time.
    """
    actions = parse_actions(params.actions)
    proposed = [a.text() for a in actions]
    with ctx.store.use(params.episode_id) as episode:
        if params.request_id is not None:
            earlier = episode.requests.result(params.request_id, proposed)
            if earlier is not None:
                return ExecutionOutput.model_validate(earlier)
        if params.expected_calls is not None and params.expected_calls != episode.calls:
            raise EpisodeStateError(
                f"the episode has had {episode.calls} execute_actions calls, not "
                f"{params.expected_calls}", field="expected_calls", value=params.expected_calls,
                fix="call get_state to see what was executed, then decide the next actions "
                    "from the current graph")
        state = episode.require_state()
        if episode.threshold_reached:
            raise EpisodeStateError(
                f"this episode already failed {episode.tau} times in a row (t={episode.t})",
                field="episode_id", value=episode.id,
                fix="call end_episode for the verdict, then load_scene to try again")
        moves = count_moves(actions)
        if moves > episode.k:
            raise ToolArgumentError(
                f"{moves} actions given but this episode allows at most k={episode.k} per call",
                field="actions", value=moves,
                fix=f"send the first {episode.k} actions now and the rest after seeing the "
                    "result (or load the scene with a larger k)")
        if len(episode.executed) + moves > ctx.config.max_actions_per_episode:
            raise EpisodeStateError(
                "this episode reached the maximum number of executed actions "
                f"({ctx.config.max_actions_per_episode})", field="actions", value=moves,
                fix="call end_episode and start a new episode")
        executed, edits, violation, done, new_state = execute_in_world(
            state, actions, episode.world, first_step=len(episode.executed) + 1)
        tau = episode.tau + 1 if violation is not None else 0
        diff = core_check_goal(new_state, episode.goal) if episode.goal else None
        episode.calls += 1
        episode.trace.append(TraceEntry(
            call=episode.calls, proposed=[a.text() for a in actions],
            executed=[a.text() for a in executed], violation=violation, done=done, tau=tau,
            goal_satisfied=diff.satisfied if diff else None))
        episode.state = new_state
        episode.executed.extend(executed)
        episode.tau = tau
        episode.last_violation = violation
        episode.done = episode.done or done
        output = ExecutionOutput(
            episode_id=episode.id, ok=violation is None,
            executed=[a.text() for a in executed],
            not_executed=[a.text() for a in actions[len(executed):]] if violation else [],
            violation=violation, edits=edits, graph=new_state.to_graph(), tau=tau,
            t=episode.t, threshold_reached=episode.threshold_reached, done=done,
            goal_satisfied=diff.satisfied if diff else None, goal_diff=diff)
        if params.request_id is not None:
            episode.requests.record(params.request_id, proposed, output.model_dump(mode="json"))
            episode.mark_changed()  # an in-place edit: durable stores save it with the rest
        return output


# -- check_goal -----------------------------------------------------------------------------
class CheckGoalInput(BaseModel):
    """The episode's goal, or another goal to compare against without storing it."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId
    goal: BoundedGoal | None = Field(default=None,
                              description="check this goal instead of the episode's")


class GoalCheck(BaseModel):
    """How the current graph differs from the goal."""

    episode_id: str
    satisfied: bool
    goal: Goal
    diff: GraphDiff

    def summary(self) -> str:
        return self.diff.summary()


def check_goal(ctx: ToolContext, params: CheckGoalInput) -> GoalCheck:
    with ctx.store.use(params.episode_id) as episode:
        state = episode.require_state()
        goal = params.goal or episode.goal
        if goal is None:
            raise ToolArgumentError("this episode has no goal and none was given",
                                    field="goal", value=None,
                                    fix="call set_goal first, or pass goal here")
        if params.goal is not None:
            check_goal_against(params.goal, state, field="goal")
        diff = core_check_goal(state, goal)
        return GoalCheck(episode_id=episode.id, satisfied=diff.satisfied, goal=goal, diff=diff)


# -- validate_plan --------------------------------------------------------------------------
class ValidatePlanInput(BaseModel):
    """A whole plan against an initial scene (stateless; episodes are only read)."""

    model_config = ConfigDict(extra="forbid")

    plan: PlanText | PlanList = Field(
        description="text plan (one action per line) or a list of actions")
    scene_id: SceneId | None = Field(default=None, description="start from a built-in scene")
    graph: BoundedGraph | None = Field(default=None, description="initial scene graph")
    episode_id: EpisodeId | None = Field(
        default=None, description="start from this episode's graph and goal")
    goal: BoundedGoal | None = Field(default=None, description="check the final graph against it")
    all_errors: bool = Field(default=False, description="skip failing actions and report "
                                                        "every violation")

    @model_validator(mode="after")
    def _one_scene(self) -> ValidatePlanInput:
        given = [n for n in ("scene_id", "graph", "episode_id") if getattr(self, n) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one initial scene: scene_id, graph or episode_id "
                             f"(got {', '.join(given) or 'none'})")
        if isinstance(self.plan, str) and len(self.plan) > 200_000:
            raise ValueError("plan text is longer than 200000 characters")
        return self


def _plan_actions(plan: str | list[ActionInput]) -> list[AnyAction]:
    if isinstance(plan, str):
        try:
            actions = parse_plan(plan)
        except PlanParseError as exc:
            raise ToolArgumentError(exc.message, field="plan", value=exc.text[:120],
                                    fix=exc.fix) from None
    else:
        if not plan:
            raise ToolArgumentError("the plan is empty", field="plan", value=[],
                                    fix="give at least one action")
        actions = parse_actions(plan, field="plan")
    if len(actions) > MAX_PLAN_ACTIONS:
        raise ToolArgumentError(f"the plan has {len(actions)} actions", field="plan",
                                value=len(actions),
                                fix=f"validate at most {MAX_PLAN_ACTIONS} actions at a time")
    return actions


def validate_plan(ctx: ToolContext, params: ValidatePlanInput) -> ValidationReport:
    """Per-step report for a plan; nothing is stored or modified."""
    actions = _plan_actions(params.plan)
    state, goal = stateless_source(ctx, episode_id=params.episode_id, scene_id=params.scene_id,
                                   graph=params.graph, goal=params.goal)
    if params.goal is not None:
        check_goal_against(params.goal, state, field="goal")
    return core_validate_plan(state, actions, goal, all_errors=params.all_errors)


def report_summary(report: ValidationReport) -> str:
    """One line: the verdict and, when invalid, the first violation."""
    verdict = "VALID" if report.valid else "INVALID"
    parts = [f"{verdict}: {len(report.steps)} step(s) checked"]
    if report.violations:
        parts.append(report.violations[0].text())
        if len(report.violations) > 1:
            parts.append(f"and {len(report.violations) - 1} more violation(s)")
    if report.goal_diff is not None:
        parts.append(report.goal_diff.summary())
    return "; ".join(parts)
