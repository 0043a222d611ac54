"""Agreement with unified-planning's SequentialPlanValidator on generated STRIPS plans.

Logistics (PlanBench's untyped domain and a typed one with equality, a negative
precondition and a constant), depots, and blocks worlds under random renamings: for
every plan the same verdict and the same first failing step; a plan the oracle cannot
even build (wrong arity, unknown object) fails at that step here.
"""

from __future__ import annotations

import random
from collections import Counter

import pytest

from blocksworld_corpus import DATA, generate
from pddl_corpus import (
    MUTATIONS,
    PDDL_DATA,
    blocks_renaming,
    depots_problem,
    logistics_problem,
    mutate,
    oracle,
    problem_text,
    random_walk,
    rename,
)
from verigraph.errors import PlanParseError
from verigraph.pddl import validate_pddl_dict

DOMAINS = {"logistics": ("logistics_domain.pddl", "logistics-strips"),
           "logistics_typed": ("logistics_typed_domain.pddl", "logistics-typed"),
           "depots": ("depots_domain.pddl", "depots")}


def ours(domain: str, problem: str, plan: list[str], engine: str = "auto"):
    try:
        report = validate_pddl_dict(domain, problem, "\n".join(plan), engine=engine)
    except PlanParseError as exc:
        return "bad input", exc.line
    v = report["violations"]
    return report, (report["valid"], v[0]["step"] if v else None)


def agree(expected, got) -> bool:
    if expected[0] == "refused":
        if got[0] == "bad input":  # wrong arity: the line of that step
            return True
        report, (valid, step) = got
        return not valid and step == expected[1] and report["violations"][0]["constraint"] in (
            "unknown_object", "wrong_type", "malformed_action")
    return got[0] != "bad input" and got[1] == expected


@pytest.mark.parametrize("name", list(DOMAINS))
def test_same_verdict_and_failing_step_on_generated_strips_plans(tmp_path, name):
    file, pddl_name = DOMAINS[name]
    domain = (PDDL_DATA / file).read_text()
    rng = random.Random(sum(map(ord, name)))
    kinds: Counter[str] = Counter()
    verdicts: Counter[object] = Counter()
    for case in range(40):  # until every mutation kind has been checked twice
        if len(kinds) == len(MUTATIONS) and min(kinds.values()) >= 2:
            break
        if name == "depots":
            objects, types, init = depots_problem(rng, places=2 + case % 2, crates=2 + case % 3)
        else:
            objects, types, init = logistics_problem(rng, typed=name == "logistics_typed",
                                                     cities=2 + case % 2, packages=1 + case % 3)
        probe = problem_text(f"p{case}", pddl_name, objects, init, [init[0]])
        walker = None
        if name == "logistics":  # the simulator cannot ground this one: walk a typed twin
            t_objects, _, t_init = logistics_problem(random.Random(case), typed=True,
                                                     cities=2 + case % 2, packages=1 + case % 3)
            objects, types, init = logistics_problem(random.Random(case), typed=False,
                                                     cities=2 + case % 2, packages=1 + case % 3)
            probe = problem_text(f"p{case}", pddl_name, objects, init, [init[0]])
            walker = (PDDL_DATA / "logistics_typed_domain.pddl",
                      problem_text("w", "logistics-typed", t_objects, t_init, [t_init[0]]))
        walk, true_end, false_end = random_walk(PDDL_DATA / file, probe, tmp_path, 10, rng,
                                                walker)
        kind = MUTATIONS[case % len(MUTATIONS)]
        goal = rng.sample(true_end, min(2, len(true_end)))
        if kind == "wrong_goal":  # an atom the walk leaves false
            wrong = false_end or [a.rsplit(" ", 1)[0] + f" {o})" for a in true_end
                                  for o in types if a.rsplit(" ", 1)[0] + f" {o})"
                                  not in true_end and a.startswith("(at ")]
            if not wrong:
                continue
            goal = goal[:1] + [rng.choice(wrong)]
        plan = mutate(walk, kind, types, rng)
        if plan is None:
            continue
        problem = problem_text(f"p{case}", pddl_name, objects, init, goal)
        expected = oracle(tmp_path, domain, problem, plan)
        got = ours(domain, problem, plan)
        assert agree(expected, got), (name, kind, problem, plan, expected, got[1])
        if got[0] != "bad input":
            assert got[0]["engine"] == "strips"
        kinds[kind] += 1
        verdicts[expected[0]] += 1
    assert len(kinds) == len(MUTATIONS) and verdicts[True] >= 2 and verdicts[False] >= 3


def renamed_cases(n: int, seed: int):
    rng = random.Random(seed)
    base = (DATA / "planbench_domain.pddl").read_text()
    for _spelling, problem, plan, kind in generate(n, seed=seed):
        if _spelling != "planbench":
            continue
        renaming = blocks_renaming(rng)
        swapped = rng.random() < 0.5
        if swapped:  # also reorder the parameters of stack
            domain = base.replace(":parameters  (?ob ?underob)\n  :precondition (and (clear "
                                  "?underob) (holding ?ob))",
                                  ":parameters  (?underob ?ob)\n  :precondition (and (clear "
                                  "?underob) (holding ?ob))", 1)
            assert domain != base
            plan = [f"(stack {a.split()[2][:-1]} {a.split()[1]})" if a.startswith("(stack")
                    else a for a in plan]
        else:
            domain = base
        yield rename(domain, renaming), rename(problem, renaming), \
            [rename(a, renaming) for a in plan], kind, swapped


def test_renamed_blocks_worlds_are_native_and_agree(tmp_path):
    kinds: Counter[str] = Counter()
    orders: Counter[bool] = Counter()
    checked = 0
    for domain, problem, plan, kind, swapped in renamed_cases(140, seed=31):
        expected = oracle(tmp_path, domain, problem, plan)
        native = ours(domain, problem, plan)
        strips = ours(domain, problem, plan, engine="strips")
        assert native[0]["engine"] == "blocksworld", domain
        assert native[1] == expected == strips[1], (kind, domain, problem, plan)
        kinds[kind] += 1
        orders[swapped] += 1
        checked += 1
    assert checked >= 30 and len(kinds) >= 5 and orders[True] >= 5 and orders[False] >= 5
