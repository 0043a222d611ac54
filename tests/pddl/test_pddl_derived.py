"""Derived predicates (`:derived`): stratified rules recomputed in every state, used in
preconditions, conditional effects and goals, with feedback that says a literal is
derived; refusals of rules that have no meaning. The compiled rule evaluation is checked
against a brute-force evaluation of the rules as written (every binding of the head,
the formula evaluated directly), on states of the psr-middle plans of the IPC corpus."""

from __future__ import annotations

import random
import time
from collections import Counter
from itertools import product
from pathlib import Path
from typing import Any

import pytest

from verigraph.errors import VeriGraphError
from verigraph.pddl import formulas, read_domain, read_problem, validate_pddl_dict
from verigraph.pddl.axioms import DerivedPredicateError, derive
from verigraph.pddl.formulas import Evaluator
from verigraph.pddl.model import Domain, GroundAtom, Problem
from verigraph.pddl.plans import parse_strips_plan
from verigraph.pddl.reader import PddlInputError
from verigraph.pddl.simulate import simulate

pytestmark = pytest.mark.fast

IPC = Path(__file__).parent.parent.parent / "benchmarks" / "data" / "ipc"

DOMAIN = """
(define (domain net)
  (:requirements :typing :adl :derived-predicates)
  (:types node)
  (:constants hub - node)
  (:predicates (link ?a ?b - node) (up ?n - node) (reach ?a ?b - node)
               (isolated ?n - node) (all-reached) (mark ?n - node) (broken ?n - node))
  (:derived (reach ?a ?b - node) (and (up ?a) (up ?b) (link ?a ?b)))
  (:derived (reach ?a ?b - node) (exists (?c - node) (and (reach ?a ?c) (reach ?c ?b))))
  (:derived (isolated ?n - node) (and (up ?n) (not (reach hub ?n)) (not (= ?n hub))))
  (:derived (all-reached) (forall (?n - node) (or (not (up ?n)) (= ?n hub) (reach hub ?n))))
  (:action raise :parameters (?n - node) :precondition (not (up ?n)) :effect (up ?n))
  (:action cut :parameters (?n - node) :precondition (and (up ?n) (not (isolated ?n)))
     :effect (not (up ?n)))
  (:action tag :parameters (?n - node) :precondition (reach hub ?n)
     :effect (and (mark ?n) (when (isolated ?n) (broken ?n))))
  (:action sweep :parameters () :precondition (not (all-reached))
     :effect (forall (?n - node) (when (isolated ?n) (broken ?n)))))
"""

PROBLEM = """
(define (problem p) (:domain net)
  (:objects a b c d - node)
  (:init (up hub) (link hub a) (link a b) (link b c) (link c d))
  (:goal (and (reach hub c) (mark c) (all-reached))))
"""


def brute_force(domain: Domain, problem: Problem, state: set[GroundAtom],
                layers: list[list[str]]) -> set[GroundAtom]:
    """The derived atoms by the rules as written: per layer (a stratum, in order), every
    head binding tried with the formula evaluated directly, until nothing changes."""
    assert domain.axioms is not None
    known = {a for a in state if a[0] not in domain.axioms.predicates}
    for layer in layers:
        grew = True
        while grew:
            grew = False
            ev = Evaluator(domain, problem, known)
            for pred in layer:
                for d in domain.axioms.definitions[pred]:
                    lists = [problem.of_type(domain, t) for t in d.head_types]
                    for objs in product(*lists):
                        atom = (pred, *objs)
                        if atom in known:
                            continue
                        slots: list[str | None] = [*objs,
                                                   *([None] * (len(d.slot_names) - len(objs)))]
                        if ev.holds(d.formula, slots):
                            known.add(atom)
                            grew = True
    return {a for a in known if a[0] in domain.axioms.predicates}


def test_rules_recursion_negation_and_forall_match_brute_force() -> None:
    domain = read_domain(DOMAIN)
    problem = read_problem(PROBLEM, domain)
    layers = [["reach"], ["isolated", "all-reached"]]
    states = [set(problem.init)]
    for ups in (["a"], ["a", "b"], ["a", "c"], ["a", "b", "c", "d"], ["b", "d"]):
        states.append(set(problem.init) | {("up", n) for n in ups})
    for state in states:
        assert derive(domain, problem, state) == brute_force(domain, problem, state, layers)
    full = derive(domain, problem, states[4])
    assert ("reach", "hub", "d") in full  # three links deep
    assert ("all-reached",) in full
    isolated = derive(domain, problem, states[5])
    assert ("isolated", "b") in isolated and ("isolated", "d") in isolated
    assert ("all-reached",) not in isolated


