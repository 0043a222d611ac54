"""The fast run of a valid plan gives exactly the step-by-step report.

`validate_strips_dict` first runs a plan on ground actions cached per distinct line
(simulate._fast_run) and falls back to the step-by-step simulation for anything that
fails; `all_errors=True` always takes the step-by-step run, so the two reports of one
valid plan can be compared field by field (the fast one has no `after_failure`).
"""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

from verigraph.actions.pddl import validate_strips_dict

pytestmark = pytest.mark.fast

IPC = Path(__file__).parents[2] / "benchmarks" / "data" / "ipc"
# The long-plan benchmark's domains (benchmarks/bench_validate.py), as shipped.
GRIPPER = (IPC.parent / "gripper" / "domain.pddl").read_text()
VISITALL = (IPC / "visitall" / "domain.pddl").read_text()


def _both(domain: str, problem: str, plan: str) -> tuple[dict, dict]:
    fast = validate_strips_dict(domain, problem, plan)
    slow = validate_strips_dict(domain, problem, plan, all_errors=True)
    slow.pop("after_failure")
    return fast, slow


def _visitall(n: int, steps: int) -> tuple[str, str]:
    cells = [(x, y) for x in range(n) for y in range(n)]

    def near(x: int, y: int) -> list[tuple[int, int]]:
        return [(x + dx, y + dy) for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))
                if 0 <= x + dx < n and 0 <= y + dy < n]

    def c(p: tuple[int, int]) -> str:
        return f"l{p[0]}-{p[1]}"

    init = [f"(at-robot {c((0, 0))})"] + [f"(connected {c(a)} {c(b)})" for a in cells
                                          for b in near(*a)]
    rng = random.Random(5)
    path = [(0, 0)]
    for _ in range(steps):
        path.append(rng.choice(near(*path[-1])))
    seen = sorted(set(path[1:]))
    problem = (f"(define (problem w) (:domain grid-visit-all) (:objects "
               f"{' '.join(map(c, cells))} - place) (:init {' '.join(init)}) "
               f"(:goal (and {' '.join(f'(visited {c(p)})' for p in seen)})))")
    moves = zip(path, path[1:], strict=False)
    return problem, "\n".join(f"(move {c(a)} {c(b)})" for a, b in moves)


def test_a_walk_that_revisits_cells_gives_the_step_by_step_edits():
    """Most steps re-add a `visited` that already holds: their edit lists only the
    robot's move, as the step-by-step run writes it."""
    problem, plan = _visitall(4, 300)
    fast, slow = _both(VISITALL, problem, plan)
    assert fast["valid"] and json.dumps(fast) == json.dumps(slow)
    assert {len(s["edit"]["added"]) for s in fast["steps"]} == {1, 2}


def test_repeated_ground_actions_and_a_final_goal_agree():
    problem = ("(define (problem g) (:domain gripper-strips) (:objects rooma roomb left b1 b2)"
               " (:init (room rooma) (room roomb) (gripper left) (at-robby rooma) (free left)"
               " (ball b1) (ball b2) (at b1 rooma) (at b2 rooma)) (:goal (and (at b1 roomb))))")
    cycle = ["(pick b2 rooma left)", "(move rooma roomb)", "(drop b2 roomb left)",
             "(pick b2 roomb left)", "(move roomb rooma)", "(drop b2 rooma left)"]
    plan = cycle * 50 + ["(pick b1 rooma left)", "(move rooma roomb)", "(drop b1 roomb left)"]
    fast, slow = _both(GRIPPER, problem, "\n".join(plan))
    assert fast["valid"] and json.dumps(fast) == json.dumps(slow)
    # a failing step or an unmet goal is explained by the step-by-step run
    bad = validate_strips_dict(GRIPPER, problem, "\n".join(plan[:-1]))
    assert not bad["valid"] and bad["unmet_goals"][0]["literal"] == "(at b1 roomb)"
    assert "achievers" in bad["unmet_goals"][0]
    swapped = validate_strips_dict(GRIPPER, problem, "\n".join([plan[1], plan[0], *plan[2:]]))
    assert swapped["violations"][0]["step"] == 2 and swapped["violations"][0]["unsatisfied"]


@pytest.mark.parametrize("plan_file", sorted(IPC.glob("*/*.plan")), ids=lambda p: p.parent.name
                         + "/" + p.stem)
def test_every_shipped_ipc_plan_gets_the_step_by_step_report(plan_file: Path):
    """ADL (conditional effects, quantifiers), action costs, constants, typing: the
    shipped Fast Downward plans of 31 IPC domains."""
    domain_file = plan_file.with_suffix(".domain.pddl")
    if not domain_file.exists():
        domain_file = plan_file.parent / "domain.pddl"
    domain, problem = domain_file.read_text(), plan_file.with_suffix(".pddl").read_text()
    fast, slow = _both(domain, problem, plan_file.read_text())
    assert json.dumps(fast, sort_keys=True) == json.dumps(slow, sort_keys=True)
