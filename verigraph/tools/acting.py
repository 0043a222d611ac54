"""Verifier tools: validate_action, execute_actions, check_goal, validate_plan.

execute_actions is Algorithm 1's inner step on an episode: validate and apply each
action until the first violation (in the simulator too when one is attached), keep the
valid prefix, and count tau, the consecutive failed calls. Everything is computed on
a copy and committed at the end, so bad input leaves the episode exactly as it was.
"""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    WithJsonSchema,
    field_validator,
    model_validator,
)

from verigraph.actions.constraints import NO_GOAL
from verigraph.actions.execution import check_plan, execute_in_world
from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction, DoneAction
from verigraph.actions.parser import parse_plan
from verigraph.actions.pddl import as_validation_report
from verigraph.actions.report import ValidationReport, validate_plan
from verigraph.actions.validator import GraphEdit, all_violations, apply_action
from verigraph.errors import PlanParseError, VeriGraphError
from verigraph.graph.dictionary import applied_line
from verigraph.graph.goal import Goal, GraphDiff, check_goal, wanted_placements
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import label_readings
from verigraph.pddl.validate import validate_pddl_dict
from verigraph.reporting import report_text, violation_text
from verigraph.tools.context import ToolContext
from verigraph.tools.errors import EpisodeStateError, ToolArgumentError
from verigraph.tools.executors import arm_mode_of, runs_on
from verigraph.tools.fields import (
    ActionInput,
    BoundedGraph,
    EpisodeId,
    RequestId,
    SceneId,
    count_moves,
    parse_actions,
)
from verigraph.tools.goals import (
    GOAL_ARGUMENT_HELP,
    GoalArgument,
    resolve_goal,
    stateless_source,
)
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
    action: ActionInput = Field(description="the action")


class ActionCheck(BaseModel):
    """Whether the action is allowed now, why not, and what it would change."""

    ok: bool
    action: str = Field(description="the action in text form")
    violation: Violation | None = None
    violations: list[Violation] = Field(default_factory=list,
                                        description="every constraint it breaks")
    would_change: GraphEdit | None = Field(default=None,
                                           description="edges it would remove and add")
    goal_satisfied_after: bool | None = Field(
        default=None, description="whether the goal would hold right after it")
    runs_on: str | None = Field(default=None, description="the episode's executor")

    def summary(self) -> str:
        checked = "checked only, nothing was executed"
        if self.runs_on is not None:
            checked += f"; episode executor: {self.runs_on}"
        if self.violation is not None:
            found = self.violations or [self.violation]
            if len(found) == 1:
                return f"INVALID {self.action}: {violation_text(found[0].model_dump())}\n{checked}"
            lines = [f"INVALID {self.action}: breaks {len(found)} constraints (fix all):"]
            lines += [f"- {violation_text(v.model_dump())}" for v in found]
            return "\n".join([*lines, checked])
        if self.action == "done":
            return f"valid: done (the end token; execute_actions then end_episode)\n{checked}"
        change = f" ({self.would_change.text()})" if self.would_change else ""
        goal = " - goal would be reached" if self.goal_satisfied_after else ""
        return f"valid: {self.action}{change}{goal}\n{checked}"



def validate_action_tool(ctx: ToolContext, params: ValidateActionInput) -> ActionCheck:
    """Check one action; the episode is never modified."""
    actions = parse_actions([params.action], field="action", indexed=False)
    if len(actions) != 1:
        raise ToolArgumentError(f"expected one action, got {len(actions)}", field="action",
                                value=len(actions), fix="validate one action at a time, or "
                                "use validate_plan for a sequence")
    action = actions[0]
    with ctx.store.use(params.episode_id) as episode:
        state = episode.require_state()
        where = runs_on(episode.executor, arm_mode_of(episode.world))
        if isinstance(action, DoneAction):
            return ActionCheck(ok=True, action="done", runs_on=where)
        found = all_violations(state, action, wanted=wanted_placements(episode.goal)
                               if episode.goal else NO_GOAL)
        if found:
            return ActionCheck(ok=False, action=action.text(), violation=found[0],
                               violations=found, runs_on=where)
        after = state.copy()
        edit = apply_action(after, action)
        reached = check_goal(after, episode.goal).satisfied if episode.goal else None
        return ActionCheck(ok=True, action=action.text(), would_change=edit,
                           goal_satisfied_after=reached, runs_on=where)


