"""ADL plans (or, imply, exists, forall, conditional and universal effects, quantified
goals) against unified-planning's SequentialPlanValidator, and the feedback they get."""

from __future__ import annotations

import random
from collections import Counter

import pytest

from pddl_corpus import PDDL_DATA, oracle, random_walk
from verigraph.pddl import validate_pddl_dict
from verigraph.reporting import report_text

DOMAIN_FILE = PDDL_DATA / "briefcase_adl_domain.pddl"
DOMAIN = DOMAIN_FILE.read_text()


def problem(rng: random.Random, locations: int, objects: int, goal_kind: int) -> str:
    locs = [f"l{i}" for i in range(locations)]
    objs = [f"o{i}" for i in range(objects)]
    init = [f"(at-b {rng.choice(locs)})", f"(key {objs[0]})"]
    init += [f"(at {o} {rng.choice(locs)})" for o in objs]
    init += [f"(road l{i} l{i + 1})" for i in range(locations - 1)]
    if rng.random() < 0.5:
        init.append("(locked)")
    goal = [f"(forall (?p - portable) (at ?p {rng.choice(locs)}))",
            f"(and (or (at o1 l0) (at o1 {locs[-1]})) (not (locked)))",
            f"(exists (?p - portable) (and (in ?p) (at ?p {rng.choice(locs)})))",
            f"(and (imply (in o0) (locked)) (at {rng.choice(objs)} {rng.choice(locs)}))",
            f"(not (exists (?p - portable) (and (key ?p) (at ?p {rng.choice(locs)}))))"][goal_kind]
    return (f"(define (problem p) (:domain briefcase) (:objects {' '.join(locs)} - location "
            f"{' '.join(objs)} - portable) (:init {' '.join(init)}) (:goal {goal}))")


def mutate(plan: list[str], rng: random.Random) -> list[str]:
    plan = list(plan)
    kind = rng.randrange(4)
    if kind == 1 and plan:
        del plan[rng.randrange(len(plan))]
    elif kind == 2 and len(plan) > 1:
        i = rng.randrange(len(plan) - 1)
        plan[i], plan[i + 1] = plan[i + 1], plan[i]
    elif kind == 3 and plan:
        plan.insert(rng.randrange(len(plan)), rng.choice(["(unlock)", "(take-out o0)"]))
    return plan


def test_adl_verdicts_and_failing_steps_agree_with_unified_planning(tmp_path):
    rng = random.Random(11)
    verdicts: Counter[object] = Counter()
    for case in range(60):
        locations, objects = rng.randint(2, 4), rng.randint(2, 3)
        text = problem(rng, locations, objects, case % 5)
        walk, _, _ = random_walk(DOMAIN_FILE, text, tmp_path, rng.randint(2, 8), rng)
        plan = mutate(walk, rng) if case % 2 else walk
        expected = oracle(tmp_path, DOMAIN, text, plan)
        report = validate_pddl_dict(DOMAIN, text, "\n".join(plan))
        v = report["violations"]
        assert (report["valid"], v[0]["step"] if v else None) == expected, (
            text, plan, report_text(report))
        assert report["engine"] == "strips"
        verdicts[expected[0], expected[1] is None] += 1
    assert verdicts[True, True] >= 3 and verdicts[False, True] >= 5 and verdicts[False, False] >= 5


P = ("(define (problem p) (:domain briefcase) (:objects l0 l1 l2 - location o0 o1 - portable)"
     " (:init (at-b l0) (at o0 l0) (at o1 l1) (key o0) (road l0 l1) (road l1 l2) (locked))"
     " (:goal (and (forall (?p - portable) (at ?p l2)) (not (locked)))))")


def test_adl_feedback_names_the_condition_and_a_counterexample():
    r = validate_pddl_dict(DOMAIN, P, "(move l0 l1)")
    (u,) = r["violations"][0]["unsatisfied"]
    assert u["literal"] == "(imply (locked) (exists (?k - portable) (and (key ?k) (in ?k))))"
    assert u["explanation"].startswith("(locked) holds but no ?k - portable makes")
    r = validate_pddl_dict(DOMAIN, P, "(put-in o0 l0)\n(move l0 l1)\n(put-in o1 l1)\n"
                           "(move l1 l2)\n(take-out o0)")
    assert r["plan_valid"] and not r["goal_reached"]
    assert sorted(r["steps"][3]["edit"]["added"]) == ["(at o0 l2)", "(at o1 l2)", "(at-b l2)"]
    assert r["steps"][4]["edit"]["added"] == []  # (locked) already holds: the when fires
    assert r["unmet_goals"][0]["literal"] == "(not (locked))"
    fine = validate_pddl_dict(DOMAIN, P, "(put-in o0 l0)\n(move l0 l1)\n(put-in o1 l1)\n"
                              "(move l1 l2)\n(take-out o0)\n(unlock)")
    assert fine["valid"], report_text(fine)
    missed = validate_pddl_dict(DOMAIN, P, "(put-in o0 l0)\n(move l0 l1)\n(take-out o0)\n"
                                "(unlock)")
    (goal,) = missed["unmet_goals"]
    assert goal["literal"] == "(forall (?p - portable) (at ?p l2))"
    assert goal["explanation"] == ("2 counterexamples: for ?p = o0: (at o0 l2) is false; "
                                   "for ?p = o1: (at o1 l2) is false")  # every one named
    text = report_text(missed)
    assert "(forall (?p - portable) (at ?p l2)): 2 counterexamples: for ?p = o0" in text


@pytest.mark.parametrize("edit,requirement", [
    (lambda d: d.replace("(:action unlock", "(:constraints (always (locked)))\n (:action unlock"),
     ":constraints"),
])
def test_what_stays_unsupported_is_refused_by_name(edit, requirement):
    with pytest.raises(Exception, match=requirement):
        validate_pddl_dict(edit(DOMAIN), P, "")
