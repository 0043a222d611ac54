"""PDDL export: a STRIPS domain and problem with the validator's semantics for move/on/in.

Capacities become counters (`load ?x ?n`, `next ?n ?m`, `allows ?x ?n`), "clear" is
`load ?x c0`, and inequality is a static `distinct` relation, so the domain needs only
:strips and :typing and runs in classical tools (unified-planning, pyperplan).
A plan accepted here is accepted by a PDDL plan validator and vice versa; the test
suite checks this on generated plans.

A household scene (openable or toggleable objects, states in the goal) gets the
household domain: the state rows of the action table (`verigraph.actions.schemas`) as
actions over `open`/`closed` and `toggled_on`/`toggled_off`, and `passable ?c` (a
container that is not openable, or is open) wherever the move row forbids passing a
closed container. `under` and `nextto` have no export yet (refused with the reason).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from itertools import product

from verigraph.actions.model import AnyAction, MoveAction, StateAction
from verigraph.actions.schemas import SCHEMAS, SetState
from verigraph.errors import GoalError, VeriGraphError
from verigraph.graph.dictionary import SUPPORT_RELATIONS
from verigraph.graph.goal import Goal
from verigraph.graph.state import WorldState

RELATIONS = SUPPORT_RELATIONS
_UNSAFE = re.compile(r"[^A-Za-z0-9_\-]")


def _kind_pre(relation: str, var: str) -> str:
    return f"(surface {var})" if relation == "on" else f"(container {var})"


# A state key's two predicates (false, true): STRIPS preconditions are positive.
STATE_PREDICATES = {"open": ("closed", "open"), "toggled_on": ("toggled_off", "toggled_on")}


def _passing(r1: str, r2: str, frm: str, to: str, household: bool) -> str:
    """`(passable ?from)` / `(passable ?to)` where a move leaves or enters a container."""
    if not household:
        return ""
    parts = [f"(passable {v})" for r, v in ((r1, frm), (r2, to)) if r == "in"]
    return (" " + " ".join(dict.fromkeys(parts))) if parts else ""


def _state_actions() -> list[str]:
    """The table's state rows as STRIPS actions (`open`, `close`, `toggle_on`, ...)."""
    actions = []
    for row in SCHEMAS.values():
        effect = row.effect
        if not isinstance(effect, SetState) or effect.key not in STATE_PREDICATES:
            continue  # moves, and the physical processes (not exported)
        role = "openable" if effect.key == "open" else "toggleable"
        before, after = (STATE_PREDICATES[effect.key][not effect.value],
                         STATE_PREDICATES[effect.key][effect.value])
        passable = ("" if effect.key != "open" else
                    " (passable ?x)" if effect.value else " (not (passable ?x))")
        actions.append(f"""  (:action {row.name.replace("_", "-")}
    :parameters (?x - thing)
    :precondition (and ({role} ?x) ({before} ?x))
    :effect (and (not ({before} ?x)) ({after} ?x){passable}))""")
    return actions


