"""The fast run gives exactly the step-by-step report.

`validate_strips_dict` runs a plan on ground actions cached per distinct line
(simulate._fast_run) and hands a failing step or an unmet goal to the step-by-step
simulation; `all_errors=True` (and `simulate(..., try_fast=False)`) takes the
step-by-step run throughout, so the two reports of one plan can be compared field by
field (the all-errors one adds `after_failure`).
"""

from __future__ import annotations

import importlib
import json
import random
from pathlib import Path

import pytest

from verigraph.pddl import read_domain, read_problem, validate_strips_dict
from verigraph.pddl.plans import line_reader, parse_strips_plan
from verigraph.pddl.simulate import cached_strips_problem, simulate

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


def _mutations(plan: str) -> dict[str, str]:
    """The ways a plan breaks (a dropped, swapped or repeated step, a misspelt action, an
    undeclared object, a wrong arity, no last step), deterministic per plan."""
    lines = plan.splitlines()
    steps = [k for k, line in enumerate(lines) if line.startswith("(")]
    mid = steps[len(steps) // 2]
    words = lines[mid].strip("()").split()
    out = {"drop": lines[:mid] + lines[mid + 1:],
           "swap": lines[:mid] + [lines[mid + 1], lines[mid]] + lines[mid + 2:]
           if mid + 1 < len(lines) else lines[::-1],
           "repeat": lines[:mid + 1] + [lines[mid]] + lines[mid + 1:],
           "misspelt": lines[:mid] + ["(" + " ".join([words[0] + "x", *words[1:]]) + ")"]
           + lines[mid + 1:],
           "undeclared": lines[:mid] + ["(" + " ".join([*words[:-1], "nosuchobject"]) + ")"
                                        if len(words) > 1 else lines[mid]] + lines[mid + 1:],
           "arity": lines[:mid] + ["(" + " ".join([*words, words[-1]]) + ")"]
           + lines[mid + 1:],
           "truncate": [lines[k] for k in steps[:-1]]}
    return {kind: "\n".join(v) for kind, v in out.items()}


@pytest.mark.parametrize("plan_file", sorted(IPC.glob("*/*.plan"))[::3],
                         ids=lambda p: p.parent.name + "/" + p.stem)
def test_a_failing_step_handed_over_gets_the_step_by_step_report(plan_file: Path):
    """The fast run meets the failing step (or the unmet goal) and hands its state to the
    step-by-step run, with the history read back from its edits: the report is the one
    the step-by-step run gives from the start (`simulate(..., try_fast=False)`)."""
    domain_file = plan_file.with_suffix(".domain.pddl")
    if not domain_file.exists():
        domain_file = plan_file.parent / "domain.pddl"
    domain_text, problem_text = domain_file.read_text(), plan_file.with_suffix(".pddl").read_text()
    domain = read_domain(domain_text)
    for kind, plan in _mutations(plan_file.read_text()).items():
        problem = read_problem(problem_text, domain)
        fast = validate_strips_dict(domain_text, problem_text, plan)
        slow = simulate(domain, problem, parse_strips_plan(plan, domain), try_fast=False)
        assert json.dumps(fast, sort_keys=True) == json.dumps(slow, sort_keys=True), kind


def test_plans_of_one_problem_share_its_ground_actions_and_get_their_own_reports():
    """A batch's plans of one problem reuse the ground actions kept on it: a broken plan
    after the valid one gets the report it gets alone."""
    problem = ("(define (problem g) (:domain gripper-strips) (:objects rooma roomb left b1)"
               " (:init (room rooma) (room roomb) (gripper left) (at-robby rooma) (free left)"
               " (ball b1) (at b1 rooma)) (:goal (and (at b1 roomb))))")
    good = "(pick b1 rooma left)\n(move rooma roomb)\n(drop b1 roomb left)"
    bad = "(pick b1 rooma left)\n(drop b1 roomb left)\n(move rooma roomb)"
    cached_strips_problem.cache_clear()
    alone = validate_strips_dict(GRIPPER, problem, bad)
    assert alone["violations"][0]["step"] == 2
    cached_strips_problem.cache_clear()
    assert validate_strips_dict(GRIPPER, problem, good)["valid"]
    assert cached_strips_problem(GRIPPER, problem).grounded  # kept for the next plan
    after = validate_strips_dict(GRIPPER, problem, bad)
    assert json.dumps(after, sort_keys=True) == json.dumps(alone, sort_keys=True)


def test_a_plan_that_leaves_too_many_ground_actions_behind_empties_the_cache(monkeypatch):
    """What a problem keeps for its next plan is bounded (a server keeps problems read)."""
    problem = ("(define (problem g) (:domain gripper-strips) (:objects rooma roomb left b1)"
               " (:init (room rooma) (room roomb) (gripper left) (at-robby rooma) (free left)"
               " (ball b1) (at b1 rooma)) (:goal (and (at b1 roomb))))")
    plan = "(pick b1 rooma left)\n(move rooma roomb)\n(drop b1 roomb left)"
    cached_strips_problem.cache_clear()
    module = importlib.import_module("verigraph.pddl.simulate")  # not the function
    monkeypatch.setattr(module, "MAX_GROUNDED", 3)
    assert validate_strips_dict(GRIPPER, problem, plan)["valid"]
    assert len(cached_strips_problem(GRIPPER, problem).grounded) == 3
    assert validate_strips_dict(GRIPPER, problem, plan + "\n(move roomb rooma)")["valid"]
    assert not cached_strips_problem(GRIPPER, problem).grounded  # four: emptied


def test_each_line_read_alone_is_the_step_the_whole_plan_reading_gives():
    """The fast run reads one line at a time (`line_reader`); every kind of line gives the
    step `parse_strips_plan` gives: plain, spaced, upper case, VAL's prefixes and
    suffixes, comments, sentences, the wrong arity, an unknown action, no action."""
    domain = read_domain(GRIPPER)
    lines = ["(pick b1 rooma left)", "(pick  b1 rooma left)", "( pick b1 rooma left)",
             "(PICK B1 RoomA left)", "0: (pick b1 rooma left) [1]", "1. (move rooma roomb)",
             "(move rooma roomb) ; a comment", "; only a comment", "", "[PLAN]",
             "pick b1 from rooma with left", "(pick b1 rooma)", "(fly rooma)", "()",
             "(1) (move rooma roomb)", "(move\trooma roomb)", "(drop b1 roomb left)"]
    text = "\n".join(lines)
    lowered = text.lower().splitlines()
    step_at = line_reader(text, lowered, domain)
    read = [step for step in map(step_at, range(len(lowered))) if step is not None]
    assert read == parse_strips_plan(text, domain)
    assert sum(s.problem is not None for s in read) == 4  # arity, unknown, (), (1) (...)
