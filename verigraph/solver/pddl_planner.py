"""A plan for a PDDL domain and problem from Fast Downward (the `pddl` extra).

The reference solver (`verigraph.solver.search`) plans on scene graphs; a PDDL domain
of the client's own (action costs, ADL) goes to Fast Downward through unified-planning:
first its optimal search (`seq-opt-lmcut`, admissible, so a plan it returns has the
least total cost, the domain's `total-cost` when it has one, else the fewest actions),
and when that does not finish within the time given, its satisficing search
(`lama-first`), said to be so.
The plan comes back as PDDL text lines; the caller checks it with the PDDL validator.
"""

from __future__ import annotations

import io
import warnings
from dataclasses import dataclass

from verigraph.errors import VeriGraphError
from verigraph.extras import require

OPTIMAL = ("fast-downward-opt", "Fast Downward seq-opt-lmcut")
SATISFICING = ("fast-downward", "Fast Downward lama-first")


@dataclass(frozen=True)
class PddlPlan:
    """The planner's answer: the plan (PDDL action lines, None when none was found),
    whether the planner proved it optimal, which search found it, and why not."""

    plan: list[str] | None
    optimal: bool
    planner: str
    reason: str | None = None
    unsolvable: bool = False


def plan_pddl(domain: str, problem: str, *, time_limit: float) -> PddlPlan:
    """Fast Downward's plan: optimal where it proves it within `time_limit` seconds,
    else satisficing (another `time_limit`)."""
    require("pddl")
    from unified_planning.engines import PlanGenerationResultStatus as Status
    from unified_planning.io import PDDLReader
    from unified_planning.shortcuts import (
        MinimizeSequentialPlanLength,
        OneshotPlanner,
        get_environment,
    )

    get_environment().credits_stream = None  # stdout may be the MCP wire
    try:
        parsed = PDDLReader().parse_problem_string(domain, problem)
    except Exception as exc:  # noqa: BLE001 - the reader raises many kinds
        raise VeriGraphError(f"the planner cannot read this PDDL: {str(exc)[:200]}",
                             field="pddl", value=None,
                             fix="check the domain and problem (validate_plan with pddl "
                                 "reports where they fail)") from None
    if not parsed.quality_metrics:  # no action costs: every action counts 1, and the
        # optimal search's plan is the shortest; unified-planning says so only when asked
        parsed.add_quality_metric(MinimizeSequentialPlanLength())
    tried: list[str] = []
    for engine, name in (OPTIMAL, SATISFICING):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with OneshotPlanner(name=engine) as planner:
                result = planner.solve(parsed, timeout=time_limit, output_stream=io.StringIO())
        status = result.status
        if result.plan is not None and status in (Status.SOLVED_OPTIMALLY,
                                                   Status.SOLVED_SATISFICING):
            lines = [f"({a.action.name}{''.join(f' {p}' for p in a.actual_parameters)})"
                     for a in result.plan.actions]
            return PddlPlan(lines, optimal=status == Status.SOLVED_OPTIMALLY, planner=name,
                            reason="; ".join(tried) or None)
        if status == Status.UNSOLVABLE_PROVEN:
            return PddlPlan(None, optimal=False, planner=name, unsolvable=True,
                            reason=f"{name}: the problem has no plan")
        tried.append(f"{name}: " + {
            Status.TIMEOUT: f"no answer within {time_limit:g} s",
            Status.UNSUPPORTED_PROBLEM: "does not take this domain's features",
        }.get(status, status.name.lower().replace("_", " ")))
    return PddlPlan(None, optimal=False, planner=SATISFICING[1], reason="; ".join(tried))
