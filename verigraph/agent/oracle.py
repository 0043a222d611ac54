"""The `oracle` planner: the reference solver in the planner's seat.

Not an LLM: it reads the ground-truth goal and plans optimally, so it is the upper
bound of every table and the check that the pipeline (tools, loop, goal check) is sound.
It re-plans from the current graph on every call, so it also recovers from states a
noisy planner left behind.
"""

from __future__ import annotations

from verigraph.actions.model import AnyAction, DoneAction
from verigraph.agent.models import PlannerReply, PlannerRequest
from verigraph.graph.goal import check_goal
from verigraph.graph.state import WorldState
from verigraph.solver import solve


def reference_plan(request: PlannerRequest) -> tuple[list[AnyAction], str | None]:
    """An optimal plan from the request's graph to its goal, and a note when there is none."""
    if request.goal is None:
        return [], "no checkable goal: the oracle can only answer done"
    state = WorldState.from_graph(request.graph)
    if check_goal(state, request.goal).satisfied:
        return [], None
    result = solve(state, request.goal)
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

    def propose(self, request: PlannerRequest) -> PlannerReply:
        plan, note = reference_plan(request)
        return PlannerReply(actions=chunk(plan, request.k), llm_calls=1, note=note)

    def close(self) -> None:
        return None
