"""Simulate a STRIPS plan on sets of ground atoms and explain every failure.

Grounding is lazy: only the actions the plan names are instantiated, one step at a time,
so a problem with millions of possible ground actions costs what its plan costs. The
state is a set of atom tuples; a step's deletes apply before its adds (PDDL's and VAL's
order). Every atom a step changes is recorded with that step, which is what the
explanations need (see explain): for an unsatisfied precondition, the step and action
that last made it false (or "never true", with what holds instead); for an unmet goal,
the same, and the actions that would achieve it, each with its closest grounding.

A plan takes the fast run (`_fast_run`: each distinct line read and grounded once into
frozen sets, its static preconditions checked then, the ground actions kept on the
problem for its next plan; no history kept). At a failing step, or with the goal unmet,
it hands its state to the step-by-step run (`_Simulation`), which reads the history back
from the report's edits and gives every explanation; with `all_errors` or derived
predicates the step-by-step run takes the whole plan (docs/validator.md, Performance).

Both runs ground a step one way, `_ground_action` (the schema's generated function,
`fastground.py`, once made; the closures before that and for what it does not cover),
kept on the problem under (action, args) or the line, and give the same report, byte for
byte: the step-by-step run applies each step from that ground action and also records
the step that last changed each atom, which is what lets it alone explain a failure, go
on after one (`all_errors`) and evaluate derived predicates; the fast run keeps no
history and is 1.4 to 4 times faster on long valid plans (`benchmarks/bench_validate.py
--grounding`, results/validate.md).

A plan line that is no action of the domain (an unknown action, the wrong number of
arguments, `(no plan possible)`, `(1) (feast d b)`) is a failing step of an invalid plan,
as VAL and PlanBench's graders count it (`malformed_action`, with the reason and the fix).
A step whose cost function has no value in the initial state is not applicable (PDDL's
rule for an undefined numeric value).

By default the simulation stops at the first failing step. With `all_errors=True` it
goes on as VAL does when asked to continue: the failing step is skipped (the state stays
as it was before it) and every later step is checked from there; the report says so
(`after_failure`). A plan the native blocks world hands over (docs/validator.md) comes
as its steps (`validate_strips_steps`): the steps that engine applied are replayed
(`_Simulation.replay`, which `explain_steps` uses too) and the step-by-step run judges
from the next one. With action costs, the report's `total_cost` is the initial
`(= (total-cost) N)` (0 when not given) plus the applied steps' `(increase (total-cost)
...)`, VAL's "Final value" (`total_value` says how it is written). The report is the
plan report every engine returns (`verigraph.reporting`: valid, plan_valid,
goal_reached, steps, violations, not_checked, goal_diff, ...).
"""

from __future__ import annotations

import difflib
import gc
import math
from collections.abc import Callable, Iterable, Iterator, Sequence
from functools import lru_cache
from itertools import product
from typing import Any, cast

from verigraph.budget import checkpoint
from verigraph.errors import PlanParseError, VeriGraphError
from verigraph.graph.bulk import LARGE_GRAPH_ITEMS, collector_paused, promote_young_objects
from verigraph.pddl import axioms as derived_predicates
from verigraph.pddl.explain import (
    MAX_ACHIEVERS,
    Changed,
    Explainer,
    StateIndex,
    atom_holds,
    complete_binding,
    history,
    literal_text,
)
from verigraph.pddl.fastground import UNUSUAL, Generated
from verigraph.pddl.formulas import (
    MAX_QUANTIFIED,
    Check,
    Evaluator,
    QuantifierLimitError,
)
from verigraph.pddl.formulas import text as formula_text
from verigraph.pddl.joins import Joiner, static_index
from verigraph.pddl.model import (
    Domain,
    GroundAtom,
    Grounder,
    Problem,
    Schema,
    Shower,
    atom_text,
    grounder,
    shower,
)
from verigraph.pddl.plans import MAX_STEPS, Step, line_reader, parse_strips_plan
from verigraph.pddl.reader import PddlInputError, read_domain, read_problem

__all__ = ["MAX_ACHIEVERS", "complete_binding", "explain_steps", "simulate", "total_value",
           "validate_strips_dict", "validate_strips_steps"]
MAX_EXPLAINED_GOALS = 20
# a plan that stopped at a failing step: that step is what to fix, and its state is not
# where the plan meant to end, so only the first unmet goals get achievers
MAX_EXPLAINED_GOALS_AFTER_FAILURE = 3
MAX_EXPLAINED_FAILURES = 20  # with all_errors: failing steps that get achievers
SKIPPED = "skipped"  # all_errors: a failing step changes nothing, later steps go on


@lru_cache(maxsize=64)
def cached_strips_domain(text: str) -> Domain:
    """Domains repeat across a batch: read each text once."""
    return read_domain(text)


@lru_cache(maxsize=16)
def cached_strips_problem(domain_text: str, problem_text: str) -> Problem:
    """A batch checks many plans of one problem (a planner's plans, their mutations):
    read each (domain, problem) pair once. Nothing changes what a Problem says after
    reading (a simulation copies the initial state); its caches (`by_type`, the static
    index, the fast run's ground actions) only fill."""
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
        if kind is None:  # suggest objects the parameter takes
            fitting = problem.of_type(domain, schema.types[k]) or list(objects)
            near = difflib.get_close_matches(a, fitting[:5000], n=3, cutoff=0.5)
            hint = (f"did you mean {' or '.join(near)}?" if near else
                    f"use a declared object: {', '.join(fitting[:8])}")
            return "unknown_object", f"the problem declares no object '{a}'", hint
        if not domain.is_a(kind, schema.types[k]):
            return ("wrong_type", f"{a} is a {kind}, but {schema.params[k]} of {schema.name} "
                    f"takes a {schema.types[k]}",
                    f"give {schema.params[k]} an object of type {schema.types[k]}")
    return None


