"""The action table: every tabletop and household action as one row of data.

A row (`ActionSchema`) names the action, its parameters with what each must be, its
preconditions in check order and its effect. A precondition is a constraint id, a
`test` (a Python expression over the bound parameters that is true when the
precondition holds) and an `explain` function that builds the refusal, message and
fix, only when the test fails. The effect is `apply` (the graph edit, in place,
returning what it replaced) and `changes` (that edit as removed and added edges and
state changes). Everything that checks or applies an action reads this table: the
validator (`validator.validate_action`, `all_violations`, `apply_action`), the
execution loop (`execution.run_actions`, whose fast path is the row's `accepted`, the
tests compiled into one function), the plan report, the solver's successors, the
planner prompt's list of constraints, the tool descriptions and docs/worlds.md. The
arguments a row can take are the table's too: `candidates` (each parameter role's
objects in scene order), `ActionSchema.arguments` (a row's bindings to them) and
`valid_actions` (every action the verifier accepts on a state), which the solver, the
household suite and the simulator's agreement check share.

Adding an action is adding a row (its model in `actions.model`, its parser form in
`actions.parser`) and its tests.

The tangram `align` action is not a row: its preconditions are about sides and
contacts, its effect detaches every contact of the piece and adds one, and the
contacts it really makes come from geometry (sim2d), so it keeps its own check
(`constraints.check_align`) and edit (`validator.apply_action`).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from operator import attrgetter
from typing import Any

from verigraph.actions import constraints as c
from verigraph.actions import processes as p
from verigraph.actions.constraints import closed_passage
from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction, MoveAction, StateAction
from verigraph.graph.dictionary import STATE_WORDS, SUPPORT_RELATIONS, state_value
from verigraph.graph.state import WorldState

# (removed edges, added edges, state changes): edges as (source, relation, target),
# state changes as (object, key, before, after).
Triple = tuple[str, str, str]
StateChange = tuple[str, str, bool, bool]
Changes = tuple[list[Triple], list[Triple], list[StateChange]]


@dataclass(frozen=True, slots=True)
class Parameter:
    """One parameter: the action field it is read from, what it must be (in words), and
    the role a binding needs (`movable`, `openable`, `toggleable`: an object property;
    `relation`: one of the scene's placement relations; None: any object), from which a
    search enumerates the candidates before the preconditions decide."""

    name: str
    needs: str
    role: str | None = None


@dataclass(frozen=True)
class Precondition:
    """One precondition: its constraint id, the test that holds when it is met, and the
    refusal (`explain`) built when it is not. A `gate` failing makes the later tests
    meaningless (they index the objects it checks), so a full report stops there."""

    constraint: str
    test: str
    explain: Callable[[WorldState, Any], Violation]
    gate: bool = False
    # Other ids `explain` may report (one test, a refusal per kind of target).
    also: tuple[str, ...] = ()
    # Skipped in a full report after a refusal with one of these ids.
    skip_after: frozenset[str] = frozenset()
    # `explain` takes the goal's wanted placements (`wanted=`) to rank its fix by them.
    goal_aware: bool = False
    holds: Callable[..., bool] = field(init=False, repr=False)

    @property
    def constraints(self) -> tuple[str, ...]:
        return (self.constraint, *self.also)


@dataclass(frozen=True, slots=True)
class Place:
    """Effect: the object's placement edge becomes `object relation target` (the row's
    parameters, in that order); the step keeps the old placement."""

    def text(self) -> str:
        return "the object's placement edge becomes `object relation target`"


@dataclass(frozen=True, slots=True)
class SetState:
    """Effect: the object's state `key` becomes `value`; the step keeps the old value."""

    key: str
    value: bool

    def text(self) -> str:
        return (f"the object's state {self.key} becomes {str(self.value).lower()} "
                f"({STATE_WORDS[self.key][self.value]})")


Effect = Place | SetState
# The effects as statements over the bound parameters (a placement's row binds `old`,
# the object's placement now), returning what they replaced.
# A placement is `SupportIndex.set_support` inlined: a call per step is measurable on
# long plans.
_PLACE_CODE = """
if old is not None:
    del carried[old[1]][obj]
support[obj] = (relation, target)
carried[target][obj] = relation
return old
"""
_STATE_CODE = """
before = state.state_value(obj, {key!r})
state.set_state(obj, {key!r}, {value})
return before
"""


