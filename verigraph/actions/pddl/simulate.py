"""Simulate a STRIPS plan on sets of ground atoms and explain every failure.

Grounding is lazy: only the actions the plan names are instantiated, one step at a time,
so a problem with millions of possible ground actions costs what its plan costs. The
state is a set of atom tuples; a step's deletes apply before its adds (PDDL's and VAL's
order). Every atom a step changes is recorded with that step, which is what the
explanations need (see explain): for an unsatisfied precondition, the step and action
that last made it false (or "never true", with what holds instead); for an unmet goal,
the same, and the actions that would achieve it, each with its closest grounding.

A valid plan takes a fast run first (`_fast_run`: each distinct line grounded once into
frozen sets, no history kept); a failing step or an unmet goal sends the plan through the
step-by-step run below, which gives every explanation (docs/validator.md, Performance).

A plan line that is no action of the domain (an unknown action, the wrong number of
arguments, `(no plan possible)`, `(1) (feast d b)`) is a failing step of an invalid plan,
as VAL and PlanBench's graders count it (`malformed_action`, with the reason and the fix).
A step whose cost function has no value in the initial state is not applicable (PDDL's
rule for an undefined numeric value).

By default the simulation stops at the first failing step. With `all_errors=True` it
goes on as VAL does when asked to continue: the failing step is skipped (the state stays
as it was before it) and every later step is checked from there; the report says so
(`after_failure`). With action costs, the report's `total_cost` is the sum of the
applied steps' `(increase (total-cost) ...)`, VAL's "Final value". The report is a
JSON-ready dict with the keys of the blocks-world report (valid, plan_valid,
goal_reached, steps, violations, not_checked, goal_diff).
"""

from __future__ import annotations

import difflib
import gc
import re
from collections.abc import Callable
from functools import lru_cache
from operator import itemgetter
from typing import Any

from verigraph.actions.pddl import axioms as derived_predicates
from verigraph.actions.pddl.explain import (
    MAX_ACHIEVERS,
    Changed,
    Explainer,
    StateIndex,
    complete_binding,
    history,
    holds,
    literal_text,
)
from verigraph.actions.pddl.formulas import Check, Evaluator, _atom, compile_condition
from verigraph.actions.pddl.formulas import text as formula_text
from verigraph.actions.pddl.model import Domain, GroundAtom, Literal, Problem, Schema, show
from verigraph.actions.pddl.plans import MAX_STEPS, Step, parse_strips_plan
from verigraph.actions.pddl.reader import read_domain, read_problem
from verigraph.budget import checkpoint
from verigraph.graph.bulk import LARGE_GRAPH_ITEMS, collector_paused, promote_young_objects

__all__ = ["MAX_ACHIEVERS", "complete_binding", "simulate", "validate_strips_dict"]
_ONE_PLAIN_LINE = re.compile(r"\(([^\s()]+)((?: [^\s()]+)*)\)")  # plans._PLAIN_LINE, one line
MAX_EXPLAINED_GOALS = 20
MAX_EXPLAINED_FAILURES = 20  # with all_errors: failing steps that get achievers
SKIPPED = "skipped"  # all_errors: a failing step changes nothing, later steps go on


@lru_cache(maxsize=64)
def cached_strips_domain(text: str) -> Domain:
    """Domains repeat across a batch: read each text once."""
    return read_domain(text)


@lru_cache(maxsize=16)
def cached_strips_problem(domain_text: str, problem_text: str) -> Problem:
    """A batch checks many plans of one problem (a planner's plans, their mutations):
    read each (domain, problem) pair once. Nothing changes a Problem after reading
    (a simulation copies the initial state; `by_type` only fills a cache)."""
    return read_problem(problem_text, cached_strips_domain(domain_text))


