"""A schema's generated grounding (actions.pddl.fastground) gives exactly the ground
action the closures give, for every binding: types, static and equality preconditions
of both signs, constants, costs from static functions, and the bindings that make two
effect literals one atom (handed back to the closures); and a plan's report is the same
whichever grounds its actions."""

from __future__ import annotations

import importlib
import itertools
import json
from pathlib import Path

import pytest

from verigraph.pddl import read_domain, read_problem, validate_strips_dict
from verigraph.pddl.fastground import UNUSUAL, ground_function
from verigraph.pddl.plans import Step
from verigraph.pddl.simulate import cached_strips_domain, cached_strips_problem

pytestmark = pytest.mark.fast
simulate = importlib.import_module("verigraph.pddl.simulate")  # not the function
fastground = importlib.import_module("verigraph.pddl.fastground")
IPC = Path(__file__).parents[2] / "benchmarks" / "data" / "ipc"

DOMAIN = """(define (domain shop) (:requirements :typing :equality :negative-preconditions
  :action-costs)
 (:types item place - object crate - item)
 (:constants home - place)
 (:predicates (at ?i - item ?p - place) (road ?a ?b - place) (closed ?p - place)
              (held ?i - item) (free) (seen ?p - place))
 (:functions (total-cost) - number (dist ?a ?b - place) - number)
 (:action carry :parameters (?i - item ?a ?b - place)
  :precondition (and (at ?i ?a) (road ?a ?b) (not (closed ?b)) (not (= ?a ?b)) (free))
  :effect (and (not (at ?i ?a)) (at ?i ?b) (seen ?b) (seen home)
               (increase (total-cost) (dist ?a ?b)) (increase (total-cost) 2)))
 (:action swap :parameters (?i ?j - item ?p - place)
  :precondition (and (at ?i ?p) (= ?p home))
  :effect (and (not (at ?i ?p)) (not (at ?j ?p)) (at ?j ?p) (held ?i) (held ?j)))
 (:action rest :parameters () :precondition (free) :effect (and (not (free)) (free))))"""

PROBLEM = """(define (problem p) (:domain shop)
 (:objects box - crate pen - item shed yard - place)
 (:init (at box home) (at pen shed) (free) (road home shed) (road shed yard)
        (road yard yard) (road shed home) (closed yard)
        (= (dist home shed) 3) (= (dist shed home) 4) (= (dist yard yard) 0))
 (:goal (and (at box shed))))"""


def test_every_binding_grounds_as_the_closures_ground_it() -> None:
    domain = read_domain(DOMAIN)
    problem = read_problem(PROBLEM, domain)
    names = [*problem.objects, "nosuch"]
    seen = {"action": 0, "none": 0, "unusual": 0}
    for schema in domain.schemas.values():
        fast = simulate._Compiled(domain, problem, schema)
        generated = ground_function(schema, domain.static | {"="}, fast.checks)
        assert generated is not None
        for binding in itertools.product(names, repeat=len(schema.params)):
            got = generated(binding, problem.init, problem.values, fast.admits)
            fast.generated = None  # the closures, from the same compiled schema
            want = simulate._ground_action(domain, problem, fast, Step(schema.name, binding, 1))
            if got is UNUSUAL:
                seen["unusual"] += 1
                assert want is not None
                continue
            seen["action" if got is not None else "none"] += 1
            assert got == want, (schema.name, binding)
    # each outcome happens: ground actions, refusals, and effects that coincide
    assert min(seen.values()) > 0, seen


def test_a_name_cannot_become_code() -> None:
    """Names reach the generated source only through repr."""
    hostile = "a')or(__import__('os').system('false')#"
    domain = read_domain(DOMAIN)
    schema = domain.schemas["carry"]
    schema.add.append(("held", (hostile,)))
    ground = ground_function(schema, domain.static | {"="}, None)
    assert ground is not None
    problem = read_problem(PROBLEM, domain)
    admits = [frozenset(problem.of_type(domain, t)) for t in schema.types]
    got = ground(("box", "home", "shed"), problem.init, problem.values, admits)
    assert ("held", hostile) in got[3] and f"(held {hostile})" in got[4]["added"]


@pytest.mark.parametrize("plan_file", sorted(IPC.glob("*/*.plan"))[1::4],
                         ids=lambda p: p.parent.name + "/" + p.stem)
def test_a_plan_gets_one_report_whichever_grounds_its_actions(
        plan_file: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    domain_file = plan_file.with_suffix(".domain.pddl")
    if not domain_file.exists():
        domain_file = plan_file.parent / "domain.pddl"
    domain_text, problem_text = domain_file.read_text(), plan_file.with_suffix(".pddl").read_text()
    lines = plan_file.read_text().splitlines()
    plans = ["\n".join(lines), "\n".join(lines[:len(lines) // 2] + lines[len(lines) // 2 + 1:])]
    reports = []
    for after in (10**9, 1):  # the closures only; generated from the first action
        monkeypatch.setattr(fastground, "GENERATE_AFTER", after)
        cached_strips_domain.cache_clear()
        cached_strips_problem.cache_clear()
        reports.append([json.dumps(validate_strips_dict(domain_text, problem_text, plan),
                                   sort_keys=True) for plan in plans])
    cached_strips_domain.cache_clear()
    cached_strips_problem.cache_clear()
    assert reports[0] == reports[1]


def test_the_function_is_made_once_a_domains_problems_have_grounded_enough() -> None:
    """A plan checked once with few distinct actions pays no compilation; the domain's
    count goes on across its problems (a batch, a server), and the function is kept."""
    domain_text = (IPC / "visitall" / "domain.pddl").read_text()
    cells = [f"c{k}" for k in range(41)]
    init = " ".join(f"(connected {a} {b}) (connected {b} {a})"
                    for a, b in zip(cells, cells[1:], strict=False))

    def problem(start: int) -> str:
        return (f"(define (problem p{start}) (:domain grid-visit-all) (:objects "
                f"{' '.join(cells)} - place) (:init (at-robot c{start}) (visited c{start}) "
                f"{init}) (:goal (and (visited c{start + 20}))))")

    def walk(start: int) -> str:
        return "\n".join(f"(move c{k} c{k + 1})" for k in range(start, start + 20))

    cached_strips_domain.cache_clear()
    cached_strips_problem.cache_clear()
    assert validate_strips_dict(domain_text, problem(0), walk(0))["valid"]
    generated = cached_strips_domain(domain_text).compiled["ground move"]
    assert generated.function is None and generated.waiting == fastground.GENERATE_AFTER - 20
    assert validate_strips_dict(domain_text, problem(20), walk(20))["valid"]
    assert generated.function is not None  # the 32nd action of the schema made it
    assert cached_strips_domain(domain_text).compiled["ground move"] is generated