@dataclass(frozen=True)
class ActionSchema:
    """One row: an action's name, parameters, preconditions and effect."""

    name: str
    parameters: tuple[Parameter, ...]
    preconditions: tuple[Precondition, ...]
    effect: Effect
    # Names the tests after the gates (and the effect) may use, each `name = expression`
    # over the parameters, computed once after the gates hold (they may index objects).
    bindings: tuple[str, ...] = ()
    # The names the gate tests bind (`:=`), as statements, for the functions that run
    # without the gates (a single later test, the effect alone).
    gate_bindings: tuple[str, ...] = ()
    # True for rows that only household worlds use (shown where a scene has them).
    household: bool = False
    accepted: Callable[..., bool] = field(init=False, repr=False)
    apply: Callable[..., Any] = field(init=False, repr=False)
    step: Callable[[WorldState, Any], Any] = field(init=False, repr=False)
    args: Callable[[Any], tuple[Any, ...]] = field(init=False, repr=False)
    action_dict: Callable[..., dict[str, Any]] = field(init=False, repr=False)
    text: Callable[..., str] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        """Compile the row: each test alone (`holds`, for refusals), all of them at once
        (`accepted`), the effect (`apply`), and `step`, which reads the action's fields,
        tests and applies in one call (the execution loop's fast path)."""
        names = [p.name for p in self.parameters]
        variables = ", ".join(VARIABLES[n] for n in names)
        prelude = ("objects = state.objects; carried = state.carried; "
                   "support = state.support")
        bound = "".join(f"    {b}\n" for b in self.bindings)
        rebound = "".join(f"    {b}\n" for b in self.gate_bindings) + bound
        for pre in self.preconditions:
            object.__setattr__(pre, "holds", _compile(
                f"def holds(state, {variables}):\n    {prelude}\n"
                f"{'' if pre.gate else rebound}    return {pre.test}\n", "holds"))
        gates = " and ".join(f"({p.test})" for p in self.preconditions if p.gate) or "True"
        rest = " and ".join(f"({p.test})" for p in self.preconditions if not p.gate) or "True"
        assert all(p.gate for p in self.preconditions[:sum(p.gate for p in self.preconditions)])
        if isinstance(self.effect, Place):
            assert names == ["object", "relation", "target"], "a placement's parameters"
            code = _PLACE_CODE
        else:
            code = _STATE_CODE.format(key=self.effect.key, value=self.effect.value)
        effect = "".join(f"    {line}\n" for line in code.strip().splitlines())
        reads = "; ".join(f"{VARIABLES[n]} = action.{n}" for n in names)
        sources = {
            "accepted": f"def accepted(state, {variables}):\n    {prelude}\n"
                        f"    if not ({gates}):\n        return False\n{bound}"
                        f"    return {rest}\n",
            "apply": f"def apply(state, {variables}):\n    {prelude}\n{rebound}{effect}",
            "step": f"def step(state, action):\n    {reads}\n    {prelude}\n"
                    f"    if not ({gates}):\n        return REFUSED\n{bound}"
                    f"    if not ({rest}):\n        return REFUSED\n{effect}",
            "action_dict": f"def action_dict({variables}):\n    return {{'action': "
                           f"{self.name!r}, "
                           + ", ".join(f"{n!r}: {VARIABLES[n]}" for n in names) + "}\n",
            "text": f"def text({variables}):\n    return f'{self.name}("
                    + ", ".join(f"{{{VARIABLES[n]}}}" for n in names) + ")'\n",
        }
        for name, source in sources.items():
            object.__setattr__(self, name, _compile(source, name))
        getter = attrgetter(*names)
        object.__setattr__(self, "args", getter if len(names) > 1
                           else lambda action: (getter(action),))

    def changes(self, args: tuple[Any, ...], payload: Any) -> Changes:
        """The edit a step made, from its arguments and what its effect replaced."""
        if isinstance(self.effect, Place):
            obj = args[0]
            return ([(obj, payload[0], payload[1])] if payload is not None else [],
                    [args], [])
        return [], [], [(args[0], self.effect.key, payload, self.effect.value)]

    def arguments(self, pools: Pools) -> Iterator[tuple[str, ...]]:
        """Every argument tuple the row's parameters' roles allow, from `pools`
        (`candidates`), the first parameter slowest: what a search or `valid_actions`
        hands the row's `accepted`, the preconditions deciding the rest."""
        return itertools.product(*(pools[p.role] for p in self.parameters))

    def action(self, args: tuple[str, ...]) -> AnyAction:
        """The action model of an argument tuple (the inverse of `args`)."""
        if isinstance(self.effect, Place):
            return MoveAction(object=args[0], relation=args[1], target=args[2])
        return StateAction(action=self.name, object=args[0])  # type: ignore[arg-type]

    def form(self) -> str:
        """`move(object, relation, target)`."""
        return f"{self.name}({', '.join(p.name for p in self.parameters)})"


# The candidates of each parameter role (`Parameter.role`), in scene order.
Pools = dict[str | None, list[str]]

# The variable a parameter is bound to in tests (`object` would shadow the builtin).
VARIABLES = {"object": "obj", "relation": "relation", "target": "target"}