def test_psr_middle_derived_atoms_match_brute_force_along_the_plan() -> None:
    folder = IPC / "psr-middle"
    domain = read_domain((folder / "domain.pddl").read_text())
    assert domain.axioms is not None
    layers = [["upstream", "unsafe"], ["affected", "fed"]]
    checked = 0
    for plan_file in sorted(folder.glob("*.plan")):
        problem = read_problem((folder / f"{plan_file.stem}.pddl").read_text(), domain)
        steps = parse_strips_plan(plan_file.read_text(), domain)
        for k in range(len(steps) + 1):  # every state the plan goes through
            report = simulate(domain, problem, steps[:k])
            assert report["plan_valid"], report["violations"][:1]
            final = {tuple(a.strip("()").split()) for a in report["final_state"]}
            basic = {a for a in final if a[0] not in domain.axioms.predicates}
            got = {a for a in final if a[0] in domain.axioms.predicates}
            assert derive(domain, problem, basic) == got
            if k in (0, len(steps)) and (k == 0) == (checked == 0):  # 1 s each
                assert got == brute_force(domain, problem, basic, layers)
            checked += 1
        assert report["valid"]
        assert any(a[0] == "fed" for a in final)
    assert checked >= 4


def test_valid_plan_and_derived_precondition_feedback() -> None:
    assert validate_pddl_dict(DOMAIN, PROBLEM, "(raise a)\n(raise b)\n(raise c)\n(tag c)\n"
                              )["valid"]
    report = validate_pddl_dict(DOMAIN, PROBLEM, "(raise a)\n(raise c)\n(tag c)\n")
    assert not report["valid"]
    violation = report["violations"][0]
    assert violation["step"] == 3
    item = violation["unsatisfied"][0]
    assert item["literal"] == "(reach hub c)"
    assert item["derived"] == ["reach"]
    assert "is derived" in item["explanation"]
    assert "(up b) is false" in item["explanation"] or "(link hub c) is false" in \
        item["explanation"]


def test_derived_goal_made_false_by_a_step_is_reported_with_that_step() -> None:
    plan = "(raise a)\n(raise b)\n(raise c)\n(raise d)\n(tag c)\n(cut c)\n"
    report = validate_pddl_dict(DOMAIN, PROBLEM, plan)
    assert report["plan_valid"] and not report["goal_reached"]
    unmet = {g["literal"]: g for g in report["unmet_goals"]}
    goal = unmet["(reach hub c)"]
    assert goal["derived"] == ["reach"]
    assert goal["last_changed"] == {"step": 6, "action": "(cut c)"}
    assert "(up c) is false" in goal["explanation"]
    # d hangs off c: cutting c isolates d, and (all-reached) fails with it
    assert unmet["(all-reached)"]["last_changed"]["step"] == 6


def test_negated_derived_precondition_and_derived_effect_condition() -> None:
    # (cut c) with d up behind it isolates d; (sweep) needs (not (all-reached)) and
    # marks every isolated node broken through a conditional effect
    domain = read_domain(DOMAIN)
    problem_text = PROBLEM.replace("(:goal (and (reach hub c) (mark c) (all-reached)))",
                                   "(:goal (and (broken d) (not (broken b))))")
    plan = "(raise a)\n(raise b)\n(raise c)\n(raise d)\n(cut c)\n(sweep)\n"
    assert validate_pddl_dict(DOMAIN, problem_text, plan)["valid"]
    early = validate_pddl_dict(DOMAIN, problem_text, "(raise a)\n(sweep)\n")
    assert early["violations"][0]["step"] == 2  # everything up is reached: no sweep
    assert "all-reached" in early["violations"][0]["message"]
    # isolated d cannot be cut: (not (isolated d)) is false
    stuck = validate_pddl_dict(DOMAIN, problem_text,
                               "(raise a)\n(raise b)\n(raise d)\n(cut d)\n")
    item = stuck["violations"][0]["unsatisfied"][0]
    assert item["literal"] == "(not (isolated d))" and item["derived"] == ["isolated"]
    assert domain.axioms is not None and "isolated" not in domain.static