class _Compiled:
    """A schema's literals as grounders (built once per domain), the objects each
    parameter admits (per problem), its cost. `static_pos` / `static_neg` are the
    preconditions on static predicates (no action changes them: the fast run checks them
    once per ground action, against the initial state)."""

    __slots__ = ("pre_pos", "pre_neg", "add", "delete", "admits", "fixed_cost", "fn_costs",
                 "adl", "checks", "static_pos", "static_neg", "dynamic_pos", "dynamic_neg",
                 "add_shown", "delete_shown", "generated")
    pre_pos: list[tuple[Grounder, bool]]
    pre_neg: list[tuple[Grounder, bool]]
    add: list[Grounder]
    delete: list[Grounder]
    fixed_cost: float
    fn_costs: list[Grounder]
    adl: Schema | None  # the schema, when it has conditional effects or quantifiers
    checks: tuple[Check, ...] | None  # else its ADL preconditions, compiled (or None)
    static_pos: list[tuple[Grounder, bool]]  # equalities among them
    static_neg: list[tuple[Grounder, bool]]
    dynamic_pos: list[Grounder]
    dynamic_neg: list[Grounder]
    add_shown: list[Shower]  # the adds and deletes as the report's edit writes them
    delete_shown: list[Shower]
    # the usual case of `_ground_action` as one generated function, kept with the domain
    # (fastground.Generated; None for a schema with an ADL part)
    generated: Generated | None

    def __init__(self, domain: Domain, problem: Problem, schema: Schema) -> None:
        compiled = schema.pre_complex and all(c is not None for c in schema.checks)
        self.checks = tuple(schema.checks) if compiled and not schema.cond_effects else None
        self.adl = schema if schema.cond_effects or (schema.pre_complex and not compiled) \
            else None
        shared = domain.compiled.get(schema.name)
        if shared is None:
            static = domain.static | {"="}
            shared = domain.compiled[schema.name] = (
                [(grounder(lit), lit[0] == "=") for lit in schema.pre_pos],
                [(grounder(lit), lit[0] == "=") for lit in schema.pre_neg],
                [grounder(lit) for lit in schema.add],
                [grounder(lit) for lit in schema.delete],
                float(sum(c for c in schema.cost if isinstance(c, float))),
                [grounder(c) for c in schema.cost if not isinstance(c, float)],
                [(grounder(lit), lit[0] == "=") for lit in schema.pre_pos
                 if lit[0] in static],
                [(grounder(lit), lit[0] == "=") for lit in schema.pre_neg
                 if lit[0] in static],
                [grounder(lit) for lit in schema.pre_pos if lit[0] not in static],
                [grounder(lit) for lit in schema.pre_neg if lit[0] not in static],
                [shower(lit) for lit in schema.add], [shower(lit) for lit in schema.delete])
        (self.pre_pos, self.pre_neg, self.add, self.delete, self.fixed_cost, self.fn_costs,
         self.static_pos, self.static_neg, self.dynamic_pos, self.dynamic_neg,
         self.add_shown, self.delete_shown) = shared
        key = f"ground {schema.name}"  # beside the schemas' names (no name has a space)
        self.generated = domain.compiled.get(key)
        if self.generated is None and self.adl is None:
            self.generated = domain.compiled[key] = Generated(schema, domain.static | {"="},
                                                              self.checks)
        self.admits = [frozenset(problem.of_type(domain, t)) for t in schema.types]


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
    go on); explain the failures and any unmet goal. Without `all_errors` or derived
    predicates the plan takes the fast run (`_fast_run`); `try_fast=False` runs every
    step through `_Simulation.run` instead, which gives the same report."""
    if try_fast and not all_errors and domain.axioms is None:
        return _fast_run(domain, problem, [s[:2] for s in steps], steps.__getitem__)
    sim = _Simulation(domain, problem)
    sim.run(steps, 1, all_errors)
    return sim.report(len(steps) - len(sim.out_steps), all_errors)


def _replayed(out_steps: list[dict[str, Any]]) -> Changed:
    """The step that last changed each atom, read back from the report's edits (the fast
    run keeps no history; it is needed only to explain a failure or an unmet goal)."""
    changed: Changed = {}
    for s in out_steps:
        if not s["step"] & 4095:
            checkpoint()  # the server's per-call budget and cancellation
        mark = (s["step"], s["text"])
        edit = s["edit"]
        for shown in edit["removed"]:
            changed[tuple(shown[1:-1].split(" "))] = mark
        for shown in edit["added"]:
            changed[tuple(shown[1:-1].split(" "))] = mark
    return changed


def _has_costs(domain: Domain) -> bool:
    return bool(domain.functions) or any(s.cost for s in domain.schemas.values())


# the largest integer a total is written as (beyond it, or with a fraction: a float, whose
# JSON and text are its shortest repr, `17.5`, `1e+300`, never hundreds of digits)
MAX_INTEGRAL_TOTAL = 2 ** 53


def total_value(total: float) -> int | float:
    """A plan's total cost as the report gives it: an int when it is integral and at
    most 2**53 in size (`18`), else the float (`17.5`, `1e+300`). A total beyond a
    double's range (finite costs whose sum overflows) is refused, never written as inf."""
    if not math.isfinite(total):
        raise PddlInputError("the plan's total cost is beyond the range of a double (about "
                             "1.8e308)", field="problem", value=str(total),
                             fix="give the actions (and the initial total-cost) smaller costs")
    if total.is_integer() and abs(total) <= MAX_INTEGRAL_TOTAL:
        return int(total)
    return total