# -- execute_actions ------------------------------------------------------------------------
class ExecuteActionsInput(BaseModel):
    """At most k actions (plus optionally the end token) to execute in order."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId
    actions: list[ActionInput] = Field(
        min_length=1, max_length=MAX_ACTIONS_PER_CALL,
        description="JSON or text (lines)")
    whole_plan: bool = Field(
        default=False, description="over k (to 50): checked first; no real arm")
    request_id: RequestId | None = Field(
        default=None, description="retry key: a repeat returns the first result")
    expected_calls: int | None = Field(
        default=None, ge=0, description="run only after this many "
                                        "execute_actions calls")

    @field_validator("actions", mode="before")
    @classmethod
    def _text_plan(cls, value: Any) -> Any:
        """A plan given as one text (one action per line) is that text's actions."""
        return [value] if isinstance(value, str) else value


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
    runs_on: str | None = Field(default=None, description="the episode's executor")

    def summary(self) -> str:
        if self.executed:
            parts = [f"executed {len(self.executed)}: {', '.join(self.executed)}"]
        elif self.done and self.violation is None:
            parts = ["no action to execute: done received"]
        else:
            parts = ["executed none"]
        if self.violation is not None:
            parts.append(f"stopped: {self.violation.text()}")
        if self.goal_diff is not None:
            parts.append(self.goal_diff.summary())
        parts.append(f"tau={self.tau}/{self.t}")
        if self.threshold_reached:
            parts.append("threshold reached: call end_episode")
        elif self.done:
            parts.append("end token received: call end_episode for the verdict")
        where = [f"executor: {self.runs_on}"] if self.runs_on else []
        observed = observed_text(self.runs_on.split(" ")[0], len(self.executed),
                                 self.violation) if self.runs_on else None
        where += [observed] if observed else []
        return "\n".join(["; ".join(parts), *where, edges_line(self.graph, "graph now")])


def _check_whole_plan(state: WorldState, actions: list[AnyAction], arm_mode: str | None
                      ) -> None:
    """A whole plan runs in one call only if every step is valid on the current graph
    (checked before anything runs); a real arm keeps its k per call, each asked for."""
    if arm_mode == "real":
        raise ToolArgumentError(
            "whole_plan is not available on a real arm: the user approves each call of at "
            "most k actions", field="whole_plan", value=True,
            fix="send at most k actions per call")
    report = validate_plan(state, actions)
    if not report["valid"]:
        first = report["violations"][0]
        raise ToolArgumentError(
            f"whole_plan: the plan is not valid from the current graph, nothing was run: "
            f"step {first['step']} {violation_text(first, with_step=False)}", field="actions",
            value=first["step"], fix="correct the plan (validate_plan with this episode_id "
            "shows every step) and send it again")


