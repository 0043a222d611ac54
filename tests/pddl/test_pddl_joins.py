"""Joins where they replace enumeration, against the enumeration they replace.

A quantified conditional effect joined over the static predicates (`CondEffect.join`)
gives exactly the atoms that trying every binding gives; derived atoms kept up to date
step by step (`Derivation.follow`: an index that follows the edits, strata evaluated only
when a predicate they read changed) equal the atoms derived from scratch. Both are
checked in every state of the shipped IPC plans (benchmarks/data/ipc) that use them.
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

from verigraph.pddl import read_domain, read_problem
from verigraph.pddl.axioms import Derivation, derive
from verigraph.pddl.joins import Index
from verigraph.pddl.model import Domain, GroundAtom, Problem
from verigraph.pddl.plans import Step, parse_strips_plan
from verigraph.pddl.simulate import _adl_step

pytestmark = pytest.mark.fast

IPC = Path(__file__).parents[2] / "benchmarks" / "data" / "ipc"


def _domain_file(plan: Path) -> Path:
    own = plan.with_suffix(".domain.pddl")
    return own if own.exists() else plan.parent / "domain.pddl"


def _plans(wanted: str) -> list[Path]:
    """The shipped plans whose domain text mentions `wanted` (a cheap filter, read
    once per folder)."""
    out = []
    for folder in sorted(p for p in IPC.iterdir() if p.is_dir()):
        plans = sorted(folder.glob("*.plan"))
        if plans and wanted in _domain_file(plans[0]).read_text().lower():
            out += plans
    return out


def _walk(domain: Domain, problem: Problem, steps: list[Step]):  # type: ignore[no-untyped-def]
    """(step, state before it) along a valid plan, deletes before adds, derived atoms
    derived from scratch in every state."""
    basic = set(problem.init)
    for step in steps:
        state = basic | derive(domain, problem, basic) if domain.axioms else basic
        yield step, state
        schema = domain.schemas[step.name]
        effects = _adl_step(domain, problem, schema, step.args, state) \
            if schema.cond_effects or schema.pre_complex else ([], [])
        assert effects is not None, step
        dels = [schema.ground(lit, step.args) for lit in schema.delete] + effects[1]
        adds = [schema.ground(lit, step.args) for lit in schema.add] + effects[0]
        basic = (basic - set(dels)) | set(adds)


JOINED = [p for p in _plans("forall") if any(
    e.join is not None for s in read_domain(_domain_file(p).read_text()).schemas.values()
    for e in s.cond_effects)]


@pytest.mark.parametrize("plan", JOINED, ids=lambda p: f"{p.parent.name}/{p.stem}")
def test_a_joined_conditional_effect_gives_the_atoms_of_every_binding(plan: Path) -> None:
    text = _domain_file(plan).read_text()
    joined, enumerated = read_domain(text), read_domain(text)
    for schema in enumerated.schemas.values():
        for effect in schema.cond_effects:
            effect.join = None  # every binding tried and tested, as before joins
    problem_text = plan.with_suffix(".pddl").read_text()
    p_joined, p_enum = read_problem(problem_text, joined), read_problem(problem_text, enumerated)
    steps = [s for s in parse_strips_plan(plan.read_text(), joined) if s.problem is None]
    compared = 0
    for step, state in _walk(joined, p_joined, steps):
        if not joined.schemas[step.name].cond_effects:
            continue
        got = _adl_step(joined, p_joined, joined.schemas[step.name], step.args, state)
        want = _adl_step(enumerated, p_enum, enumerated.schemas[step.name], step.args, state)
        assert got is not None and want is not None
        assert Counter(got[0]) == Counter(want[0]) and Counter(got[1]) == Counter(want[1]), step
        compared += 1
    assert compared


DERIVED = _plans(":derived")


@pytest.mark.parametrize("plan", DERIVED, ids=lambda p: f"{p.parent.name}/{p.stem}")
def test_derived_atoms_followed_step_by_step_equal_those_derived_from_scratch(plan: Path
                                                                            ) -> None:
    domain = read_domain(_domain_file(plan).read_text())
    assert domain.axioms is not None
    problem = read_problem(plan.with_suffix(".pddl").read_text(), domain)
    steps = parse_strips_plan(plan.read_text(), domain)
    state = set(problem.init)
    followed = Derivation(domain, problem, state)
    state |= followed.atoms
    changed: dict[GroundAtom, tuple[int, str]] = {}
    for index, step in enumerate(steps, start=1):
        schema = domain.schemas[step.name]
        effects = _adl_step(domain, problem, schema, step.args, state) \
            if schema.cond_effects or schema.pre_complex else ([], [])
        assert effects is not None, step
        dels = {schema.ground(lit, step.args) for lit in schema.delete} | set(effects[1])
        adds = {schema.ground(lit, step.args) for lit in schema.add} | set(effects[0])
        removed = [a for a in dels if a in state and a not in adds]
        added = [a for a in adds if a not in state]
        state.difference_update(removed)
        state.update(added)
        before = set(followed.atoms)
        followed.follow(state, removed, added, changed, index, step.text())
        basic = {a for a in state if a[0] not in domain.axioms.predicates}
        assert followed.atoms == derive(domain, problem, basic), step
        assert {a for a in state if a[0] in domain.axioms.predicates} == followed.atoms
        assert all(changed[a] == (index, step.text()) for a in before ^ followed.atoms)
    assert steps


def test_an_index_follows_atoms_that_join_and_leave() -> None:
    index = Index([("at", "t0", "l0"), ("at", "t1", "l0"), ("in", "p0", "t0")])
    assert set(index.matching("at", 2, "l0")) == {("at", "t0", "l0"), ("at", "t1", "l0")}
    index.discard(("at", "t0", "l0"))
    index.add(("at", "t0", "l1"))
    index.discard(("at", "t9", "l9"))  # never indexed: nothing happens
    assert set(index.matching("at", 2, "l0")) == {("at", "t1", "l0")}
    assert set(index.matching("at", 2, "l1")) == {("at", "t0", "l1")}
    assert set(index.matching("at", 1, "t0")) == {("at", "t0", "l1")}  # a table built now
    assert set(index.by_pred["at"]) == {("at", "t1", "l0"), ("at", "t0", "l1")}
    assert list(index.matching("in", 1, "p9")) == []