Applied = Iterable[tuple[int, str, tuple[str, ...]]]  # (step number, action, binding)


class _Simulation:
    """The step-by-step run: the state, the step that last changed each atom, the
    report's steps and violations. `run` goes on from wherever they are: from the
    initial state, or from the state in which the fast run met a failing step."""

    def __init__(self, domain: Domain, problem: Problem,
                 state: set[GroundAtom] | None = None,
                 out_steps: list[dict[str, Any]] | None = None,
                 total_cost: float | None = None) -> None:
        self.domain, self.problem = domain, problem
        self._changed: Changed | None = None
        if state is None or out_steps is None:
            state, out_steps = set(problem.init), []
            self._changed = {}
        self.state = state
        self.out_steps = out_steps
        self.derived: derived_predicates.Derivation | None = None
        if domain.axioms is not None:
            self.derived = derived_predicates.Derivation(domain, problem, state)
            state.update(self.derived.atoms)
        self.violations: list[dict[str, Any]] = []
        self.explainer = Explainer(domain, problem)
        # the cost so far: from the initial `(= (total-cost) N)`, as VAL counts it
        self.total_cost = (problem.initial_cost or 0.0) if total_cost is None else total_cost

    @property
    def changed(self) -> Changed:
        if self._changed is None:
            self._changed = _replayed(self.out_steps)
        return self._changed

    def run(self, steps: Iterable[Step], first: int, all_errors: bool) -> None:
        """Apply `steps`, numbered from `first`, until one fails (or, with `all_errors`,
        skipping each that fails). Each step is grounded as the fast run grounds it
        (`_ground_action`, kept on the problem under its (action, args)), and applied
        from that ground action; a step it does not apply is judged and explained here."""
        domain, problem, state = self.domain, self.problem, self.state
        derived, changed = self.derived, self.changed
        out_steps, violations = self.out_steps, self.violations
        schemas = domain.schemas
        compiled: dict[str, _Compiled] = problem.compiled
        grounded: dict[Any, _Ground] = problem.grounded
        total_cost = self.total_cost
        for index, step in enumerate(steps, start=first):
            name, binding, _, failure = step
            if not index & 4095:
                checkpoint()  # the server's per-call budget and cancellation
            action = {"action": name, "args": list(binding)}
            unsatisfied: list[dict[str, Any]] = []
            if failure is not None:
                text = name
            else:
                text = "(" + " ".join((name, *binding)) + ")"
                key = step[:2]  # the key simulate's fast run grounds a step under
                entry = grounded.get(key)
                if entry is None:
                    fast = compiled.get(name)
                    if fast is None:
                        fast = compiled[name] = _Compiled(domain, problem, schemas[name])
                    got = _ground_action(domain, problem, fast, step)
                    if got is not None:
                        entry = grounded[key] = got
                if entry is not None and (edit := _edit(domain, problem, entry, state)):
                    removed, added, shown = edit
                    state.difference_update(removed)
                    state.update(added)
                    for atom in removed:
                        changed[atom] = (index, text)
                    for atom in added:
                        changed[atom] = (index, text)
                    if derived is not None:  # derived predicates follow the basic atoms
                        derived.follow(state, removed, added, changed, index, text)
                    total_cost += entry[7]
                    out_steps.append({"step": index, "ok": True, "action": action,
                                      "text": text, "edit": shown})
                    continue
                failure = self._refused(schemas[name], step, entry is not None)
            if failure is not None:
                constraint, message, suggestion = failure
            else:  # a precondition is false
                constraint = "precondition_unsatisfied"
                unsatisfied = self.unsatisfied(schemas[name], binding)
                message = f"{text} needs " + "; ".join(
                    f"{u['literal']} ({u['explanation']})" for u in unsatisfied)
                fixed = [u["literal"] for u in unsatisfied if u.get("fixed")]
                suggestion = (f"choose other arguments: {', '.join(fixed)} is fixed by the "
                              "problem" if fixed else
                              _suggest(unsatisfied, self._instead(schemas[name])))
            violation = {"ok": False, "step": index, "action": action, "constraint": constraint,
                         "message": message, "blocking": [], "suggestion": suggestion,
                         "unsatisfied": unsatisfied}
            violations.append(violation)
            out_steps.append({"step": index, "ok": False, "action": action, "text": text,
                              "violation": violation})
            if not all_errors:
                break
        self.total_cost = total_cost
        if len(grounded) > MAX_GROUNDED:
            grounded.clear()

    def replay(self, applied: Applied, record: bool) -> bool:
        """Apply the steps another engine applied (the native blocks world), numbered as
        given, each grounded and applied as `run` applies it (`_ground_action`, `_edit`),
        recording the step that last changed each atom, and with `record` each step in the
        report and its cost, as `run` records them. False at a step that does not apply
        here (this engine would judge the plan otherwise): the run is then unusable. No
        derived predicates are followed (a blocks world has none; `validate_strips_steps`
        judges a domain with them from its first step)."""
        domain, problem, state, changed = self.domain, self.problem, self.state, self.changed
        compiled: dict[str, _Compiled] = problem.compiled
        grounded: dict[Any, _Ground] = problem.grounded
        append = self.out_steps.append
        total_cost = self.total_cost
        try:
            for index, name, binding in applied:
                if not index & 4095:
                    checkpoint()  # the server's per-call budget and cancellation
                entry = grounded.get((name, binding))
                if entry is None:
                    fast = compiled.get(name)
                    if fast is None:
                        fast = compiled[name] = _Compiled(domain, problem, domain.schemas[name])
                    got = _ground_action(domain, problem, fast, Step(name, binding, index))
                    if got is None:
                        return False
                    entry = grounded[(name, binding)] = got
                edit = _edit(domain, problem, entry, state)
                if edit is None:
                    return False
                removed, added, shown = edit
                state.difference_update(removed)
                state.update(added)
                mark = (index, entry[6])
                for atom in removed:
                    changed[atom] = mark
                for atom in added:
                    changed[atom] = mark
                if record:
                    total_cost += entry[7]
                    append({"step": index, "ok": True,
                             "action": {"action": name, "args": list(binding)},
                             "text": entry[6], "edit": shown})
        finally:
            self.total_cost = total_cost
            if len(grounded) > MAX_GROUNDED:
                grounded.clear()
        return True

    def _refused(self, schema: Schema, step: Step, grounded: bool
                 ) -> tuple[str, str, str] | None:
        """Why a step that does not apply fails: an object its action does not take, a
        cost with no value in the initial state (checked after the preconditions, which
        come first), or None: a precondition is false. `grounded`: the step was grounded
        (its objects, static preconditions and cost are fine)."""
        if grounded:
            return None
        domain, problem = self.domain, self.problem
        fast = problem.compiled[schema.name]
        if not all(map(frozenset.__contains__, fast.admits, step.args)):
            failure = _check_objects(domain, problem, schema, step)
            if failure is not None:
                return failure
        if _unsatisfied(schema, step.args, self.state, self.changed, domain, problem):
            return None
        cost = _cost(fast, step.args, problem.values)
        term = atom_text(cost) if isinstance(cost, tuple) else "?"
        text = "(" + " ".join((schema.name, *step.args)) + ")"
        return ("precondition_unsatisfied", f"{text} needs a value for {term}, its cost, "
                "which the initial state does not give", f"add (= {term} N) to the problem's :init")

    def report(self, not_checked: int, all_errors: bool) -> dict[str, Any]:
        """The JSON-ready report of the run so far: its steps and violations, and the
        goal checked in the state it ended in (unmet goals explained)."""
        domain, problem, state = self.domain, self.problem, self.state
        violations = self.violations
        unmet = self.unmet_goals(MAX_EXPLAINED_GOALS if all_errors or not violations
                                 else MAX_EXPLAINED_GOALS_AFTER_FAILURE)
        plan_valid = not violations
        missing = [u["literal"] for u in unmet]
        report: dict[str, Any] = {
            "engine": "strips", "valid": plan_valid and not unmet, "plan_valid": plan_valid,
            "goal_reached": not unmet, "steps": self.out_steps, "violations": violations,
            "not_checked": not_checked, "done": False,
            "goal_diff": {"satisfied": not unmet, "missing_atoms": missing},
            "unmet_goals": unmet,
            "final_state": sorted(map(atom_text, state)),
        }
        if all_errors:
            report["after_failure"] = SKIPPED
        if _has_costs(domain) or problem.initial_cost is not None:
            report["total_cost"] = total_value(self.total_cost)
        return report

    def _instead(self, schema: Schema) -> str:
        """The fix when no action is known to make the false condition hold (an ADL
        condition, or no achiever): an action that applies in this state, one of the same
        name first, or that none does; for the first failures only, as the achievers."""
        first = ("make the condition above hold first (for the objects it names), or "
                 "choose another action")
        if len(self.violations) >= MAX_EXPLAINED_FAILURES:  # as achievers: bounded
            return first
        for other in (schema, *(s for s in self.domain.schemas.values() if s is not schema)):
            args = complete_binding(self.domain, self.problem, other,
                                    [None] * len(other.params), self.state)
            if args is not None:
                return f"{first}: ({' '.join((other.name, *args))}) applies in this state"
        return f"{first}: no action applies in this state"

    def unsatisfied(self, schema: Schema, binding: tuple[str, ...]) -> list[dict[str, Any]]:
        """The preconditions of `schema` under `binding` that are false in the state, each
        with the step that last changed it (or what holds instead) and, for the first
        three, the actions that would achieve it; [] when every one holds."""
        domain, problem, state, derived = self.domain, self.problem, self.state, self.derived
        changed = self.changed
        unsatisfied = _unsatisfied(schema, binding, state, changed, domain, problem)
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
            if k < 3 and len(self.violations) < MAX_EXPLAINED_FAILURES:
                item["achievers"] = self.explainer.achievers(state_index, atom,
                                                             item["expected"])
        return unsatisfied

    def unmet_goals(self, explained: int) -> list[dict[str, Any]]:
        """The goals that do not hold in the state, each with its history and, for the
        first `explained`, the actions that would achieve it."""
        domain, problem, state = self.domain, self.problem, self.state
        derived, explainer = self.derived, self.explainer
        unmet: list[dict[str, Any]] = []
        final_index = StateIndex(state)
        for goals, expected in ((problem.goal_pos, True), (problem.goal_neg, False)):
            for atom in goals:
                if atom_holds(atom, state) != expected:
                    goal: dict[str, Any] = {"literal": literal_text(atom, expected),
                                            "expected": expected,
                                            **history(atom, expected, self.changed, state,
                                                      final_index, domain.static)}
                    if len(unmet) < explained:
                        goal["achievers"] = explainer.achievers(final_index, atom, expected)
                    if derived is not None:
                        derived_predicates.note(domain, problem, state, goal, atom)
                    unmet.append(goal)
        if problem.goal_complex:
            ev = Evaluator(domain, problem, state)
            for f in problem.goal_complex:
                slots: list[str | None] = [None] * len(problem.goal_slots)
                ev.tried = 0  # each goal formula a check of its own
                if not ev.holds(f, slots):
                    unmet.append({"literal": formula_text(f, slots, problem.goal_slots),
                                  "expected": True, "last_changed": None,
                                  "explanation": ev.why_goal_false(f, slots,
                                                                     problem.goal_slots)})
                    if derived is not None:
                        derived_predicates.note(domain, problem, state, unmet[-1], None)
        return unmet