def domain_pddl(household: bool = False) -> str:
    """The domain: one action schema per (from relation, to relation) pair, plus re-seating
    (and, for a household, the state actions and closed containers)."""
    actions = []
    for r1, r2 in product(RELATIONS, RELATIONS):
        actions.append(f"""  (:action move-{r1}-to-{r2}
    :parameters (?x ?from ?to - thing ?fn ?fm ?tn ?tm - count)
    :precondition (and (movable ?x) ({r1} ?x ?from) (load ?x c0)
                       (distinct ?from ?to) (distinct ?x ?to) {_kind_pre(r2, "?to")}
                       (load ?to ?tn) (next ?tn ?tm) (allows ?to ?tm)
                       (load ?from ?fn) (next ?fm ?fn){_passing(r1, r2, "?from", "?to", household)})
    :effect (and (not ({r1} ?x ?from)) ({r2} ?x ?to)
                 (not (load ?to ?tn)) (load ?to ?tm)
                 (not (load ?from ?fn)) (load ?from ?fm)))""")
    for r1, r2 in (("on", "in"), ("in", "on")):
        actions.append(f"""  (:action reseat-{r1}-to-{r2}
    :parameters (?x ?y - thing)
    :precondition (and (movable ?x) ({r1} ?x ?y) (load ?x c0) {_kind_pre(r2, "?y")}{
        _passing(r1, r2, "?y", "?y", household)})
    :effect (and (not ({r1} ?x ?y)) ({r2} ?x ?y)))""")
    if household:
        actions += _state_actions()
    body = "\n".join(actions)
    extra = ("\n               (openable ?x - thing) (toggleable ?x - thing) (passable ?x - "
             "thing)\n               (open ?x - thing) (closed ?x - thing) (toggled_on ?x - "
             "thing) (toggled_off ?x - thing)") if household else ""
    return f"""(define (domain verigraph)
  (:requirements :strips :typing)
  (:types thing count)
  (:constants c0 - count)
  (:predicates (on ?x - thing ?y - thing) (in ?x - thing ?y - thing)
               (movable ?x - thing) (surface ?x - thing) (container ?x - thing)
               (load ?x - thing ?n - count) (next ?n - count ?m - count)
               (allows ?x - thing ?n - count) (distinct ?x - thing ?y - thing){extra})
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


def is_household(state: WorldState, goal: Goal | None = None) -> bool:
    """Whether the scene needs the household domain: openable or toggleable objects, or
    states in the goal."""
    return bool(state.openable) or any(
        o.props.toggleable for o in state.objects.values()) or (
        goal is not None and goal.graph is not None
        and any(n.state for n in goal.graph.nodes))


def problem_pddl(state: WorldState, goal: Goal, name: str = "scene") -> str:
    """The problem for a tabletop or household scene and a goal graph (predicates and
    formulas cannot be exported); pair it with `domain_pddl(is_household(state, goal))`."""
    if goal.graph is None or goal.formula is not None:
        what = (f"predicate '{goal.predicate}'" if goal.predicate is not None
                else "formula (quantifiers and negation)")
        raise GoalError(f"the goal {what} has no STRIPS form", field="goal",
                        value=goal.predicate or goal.formula,
                        fix="give a goal graph (scene JSON) instead")
    if state.contacts or any(o.props.sides for o in state.objects.values()):
        raise VeriGraphError("tangram scenes have no PDDL export", field="scene",
                             fix="export tabletop scenes (on/in relations) only")
    beside = next((f"{o} {r} {t}" for o, (r, t) in state.support.items()
                   if r not in RELATIONS), None) or next(
        (e.sentence() for e in goal.graph.edges if e.relation in ("under", "nextto")), None)
    if beside is not None:
        raise VeriGraphError(f"'{beside}': under and nextto have no PDDL export",
                             field="scene", value=beside,
                             fix="export scenes and goals placed with on and in only")
    household = is_household(state, goal)
    names = PddlNames(list(state.objects))
    n = len(state.objects)
    counts = [f"c{i}" for i in range(n + 1)]
    facts: list[str] = [f"(next c{i} c{i + 1})" for i in range(n)]
    for o in state.objects.values():
        p = names[o.id]
        if household:
            facts.extend(_state_facts(state, o.id, p))
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
    goal_facts += [f"({STATE_PREDICATES[key][value]} {names[node.id]})"
                   for node in goal.graph.nodes if node.id in state.objects
                   for key, value in node.state.items()]
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


def _state_facts(state: WorldState, obj: str, p: str) -> list[str]:
    """A household object's roles and states (no state given: closed, off)."""
    props = state.objects[obj].props
    facts = []
    if props.openable:
        facts += [f"(openable {p})", f"({STATE_PREDICATES['open'][state.state_value(obj, 'open')]}"
                  f" {p})"]
    if props.toggleable:
        value = state.state_value(obj, "toggled_on")
        facts += [f"(toggleable {p})", f"({STATE_PREDICATES['toggled_on'][value]} {p})"]
    if props.container and (not props.openable or state.state_value(obj, "open")):
        facts.append(f"(passable {p})")
    return facts


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
        if isinstance(action, StateAction):
            out.append((action.action.replace("_", "-"), [names[action.object]]))
            continue
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


def action_from_pddl(name: str, params: Sequence[str], names: PddlNames
                     ) -> MoveAction | StateAction:
    """A grounded PDDL action of this domain back as an action (for plans found by PDDL
    tools)."""
    back = {v: k for k, v in names.to_pddl.items()}
    if name.replace("-", "_") in SCHEMAS and name != "move":
        return StateAction(action=name.replace("-", "_"), object=back[params[0]])  # type: ignore[arg-type]
    relation = name.rsplit("-", 1)[-1]
    if name.startswith("reseat-"):
        return MoveAction(object=back[params[0]], relation=relation, target=back[params[1]])
    return MoveAction(object=back[params[0]], relation=relation, target=back[params[2]])
