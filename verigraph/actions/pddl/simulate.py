"""Simulate a STRIPS plan on sets of ground atoms and explain every failure.

Grounding is lazy: only the actions the plan names are instantiated, one step at a time,
so a problem with millions of possible ground actions costs what its plan costs. The
state is a set of atom tuples; a step's deletes apply before its adds (PDDL's and VAL's
order). Every atom a step changes is recorded with that step, which is what the
explanations need: for an unsatisfied precondition, the step and action that last made
it false (or "never true"); for an unmet goal, the same, and the actions that would
achieve it, with one grounding that is applicable in the final state when a bounded
search finds one. The report is a JSON-ready dict with the keys of the blocks-world
report (valid, plan_valid, goal_reached, steps, violations, not_checked, goal_diff).
"""

from __future__ import annotations

import difflib
import gc
from collections.abc import Callable
from functools import lru_cache
from operator import itemgetter
from typing import Any

from verigraph.actions.blocksworld.validate import promote_young_objects
from verigraph.actions.pddl.model import Domain, GroundAtom, Literal, Problem, Schema, show
from verigraph.actions.pddl.plans import Step, parse_strips_plan
from verigraph.actions.pddl.reader import read_domain, read_problem
from verigraph.graph.bulk import LARGE_GRAPH_ITEMS, collector_paused

Changed = dict[GroundAtom, tuple[int, str]]  # atom -> (step, action) that last changed it
SEARCH_BUDGET = 20_000  # bindings tried per achiever when looking for an applicable one
MAX_ACHIEVERS = 4
MAX_EXPLAINED_GOALS = 20


@lru_cache(maxsize=64)
def cached_strips_domain(text: str) -> Domain:
    """Domains repeat across a batch: read each text once."""
    return read_domain(text)


def _holds(atom: GroundAtom, state: set[GroundAtom]) -> bool:
    if atom[0] == "=":
        return atom[1] == atom[2]
    return atom in state


def _history(atom: GroundAtom, expected: bool, changed: Changed) -> dict[str, Any]:
    """Why `atom` does not have the value `expected`: the step that last changed it."""
    if atom[0] == "=":
        same = "the same object" if atom[1] == atom[2] else "different objects"
        return {"last_changed": None, "explanation": f"{atom[1]} and {atom[2]} are {same}"}
    last = changed.get(atom)
    if last is not None:
        made = "false" if expected else "true"
        return {"last_changed": {"step": last[0], "action": last[1]},
                "explanation": f"made {made} at step {last[0]} by {last[1]}"}
    return {"last_changed": None,
            "explanation": "never true" if expected else "true in the initial state, "
                                                         "never made false"}


def _literal_text(atom: GroundAtom, expected: bool) -> str:
    return show(atom) if expected else f"(not {show(atom)})"


def complete_binding(domain: Domain, problem: Problem, schema: Schema, binding: list[str | None],
                     state: set[GroundAtom]) -> tuple[str, ...] | None:
    """A full binding extending `binding` whose preconditions hold in `state`, or None.

    Depth-first over the unbound parameters (objects of each parameter's type), checking
    each precondition as soon as its parameters are bound; at most SEARCH_BUDGET nodes.
    """
    free = [i for i, b in enumerate(binding) if b is None]
    literals: list[tuple[Literal, bool]] = [(lit, True) for lit in schema.pre_pos] + \
        [(lit, False) for lit in schema.pre_neg]
    bound_at: dict[int, list[tuple[Literal, bool]]] = {}
    position = {p: k for k, p in enumerate(free)}
    for lit, expected in literals:
        params = [t for t in lit[1] if isinstance(t, int) and t in position]
        when = max((position[t] for t in params), default=-1)
        bound_at.setdefault(when, []).append((lit, expected))
    values = list(binding)
    budget = [SEARCH_BUDGET]

    def fits(level: int) -> bool:
        for lit, expected in bound_at.get(level, []):
            atom = schema.ground(lit, tuple(values))  # type: ignore[arg-type]
            if _holds(atom, state) != expected:
                return False
        return True

    def search(k: int) -> bool:
        if k == len(free):
            return True
        for obj in problem.of_type(domain, schema.types[free[k]]):
            budget[0] -= 1
            if budget[0] < 0:
                return False
            values[free[k]] = obj
            if fits(k) and search(k + 1):
                return True
        values[free[k]] = None
        return False

    if not fits(-1) or not search(0):
        return None
    return tuple(str(v) for v in values)