def explain_steps(domain: Domain, problem: Problem, applied: Applied,
                  failing: tuple[str, tuple[str, ...]] | None
                  ) -> tuple[list[dict[str, Any]] | None, list[dict[str, Any]] | None]:
    """The explanations of a plan another engine judged (the native blocks world), in this
    engine's form: `applied` are the steps it applied, `failing` the step it refused (or
    None). Each applied step is grounded and applied as the step-by-step run applies it
    (`_ground_action`, `_edit`), recording the step that last changed each atom. Returns
    the failing step's unsatisfied preconditions ([] for an object its action does not
    take) and, when no step failed, the unmet goals; None for either where this engine
    would judge the plan otherwise (a step the other engine applied that does not apply
    here, or a refused step whose preconditions all hold): nothing is explained then."""
    sim = _Simulation(domain, problem)
    if not sim.replay(applied, False):
        return None, None
    compiled = problem.compiled
    if failing is None:
        return None, sim.unmet_goals(MAX_EXPLAINED_GOALS)
    name, binding = failing
    schema = domain.schemas[name]
    fast = compiled.get(name) or _Compiled(domain, problem, schema)
    if not all(map(frozenset.__contains__, fast.admits, binding)) and _check_objects(
            domain, problem, schema, Step(name, binding, 0, None)) is not None:
        return [], None
    return sim.unsatisfied(schema, binding) or None, None