def fits(props: Any, relation: str) -> bool:
    """Whether a target with these properties takes an object by `relation`: `on` a
    surface, `in` a container, `under` furniture (a fixed surface), `nextto` anything
    but a room."""
    if relation == "on":
        return bool(props.surface)
    if relation == "in":
        return bool(props.container)
    if relation == "under":
        return bool(props.surface and not props.movable)
    return not props.room


class _Refused:
    """What a row's `step` returns for an action it refuses (its payloads may be None)."""

    def __repr__(self) -> str:
        return "REFUSED"


REFUSED = _Refused()
_NAMESPACE: dict[str, Any] = {"fits": fits, "closed_passage": closed_passage,
                              "CARRYING": SUPPORT_RELATIONS, "REFUSED": REFUSED, **p.HELPERS}


def _compile(source: str, name: str) -> Callable[..., Any]:
    """One function of a row, compiled from the row's data (tests and effect)."""
    scope: dict[str, Any] = {}
    exec(compile(source, f"<action table: {name}>", "exec"), _NAMESPACE, scope)  # noqa: S102
    function: Callable[..., Any] = scope[name]
    return function


# -- move -------------------------------------------------------------------------------------
MOVE = ActionSchema(
    name="move",
    parameters=(Parameter("object", "a movable object with nothing on, in, under or next "
                                    "to it, not inside a closed container", "movable"),
                Parameter("relation", "on, in (household: under, nextto)", "relation"),
                Parameter("target", "on: a surface; in: an open container; under: "
                                    "furniture; nextto: any object but a room; with room "
                                    "for on and in")),
    preconditions=(
        Precondition("unknown_object", "(info := objects.get(obj)) is not None and "
                     "(about := objects.get(target)) is not None",
                     c.explain_unknown_object, gate=True, goal_aware=True),
        Precondition("unknown_relation", "relation in state.move_relations",
                     c.explain_relation, gate=True),
        Precondition("same_object", "obj != target", c.explain_same_object, gate=True,
                     goal_aware=True),
        Precondition("not_movable", "info.props.movable", c.explain_movable),
        Precondition("already_there", "old != (relation, target)", c.explain_already_there),
        Precondition("would_create_cycle",
                     "not held or obj not in state.supports_chain(target)", c.explain_cycle,
                     goal_aware=True),
        Precondition("object_not_clear", "not held", c.explain_clear, goal_aware=True),
        Precondition("target_not_surface",
                     "props.surface if relation == 'on' else props.container if "
                     "relation == 'in' else fits(props, relation)",
                     c.explain_target_kind, goal_aware=True,
                     also=("target_not_container", "target_not_furniture", "target_is_room")),
        Precondition("container_closed",
                     "not state.openable or closed_passage(state, obj, relation, target) "
                     "is None", c.explain_container_closed, goal_aware=True),
        Precondition("target_full",
                     "relation not in CARRYING or (cap := props.capacity) is None "
                     "or len(carried[target]) < cap or state.has_room(target)",
                     c.explain_capacity, goal_aware=True,
                     skip_after=frozenset({"target_not_surface", "target_not_container"})),
    ),
    effect=Place(),
    bindings=("old = support.get(obj)", "held = carried[obj]", "props = about.props"),
    gate_bindings=("info = objects[obj]", "about = objects[target]"))


# -- open, close, toggle_on, toggle_off ---------------------------------------------------------
def _state_row(name: str, key: str, value: bool) -> ActionSchema:
    role = "openable" if key == "open" else "toggleable"
    word = STATE_WORDS[key][value]
    wrong_role = f"not_{role}"
    already = f"already_{word}"

    return ActionSchema(
        name=name,
        parameters=(Parameter("object", f"{'an' if role[0] == 'o' else 'a'} {role} object "
                                        f"that is not {word} already", role),),
        preconditions=(
            Precondition("unknown_object", "obj in objects", c.explain_unknown_object,
                         gate=True),
            Precondition(wrong_role, f"objects[obj].props.{role}",
                         c.role_explainer(name, role)),
            Precondition(already, f"state.state_value(obj, {key!r}) != {value}",
                         c.already_explainer(name, key, value), goal_aware=True),
        ),
        effect=SetState(key, value), household=True)


