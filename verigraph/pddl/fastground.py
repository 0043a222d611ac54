"""One schema's grounding as one generated Python function, for the fast run.

The fast run (`simulate._fast_run`) grounds each distinct action of a plan once: checks
its objects' types and its static preconditions against the initial state, builds its
precondition and effect sets, the report's edit and its text. Done literal by literal
through closures (`model.grounder`), that is a dozen calls and several comprehensions
per action, and on a short plan over a large problem (a few hundred distinct moves on a
grid) grounding is a third of the whole check. Here the literals of a schema are
written out once as one function, the way `dataclasses` writes `__init__`: the binding
is unpacked into locals and every atom is a tuple display, so an action grounds more
than twice as fast (visitall's moves: 1.5 us against 3.5 us).

The function is `ground(binding, init, values, admits)` and returns what
`simulate._ground_action` returns in its usual case (every delete distinct, none also
added, no add given twice; see there for the fields), None when the action can apply in
no state (an object a parameter does not take, a false static precondition, a cost with
no value), or `UNUSUAL` for the rare binding that makes two effect literals the same
atom, which the generic code grounds. Names enter the source only through `repr`, so a
domain's text cannot become code. The simulator asks for none for a schema with
conditional effects or a precondition it evaluates rather than compiles
(`simulate._Compiled.adl`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from verigraph.pddl.model import CostTerm, GroundAtom, Literal, Schema

UNUSUAL: Any = object()  # the binding makes two effect literals one atom
GroundFunction = Callable[[tuple[str, ...], set[GroundAtom], dict[GroundAtom, float],
                           list[frozenset[str]]], Any]
GENERATE_AFTER = 32  # see Generated


class Generated:
    """A schema's `ground`, generated for its domain once GENERATE_AFTER of its actions
    have been grounded without it, in any of the domain's problems: compiling (about
    0.25 ms) costs what grounding about a hundred actions through the closures does, so
    a short plan checked once never pays it, and a batch or a server, which keep the
    domain read, pay it once."""

    __slots__ = ("checks", "function", "schema", "static", "waiting")

    def __init__(self, schema: Schema, static: frozenset[str],
                 checks: tuple[Any, ...] | None) -> None:
        self.schema, self.static, self.checks = schema, static, checks
        self.waiting = GENERATE_AFTER
        self.function: GroundFunction | None = None

    def counted(self) -> GroundFunction | None:
        """Count one action grounded without the function; the function once made."""
        self.waiting -= 1
        if self.waiting == 0:
            self.function = ground_function(self.schema, self.static, self.checks)
        return self.function


def _term(t: int | str) -> str:
    return f"b{t}" if isinstance(t, int) else repr(t)


def _atom(literal: Literal | CostTerm) -> str:
    """A tuple display of the literal's atom, e.g. `('at', b0, 'home')`."""
    pred, terms = literal  # type: ignore[misc]
    return "(" + ", ".join([repr(pred), *map(_term, terms)]) + ",)"


def _shown(literal: Literal) -> str:
    """An expression for the literal's atom as the report writes it, `(at b0 home)`."""
    pred, terms = literal
    parts = [repr(f"({pred}")]
    for t in terms:
        parts.append(f"' ' + b{t}" if isinstance(t, int) else repr(f" {t}"))
    parts.append("')'")
    return " + ".join(parts)


def _set(literals: list[Literal]) -> str:
    return "frozenset((" + "".join(_atom(lit) + ", " for lit in literals) + "))"


def ground_function(schema: Schema, static: frozenset[str], checks: tuple[Any, ...] | None
                    ) -> GroundFunction:
    """The generated `ground` for `schema` (module docstring); `static` names the
    predicates no action changes (and `=`), whose preconditions are checked here once.
    The binding has the schema's arity (the fast run hands a step of another arity to
    the step-by-step run before grounding), and a schema's literals and costs name only
    its parameters (quantified variables live in its ADL parts)."""
    arity = len(schema.params)
    names = [f"b{k}" for k in range(arity)]
    lines = ["def ground(b, init, values, admits):"]
    if arity:
        lines.append(f"    {', '.join(names)}, = b")
        takes = " and ".join(f"b{k} in admits[{k}]" for k in range(arity))
        lines += [f"    if not ({takes}):", "        return None"]
    for literals, holds in ((schema.pre_pos, True), (schema.pre_neg, False)):
        for lit in literals:
            if lit[0] not in static:
                continue
            if lit[0] == "=":
                test = f"{_term(lit[1][0])} == {_term(lit[1][1])}"
            else:
                test = f"{_atom(lit)} in init"
            lines += [f"    if {'not ' if holds else ''}({test}):", "        return None"]
    lines.append("    cost = FIXED")
    for term in schema.cost:
        if not isinstance(term, float):
            lines += [f"    value = values.get({_atom(term)})", "    if value is None:",
                      "        return None", "    cost += value"]
    dynamic_pos = [lit for lit in schema.pre_pos if lit[0] not in static]
    dynamic_neg = [lit for lit in schema.pre_neg if lit[0] not in static]
    dels = "(" + "".join(_atom(lit) + ", " for lit in schema.delete) + ")"
    adds = "(" + "".join(_atom(lit) + ", " for lit in schema.add) + ")"
    lines += [f"    pre = {_set(dynamic_pos)}",
              f"    neg = {_set(dynamic_neg) if dynamic_neg else None}",
              f"    dels = {dels}",
              f"    adds = {adds}",
              "    removed = frozenset(dels)"]
    unusual = ["not removed.isdisjoint(adds)"]
    if len(schema.delete) > 1:
        unusual.append(f"len(removed) != {len(schema.delete)}")
    if len(schema.add) > 1:
        unusual.append(f"len(set(adds)) != {len(schema.add)}")
    lines += [f"    if {' or '.join(unusual)}:", "        return UNUSUAL"]
    removed_shown = ", ".join(map(_shown, schema.delete))
    added_shown = ", ".join(map(_shown, schema.add))
    text = " + ".join([repr(f"({schema.name}"), *(f"' ' + {n}" for n in names), "')'"])
    lines += [f"    edit = {{'removed': [{removed_shown}], 'added': [{added_shown}]}}",
              f"    return (pre, neg, removed, adds, edit, {{'action': {schema.name!r}, "
              f"'args': list(b)}}, {text}, cost, removed <= pre, CHECKS, dels, None, {{}})"]
    namespace: dict[str, Any] = {"UNUSUAL": UNUSUAL, "CHECKS": checks, "FIXED": float(
        sum(c for c in schema.cost if isinstance(c, float)))}
    exec(compile("\n".join(lines), f"<ground {schema.name}>", "exec"), namespace)  # noqa: S102
    function: GroundFunction = namespace["ground"]
    return function