def observed_text(executor: str, executed: int, violation: Violation | None) -> str | None:
    """For an episode with a world (sim2d, an arm): whether what it observed after each
    action matched what the plan predicted, said every time (the graph alone: None)."""
    if executor == "graph":
        return None
    world = "the 2D simulator" if executor == "sim2d" else f"the arm ({executor})"
    if violation is not None and violation.constraint == "execution_failed":
        return (f"observed != predicted: {world} did not end as planned (see stopped); "
                "the graph below is what it observed")
    if not executed:
        return f"observed = predicted: nothing ran in {world}, nothing changed"
    return (f"observed = predicted: after each of the {executed} action(s) {world}'s "
            "observed graph matched the plan's prediction")


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
        if moves > episode.k and params.whole_plan:
            _check_whole_plan(state, actions, arm_mode_of(episode.world))
        elif moves > episode.k:
            raise ToolArgumentError(
                f"{moves} actions given but this episode allows at most k={episode.k} per call",
                field="actions", value=moves,
                fix=f"send the first {episode.k} actions now and the rest after seeing the "
                    "result, or the whole plan with whole_plan=true (checked first, then "
                    "run step by step)")
        if len(episode.executed) + moves > ctx.config.max_actions_per_episode:
            raise EpisodeStateError(
                "this episode reached the maximum number of executed actions "
                f"({ctx.config.max_actions_per_episode})", field="actions", value=moves,
                fix="call end_episode and start a new episode")
        executed, edits, violation, done, new_state = execute_in_world(
            state, actions, episode.world, first_step=len(episode.executed) + 1,
            wanted=wanted_placements(episode.goal) if episode.goal else NO_GOAL)
        tau = episode.tau + 1 if violation is not None else 0
        diff = check_goal(new_state, episode.goal) if episode.goal else None
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
            goal_satisfied=diff.satisfied if diff else None, goal_diff=diff,
            runs_on=runs_on(episode.executor, arm_mode_of(episode.world)))
        if params.request_id is not None:
            episode.requests.record(params.request_id, proposed, output.model_dump(mode="json"))
            episode.mark_changed()  # an in-place edit: durable stores save it with the rest
        return output


# -- check_goal -----------------------------------------------------------------------------
class CheckGoalInput(BaseModel):
    """The episode's goal, or another goal to compare against without storing it."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId
    goal: GoalArgument | None = Field(default=None, description="instead of the episode's; "
                                                                "edges or formula text too")


# The goal a result echoes is published as a plain object: its shape is the goal input's
# (tools/list sends it there), and repeating it would cost every chat turn its bytes.
EchoedGoal = Annotated[Goal, WithJsonSchema({"type": "object"})]


class GoalCheck(BaseModel):
    """How the current graph differs from the goal."""

    episode_id: str
    satisfied: bool
    goal: EchoedGoal
    diff: GraphDiff

    def summary(self) -> str:
        return self.diff.summary()


def check_goal_tool(ctx: ToolContext, params: CheckGoalInput) -> GoalCheck:
    with ctx.store.use(params.episode_id) as episode:
        state = episode.require_state()
        goal = resolve_goal(params.goal, state) if params.goal is not None else episode.goal
        if goal is None:
            raise ToolArgumentError("this episode has no goal and none was given",
                                    field="goal", value=None,
                                    fix="call set_goal first, or pass goal here")
        diff = check_goal(state, goal)
        return GoalCheck(episode_id=episode.id, satisfied=diff.satisfied, goal=goal, diff=diff)


# -- validate_plan --------------------------------------------------------------------------
MAX_PDDL_CHARS = 1_000_000  # a domain or problem text; the reader also bounds depth and size
PDDL_KEYS = ("domain", "problem")


class ValidatePlanInput(BaseModel):
    """A whole plan against an initial scene (stateless; episodes are only read)."""

    model_config = ConfigDict(extra="forbid")

    plan: PlanText | PlanList = Field(
        description="one action per line, or a list")
    scene_id: SceneId | None = Field(default=None, description="a built-in scene")
    graph: BoundedGraph | None = Field(default=None, description="initial graph")
    episode_id: EpisodeId | None = Field(
        default=None, description="this episode's graph and goal")
    goal: GoalArgument | None = Field(default=None, description="check the final graph; "
                                      + GOAL_ARGUMENT_HELP)
    all_errors: bool = Field(default=False, description="go on after a failing action")
    pddl: dict[str, str] | None = Field(default=None,
                                        description="{domain, problem} PDDL text, not a scene")

    @model_validator(mode="after")
    def _one_scene(self) -> ValidatePlanInput:
        given = [n for n in ("scene_id", "graph", "episode_id") if getattr(self, n) is not None]
        if self.pddl is not None:
            if sorted(self.pddl) != sorted(PDDL_KEYS):
                raise ValueError("pddl holds exactly 'domain' and 'problem' (PDDL texts)")
            if any(len(t) > MAX_PDDL_CHARS for t in self.pddl.values()):
                raise ValueError(f"a pddl text is longer than {MAX_PDDL_CHARS} characters")
            if given or self.goal is not None or not isinstance(self.plan, str):
                raise ValueError("with pddl, give the plan as text and no scene or goal (the "
                                 "goal is in the problem)")
            return self
        if len(given) != 1:
            raise ValueError("give exactly one initial scene: scene_id, graph or episode_id "
                             f"(got {', '.join(given) or 'none'})")
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


def validate_plan_tool(ctx: ToolContext, params: ValidatePlanInput) -> ValidationReport:
    """Per-step report for a plan; nothing is stored or modified. Its `label_readings`
    say how the graphs the client wrote were read, as load_scene reports them."""
    if params.pddl is not None:
        return pddl_report(params.pddl, str(params.plan), all_errors=params.all_errors)
    actions = _plan_actions(params.plan)
    state, goal = stateless_source(ctx, episode_id=params.episode_id, scene_id=params.scene_id,
                                   graph=params.graph, goal=params.goal)
    written = params.goal.graph if isinstance(params.goal, Goal) else None
    readings = [] if params.graph is None and written is None else label_readings(
        params.graph, state.dictionary, written)  # the graphs the client wrote, if any
    return ValidationReport.model_validate(  # the plain report as the tool's model
        check_plan(state, actions, goal, all_errors=params.all_errors, readings=readings))


# The text of a plan report shows the first steps and every failure (up to a bound)
# in full; a long plan's other accepted steps are only counted.
SHOWN_FIRST_STEPS = 20
SHOWN_MAX_FAILURES = 50


def pddl_report(pddl: dict[str, str], plan: str, *, all_errors: bool = False
                ) -> ValidationReport:
    """The PDDL plan's report as the tools return it."""
    return as_validation_report(pddl_data(pddl, plan, all_errors=all_errors))