def _edit(domain: Domain, problem: Problem, entry: _Ground, state: set[GroundAtom]
          ) -> tuple[list[GroundAtom], list[GroundAtom], dict[str, list[str]]] | None:
    """What the ground action `entry` changes in `state` (the atoms it removes and adds,
    and the report's edit), or None when a precondition is false: the step-by-step run's
    way of applying a step (the fast run inlines the same tests)."""
    pre, neg, removed, added, edit, action, _, _, sure, checks, ordered, adl, _ = entry
    if not pre <= state or (neg is not None and not state.isdisjoint(neg)) or (
            checks is not None and not all(c(action["args"], state) for c in checks)):
        return None
    if adl is not None:
        changes = _adl_changes(domain, problem, adl, tuple(action["args"]), state)
        if changes is None:
            return None
        gone, new = changes
    elif sure and state.isdisjoint(added):
        return list(ordered), list(added), edit
    else:
        gone = [a for a in ordered if a in state]
        new = [a for a in added if a not in state]
    return gone, new, {"removed": [atom_text(a) for a in gone],
                       "added": [atom_text(a) for a in new]}


def _adl_changes(domain: Domain, problem: Problem, fast: _Compiled, args: tuple[str, ...],
                 state: set[GroundAtom]) -> tuple[list[GroundAtom], list[GroundAtom]] | None:
    """The atoms a step of a schema with an ADL part removes from `state` and adds to it
    (each once, in order; an atom both deleted and added is added), or None when an ADL
    precondition is false."""
    assert fast.adl is not None
    effects = _adl_step(domain, problem, fast.adl, args, state)
    if effects is None:
        return None
    adds = [g(args) for g in fast.add] + effects[0]
    add_set = set(adds)
    gone = [a for a in dict.fromkeys([g(args) for g in fast.delete] + effects[1])
            if a in state and a not in add_set]
    return gone, [a for a in dict.fromkeys(adds) if a not in state]


# A ground action of the fast run: the positive and negative preconditions on predicates
# some action changes (the static ones are checked once, when it is grounded; no
# negative ones: None), the deletes that are not also added, the adds, the report's edit
# when every delete held and no add did, the step's action and text, its cost, whether
# every delete is a precondition (so it surely held) and there is no ADL part, its
# compiled ADL preconditions (or None), the deletes in order (for another edit), for a
# step with conditional effects or quantified preconditions its compiled schema, and the
# other edits seen so far, by which atoms held
_Ground = tuple[frozenset[GroundAtom], frozenset[GroundAtom] | None, frozenset[GroundAtom],
                tuple[GroundAtom, ...], dict[str, list[str]], dict[str, Any], str, float,
                bool, tuple[Check, ...] | None, tuple[GroundAtom, ...], _Compiled | None,
                dict[tuple[bool, ...], Any]]


