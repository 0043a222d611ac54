"""PDDL export: a STRIPS domain and problem with the validator's semantics for move/on/in.

Capacities become counters (`load ?x ?n`, `next ?n ?m`, `allows ?x ?n`), "clear" is
`load ?x c0`, and inequality is a static `distinct` relation, so the domain needs only
:strips and :typing and runs in classical tools (unified-planning, pyperplan).
A plan accepted here is accepted by a PDDL plan validator and vice versa; the test
suite checks this on generated plans.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from itertools import product

from verigraph.actions.model import AnyAction, MoveAction
from verigraph.errors import GoalError, VeriGraphError
from verigraph.graph.dictionary import SUPPORT_RELATIONS
from verigraph.graph.goal import Goal
from verigraph.graph.state import WorldState

RELATIONS = SUPPORT_RELATIONS
_UNSAFE = re.compile(r"[^A-Za-z0-9_\-]")


def _kind_pre(relation: str, var: str) -> str:
    return f"(surface {var})" if relation == "on" else f"(container {var})"


def domain_pddl() -> str:
    """The domain: one action schema per (from relation, to relation) pair, plus re-seating."""
    actions = []
    for r1, r2 in product(RELATIONS, RELATIONS):
        actions.append(f"""  (:action move-{r1}-to-{r2}
    :parameters (?x ?from ?to - thing ?fn ?fm ?tn ?tm - count)
    :precondition (and (movable ?x) ({r1} ?x ?from) (load ?x c0)
                       (distinct ?from ?to) (distinct ?x ?to) {_kind_pre(r2, "?to")}
                       (load ?to ?tn) (next ?tn ?tm) (allows ?to ?tm)
                       (load ?from ?fn) (next ?fm ?fn))
    :effect (and (not ({r1} ?x ?from)) ({r2} ?x ?to)
                 (not (load ?to ?tn)) (load ?to ?tm)
                 (not (load ?from ?fn)) (load ?from ?fm)))""")
    for r1, r2 in (("on", "in"), ("in", "on")):
        actions.append(f"""  (:action reseat-{r1}-to-{r2}
    :parameters (?x ?y - thing)
    :precondition (and (movable ?x) ({r1} ?x ?y) (load ?x c0) {_kind_pre(r2, "?y")})
    :effect (and (not ({r1} ?x ?y)) ({r2} ?x ?y)))""")
    body = "\n".join(actions)
    return f"""(define (domain verigraph)
  (:requirements :strips :typing)
  (:types thing count)
  (:constants c0 - count)
  (:predicates (on ?x - thing ?y - thing) (in ?x - thing ?y - thing)
               (movable ?x - thing) (surface ?x - thing) (container ?x - thing)
               (load ?x - thing ?n - count) (next ?n - count ?m - count)
               (allows ?x - thing ?n - count) (distinct ?x - thing ?y - thing))
{body}
)
"""


class PddlNames:
    """Scene ids <-> PDDL-safe names (letters, digits, '-', '_', starting with a letter)."""

    def __init__(self, ids: Sequence[str]) -> None:
        self.to_pddl: dict[str, str] = {}
        used: set[str] = {"c0"}
        for obj in ids:
            base = _UNSAFE.sub("_", obj).lower()
            if not base[0].isalpha():
                base = f"o_{base}"
            name, k = base, 2
            while name in used:
                name, k = f"{base}_{k}", k + 1
            used.add(name)
            self.to_pddl[obj] = name

    def __getitem__(self, obj: str) -> str:
        return self.to_pddl[obj]


def problem_pddl(state: WorldState, goal: Goal, name: str = "scene") -> str:
    """The problem for a tabletop scene and a goal graph (predicates cannot be exported)."""
    if goal.graph is None or goal.formula is not None:
        what = (f"predicate '{goal.predicate}'" if goal.predicate is not None
                else "formula (quantifiers and negation)")
        raise GoalError(f"the goal {what} has no STRIPS form", field="goal",
                        value=goal.predicate or goal.formula,
                        fix="give a goal graph (scene JSON) instead")
    if state.contacts or any(o.props.sides for o in state.objects.values()):
        raise VeriGraphError("tangram scenes have no PDDL export", field="scene",
                             fix="export tabletop scenes (on/in relations) only")
    names = PddlNames(list(state.objects))
    n = len(state.objects)
    counts = [f"c{i}" for i in range(n + 1)]
    facts: list[str] = [f"(next c{i} c{i + 1})" for i in range(n)]
    for o in state.objects.values():
        p = names[o.id]
        if o.props.movable:
            facts.append(f"(movable {p})")
        if o.props.surface:
            facts.append(f"(surface {p})")
        if o.props.container:
            facts.append(f"(container {p})")
        if o.props.surface or o.props.container:
            cap = n if o.props.capacity is None else min(o.props.capacity, n)
            facts.extend(f"(allows {p} c{k})" for k in range(1, cap + 1))
        facts.append(f"(load {p} c{len(state.carried[o.id])})")
    for obj, (rel, target) in state.support.items():
        facts.append(f"({rel} {names[obj]} {names[target]})")
    ids = list(state.objects)
    facts.extend(f"(distinct {names[a]} {names[b]})" for a in ids for b in ids if a != b)
    goal_facts = [f"({e.relation} {names[e.source]} {names[e.target]})"
                  for e in goal.graph.edges if e.relation in RELATIONS
                  and e.source in state.objects and e.target in state.objects]
    objects = " ".join(names[o] for o in ids)
    init = "\n    ".join(facts)
    goals = "\n    ".join(goal_facts)
    return f"""(define (problem {name})
  (:domain verigraph)
  (:objects {objects} - thing
            {" ".join(counts[1:])} - count)
  (:init
    {init})
  (:goal (and
    {goals}))
)
"""


def ground_plan(state: WorldState, actions: Sequence[AnyAction]) -> list[tuple[str, list[str]]]:
    """The grounded PDDL action for each move, tracking supports without validating.

    Used to replay our plans in a PDDL validator: an action our validator rejects maps
    to a grounded action whose precondition fails there too.
    """
    names = PddlNames(list(state.objects))
    support = dict(state.support)
    load = {o: len(c) for o, c in state.carried.items()}
    out: list[tuple[str, list[str]]] = []
    for action in actions:
        if not isinstance(action, MoveAction):
            continue
        x, r2, to = action.object, action.relation, action.target
        if x not in support:
            # A fixed object has no support: ground it "from itself", which never holds.
            out.append((f"move-on-to-{r2}", [names[x], names[x], names[to], "c0", "c0",
                                             f"c{load[to]}", f"c{load[to] + 1}"]))
            continue
        r1, frm = support[x]
        if frm == to and r1 != r2:
            out.append((f"reseat-{r1}-to-{r2}", [names[x], names[to]]))
        else:
            fn, tn = load[frm], load[to]
            out.append((f"move-{r1}-to-{r2}", [names[x], names[frm], names[to], f"c{fn}",
                                               f"c{max(fn - 1, 0)}", f"c{tn}", f"c{tn + 1}"]))
            load[frm] -= 1
            load[to] += 1
        support[x] = (r2, to)
    return out


def action_from_pddl(name: str, params: Sequence[str], names: PddlNames) -> MoveAction:
    """A grounded PDDL action of this domain back as a move (for plans found by PDDL tools)."""
    back = {v: k for k, v in names.to_pddl.items()}
    relation = name.rsplit("-", 1)[-1]
    if name.startswith("reseat-"):
        return MoveAction(object=back[params[0]], relation=relation, target=back[params[1]])
    return MoveAction(object=back[params[0]], relation=relation, target=back[params[2]])
