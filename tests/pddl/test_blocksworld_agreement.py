"""Agreement with a reference PDDL validator on generated 4-op and 3-op blocks-world plans.

The oracle is unified-planning's SequentialPlanValidator on the same domain, problem and
plan: same verdict, same first failing step, on every mutation kind LLM plans show.
"""

from __future__ import annotations

import random
from collections import Counter

import pytest

from blocksworld_corpus import DATA, MUTATIONS, domain_text, generate
from pddl_corpus import oracle
from verigraph.actions.pddl import validate_pddl_plan
from verigraph.errors import PlanParseError

TYPED_NAMES = {"pick-up": "pickup", "put-down": "putdown"}


def spelled(plan: list[str], spelling: str) -> list[str]:
    if spelling != "typed":
        return plan
    out = []
    for a in plan:
        op, rest = a[1:].split(" ", 1)
        out.append(f"({TYPED_NAMES.get(op, op)} {rest}")
    return out


def ours(domain: str, problem: str, plan: list[str]) -> tuple[bool, int | None]:
    report = validate_pddl_plan(domain, problem, "\n".join(plan))
    return report.valid, report.violations[0].step if report.violations else None


def test_same_verdict_and_first_failing_step_as_unified_planning(tmp_path):
    kinds: Counter[str] = Counter()
    verdicts: Counter[bool] = Counter()
    for spelling, problem, plan, kind in generate(105, seed=11):
        plan = spelled(plan, spelling)
        domain = domain_text(spelling)
        expected = oracle(tmp_path, domain, problem, plan)
        assert ours(domain, problem, plan) == expected, (spelling, kind, problem, plan)
        kinds[kind] += 1
        verdicts[expected[0]] += 1
    assert set(kinds) == set(MUTATIONS) and min(kinds.values()) >= 8
    assert verdicts[True] >= 20 and verdicts[False] >= 40


def to_three_ops(plan: list[str]) -> list[str]:
    """Pair each grasp with its release: (unstack x y)(put-down x) -> (move-b-to-t x y)."""
    out = []
    for grasp, release in zip(plan[::2], plan[1::2], strict=False):
        g, r = grasp.strip("()").split(), release.strip("()").split()
        src = g[2] if g[0] == "unstack" else None
        dst = r[2] if r[0] == "stack" else None
        if src and dst:
            out.append(f"(move-b-to-b {g[1]} {src} {dst})")
        elif src:
            out.append(f"(move-b-to-t {g[1]} {src})")
        elif dst:
            out.append(f"(move-t-to-b {g[1]} {dst})")
    return out


def test_three_operator_domain_agrees_too(tmp_path):
    domain = (DATA / "three_op_domain.pddl").read_text()
    rng = random.Random(5)
    verdicts = Counter()
    for _spelling, problem, plan, kind in generate(60, seed=23):
        if kind != "valid":
            continue
        moves = to_three_ops(plan)
        problem3 = problem.replace("(handempty)", "").replace("(arm-empty)", "") \
            .replace("(ontable", "(on-table").replace(" - block", "")
        for variant in range(3):
            trial = list(moves)
            if variant and len(trial) > 1:
                i = rng.randrange(len(trial) - 1)
                trial[i], trial[i + 1] = trial[i + 1], trial[i]
            expected = oracle(tmp_path, domain, problem3, trial)
            assert ours(domain, problem3, trial) == expected, (problem3, trial)
            verdicts[expected[0]] += 1
    assert verdicts[True] >= 5 and verdicts[False] >= 5


def test_wrong_arity_is_bad_input_naming_the_line():
    domain = domain_text("planbench")
    problem = (DATA / "planbench_instance.pddl").read_text()
    for plan, line in (("(unstack d c)\n(put-down d)\n\n(unstack b)", 4),
                       ("(pick-up c d)", 1), ("stack the red block", 1)):
        with pytest.raises(PlanParseError, match=f"line {line}"):
            validate_pddl_plan(domain, problem, plan)


def test_undeclared_object_fails_the_step_that_names_it():
    report = validate_pddl_plan(domain_text("planbench"),
                                (DATA / "planbench_instance.pddl").read_text(),
                                "(unstack d c)\n(put-down d)\n(pick-up z)")
    assert not report.valid and report.violations[0].step == 3
    assert report.violations[0].constraint == "unknown_object"