def test_unstratifiable_rules_are_refused_by_name() -> None:
    bad = DOMAIN.replace("(:derived (isolated ?n - node) (and (up ?n) (not (reach hub ?n)) "
                         "(not (= ?n hub))))",
                         "(:derived (isolated ?n - node) (and (up ?n) (not (reach hub ?n))))\n"
                         "  (:derived (reach ?a ?b - node) (and (up ?a) (isolated ?b)))")
    with pytest.raises(DerivedPredicateError) as err:
        read_domain(bad)
    assert err.value.field == "domain"
    assert err.value.value in ("isolated", "reach")
    assert "stratif" in err.value.message and err.value.fix
    # negation through a forall counts: p := forall x. p'(x) with p' := not p
    loop = """(define (domain l) (:requirements :adl :derived-predicates)
      (:predicates (p) (q ?x) (r ?x))
      (:derived (p) (forall (?x) (q ?x)))
      (:derived (q ?x) (and (r ?x) (not (p))))
      (:action a :parameters (?x) :precondition (p) :effect (r ?x)))"""
    with pytest.raises(DerivedPredicateError, match="stratified"):
        read_domain(loop)


@pytest.mark.parametrize(("domain", "problem", "match", "value"), [
    (DOMAIN.replace("(:action raise :parameters (?n - node) :precondition (not (up ?n)) "
                    ":effect (up ?n))",
                    "(:action raise :parameters (?n - node) :precondition (not (up ?n)) "
                    ":effect (and (up ?n) (reach hub ?n)))"), PROBLEM,
     "changes derived predicate reach", "reach"),
    (DOMAIN, PROBLEM.replace("(up hub)", "(up hub) (reach hub a)"),
     "derived predicate reach", "reach"),
    (DOMAIN.replace("(:derived (all-reached)", "(:derived (everything)"), PROBLEM,
     "not declared", "everything"),
    (DOMAIN.replace("(:derived (isolated ?n - node)", "(:derived (isolated ?n ?m - node)"),
     PROBLEM, "variable", "isolated"),
])
def test_malformed_derived_rules_are_refused(domain: str, problem: str, match: str,
                                             value: str) -> None:
    with pytest.raises(VeriGraphError, match=match) as err:
        validate_pddl_dict(domain, problem, "(raise a)\n")
    assert err.value.value == value and err.value.fix


def test_glued_variable_reads_as_in_val() -> None:
    # IPC 2002 zenotravel writes (aircraft?a): '?' cannot be part of a name
    folder = IPC / "zenotravel"
    text = (folder / "domain.pddl").read_text()
    assert "(aircraft?a)" in text
    domain = read_domain(text)
    assert ("aircraft", (0,)) in domain.schemas["refuel"].pre_pos
    with pytest.raises(PddlInputError, match="does not declare"):
        read_domain(text.replace("(aircraft?a)", "(aircraft?undeclared)"))
    plan = (folder / "p01.plan").read_text()
    assert validate_pddl_dict(text, (folder / "p01.pddl").read_text(), plan)["valid"]


def test_predicate_changed_only_by_conditional_effects_is_not_fixed() -> None:
    # (broken ?n) is set only under `when`: an unmet goal on it is not "fixed"
    domain = read_domain(DOMAIN)
    assert "broken" not in domain.static and "link" in domain.static
    problem_text = PROBLEM.replace("(:goal (and (reach hub c) (mark c) (all-reached)))",
                                   "(:goal (broken b))")
    report = validate_pddl_dict(DOMAIN, problem_text, "(raise a)\n")
    goal = report["unmet_goals"][0]
    assert goal["literal"] == "(broken b)"
    assert not goal.get("fixed") and "no action changes" not in goal["explanation"]


# -- quantifiers over a type with no objects ------------------------------------------------

EMPTY = """
(define (domain tools) (:requirements :typing :adl :derived-predicates)
  (:types tool thing)
  (:predicates (ready) (ok ?x - thing) (has ?t - tool) (done)
               (usable) (vacuous) (all-have) (some-same) (fits ?x - thing) (nested)
               (none-ready))
  (:derived (usable) (exists (?t - tool) (ready)))
  (:derived (vacuous) (forall (?t - tool) (not (ready))))
  (:derived (all-have) (forall (?t - tool) (has ?t)))
  (:derived (some-same) (exists (?t - tool) (= ?t ?t)))
  (:derived (fits ?x - thing) (exists (?t - tool) (ok ?x)))
  (:derived (nested) (exists (?t - tool) (forall (?x - thing) (ready))))
  (:derived (none-ready) (not (exists (?t - tool) (ready))))
  (:action go :parameters () :precondition (and) :effect (done)))
"""