def _suggest(items: list[dict[str, Any]], fallback: str) -> str:
    for item in items:
        for a in item.get("achievers", []):
            verb = "true" if item["expected"] else "false"
            if a["applicable_now"]:
                return f"make {item['literal']} {verb} first, e.g. {a['applicable_now']}"
            if a.get("closest"):
                return (f"make {item['literal']} {verb} first with {a['closest']}, which "
                        f"still needs {' and '.join(a['needs'][:3])}")
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
    """A schema's literals as grounders (built once per domain), the objects each
    parameter admits (per problem), its cost."""

    __slots__ = ("pre_pos", "pre_neg", "add", "delete", "admits", "fixed_cost", "fn_costs",
                 "adl")
    pre_pos: list[tuple[Grounder, bool]]
    pre_neg: list[tuple[Grounder, bool]]
    add: list[Grounder]
    delete: list[Grounder]
    fixed_cost: float
    fn_costs: list[Grounder]
    adl: Schema | None  # the schema, when it has ADL conditions or effects

    def __init__(self, domain: Domain, problem: Problem, schema: Schema) -> None:
        shared = domain.compiled.get(schema.name)
        if shared is None:
            shared = domain.compiled[schema.name] = (
                [(_grounder(schema, lit), lit[0] == "=") for lit in schema.pre_pos],
                [(_grounder(schema, lit), lit[0] == "=") for lit in schema.pre_neg],
                [_grounder(schema, lit) for lit in schema.add],
                [_grounder(schema, lit) for lit in schema.delete],
                float(sum(c for c in schema.cost if isinstance(c, float))),
                [_grounder(schema, c) for c in schema.cost if not isinstance(c, float)])
        self.pre_pos, self.pre_neg, self.add, self.delete, self.fixed_cost, self.fn_costs = \
            shared
        self.admits = [frozenset(problem.of_type(domain, t)) for t in schema.types]
        self.adl = schema if schema.pre_complex or schema.cond_effects else None


def _cost(fast: _Compiled, binding: tuple[str, ...], values: dict[GroundAtom, float]
          ) -> float | GroundAtom:
    """The step's cost, or the function term that has no value."""
    total = fast.fixed_cost
    for g in fast.fn_costs:
        term = g(binding)
        value = values.get(term)
        if value is None:
            return term
        total += value
    return total