def _ground_action(domain: Domain, problem: Problem, fast: _Compiled, step: Step
                   ) -> _Ground | None:
    """Ground one distinct (action, args) of the plan once, for every step that repeats
    it; None when it cannot apply in any state (an undeclared or mistyped object, a false
    equality or static precondition, a cost with no value): the step-by-step run then
    explains it. Once the schema's generated function is made (fastground.Generated),
    it grounds the usual case; the closures below ground the rest."""
    name, binding = step.name, step.args
    generated = fast.generated
    ground = None if generated is None else generated.function or generated.counted()
    if ground is not None:
        got = ground(binding, problem.init, problem.values, fast.admits)
        if got is not UNUSUAL:
            return cast(_Ground | None, got)
    if not all(map(frozenset.__contains__, fast.admits, binding)):
        return None
    init = problem.init
    for g, eq in fast.static_pos:
        atom = g(binding)
        if not (atom[1] == atom[2] if eq else atom in init):
            return None
    for g, eq in fast.static_neg:
        atom = g(binding)
        if atom[1] == atom[2] if eq else atom in init:
            return None
    cost = _cost(fast, binding, problem.values)
    if isinstance(cost, tuple):
        return None
    pre = frozenset([g(binding) for g in fast.dynamic_pos])
    neg = frozenset([g(binding) for g in fast.dynamic_neg]) if fast.dynamic_neg else None
    dels = [g(binding) for g in fast.delete]
    adds = [g(binding) for g in fast.add]
    removed = frozenset(dels)
    if len(removed) == len(dels) and removed.isdisjoint(adds) and len(set(adds)) == len(adds):
        ordered, added = tuple(dels), tuple(adds)  # the usual case: the literals' own texts
        edit = {"removed": [sh(binding) for sh in fast.delete_shown],
                "added": [sh(binding) for sh in fast.add_shown]}
    else:  # a delete that is also added (PDDL: the add wins), or one given twice
        add_set = set(adds)
        ordered = tuple(a for a in dict.fromkeys(dels) if a not in add_set)
        removed = frozenset(ordered)
        added = tuple(dict.fromkeys(adds))
        edit = {"removed": [atom_text(a) for a in ordered], "added": [atom_text(a) for a in added]}
    text = "(" + " ".join((name, *binding)) + ")"
    sure = fast.adl is None and removed <= pre
    return (pre, neg, removed, added, edit, {"action": name, "args": list(binding)}, text,
            cost, sure, fast.checks, ordered, fast if fast.adl is not None else None, {})


_SKIP: Any = ()  # the fast run's entry for a line that holds no step
# ground actions kept per problem for the plans after (see Problem.grounded), about a
# kilobyte each: a plan that leaves more behind empties the cache (a server keeps up to
# 16 problems read)
MAX_GROUNDED = 20_000


def _fast_run(domain: Domain, problem: Problem, keys: Sequence[Any],
              step_at: Callable[[int], Step | None]) -> dict[str, Any]:
    """The report of the plan whose steps are `keys` (its lines, or (action, args)),
    `step_at(position)` reading the step at a position (None: a line that holds none).

    Each distinct key is read and grounded once into frozen sets (`_ground_action`; kept
    on the problem for its next plan, up to `MAX_GROUNDED` of them), so a step costs a
    dict lookup, a subset test, a disjointness test and two set updates; no history of
    changed atoms is kept. Steps of one ground action with the same edit (which deletes
    held, which adds did not) share their `action` and `edit` objects, also across plans
    of one problem: a report is read-only JSON data. At the first step that does not
    apply (a line that is no action, a failing precondition, an undeclared object) the
    run hands its state to the step-by-step run (`_Simulation`), which judges and
    explains that step with the history read back from the report's edits; an unmet goal
    is explained the same way.
    """
    try:
        return _fast_steps(domain, problem, keys, step_at)
    finally:
        if len(problem.grounded) > MAX_GROUNDED:
            problem.grounded.clear()