def _derived_in_init(objects: str) -> set[GroundAtom]:
    domain = read_domain(EMPTY)
    problem = read_problem(f"(define (problem p) (:domain tools) (:objects {objects}) "
                           "(:init (ready) (ok x)) (:goal (done)))", domain)
    return derive(domain, problem, set(problem.init))


def test_a_quantifier_over_a_type_with_no_objects_in_a_derived_rule() -> None:
    """PDDL: `exists` over no objects is false and `forall` true, also when no literal
    of the body mentions the variable (it must not be dropped)."""
    none = _derived_in_init("x - thing")
    assert none == {("vacuous",), ("all-have",), ("none-ready",)}
    one = _derived_in_init("x - thing h - tool")
    assert one == {("usable",), ("some-same",), ("fits", "x"), ("nested",)}
    goal = ("(define (problem p) (:domain tools) (:objects x - thing) (:init (ready)) "
            "(:goal {}))")
    assert not validate_pddl_dict(EMPTY, goal.format("(usable)"), "(go)")["valid"]
    assert validate_pddl_dict(EMPTY, goal.format("(vacuous)"), "(go)")["valid"]


QUANTIFIED = """
(define (domain q) (:requirements :typing :adl)
  (:types tool thing)
  (:predicates (ready) (done) (flag) (has ?t - tool))
  (:action some :parameters () :precondition (exists (?t - tool) (ready)) :effect (done))
  (:action every :parameters () :precondition (forall (?t - tool) (not (ready)))
     :effect (done))
  (:action when-each :parameters () :precondition (and)
     :effect (forall (?t - tool) (when (ready) (flag))))
  (:action each :parameters () :precondition (and) :effect (forall (?t - tool) (flag)))
  (:action joined :parameters () :precondition (and)
     :effect (forall (?t - tool) (when (and (ready) (not (has ?t))) (flag)))))
"""


@pytest.mark.parametrize(("objects", "plan", "goal", "valid"), [
    ("x - thing", "(some)", "(done)", False),  # exists over no tool: false
    ("x - thing h - tool", "(some)", "(done)", True),
    ("x - thing", "(every)", "(done)", True),  # forall over no tool: true
    ("x - thing h - tool", "(every)", "(done)", False),
    ("x - thing", "(when-each)", "(not (flag))", True),  # no binding: no effect
    ("x - thing", "(each)", "(not (flag))", True),
    ("x - thing", "(joined)", "(not (flag))", True),
    ("x - thing h - tool", "(joined)", "(flag)", True),
    ("x - thing", "", "(exists (?t - tool) (ready))", False),
    ("x - thing", "", "(forall (?t - tool) (not (ready)))", True),
    ("x - thing h - tool", "", "(forall (?t - tool) (not (ready)))", False),
])
def test_a_quantifier_over_no_objects_in_preconditions_effects_and_goals(
        objects: str, plan: str, goal: str, valid: bool) -> None:
    problem = (f"(define (problem p) (:domain q) (:objects {objects}) (:init (ready)) "
               f"(:goal {goal}))")
    assert validate_pddl_dict(QUANTIFIED, problem, plan)["valid"] is valid
    stepwise = validate_pddl_dict(QUANTIFIED, problem, plan, all_errors=True)
    assert stepwise["valid"] is valid


def _formula(rng: random.Random, scope: list[tuple[str, str]], depth: int) -> str:
    """A random ADL formula over the basic predicates of `RANDOM_DOMAIN` (variables in
    `scope` with their types), quantifiers over a type that may have no objects."""
    def term(kind: str) -> str:
        fitting = [v for v, t in scope if t == kind]
        return rng.choice(fitting + (["a0"] if kind == "A" else []))

    roll = rng.random()
    if depth <= 0 or roll < 0.3:
        pick = rng.randrange(4)
        if pick == 0:
            return "(p)"
        if pick == 1:
            return f"(q {term('A')})"
        if pick == 2 and any(t == "B" for _, t in scope):
            return f"(r {term('A')} {term('B')})"
        if scope:
            a, b = rng.choice(scope)[0], rng.choice(scope)[0]
            return f"(= {a} {b})"
        return "(p)"
    if roll < 0.45:
        return f"(not {_formula(rng, scope, depth - 1)})"
    if roll < 0.6:
        head = rng.choice(["and", "or"])
        return f"({head} {_formula(rng, scope, depth - 1)} {_formula(rng, scope, depth - 1)})"
    if roll < 0.7:
        return f"(imply {_formula(rng, scope, depth - 1)} {_formula(rng, scope, depth - 1)})"
    kind = rng.choice(["A", "B"])
    name = f"?v{len(scope)}"
    head = rng.choice(["exists", "forall"])
    return f"({head} ({name} - {kind}) {_formula(rng, [*scope, (name, kind)], depth - 1)})"


