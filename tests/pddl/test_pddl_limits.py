"""The PDDL engine's limits: a step's quantifiers at the documented 1,000,000 bindings
give a verdict (with its counterexample, also when the explanation goes over them once
more), one binding more is refused by name; the command line's CPU budget stops a
check that runs longer, with a structured error."""

from __future__ import annotations

import time

import pytest

from verigraph.pddl import validate_pddl_dict
from verigraph.pddl.formulas import MAX_QUANTIFIED, QuantifierLimitError

pytestmark = pytest.mark.fast

N = 1000  # N * N = MAX_QUANTIFIED
DOMAIN = """(define (domain big) (:requirements :typing :adl)
 (:types obj) (:predicates (p ?x - obj) (q ?x - obj) (done))
 (:action every :parameters () :precondition (forall (?x ?y - obj) (or (p ?x) (q ?y)))
   :effect (done)))"""


def problem(objects: int, missing: str | None = None) -> str:
    names = " ".join(f"o{i}" for i in range(objects))
    atoms = " ".join(f"(p o{i})" for i in range(objects) if f"o{i}" != missing)
    return (f"(define (problem b) (:domain big) (:objects {names} - obj) (:init {atoms}) "
            "(:goal (done)))")


def test_a_step_at_the_binding_limit_is_judged_and_explained():
    assert N * N == MAX_QUANTIFIED
    started = time.process_time()
    assert validate_pddl_dict(DOMAIN, problem(N), "(every)")["valid"]
    report = validate_pddl_dict(DOMAIN, problem(N, missing=f"o{N - 1}"), "(every)")
    spent = time.process_time() - started
    (violation,) = report["violations"]
    assert violation["constraint"] == "precondition_unsatisfied"
    assert f"for ?x = o{N - 1}, ?y = o0: none of (p o{N - 1}), (q o0) holds" \
        in violation["message"]
    assert spent < 20  # about 0.6 s: the bodies are compiled (was some 6 s, then an error)


def test_one_binding_beyond_the_limit_is_refused_by_name():
    with pytest.raises(QuantifierLimitError) as caught:
        validate_pddl_dict(DOMAIN, problem(N + 1), "(every)")
    assert "?x ?y" in caught.value.message and f"{MAX_QUANTIFIED:,}" in caught.value.message
    assert caught.value.fix


ACHIEVER = """(define (domain ach) (:requirements :typing :adl)
 (:types obj) (:predicates (p ?x - obj) (q ?x - obj) (r ?x - obj) (done))
 (:action a :parameters (?x - obj)
   :precondition (and (p ?x) (forall (?y ?z - obj) (or (r ?y) (q ?z)))) :effect (done)))"""


def test_explaining_an_unmet_goal_tries_a_bounded_number_of_quantified_bindings():
    """Every candidate grounding of an achiever evaluates its ADL preconditions: 1,000
    candidates of a forall over a million bindings took minutes; the report's share of
    quantified bindings bounds them (one step's worth)."""
    names = " ".join(f"o{i}" for i in range(N))
    atoms = " ".join(f"(p o{i}) (r o{i})" for i in range(N - 1))
    problem = (f"(define (problem b) (:domain ach) (:objects {names} - obj) (:init {atoms}) "
               "(:goal (done)))")
    started = time.process_time()
    report = validate_pddl_dict(ACHIEVER, problem, "")
    assert time.process_time() - started < 20  # about 0.1 s
    (goal,) = report["unmet_goals"]
    assert goal["achievers"][0]["action"].startswith("(a ")


def test_each_goal_formula_may_try_the_limit_on_its_own():
    goal = "(forall (?x ?y - obj) (or (p ?x) (q ?y)))"
    problem_text = problem(N).replace("(:goal (done))", f"(:goal (and {goal} {goal}))")
    report = validate_pddl_dict(DOMAIN, problem_text, "")
    assert report["valid"]


EFFECTS = DOMAIN.replace(
    "(:action every", "(:action mark :parameters () :precondition (and)\n"
    "   :effect (forall (?x ?y - obj) (when (or (q ?x) (p ?y)) (done))))\n (:action every")


def test_a_conditional_effect_at_the_binding_limit_applies_its_atoms_once():
    started = time.process_time()
    report = validate_pddl_dict(EFFECTS, problem(N), "(mark)")
    assert time.process_time() - started < 20  # about 0.2 s (was 1.2 s and 80 MB)
    assert report["valid"] and report["steps"][0]["edit"]["added"] == ["(done)"]
    with pytest.raises(QuantifierLimitError):
        validate_pddl_dict(EFFECTS, problem(N + 1), "(mark)")


def test_a_quantified_effect_over_a_type_with_no_objects_costs_nothing():
    """Three variables over 1,000 objects and one over none: no binding, and no loop over
    the billion combinations of the others (the count of bindings is 0)."""
    domain = EFFECTS.replace("(:types obj)", "(:types obj none)").replace(
        "(forall (?x ?y - obj) (when", "(forall (?x ?y ?w - obj ?n - none) (when")
    started = time.process_time()
    report = validate_pddl_dict(domain, problem(N), "(mark)")
    assert time.process_time() - started < 5
    assert report["valid"] is False and report["steps"][0]["edit"]["added"] == []