def _fast_steps(domain: Domain, problem: Problem, keys: Sequence[Any],
                step_at: Callable[[int], Step | None]) -> dict[str, Any]:
    """`_fast_run`'s loop."""
    state = set(problem.init)
    schemas = domain.schemas
    compiled: dict[str, _Compiled] = problem.compiled
    grounded: dict[Any, _Ground] = problem.grounded
    out_steps: list[dict[str, Any]] = []
    append = out_steps.append
    total_cost = problem.initial_cost or 0.0
    contains = state.__contains__
    index = 0
    for position, key in enumerate(keys):
        entry = grounded.get(key)
        if entry is None:
            step = step_at(position)
            if step is None:
                grounded[key] = _SKIP
                continue
            index += 1
            if step.problem is not None:
                return _handed_over(domain, problem, state, out_steps, total_cost, keys,
                                    step_at, position, index, step)
            fast = compiled.get(step.name)
            if fast is None:
                fast = compiled[step.name] = _Compiled(domain, problem, schemas[step.name])
            got = _ground_action(domain, problem, fast, step)
            if got is None:
                return _handed_over(domain, problem, state, out_steps, total_cost, keys,
                                    step_at, position, index, step)
            entry = grounded[key] = got
        elif entry is _SKIP:
            continue
        else:
            index += 1
        if not index & 4095:
            checkpoint()  # the server's per-call budget and cancellation
        pre, neg, removed, added, edit, action, text, cost, sure, checks, ordered, adl, \
            edits = entry
        if not pre <= state or (neg is not None and not state.isdisjoint(neg)) or (
                checks is not None and not all(c(action["args"], state) for c in checks)):
            return _handed_over(domain, problem, state, out_steps, total_cost, keys, step_at,
                                position, index)
        if sure and state.isdisjoint(added):  # the common case: the edit made at grounding
            state -= removed
            state.update(added)
            append({"step": index, "ok": True, "action": action, "text": text, "edit": edit})
        elif adl is None:  # a delete that did not hold or an add that did: another edit
            probe = added if sure else ordered + added  # the atoms that pick the edit
            held = tuple(map(contains, probe))
            variant = edits.get(held)
            if variant is None:
                if sure:  # every delete held (a precondition): the adds pick the edit
                    gone, new = list(ordered), [a for a, h in zip(added, held, strict=True)
                                                if not h]
                else:
                    gone = [a for a, h in zip(ordered, held, strict=False) if h]
                    new = [a for a, h in zip(added, held[len(ordered):], strict=True)
                           if not h]
                variant = edits[held] = (gone, new, {
                    "removed": [atom_text(a) for a in gone], "added": [atom_text(a) for a in new]})
            state.difference_update(variant[0])
            state.update(variant[1])
            append({"step": index, "ok": True, "action": action, "text": text,
                    "edit": variant[2]})
        else:
            changes = _adl_changes(domain, problem, adl, tuple(action["args"]), state)
            if changes is None:
                return _handed_over(domain, problem, state, out_steps, total_cost, keys,
                                    step_at, position, index)
            gone, new = changes
            state.difference_update(gone)
            state.update(new)
            append({"step": index, "ok": True, "action": action, "text": text,
                    "edit": {"removed": [atom_text(a) for a in gone],
                             "added": [atom_text(a) for a in new]}})
        total_cost += cost
    return _Simulation(domain, problem, state, out_steps, total_cost).report(0, False)


def _handed_over(domain: Domain, problem: Problem, state: set[GroundAtom],
                 out_steps: list[dict[str, Any]], total_cost: float, keys: Sequence[Any],
                 step_at: Callable[[int], Step | None], position: int, index: int,
                 read: Step | None = None) -> dict[str, Any]:
    """The fast run met a step it does not apply (number `index`, at `position`; `read`:
    that step, if it was read just now): the step-by-step run takes the plan from there,
    in the state before that step."""
    def rest() -> Iterator[Step]:
        if read is not None:
            yield read
        for q in range(position + (read is not None), len(keys)):
            step = step_at(q)
            if step is not None:
                yield step

    steps = rest()
    sim = _Simulation(domain, problem, state, out_steps, total_cost)
    sim.run(steps, index, False)
    return sim.report(sum(1 for _ in steps), False)


def _slots(schema: Schema, binding: tuple[str, ...]) -> list[str | None]:
    return [*binding, *([None] * (len(schema.slot_names) - len(binding)))]


def _adl_step(domain: Domain, problem: Problem, schema: Schema, binding: tuple[str, ...],
              state: set[GroundAtom]) -> tuple[list[GroundAtom], list[GroundAtom]] | None:
    """None when an ADL precondition is false; else the conditional effects' (adds,
    deletes), every condition evaluated in the state before the step (PDDL's rule). A
    quantified effect whose condition is a conjunction of literals is a join over the
    static predicates (`CondEffect.join`); the others enumerate their bindings."""
    ev = Evaluator(domain, problem, state)
    slots = _slots(schema, binding)
    for f, check in zip(schema.pre_complex, schema.checks, strict=True):
        if not (ev.holds(f, slots) if check is None else check(slots, state)):
            return None
    # each atom once, in the order of first occurrence (what the callers keep of them)
    adds: dict[GroundAtom, None] = {}
    dels: dict[GroundAtom, None] = {}
    joiner: Joiner | None = None
    for effect in schema.cond_effects:
        if effect.grounders is None:
            effect.grounders = ([grounder(lit) for lit in effect.add],
                                [grounder(lit) for lit in effect.delete])
        add_g, del_g = effect.grounders
        if effect.join is not None:
            if joiner is None:
                joiner = Joiner(domain, problem, state, static_index(domain, problem),
                                limit=MAX_QUANTIFIED, error=_too_many_bindings)

            def emit(b: list[Any], add_g: list[Grounder] = add_g,
                     del_g: list[Grounder] = del_g) -> None:
                for g in add_g:
                    adds[g(b)] = None
                for g in del_g:
                    dels[g(b)] = None

            joiner.run(effect.join, slots, emit)
            continue
        condition, check = effect.condition, effect.check
        if not effect.variables:
            if condition is None or (ev.holds(condition, slots) if check is None
                                     else check(slots, state)):
                adds.update(dict.fromkeys(g(slots) for g in add_g))
                dels.update(dict.fromkeys(g(slots) for g in del_g))
            continue
        ev.bindings(effect.variables)  # counted against the step's limit
        *outer, (last, _, kind) = effect.variables
        inner = problem.of_type(domain, kind)
        places = [slot for slot, _, _ in outer]
        lists = [problem.of_type(domain, k) for _, _, k in outer]
        if not inner or not all(lists):
            continue  # a type with no objects: no binding (and no empty loop over others)
        tried = 0
        for objs in product(*lists):
            tried += len(inner)
            if tried >= 4096:
                tried = 0
                checkpoint()  # the call's budget and cancellation
            for slot, obj in zip(places, objs, strict=True):
                slots[slot] = obj
            for obj in inner:  # the last variable in the inner loop
                slots[last] = obj
                if condition is None or (ev.holds(condition, slots) if check is None
                                         else check(slots, state)):
                    for g in add_g:
                        adds[g(slots)] = None
                    for g in del_g:
                        dels[g(slots)] = None
    return list(adds), list(dels)


