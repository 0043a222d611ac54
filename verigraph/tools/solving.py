"""solve: a reference plan by classical search, re-checked by the verifier.

The search itself lives in verigraph.solver; this tool feeds it the episode's current
graph (or a scene) and goal, and validates the plan it returns, so a solver bug shows
up as `verified: false` instead of a wrong answer.
"""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field, model_validator

from verigraph.actions.model import Action, AnyAction
from verigraph.actions.report import validate_plan
from verigraph.graph.dictionary import applied_line
from verigraph.solver import solve as search_plan
from verigraph.solver.pddl_planner import plan_pddl
from verigraph.tools.acting import MAX_ACTIONS_PER_CALL, MAX_PDDL_CHARS, PDDL_KEYS, pddl_data
from verigraph.tools.context import ToolContext
from verigraph.tools.errors import FeatureUnavailableError, ToolArgumentError
from verigraph.tools.executors import arm_mode_of, runs_on
from verigraph.tools.fields import (
    BoundedGraph,
    EpisodeId,
    SceneId,
)
from verigraph.tools.goals import GoalArgument, stateless_source


class SolveInput(BaseModel):
    """Where to plan from (episode, built-in scene or graph) and the goal."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId | None = Field(default=None, description="this episode's "
                                                                   "current graph")
    scene_id: SceneId | None = Field(default=None, description="a built-in scene")
    graph: BoundedGraph | None = Field(default=None, description="plan from this graph")
    goal: GoalArgument | None = Field(default=None, description="default: the episode's "
                                      "or scene's; edges or formula text too")
    max_expansions: int = Field(default=200_000, ge=1, le=2_000_000,
                                description="max nodes expanded")
    time_limit: float = Field(default=5.0, gt=0, le=600,
                              description="CPU seconds of the search")
    memory_limit_mb: float = Field(default=200, gt=0, le=16_384,
                                   description="MiB of growth")
    anytime: bool = Field(default=False, description="fast plan, then refined")
    pddl: dict[str, str] | None = Field(
        default=None, description="{domain, problem}")

    @model_validator(mode="after")
    def _one_scene(self) -> SolveInput:
        given = [n for n in ("episode_id", "scene_id", "graph") if getattr(self, n) is not None]
        if self.pddl is not None:
            if sorted(self.pddl) != sorted(PDDL_KEYS):
                raise ValueError("pddl holds exactly 'domain' and 'problem' (PDDL texts)")
            if any(len(t) > MAX_PDDL_CHARS for t in self.pddl.values()):
                raise ValueError(f"a pddl text is longer than {MAX_PDDL_CHARS} characters")
            if given or self.goal is not None:
                raise ValueError("with pddl, give no scene or goal (the goal is in the problem)")
            return self
        if len(given) != 1:
            raise ValueError("give exactly one of episode_id, scene_id, graph "
                             f"(got {', '.join(given) or 'none'})")
        return self


class SolveOutput(BaseModel):
    """The solver's answer and whether the verifier accepts its plan."""

    reachable: bool | None = Field(description="null when the search budget ran out first")
    plan: list[str] = Field(description="the plan in text form")
    actions: list[Action] = Field(description="the plan as action objects")
    length: int
    reason: str | None = Field(default=None, description="why no plan was found")
    verified: bool = Field(description="the verifier accepts every step and the goal holds")
    optimal: bool = Field(default=False, description="no shorter plan exists")
    expanded: int = Field(default=0, description="search nodes expanded")
    lower_bound: int | None = Field(default=None, description="no plan is shorter than this")
    runs_on: str | None = Field(default=None, description="the episode's executor")
    assumed: str | None = Field(default=None, description="built-in properties applied")
    cost: float | None = Field(default=None, description="a PDDL plan's total cost")
    planner: str | None = Field(default=None, description="a PDDL plan: the search that "
                                                          "found it")
    run_with: str | None = Field(default=None, description="an episode's plan: the call "
                                                           "that runs it")

    def optimality(self) -> str:
        """`optimal (no plan has fewer moves)`, or the proven bound when it is not shown; a
        PDDL plan's says which planner proved what: no cheaper plan (a domain with action
        costs) or none with fewer actions."""
        if self.planner is not None:
            cost = f"plan cost {self.cost:g}, " if self.cost is not None else ""
            if self.optimal and self.cost is not None:
                return f"{cost}cost-optimal ({self.planner} proved that no plan costs less)"
            if self.optimal:  # a domain without action costs: every action counts 1
                return f"optimal ({self.planner} proved that no plan has fewer actions)"
            return f"{cost}satisficing ({self.planner}; not proven optimal)"
        if self.optimal:
            return "optimal (no plan has fewer moves)"
        if self.lower_bound is not None:
            return (f"not proven optimal: every plan needs at least {self.lower_bound} "
                    "move(s) (lower bound)")
        return "not proven optimal, no lower bound proven"

    def summary(self) -> str:
        if self.reachable is None:
            head = f"no plan found: {self.reason or 'search budget exhausted'}"
            if self.lower_bound:
                head += f"; every plan needs at least {self.lower_bound} move(s) (lower bound)"
        elif not self.reachable:
            head = f"no plan: {self.reason or 'goal unreachable'}"
        else:
            check = "verified" if self.verified else "NOT verified by the validator"
            head = (f"plan of {self.length} action(s), {check}, {self.optimality()}: "
                    f"{'; '.join(self.plan) or '(empty)'}")
            if not self.optimal and self.reason:
                head += f"\n{self.reason}"
        # Like validate_action: a plan is not a motion, and the executor says where
        # execute_actions would run it.
        planned = "planned only, nothing was executed"
        if self.assumed:
            head += f"\n{self.assumed}"
        if self.runs_on is not None:
            planned += f"; episode executor: {self.runs_on}"
        if self.run_with is not None:
            planned += f"\n{self.run_with}"
        return f"{head}\n{planned}"