def achievers(domain: Domain, problem: Problem, state: set[GroundAtom], atom: GroundAtom,
              make_true: bool) -> list[dict[str, Any]]:
    """Actions whose effects would give `atom` the value `make_true`, lifted (`?x` for what
    the atom does not fix) and, where found, grounded so that it is applicable now."""
    if atom[0] == "=":
        return []
    found: list[dict[str, Any]] = []
    for schema in domain.schemas.values():
        for pred, terms in (schema.add if make_true else schema.delete):
            if pred != atom[0]:
                continue
            binding: list[str | None] = [None] * len(schema.params)
            ok = True
            for term, value in zip(terms, atom[1:], strict=True):
                if isinstance(term, int):
                    ok = ok and binding[term] in (None, value) and domain.is_a(
                        problem.objects[value], schema.types[term])
                    binding[term] = value
                else:
                    ok = ok and term == value
            if not ok:
                continue
            lifted = "(" + " ".join((schema.name, *(b or schema.params[i]
                                                    for i, b in enumerate(binding)))) + ")"
            ground = complete_binding(domain, problem, schema, binding, state)
            found.append({"action": lifted, "applicable_now":
                          None if ground is None else "(" + " ".join((schema.name, *ground)) + ")"})
    found.sort(key=lambda a: a["applicable_now"] is None)
    return found[:MAX_ACHIEVERS]


def _suggest(items: list[dict[str, Any]], fallback: str) -> str:
    for item in items:
        for a in item.get("achievers", []):
            verb = "true" if item["expected"] else "false"
            if a["applicable_now"]:
                return f"make {item['literal']} {verb} first, e.g. {a['applicable_now']}"
            return f"make {item['literal']} {verb} first with {a['action']}"
    return fallback


def _check_objects(domain: Domain, problem: Problem, schema: Schema, step: Step
                   ) -> tuple[str, str, str] | None:
    objects = problem.objects
    for k, a in enumerate(step.args):
        kind = objects.get(a)
        if kind is None:
            near = difflib.get_close_matches(a, list(objects)[:5000], n=3, cutoff=0.5)
            hint = (f"did you mean {' or '.join(near)}?" if near else
                    f"use a declared object: {', '.join(list(objects)[:8])}")
            return "unknown_object", f"the problem declares no object '{a}'", hint
        if not domain.is_a(kind, schema.types[k]):
            return ("wrong_type", f"{a} is a {kind}, but {schema.params[k]} of {schema.name} "
                    f"takes a {schema.types[k]}",
                    f"give {schema.params[k]} an object of type {schema.types[k]}")
    return None


Grounder = Callable[[tuple[str, ...]], GroundAtom]


def _grounder(schema: Schema, literal: Literal) -> Grounder:
    """A C-speed grounding of one literal: itemgetter over the binding when every term is
    a parameter, the general path when a constant appears."""
    pred, terms = literal
    if not all(isinstance(t, int) for t in terms):
        return lambda binding: schema.ground(literal, binding)
    idx = [int(t) for t in terms]
    if not idx:
        atom = (pred,)
        return lambda binding: atom
    if len(idx) == 1:
        one = idx[0]
        return lambda binding: (pred, binding[one])
    get = itemgetter(*idx)
    return lambda binding: (pred, *get(binding))


class _Compiled:
    """A schema's literals as grounders, and the objects each parameter admits."""

    __slots__ = ("pre_pos", "pre_neg", "add", "delete", "admits")

    def __init__(self, domain: Domain, problem: Problem, schema: Schema) -> None:
        self.pre_pos = [(_grounder(schema, lit), lit[0] == "=") for lit in schema.pre_pos]
        self.pre_neg = [(_grounder(schema, lit), lit[0] == "=") for lit in schema.pre_neg]
        self.add = [_grounder(schema, lit) for lit in schema.add]
        self.delete = [_grounder(schema, lit) for lit in schema.delete]
        self.admits = [frozenset(problem.of_type(domain, t)) for t in schema.types]