def _truth(f: Any, binding: list[str | None], state: set[GroundAtom], problem: Problem,
           domain: Domain) -> bool:
    """The formula's truth by its definition, written independently of the evaluators
    under test: atoms looked up, quantifiers tried over every object of their type."""
    kind = f[0]
    if kind == "atom":
        pred, terms = f[1]
        args = [binding[t] if isinstance(t, int) else t for t in terms]
        return args[0] == args[1] if pred == "=" else (pred, *args) in state
    if kind == "not":
        return not _truth(f[1], binding, state, problem, domain)
    if kind == "and":
        return all(_truth(g, binding, state, problem, domain) for g in f[1])
    if kind == "or":
        return any(_truth(g, binding, state, problem, domain) for g in f[1])
    if kind == "imply":
        return (not _truth(f[1], binding, state, problem, domain)
                or _truth(f[2], binding, state, problem, domain))
    results = []
    lists = [[o for o, t in problem.objects.items() if domain.is_a(t, k)] for _, _, k in f[1]]
    for objs in product(*lists):
        inner = list(binding)
        for (slot, _, _), obj in zip(f[1], objs, strict=True):
            inner[slot] = obj
        results.append(_truth(f[2], inner, state, problem, domain))
    return any(results) if kind == "exists" else all(results)


@pytest.mark.parametrize("compile_from", [formulas.COMPILE_FROM, 1])
def test_random_quantified_rules_agree_with_their_definition_when_a_type_may_be_empty(
        compile_from: int, monkeypatch: pytest.MonkeyPatch) -> None:
    """Random rule bodies (and, or, not, imply, equality, exists and forall over a type
    that has objects or none): the compiled derivation and the precondition evaluator
    (its quantifiers' bodies interpreted, or compiled into closures as over many
    bindings) give the truth value of the formula by definition."""
    monkeypatch.setattr(formulas, "COMPILE_FROM", compile_from)
    rng = random.Random(43)
    compared: Counter[tuple[bool, bool]] = Counter()
    for _ in range(40):
        bodies = [_formula(rng, [("?h", "A")] if k % 2 else [], 3) for k in range(8)]
        rules = "\n".join(f"(:derived (d{k}{' ?h - A' if k % 2 else ''}) {body})"
                          for k, body in enumerate(bodies))
        heads = " ".join(f"(d{k}{' ?h - A' if k % 2 else ''})" for k in range(8))
        text = (f"(define (domain rnd) (:requirements :typing :adl :derived-predicates) "
                f"(:types A B) (:constants a0 - A) "
                f"(:predicates (p) (q ?x - A) (r ?x - A ?y - B) {heads}) "
                f"{rules} (:action noop :parameters () :precondition (and) :effect (p)))")
        domain = read_domain(text)
        assert domain.axioms is not None
        a_objects = ["a0"] + [f"a{i}" for i in range(1, rng.randint(1, 3))]
        b_objects = [f"b{i}" for i in range(rng.choice([0, 0, 1, 2]))]
        objects = " ".join(a_objects[1:]) + " - A " + (" ".join(b_objects) + " - B"
                                                   if b_objects else "")
        atoms = ["(p)"] * rng.randint(0, 1) + [f"(q {a})" for a in a_objects if rng.random() < 0.5]
        atoms += [f"(r {a} {b})" for a in a_objects for b in b_objects if rng.random() < 0.5]
        problem = read_problem(f"(define (problem x) (:domain rnd) (:objects {objects}) "
                               f"(:init {' '.join(atoms)}) (:goal (and)))", domain)
        state = set(problem.init)
        got = derive(domain, problem, state)
        for k in range(8):
            (d,) = domain.axioms.definitions[f"d{k}"]
            heads_of = [(o,) for o in a_objects] if k % 2 else [()]
            for head in heads_of:
                slots: list[str | None] = [*head, *([None] * (len(d.slot_names) - len(head)))]
                want = _truth(d.formula, list(slots), state, problem, domain)
                assert ((f"d{k}", *head) in got) is want, (bodies[k], head, objects, atoms)
                ev = Evaluator(domain, problem, state)
                assert ev.holds(d.formula, list(slots)) is want, (bodies[k], head)
                compared[want, bool(b_objects)] += 1
    assert min(compared.values()) >= 20, compared