def pddl_data(pddl: dict[str, str], plan: str, *, all_errors: bool = False
              ) -> dict[str, Any]:
    """The PDDL plan's report in plain data (`reporting`'s form: `valid`, `total_cost`),
    its errors named by the tool's fields (`pddl.domain`)."""
    try:
        data = validate_pddl_dict(pddl["domain"], pddl["problem"], plan, all_errors=all_errors)
        if len(data["steps"]) + data["not_checked"] > MAX_PLAN_ACTIONS:
            raise ToolArgumentError(f"the plan has more than {MAX_PLAN_ACTIONS} actions",
                                    field="plan", value=None,
                                    fix="use verigraph validate --batch for longer plans")
        return data
    except VeriGraphError as exc:
        field = exc.field if exc.field in ("domain", "problem") else exc.field or "plan"
        raise ToolArgumentError(exc.message, field=f"pddl.{field}" if field in (
            "domain", "problem") else field, value=exc.value if isinstance(
            exc.value, int | None) else str(exc.value)[:120], fix=exc.fix) from None


def report_summary(report: ValidationReport, data: dict[str, Any] | None = None) -> str:
    """The report's text (`reporting.report_text`): the verdict, then the first 20 steps
    and every failure.

    Many clients hand a model only the text of a result, so every violation found (with
    all_errors, one per failed step) is in it, with its fix; accepted steps beyond the
    first 20 are counted, as are failures beyond 50. Nothing is executed or stored.
    `data`: the report as the structured content sends it (the server's one dump of
    it); without it, the report is dumped here.
    """
    text = report_text(report.model_dump(mode="json") if data is None else data,
                       max_steps=SHOWN_FIRST_STEPS, max_failures=SHOWN_MAX_FAILURES)
    if report.final_graph.nodes:  # what the check assumed about each built-in kind
        assumed = applied_line(report.final_graph)
        text += f"\n{assumed}" if assumed else ""
    return text