def simulate(domain: Domain, problem: Problem, steps: list[Step]) -> dict[str, Any]:
    """Run the plan; stop at the first failing step; explain it and any unmet goal."""
    state = set(problem.init)
    changed: Changed = {}
    out_steps: list[dict[str, Any]] = []
    violations: list[dict[str, Any]] = []
    schemas = domain.schemas
    compiled: dict[str, _Compiled] = {}
    for index, step in enumerate(steps, start=1):
        schema = schemas[step.name]
        fast = compiled.get(step.name)
        if fast is None:
            fast = compiled[step.name] = _Compiled(domain, problem, schema)
        binding = step.args
        text = step.text()
        action = {"action": step.name, "args": list(binding)}
        failure = None
        for arg, admits in zip(binding, fast.admits, strict=True):
            if arg not in admits:
                failure = _check_objects(domain, problem, schema, step)
                break
        unsatisfied: list[dict[str, Any]] = []
        if failure is None:
            holds = True
            for g, eq in fast.pre_pos:
                atom = g(binding)
                if not (atom[1] == atom[2] if eq else atom in state):
                    holds = False
                    break
            if holds:
                for g, eq in fast.pre_neg:
                    atom = g(binding)
                    if atom[1] == atom[2] if eq else atom in state:
                        holds = False
                        break
            if holds:
                dels = [g(binding) for g in fast.delete]
                adds = [g(binding) for g in fast.add]
                if len(dels) < 2 and len(adds) < 2:
                    add_set: set[GroundAtom] | tuple[GroundAtom, ...] = tuple(adds)
                else:
                    add_set = set(adds)
                removed = [a for a in dict.fromkeys(dels) if a in state and a not in add_set]
                state.difference_update(removed)
                added = [a for a in dict.fromkeys(adds) if a not in state]
                state.update(added)
                for atom in removed:
                    changed[atom] = (index, text)
                for atom in added:
                    changed[atom] = (index, text)
                out_steps.append({"step": index, "ok": True, "action": action, "text": text,
                                  "edit": {"removed": [show(a) for a in removed],
                                           "added": [show(a) for a in added]}})
                continue
            for lit in schema.pre_pos:
                atom = schema.ground(lit, binding)
                if not _holds(atom, state):
                    unsatisfied.append({"literal": _literal_text(atom, True), "expected": True,
                                        **_history(atom, True, changed), "atom": atom})
            for lit in schema.pre_neg:
                atom = schema.ground(lit, binding)
                if _holds(atom, state):
                    unsatisfied.append({"literal": _literal_text(atom, False),
                                        "expected": False, **_history(atom, False, changed),
                                        "atom": atom})
        if failure is not None:
            constraint, message, suggestion = failure
        else:
            for item in unsatisfied[:3]:
                atom = item.pop("atom")
                item["achievers"] = achievers(domain, problem, state, atom, item["expected"])
            for item in unsatisfied[3:]:
                item.pop("atom")
            constraint = "precondition_unsatisfied"
            message = f"{text} needs " + "; ".join(
                f"{u['literal']} ({u['explanation']})" for u in unsatisfied)
            suggestion = _suggest(unsatisfied, "choose an action whose preconditions hold")
        violation = {"ok": False, "step": index, "action": action, "constraint": constraint,
                     "message": message, "blocking": [], "suggestion": suggestion,
                     "unsatisfied": unsatisfied}
        violations.append(violation)
        out_steps.append({"step": index, "ok": False, "action": action, "text": text,
                          "violation": violation})
        break
    unmet: list[dict[str, Any]] = []
    for goals, expected in ((problem.goal_pos, True), (problem.goal_neg, False)):
        for atom in goals:
            if _holds(atom, state) != expected:
                goal: dict[str, Any] = {"literal": _literal_text(atom, expected),
                                        "expected": expected, **_history(atom, expected, changed)}
                if len(unmet) < MAX_EXPLAINED_GOALS:
                    goal["achievers"] = achievers(domain, problem, state, atom, expected)
                unmet.append(goal)
    plan_valid = not violations
    missing = [u["literal"] for u in unmet]
    return {
        "engine": "strips", "valid": plan_valid and not unmet, "plan_valid": plan_valid,
        "goal_reached": not unmet, "steps": out_steps, "violations": violations,
        "not_checked": len(steps) - len(out_steps), "done": False,
        "goal_diff": {"satisfied": not unmet, "missing_nodes": [], "extra_nodes": [],
                      "missing_edges": missing, "extra_edges": []},
        "unmet_goals": unmet,
        "final_state": sorted(show(a) for a in state),
    }


def validate_strips_dict(domain_text: str, problem_text: str, plan_text: str
                         ) -> dict[str, Any]:
    """Domain + problem + plan text -> the JSON-ready report (bad input raises a
    VeriGraphError naming the requirement, name or plan line at fault)."""
    lines = plan_text.count("\n") + 1
    with collector_paused(lines):
        domain = cached_strips_domain(domain_text)
        problem = read_problem(problem_text, domain)
        report = simulate(domain, problem, parse_strips_plan(plan_text, domain))
        if lines >= LARGE_GRAPH_ITEMS and gc.get_freeze_count() == 0:
            promote_young_objects()  # see there: the report is acyclic
    return report