def simulate(domain: Domain, problem: Problem, steps: list[Step], *,
             all_errors: bool = False, try_fast: bool = True) -> dict[str, Any]:
    """Run the plan; stop at the first failing step (or, with `all_errors`, skip it and
    go on); explain the failures and any unmet goal. A valid plan is judged by
    `_fast_run` alone (unless `try_fast` is False: the caller tried it already); any other
    goes (again) through the step-by-step run below."""
    if try_fast and not all_errors and domain.axioms is None:
        fast_report = _fast_steps(domain, problem, steps)
        if fast_report is not None:
            return fast_report
    state = set(problem.init)
    derived = None if domain.axioms is None else \
        derived_predicates.refresh(domain, problem, state, set(), None, 0, "")
    changed: Changed = {}
    out_steps: list[dict[str, Any]] = []
    violations: list[dict[str, Any]] = []
    schemas = domain.schemas
    compiled: dict[str, _Compiled] = {}
    explainer = Explainer(domain, problem)
    costs = bool(domain.functions) or any(s.cost for s in schemas.values())
    total_cost = 0.0
    values = problem.values
    fast: _Compiled
    for index, step in enumerate(steps, start=1):
        name, binding, _, failure = step
        if not index & 4095:
            checkpoint()  # the server's per-call budget and cancellation
        if failure is not None:
            text = name
            action = {"action": name, "args": list(binding)}
            unsatisfied: list[dict[str, Any]] = []
        else:
            got = compiled.get(name)
            if got is None:
                got = compiled[name] = _Compiled(domain, problem, schemas[name])
            fast = got
            text = "(" + " ".join((name, *binding)) + ")"
            action = {"action": name, "args": list(binding)}
            for arg, admits in zip(binding, fast.admits, strict=True):
                if arg not in admits:
                    failure = _check_objects(domain, problem, schemas[name], step)
                    break
            unsatisfied = []
        if failure is None:
            holds_all = True
            for g, eq in fast.pre_pos:
                atom = g(binding)
                if not (atom[1] == atom[2] if eq else atom in state):
                    holds_all = False
                    break
            if holds_all:
                for g, eq in fast.pre_neg:
                    atom = g(binding)
                    if atom[1] == atom[2] if eq else atom in state:
                        holds_all = False
                        break
            if holds_all and fast.adl is not None:
                adl = _adl_step(domain, problem, fast.adl, binding, state)
                if adl is None:
                    holds_all = False
            if holds_all and costs:
                cost = _cost(fast, binding, values)
                if isinstance(cost, tuple):
                    failure = ("precondition_unsatisfied", f"{text} needs a value for "
                               f"{show(cost)}, its cost, which the initial state does not give",
                               f"add (= {show(cost)} N) to the problem's :init")
                    holds_all = False
                else:
                    total_cost += cost
            if holds_all:
                dels = [g(binding) for g in fast.delete]
                adds = [g(binding) for g in fast.add]
                if fast.adl is not None and adl is not None:
                    dels += adl[1]
                    adds += adl[0]
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
                if derived is not None:  # derived predicates follow the basic atoms
                    derived = derived_predicates.refresh(domain, problem, state, derived,
                                                         changed, index, text)
                out_steps.append({"step": index, "ok": True, "action": action, "text": text,
                                  "edit": {"removed": [show(a) for a in removed],
                                           "added": [show(a) for a in added]}})
                continue
            if failure is None:
                unsatisfied = _unsatisfied(schemas[name], binding, state, changed, domain,
                                           problem)
        if failure is not None:
            constraint, message, suggestion = failure
        else:
            state_index = StateIndex(state)
            for k, item in enumerate(unsatisfied):
                if "atom" not in item:
                    if derived is not None:
                        derived_predicates.note(domain, problem, state, item, None)
                    continue  # an ADL condition: explained by why_false already
                atom = item.pop("atom")
                item.update(history(atom, item["expected"], changed, state, state_index,
                                    domain.static))
                if derived is not None:
                    derived_predicates.note(domain, problem, state, item, atom)
                if k < 3 and len(violations) < MAX_EXPLAINED_FAILURES:
                    item["achievers"] = explainer.achievers(state_index, atom,
                                                            item["expected"])
            constraint = "precondition_unsatisfied"
            message = f"{text} needs " + "; ".join(
                f"{u['literal']} ({u['explanation']})" for u in unsatisfied)
            fixed = [u["literal"] for u in unsatisfied if u.get("fixed")]
            suggestion = (f"choose other arguments: {', '.join(fixed)} is fixed by the problem"
                          if fixed else _suggest(unsatisfied, "choose an action whose "
                                                 "preconditions hold"))
        violation = {"ok": False, "step": index, "action": action, "constraint": constraint,
                     "message": message, "blocking": [], "suggestion": suggestion,
                     "unsatisfied": unsatisfied}
        violations.append(violation)
        out_steps.append({"step": index, "ok": False, "action": action, "text": text,
                          "violation": violation})
        if not all_errors:
            break
    unmet: list[dict[str, Any]] = []
    final_index = StateIndex(state)
    for goals, expected in ((problem.goal_pos, True), (problem.goal_neg, False)):
        for atom in goals:
            if holds(atom, state) != expected:
                goal: dict[str, Any] = {"literal": literal_text(atom, expected),
                                        "expected": expected,
                                        **history(atom, expected, changed, state, final_index,
                                                domain.static)}
                if len(unmet) < MAX_EXPLAINED_GOALS:
                    goal["achievers"] = explainer.achievers(final_index, atom, expected)
                if derived is not None:
                    derived_predicates.note(domain, problem, state, goal, atom)
                unmet.append(goal)
    if problem.goal_complex:
        ev = Evaluator(domain, problem, state)
        for f in problem.goal_complex:
            slots: list[str | None] = [None] * len(problem.goal_slots)
            if not ev.holds(f, slots):
                unmet.append({"literal": formula_text(f, slots, problem.goal_slots),
                              "expected": True, "last_changed": None,
                              "explanation": ev.why_false(f, slots, problem.goal_slots)})
                if derived is not None:
                    derived_predicates.note(domain, problem, state, unmet[-1], None)
    plan_valid = not violations
    missing = [u["literal"] for u in unmet]
    report: dict[str, Any] = {
        "engine": "strips", "valid": plan_valid and not unmet, "plan_valid": plan_valid,
        "goal_reached": not unmet, "steps": out_steps, "violations": violations,
        "not_checked": len(steps) - len(out_steps), "done": False,
        "goal_diff": {"satisfied": not unmet, "missing_nodes": [], "extra_nodes": [],
                      "missing_edges": missing, "extra_edges": []},
        "unmet_goals": unmet,
        "final_state": sorted(show(a) for a in state),
    }
    if all_errors:
        report["after_failure"] = SKIPPED
    if costs:
        report["total_cost"] = int(total_cost) if total_cost == int(total_cost) else total_cost
    return report