def _too_many_bindings(tried: int) -> VeriGraphError:
    return QuantifierLimitError(
        f"a conditional effect's quantified variables range over more than "
        f"{MAX_QUANTIFIED:,} bindings in one step", field="domain", value=tried,
        fix="quantify over smaller types, or compile the quantifier away")


def _unsatisfied(schema: Schema, binding: tuple[str, ...], state: set[GroundAtom],
                 changed: Changed, domain: Domain, problem: Problem) -> list[dict[str, Any]]:
    out: list[dict[str, Any]] = []
    if schema.pre_complex:
        ev = Evaluator(domain, problem, state)
        slots = _slots(schema, binding)
        for f in schema.pre_complex:
            ev.tried = 0  # each condition a check of its own (the step stopped at one)
            if not ev.holds(f, slots):
                out.append({"literal": formula_text(f, slots, schema.slot_names),
                            "expected": True,
                            "last_changed": None,
                            "explanation": ev.why_false(f, slots, schema.slot_names)})
    for lit in schema.pre_pos:
        atom = schema.ground(lit, binding)
        if not atom_holds(atom, state):
            out.append({"literal": literal_text(atom, True), "expected": True, "atom": atom})
    for lit in schema.pre_neg:
        atom = schema.ground(lit, binding)
        if atom_holds(atom, state):
            out.append({"literal": literal_text(atom, False), "expected": False, "atom": atom})
    return out


def validate_strips_dict(domain_text: str, problem_text: str, plan_text: str, *,
                         all_errors: bool = False) -> dict[str, Any]:
    """Domain + problem + plan text -> the JSON-ready report (a domain or problem that
    cannot be read raises a VeriGraphError naming the requirement or name at fault; a plan
    line that is no action of the domain is a failing step)."""
    lines = plan_text.count("\n") + 1
    # a long plan's report, or a large problem's state and its explanations
    with collector_paused(lines + problem_text.count("(")):
        domain = cached_strips_domain(domain_text)
        problem = cached_strips_problem(domain_text, problem_text)
        lowered = plan_text.lower().splitlines() if plan_text.isascii() else []
        if all_errors or domain.axioms is not None or not plan_text.isascii() \
                or len(lowered) > MAX_STEPS:
            report = simulate(domain, problem, parse_strips_plan(plan_text, domain),
                              all_errors=all_errors)
        else:  # the lines are read as they run, each distinct line once
            report = _fast_run(domain, problem, lowered,
                               line_reader(plan_text, lowered, domain))
        if lines >= LARGE_GRAPH_ITEMS and gc.get_freeze_count() == 0:
            promote_young_objects()  # see there: the report is acyclic
    return report


def validate_strips_steps(domain_text: str, problem_text: str, steps: list[Step], *,
                          all_errors: bool = False, applied: int = 0) -> dict[str, Any]:
    """The report `validate_strips_dict` gives for a plan whose steps another reader read
    (the native blocks world's, which also reads PlanBench's sentences and colours): the
    steps as `parse_strips_plan` would read the plan with each of them written `(action
    args)`, a line that reader cannot read as this engine reads it (a malformed one a
    failing step).

    `applied`: the leading steps another engine already judged and applied (with
    `all_errors`, the native engine hands a plan over at its first failing step). They
    are replayed (`_Simulation.replay`, as `explain_steps` replays them), which builds
    this engine's history and its form of their report steps, and the step-by-step run
    judges the plan from the next step on; should one of them not apply here, this
    engine judges the whole plan."""
    if len(steps) > MAX_STEPS:
        raise PlanParseError(f"the plan has more than {MAX_STEPS:,} actions",
                             line=steps[MAX_STEPS].line, column=1, text="",
                             expected=f"at most {MAX_STEPS:,} actions")
    with collector_paused(len(steps) + problem_text.count("(")):
        domain = cached_strips_domain(domain_text)
        problem = cached_strips_problem(domain_text, problem_text)
        sim = _Simulation(domain, problem) if applied and domain.axioms is None else None
        if sim is not None and sim.replay(
                ((i, s.name, s.args) for i, s in enumerate(steps[:applied], start=1)), True):
            sim.run(steps[applied:], applied + 1, all_errors)
            report = sim.report(len(steps) - len(sim.out_steps), all_errors)
        else:
            report = simulate(domain, problem, steps, all_errors=all_errors)
        if len(steps) >= LARGE_GRAPH_ITEMS and gc.get_freeze_count() == 0:
            promote_young_objects()  # see validate_strips_dict
    return report