# -- cook, heat, freeze, cool, thaw (physical processes: verigraph.actions.processes) ----------
def _process_row(name: str) -> ActionSchema:
    key, value, role, source, needed = p.PROCESSES[name]
    word = p.SOURCE_WORDS[source]
    where: tuple[Precondition, ...]
    if needed:
        where = (
            Precondition(p.NO_SOURCE[source], f"source_below(state, obj, {source!r}) is not None",
                         p.no_source_explainer(name), gate=True, goal_aware=True),
            Precondition(p.SOURCE_OFF[source], f"active_source_below(state, obj, {source!r})",
                         p.source_off_explainer(name), goal_aware=True))
        needs = f"a {role} object, not {STATE_WORDS[key][value]}, on or in a {word} that is on"
    else:
        where = (Precondition(p.STILL_AT_SOURCE[source],
                              f"not active_source_below(state, obj, {source!r})",
                              p.still_at_source_explainer(name), goal_aware=True),)
        needs = f"a {STATE_WORDS[key][True]} object, not on or in a {word} that is on"
    return ActionSchema(
        name=name, parameters=(Parameter("object", needs, role),),
        preconditions=(
            Precondition("unknown_object", "obj in objects", c.explain_unknown_object,
                         gate=True),
            Precondition(f"not_{role}", f"objects[obj].props.{role}",
                         c.role_explainer(name, role), gate=True),
            *(pre for pre in where if pre.gate),  # the table checks gates first
            Precondition(p.ALREADY[name], f"state.state_value(obj, {key!r}) != {value}",
                         p.already_processed_explainer(name)),
            *(pre for pre in where if not pre.gate)),
        effect=SetState(key, value), household=True)


SCHEMAS: dict[str, ActionSchema] = {row.name: row for row in (
    MOVE,
    _state_row("open", "open", True),
    _state_row("close", "open", False),
    _state_row("toggle_on", "toggled_on", True),
    _state_row("toggle_off", "toggled_on", False),
    *(_process_row(name) for name in p.PROCESSES),
)}
"""The action table, by action name."""
# The object properties the parameters' roles name.
_ROLES = tuple(dict.fromkeys(p.role for row in SCHEMAS.values() for p in row.parameters
                             if p.role is not None and p.role != "relation"))


def schema_of(action: AnyAction) -> ActionSchema | None:
    """The row of an action (None for `align` and `done`, which are not rows)."""
    if type(action) is MoveAction:
        return MOVE
    if type(action) is StateAction:
        return SCHEMAS[action.action]
    return None


def candidates(state: WorldState, relations: Sequence[str] | None = None) -> Pools:
    """The candidates of each parameter role on `state`, in scene order (sorted ids):
    for an object property (`movable`, `openable`, ...) the objects that have it, for
    None every object, for `relation` the `relations` given (by default the scene's
    placement relations, `state.move_relations`, in their order). The objects and their
    properties never change, so a search computes these once (and may narrow the
    relations to those its goal needs)."""
    ids = sorted(state.objects)
    pools: Pools = {None: ids, "relation": list(state.move_relations if relations is None
                                                else relations)}
    for role in _ROLES:
        pools[role] = [o for o in ids if getattr(state.objects[o].props, role)]
    return pools


def valid_actions(state: WorldState) -> list[AnyAction]:
    """Every action of the table the verifier accepts on `state` now: the rows in table
    order, each row's arguments from `candidates` (scene order) kept where the row's
    compiled preconditions (`accepted`) hold. The same set as every move, open, close,
    toggle and process over every object, relation and target that `validate_action`
    accepts, found by the parameters' roles instead of trying them all; the order is
    stable (the household suite draws from it with a seeded generator)."""
    pools = candidates(state)
    return [row.action(args) for row in SCHEMAS.values() for args in row.arguments(pools)
            if row.accepted(state, *args)]


def table_constraints(*, household: bool) -> list[str]:
    """Every constraint id of the table, in row and check order, once each; the
    household rows' and tests' ids only with `household`."""
    ids: dict[str, None] = {}
    for row in SCHEMAS.values():
        if row.household and not household:
            continue
        for pre in row.preconditions:
            for cid in pre.constraints:
                if household or cid not in HOUSEHOLD_CONSTRAINTS:
                    ids.setdefault(cid)
    return list(ids)


# Constraints that only a household world (openables, under/nextto, rooms) can break.
HOUSEHOLD_CONSTRAINTS = frozenset({
    "container_closed", "target_not_furniture", "target_is_room", "not_openable",
    "already_open", "already_closed", "not_toggleable", "already_on", "already_off",
    *(f"not_{row[2]}" for row in p.PROCESSES.values()), *p.ALREADY.values(),
    *p.NO_SOURCE.values(), *p.SOURCE_OFF.values(), *p.STILL_AT_SOURCE.values()})


def action_lines(*, household: bool) -> list[str]:
    """One line per row: `move(object, relation, target): object: ...; target: ...`."""
    lines = []
    for row in SCHEMAS.values():
        if row.household and not household:
            continue
        needs = "; ".join(f"{p.name}: {p.needs}" for p in row.parameters)
        lines.append(f"{row.form()}: {needs}")
    return lines


__all__ = ["SCHEMAS", "ActionSchema", "Parameter", "Pools", "Precondition", "action_lines",
           "candidates", "closed_passage", "fits", "schema_of", "state_value",
           "table_constraints", "valid_actions"]