# A ground action of the fast run: positive and negative preconditions, the deletes that
# are not also added (a set and in order), the adds, their texts in the report's edit,
# the atoms whose membership picks the edit of a step, the cost, the step's text and
# action, and (ADL) the schema whose conditions are evaluated per step, with its plain
# deletes and adds
_Ground = tuple[frozenset[GroundAtom], frozenset[GroundAtom], frozenset[GroundAtom],
                tuple[GroundAtom, ...], tuple[GroundAtom, ...], dict[str, list[str]],
                tuple[GroundAtom, ...], float, str, dict[str, Any], Schema | None,
                list[GroundAtom], list[GroundAtom],
                dict[tuple[bool, ...], tuple[list[GroundAtom], list[GroundAtom],
                                             dict[str, list[str]]]]]


def _ground_action(domain: Domain, problem: Problem, fast: _Compiled, step: Step
                   ) -> _Ground | None:
    """Ground one distinct (action, args) of the plan once, for every step that repeats
    it; None when the fast run cannot take it (an undeclared or mistyped object, a false
    equality, a cost with no value): the step-by-step run then explains it."""
    name, binding = step.name, step.args
    for arg, admits in zip(binding, fast.admits, strict=True):
        if arg not in admits:
            return None
    pos: list[GroundAtom] = []
    for g, eq in fast.pre_pos:
        atom = g(binding)
        if eq:
            if atom[1] != atom[2]:
                return None
        else:
            pos.append(atom)
    neg: list[GroundAtom] = []
    for g, eq in fast.pre_neg:
        atom = g(binding)
        if eq:
            if atom[1] == atom[2]:
                return None
        else:
            neg.append(atom)
    cost = _cost(fast, binding, problem.values)
    if isinstance(cost, tuple):
        return None
    dels = [g(binding) for g in fast.delete]
    adds = [g(binding) for g in fast.add]
    add_set = set(adds)
    removed = tuple(a for a in dict.fromkeys(dels) if a not in add_set)
    added = tuple(dict.fromkeys(adds))
    text = "(" + " ".join((name, *binding)) + ")"
    edit = {"removed": [show(a) for a in removed], "added": [show(a) for a in added]}
    return (frozenset(pos), frozenset(neg), frozenset(removed), removed, added, edit,
            removed + added, cost, text, {"action": name, "args": list(binding)}, fast.adl,
            dels, adds, {})


