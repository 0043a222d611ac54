"""The PDDL engine's limits: a step's quantifiers at the documented 1,000,000 bindings
give a verdict (with its counterexample, also when the explanation goes over them once
more), one binding more is refused by name; the command line's CPU budget stops a
check that runs longer, with a structured error."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest

from verigraph.actions.pddl import validate_pddl_dict
from verigraph.actions.pddl.formulas import MAX_QUANTIFIED, QuantifierLimitError
from verigraph.cli import main as verigraph_main
from verigraph.cli import val

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
