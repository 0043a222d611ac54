"""The `oracle` planner: the reference solver in the planner's seat.

Not an LLM and not a fair competitor: it reads the ground-truth goal
(`request.privileged_goal`, also when the prompt shows only an instruction) and plans
optimally, so it is the privileged ceiling of every table and the check that the
pipeline (tools, loop, goal check) is sound.
It re-plans from the current graph on every call, so it also recovers from states a
noisy planner left behind.
"""

from __future__ import annotations

from verigraph.actions.model import AnyAction, DoneAction
from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.state import WorldState
from verigraph.planning.models import PlannerReply, PlannerRequest
from verigraph.planning.tangram_plan import tangram_plan
from verigraph.solver import solve


def reference_plan(request: PlannerRequest, goal: Goal | None
                   ) -> tuple[list[AnyAction], str | None]:
    """An optimal plan from the request's graph to `goal`, and a note when there is none."""
    if goal is None:
        return [], "no checkable goal: the planner can only answer done"
    state = WorldState.from_graph(request.graph)
    if check_goal(state, goal).satisfied:
        return [], None
    if goal.graph is not None and any(o.props.sides for o in state.objects.values()):
        aligns = tangram_plan(state, goal)
        if aligns is None:
            return [], "no tangram plan found"
        return list[AnyAction](aligns), None
    result = solve(state, goal)
    if not result.reachable:
        return [], f"solver found no plan: {result.reason}"
    return list(result.plan), None


def chunk(plan: list[AnyAction], k: int | None) -> list[AnyAction]:
    """The first k actions, with the end token appended when they finish the plan."""
    if k is None or len(plan) <= k:
        return [*plan, DoneAction()]
    return plan[:k]


class OraclePlanner:
    """First k actions of an optimal plan; `done` once the goal holds."""

    name = "oracle"
    privileged = True  # the episode hands it the ground-truth goal (planner.py)

    def propose(self, request: PlannerRequest) -> PlannerReply:
        plan, note = reference_plan(request, request.privileged_goal or request.goal)
        return PlannerReply(actions=chunk(plan, request.k), llm_calls=1, note=note)

    def close(self) -> None:
        return None