def _fast_run(domain: Domain, problem: Problem, keys: list[Any],
              resolve: Callable[[Any], Step | None]) -> dict[str, Any] | None:
    """The report of a plan whose every step applies and whose goal holds, or None.

    `keys` are the plan's steps as hashable keys (its lines, or (action, args)), and
    `resolve` reads one key into a Step (None: no action of the domain). Each distinct
    key is read and grounded once into frozen sets (`_ground_action`), so a step costs a
    dict lookup, a subset test, a disjointness test and two set updates; no history of
    changed atoms is kept and no failure is explained. Steps of one ground action with
    the same edit (which deletes held, which adds did not) share their `action` and
    `edit` objects: the report is read-only JSON data. Anything else (a line that is no
    action, a failing step, an unmet goal) returns None at once, and the plan is run
    again step by step (`simulate`), which gives every explanation: a failing plan
    costs at most one extra pass up to its failure.
    """
    state = set(problem.init)
    schemas = domain.schemas
    compiled: dict[str, _Compiled] = {}
    grounded: dict[Any, _Ground] = {}
    out_steps: list[dict[str, Any]] = []
    append = out_steps.append
    total_cost = 0.0
    contains = state.__contains__
    for index, key in enumerate(keys, start=1):
        if not index & 4095:
            checkpoint()  # the server's per-call budget and cancellation
        entry = grounded.get(key)
        if entry is None:
            step = resolve(key)
            if step is None or step.problem is not None:
                return None
            fast = compiled.get(step.name)
            if fast is None:
                fast = compiled[step.name] = _Compiled(domain, problem, schemas[step.name])
            got = _ground_action(domain, problem, fast, step)
            if got is None:
                return None
            entry = grounded[key] = got
        pre, neg, removed, ordered, added, edit, probe, cost, text, action, adl, dels, adds, \
            variants = entry
        if not pre <= state or not state.isdisjoint(neg):
            return None
        total_cost += cost
        if adl is None:
            if removed <= state and state.isdisjoint(added):
                state -= removed
                state.update(added)
            else:  # a delete that did not hold or an add that did: another edit
                held = tuple(map(contains, probe))
                variant = variants.get(held)
                if variant is None:
                    gone = [a for a, h in zip(ordered, held, strict=False) if h]
                    new = [a for a, h in zip(added, held[len(ordered):], strict=True) if not h]
                    variant = variants[held] = (gone, new, {
                        "removed": [show(a) for a in gone], "added": [show(a) for a in new]})
                state.difference_update(variant[0])
                state.update(variant[1])
                edit = variant[2]
            append({"step": index, "ok": True, "action": action, "text": text, "edit": edit})
        else:
            effects = _adl_step(domain, problem, adl, tuple(action["args"]), state)
            if effects is None:
                return None
            step_dels, step_adds = dels + effects[1], adds + effects[0]
            add_set = set(step_adds)
            gone = [a for a in dict.fromkeys(step_dels) if a in state and a not in add_set]
            state.difference_update(gone)
            new = [a for a in dict.fromkeys(step_adds) if a not in state]
            state.update(new)
            append({"step": index, "ok": True, "action": action, "text": text,
                    "edit": {"removed": [show(a) for a in gone],
                             "added": [show(a) for a in new]}})
    if any(a[1] != a[2] if a[0] == "=" else a not in state for a in problem.goal_pos) \
            or any(a[1] == a[2] if a[0] == "=" else a in state for a in problem.goal_neg):
        return None
    if problem.goal_complex:
        ev = Evaluator(domain, problem, state)
        if not all(ev.holds(f, [None] * len(problem.goal_slots)) for f in problem.goal_complex):
            return None
    report: dict[str, Any] = {
        "engine": "strips", "valid": True, "plan_valid": True, "goal_reached": True,
        "steps": out_steps, "violations": [], "not_checked": 0, "done": False,
        "goal_diff": {"satisfied": True, "missing_nodes": [], "extra_nodes": [],
                      "missing_edges": [], "extra_edges": []},
        "unmet_goals": [], "final_state": sorted(show(a) for a in state)}
    if bool(domain.functions) or any(s.cost for s in schemas.values()):
        report["total_cost"] = int(total_cost) if total_cost == int(total_cost) else total_cost
    return report


def _plain_line(domain: Domain) -> Callable[[str], Step | None]:
    """Reads one lower-case plan line that is exactly `(action arg ...)` of the domain's
    arity into a Step (None for any other line: the general reader takes the plan)."""
    schemas = domain.schemas

    def resolve(line: str) -> Step | None:
        m = _ONE_PLAIN_LINE.fullmatch(line)
        if m is None:
            return None
        name, rest = m.groups()
        args = tuple(rest.split())
        schema = schemas.get(name)
        if schema is None or len(schema.params) != len(args):
            return None
        return Step(name, args, 0)

    return resolve


def _fast_steps(domain: Domain, problem: Problem, steps: list[Step]) -> dict[str, Any] | None:
    """`_fast_run` over steps already read (keyed by action and arguments)."""
    if any(s.problem is not None for s in steps):
        return None
    return _fast_run(domain, problem, [s[:2] for s in steps],
                     lambda key: Step(key[0], key[1], 0))


def _slots(schema: Schema, binding: tuple[str, ...]) -> list[str | None]:
    return [*binding, *([None] * (len(schema.slot_names) - len(binding)))]