# -- rule bodies that expand a lot ------------------------------------------------------------

def _expanding(body: str, rules: int = 1) -> str:
    preds = " ".join(f"(a{i}) (b{i}) (c{i} ?x) (e{i} ?x)" for i in range(64))
    derived = "\n".join(f"(:derived (z{k}) {body.replace('K', str(k))})" for k in range(rules))
    heads = " ".join(f"(z{k})" for k in range(rules))
    return (f"(define (domain blow) (:requirements :adl :derived-predicates) "
            f"(:predicates {preds} {heads} (done)) {derived} "
            "(:action go :parameters () :precondition (and) :effect (done)))")


def _any(letter: str) -> str:
    return "(or " + " ".join(f"({letter}{i})" for i in range(64)) + ")"


def test_a_body_beyond_the_conjunction_limit_is_refused_before_it_is_built() -> None:
    """(and X Y) of two halves of 4,096 conjunctions each: refused by the count, not
    after building 16.7 million (1.7 GB, 6 s)."""
    body = f"(and (and {_any('a')} {_any('b')}) (and {_any('a')} {_any('b')}))"
    started = time.process_time()
    with pytest.raises(DerivedPredicateError, match="4,096 conjunctions") as caught:
        read_domain(_expanding(body))
    assert time.process_time() - started < 2 and caught.value.value == "z0"
    union = "(or " + " ".join([f"(and {_any('a')} {_any('b')})"] * 3) + ")"
    with pytest.raises(DerivedPredicateError, match="4,096 conjunctions"):
        read_domain(_expanding(union))


def test_a_forall_in_many_conjunctions_is_compiled_once() -> None:
    """A forall whose negation has 4,096 conjunctions, in a body of 4,096 conjunctions:
    one auxiliary predicate (8,192 rules), not 4,096 of them (16.7 million rules)."""
    inner = "(or " + " ".join(f"(and (c{i} ?x) (e{i} ?x))" for i in range(12)) + ")"
    body = f"(and {_any('a')} {_any('b')} (forall (?x) {inner}))"
    domain = read_domain(_expanding(body))
    assert domain.axioms is not None
    assert sum(len(group) for group, _ in domain.axioms.strata) == 2 * 4096
    with pytest.raises(DerivedPredicateError, match="16,384 conjunctive rules"):
        read_domain(_expanding(f"(forall (?x) {inner})",
                               rules=5))


def test_a_step_that_changes_nothing_the_rules_read_costs_no_derivation(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """(tag c) adds (mark c), which no rule reads: no stratum is evaluated and no derived
    atom is touched (with a million derived atoms such a step took 0.3 s)."""
    from verigraph.pddl import axioms

    domain = read_domain(DOMAIN)
    problem = read_problem(PROBLEM, domain)
    state = set(problem.init) | {("up", n) for n in "abcd"}
    followed = axioms.Derivation(domain, problem, state)
    state |= followed.atoms
    evaluated: list[int] = []
    real = axioms._stratum
    monkeypatch.setattr(axioms, "_stratum", lambda *a: evaluated.append(1) or real(*a))
    monkeypatch.setattr(axioms.Index, "add", lambda *a: evaluated.append(2))
    before = set(followed.atoms)
    state.add(("mark", "c"))
    followed.follow(state, [], [("mark", "c")], {}, 1, "(tag c)")
    assert evaluated == [] and followed.atoms == before


def test_a_long_conjunction_is_compiled_in_linear_time() -> None:
    """A rule body of 60,000 literals: each conjunction is built once and the join plan
    drops literals without list.remove (growing the conjunction part by part made
    200,000 literals take 36 s)."""
    n = 60_000
    body = "(and " + " ".join("(p)" for _ in range(n)) + ")"
    text = ("(define (domain flat) (:requirements :adl :derived-predicates) "
            f"(:predicates (p) (z) (done)) (:derived (z) {body}) "
            "(:action go :parameters () :precondition (and) :effect (done)))")
    started = time.process_time()
    domain = read_domain(text)
    problem = read_problem("(define (problem p) (:domain flat) (:init (p)) (:goal (z)))",
                           domain)
    assert derive(domain, problem, set(problem.init)) == {("z",)}
    assert time.process_time() - started < 5  # about 1 s (was about 9 s)
