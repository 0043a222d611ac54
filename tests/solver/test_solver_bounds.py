"""solve says whether its plan is optimal, or the lower bound it proved, in its text.

A model asked for "as few moves as possible" must not have to prove optimality itself:
an optimal plan says so, an anytime plan cut short says how many moves any plan needs,
and a search the budget stops before any plan still gives that bound.
"""

from __future__ import annotations

import pytest
from mcp import Client
from mcp_helpers import structured, text

from scenes import random_blocks
from verigraph.graph import Goal
from verigraph.server import build_server
from verigraph.solver import solve
from verigraph.tools import Toolbox

pytestmark = pytest.mark.fast


@pytest.mark.parametrize("seed", range(4))
def test_a_search_stopped_before_any_plan_still_proves_a_lower_bound(seed: int) -> None:
    start, goal = random_blocks(7, seed), Goal(graph=random_blocks(7, seed + 50))
    optimal = solve(start, goal)
    assert optimal.optimal and optimal.lower_bound == len(optimal.plan)
    for anytime in (False, True):
        stopped = solve(start, goal, max_expansions=1, anytime=anytime)
        if stopped.reachable is None:
            assert stopped.status == "budget_exhausted"
            assert stopped.lower_bound is not None
            assert 0 < stopped.lower_bound <= len(optimal.plan)
        else:  # anytime: the fast strategy's plan, with the bound proved so far
            assert stopped.lower_bound is not None
            assert stopped.lower_bound <= len(optimal.plan) <= len(stopped.plan)
            assert stopped.optimal == (len(stopped.plan) == stopped.lower_bound)


@pytest.mark.anyio
async def test_the_solve_text_says_optimal_or_gives_the_bound() -> None:
    said_optimal = said_bound = False
    async with Client(build_server(Toolbox())) as client:
        for seed in range(6):
            start, goal = random_blocks(9, seed), random_blocks(9, seed + 100)
            args = {"graph": start.model_dump(), "goal": {"graph": goal.model_dump()}}
            for extra in ({}, {"anytime": True, "max_expansions": 1}):
                result = await client.call_tool("solve", {**args, **extra})
                out, said = structured(result), text(result)
                head = f"plan of {out['length']} action(s), verified, "
                if out["optimal"]:
                    assert said.startswith(head + "optimal (no plan has fewer moves): "), said
                    said_optimal = True
                else:
                    assert said.startswith(
                        head + f"not proven optimal: every plan needs at least "
                        f"{out['lower_bound']} move(s) (lower bound): "), said
                    said_bound = True
        stopped = await client.call_tool("solve", {**args, "max_expansions": 1})
    assert said_optimal and said_bound
    out = structured(stopped)
    assert out["reachable"] is None and out["lower_bound"] > 0
    assert text(stopped).startswith("no plan found: budget exhausted")
    assert f"every plan needs at least {out['lower_bound']} move(s) (lower bound)" in \
        text(stopped)