def _adl_step(domain: Domain, problem: Problem, schema: Schema, binding: tuple[str, ...],
              state: set[GroundAtom]) -> tuple[list[GroundAtom], list[GroundAtom]] | None:
    """None when an ADL precondition is false; else the conditional effects' (adds,
    deletes), every condition evaluated in the state before the step (PDDL's rule)."""
    ev = Evaluator(domain, problem, state)
    slots = _slots(schema, binding)
    if not all(ev.holds(f, slots) for f in schema.pre_complex):
        return None
    adds: list[GroundAtom] = []
    dels: list[GroundAtom] = []
    for effect in schema.cond_effects:
        combos = ev.bindings(effect.variables) if effect.variables else [()]
        check = _condition_check(domain, effect.condition)
        places = [slot for slot, _, _ in effect.variables]
        for objs in combos:
            for slot, obj in zip(places, objs, strict=True):
                slots[slot] = obj
            if effect.condition is None or (ev.holds(effect.condition, slots) if check is None
                                            else check(slots, state)):
                adds += [_atom(lit, slots) for lit in effect.add]
                dels += [_atom(lit, slots) for lit in effect.delete]
    return adds, dels


def _condition_check(domain: Domain, condition: Any) -> Check | None:
    """The condition of a conditional effect as a closure over (slots, state), built once
    per domain: a `forall` effect tests it once per object of its variables' types, and
    the general evaluator's recursion dominated such steps. Atoms, equality, not, and,
    or and imply are compiled; a condition with a quantifier inside gets None (the
    evaluator takes it). The same truth value as `Evaluator.holds` on a full binding."""
    if condition is None:
        return None
    key = f"condition {id(condition)}"  # beside the schemas' names (no name has a space)
    found = domain.compiled.get(key)
    if found is None or found[0] is not condition:  # the condition kept: no id reuse
        found = domain.compiled[key] = (condition, compile_condition(condition))
    check: Check | None = found[1]
    return check


def _unsatisfied(schema: Schema, binding: tuple[str, ...], state: set[GroundAtom],
                 changed: Changed, domain: Domain, problem: Problem) -> list[dict[str, Any]]:
    out: list[dict[str, Any]] = []
    if schema.pre_complex:
        ev = Evaluator(domain, problem, state)
        slots = _slots(schema, binding)
        for f in schema.pre_complex:
            if not ev.holds(f, slots):
                out.append({"literal": formula_text(f, slots, schema.slot_names),
                            "expected": True,
                            "last_changed": None,
                            "explanation": ev.why_false(f, slots, schema.slot_names)})
    for lit in schema.pre_pos:
        atom = schema.ground(lit, binding)
        if not holds(atom, state):
            out.append({"literal": literal_text(atom, True), "expected": True, "atom": atom})
    for lit in schema.pre_neg:
        atom = schema.ground(lit, binding)
        if holds(atom, state):
            out.append({"literal": literal_text(atom, False), "expected": False, "atom": atom})
    return out


def validate_strips_dict(domain_text: str, problem_text: str, plan_text: str, *,
                         all_errors: bool = False) -> dict[str, Any]:
    """Domain + problem + plan text -> the JSON-ready report (a domain or problem that
    cannot be read raises a VeriGraphError naming the requirement or name at fault; a plan
    line that is no action of the domain is a failing step)."""
    lines = plan_text.count("\n") + 1
    with collector_paused(lines):
        domain = cached_strips_domain(domain_text)
        problem = cached_strips_problem(domain_text, problem_text)
        report: dict[str, Any] | None = None
        tried = False
        if not all_errors and domain.axioms is None and plan_text.isascii():
            plain = plan_text.lower().splitlines()  # a valid plain plan: read as it runs
            if len(plain) <= MAX_STEPS:
                tried = True
                report = _fast_run(domain, problem, plain, _plain_line(domain))
        if report is None:
            report = simulate(domain, problem, parse_strips_plan(plan_text, domain),
                              all_errors=all_errors, try_fast=not tried)
        if lines >= LARGE_GRAPH_ITEMS and gc.get_freeze_count() == 0:
            promote_young_objects()  # see there: the report is acyclic
    return report