def solve_tool(ctx: ToolContext, params: SolveInput) -> SolveOutput:
    if not ctx.config.enable_solve:
        raise FeatureUnavailableError("solve is disabled on this server", field="solve",
                                      value=None, fix="plan with validate_action and "
                                                      "execute_actions feedback instead")
    if params.pddl is not None:
        return _solve_pddl(params.pddl, params.time_limit)
    state, goal = stateless_source(ctx, episode_id=params.episode_id, scene_id=params.scene_id,
                                   graph=params.graph, goal=params.goal)
    if goal is None:
        raise ToolArgumentError("there is no goal to solve for", field="goal", value=None,
                                fix="pass goal, or call set_goal on the episode first")
    result = search_plan(state, goal, max_expansions=params.max_expansions,
                         time_limit=params.time_limit, memory_limit_mb=params.memory_limit_mb,
                         anytime=params.anytime)
    plan: list[AnyAction] = list(result.plan or [])
    verified = False
    if result.reachable:
        verified = validate_plan(state, plan or "done", goal)["valid"]
    where, run_with = _episode_run(ctx, params.episode_id, len(plan) if verified else 0)
    return SolveOutput(reachable=result.reachable, plan=[a.text() for a in plan],
                       actions=plan, length=len(plan), reason=result.reason,
                       verified=verified, optimal=result.optimal, expanded=result.expanded,
                       lower_bound=result.lower_bound, runs_on=where, run_with=run_with,
                       assumed=applied_line(state.to_graph(), dictionary=state.dictionary) or None)


def _episode_run(ctx: ToolContext, episode_id: str | None, length: int
                 ) -> tuple[str | None, str | None]:
    """Where the episode's actions run, and the call that runs a verified plan of
    `length` actions there (`run_hint`); (None, None) for a plan on a scene or graph."""
    if episode_id is None:
        return None, None
    with ctx.store.use(episode_id) as episode:
        mode = arm_mode_of(episode.world)
        where, k = runs_on(episode.executor, mode), episode.k
    return where, run_hint(length, k, mode)


def run_hint(length: int, k: int, arm_mode: str | None) -> str | None:
    """How execute_actions runs a verified plan of `length` actions, so the first call is
    the right one: one call when it fits in k or may go whole (`whole_plan`, up to its
    limit, never on a real arm, where the user approves each call), else calls of k.
    None for an empty plan."""
    if length == 0:
        return None
    if length <= k:
        return "to run it: execute_actions with these actions, one call"
    calls = -(-length // k)
    if arm_mode == "real" or length > MAX_ACTIONS_PER_CALL:
        return (f"to run it: execute_actions in {calls} calls of at most k={k} actions, in "
                "this order (each call's result before the next)")
    return ("to run it in one call: execute_actions with these actions and whole_plan=true "
            f"(checked first, then run step by step; k={k} per call otherwise, {calls} "
            "calls)")


def _solve_pddl(pddl: dict[str, str], time_limit: float) -> SolveOutput:
    """Fast Downward's plan for a PDDL domain and problem, re-checked by the PDDL
    validator (which also gives its cost)."""
    found = plan_pddl(pddl["domain"], pddl["problem"], time_limit=time_limit)
    if found.plan is None:
        return SolveOutput(reachable=False if found.unsolvable else None, plan=[], actions=[],
                           length=0, reason=found.reason, verified=False,
                           planner=found.planner)
    report = pddl_data(pddl, "\n".join(found.plan))
    cost = None if report.get("unmet_goals") else report.get("total_cost")  # a goal reached
    return SolveOutput(reachable=True, plan=found.plan, actions=[], length=len(found.plan),
                       reason=found.reason, verified=report["valid"], optimal=found.optimal,
                       planner=found.planner, cost=None if cost is None else float(cost))
