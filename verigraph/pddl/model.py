"""The STRIPS model: action schemas, domains and problems as plain data.

Plain dataclasses and tuples, not pydantic: a plan of 100,000 steps grounds 100,000
actions, and every atom is a tuple `(predicate, arg, ...)` hashed into a set. A schema's
literal arguments are `int` (the index of a parameter) or `str` (a constant), so
grounding an action is one tuple comprehension per literal.

Types form a tree under `object`. `Domain.is_a` is O(1) whatever the depth of the tree:
`index_types` numbers the tree once in depth-first order, and a type is a subtype of
another exactly when its number lies in the other's interval (2,000 types in a chain
with 10,000 objects read in about 0.1 s, where walking up the chain took 6 s).
`(either a b)` is a type of its own name, `either a b`, whose members are listed in
`Domain.either`: an object fits it when it fits a member.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from operator import itemgetter
from typing import Any

Term = int | str  # parameter index, or constant / object name
Literal = tuple[str, tuple[Term, ...]]  # (predicate, terms); "=" for equality
GroundAtom = tuple[str, ...]  # (predicate, object, ...)
# A cost term: a number, or a function and its terms (parameters or constants)
CostTerm = float | tuple[str, tuple[Term, ...]]

SUPPORTED_REQUIREMENTS = (":strips", ":typing", ":negative-preconditions", ":equality",
                          ":action-costs", ":disjunctive-preconditions",
                          ":existential-preconditions", ":universal-preconditions",
                          ":quantified-preconditions", ":conditional-effects", ":adl",
                          ":derived-predicates")
ROOT_TYPE = "object"


@dataclass(slots=True)
class CondEffect:
    """`(forall (vars) (when condition (and adds (not deletes))))`, flattened: for each
    binding of `variables` whose `condition` holds before the step (None: always)."""

    variables: list[tuple[int, str, str]]
    condition: tuple[Any, ...] | None
    add: list[Literal]
    delete: list[Literal]
    # the variables' bindings as a join over static predicates (joins.plan), when the
    # condition is a conjunction of literals; else each binding is enumerated and tested
    join: list[tuple[Any, ...]] | None = None
    # the condition compiled into a closure over (slots, state) (formulas.compile_condition);
    # None: no condition, or one with a quantifier inside (the evaluator takes it)
    check: Any = None
    # the adds' and deletes' grounders (model.grounder), made on first use
    grounders: tuple[list[Any], list[Any]] | None = None


@dataclass(slots=True)
class Schema:
    """One action: typed parameters, precondition literals, effects and cost (lifted)."""

    name: str
    params: list[str]
    types: list[str]
    pre_pos: list[Literal]
    pre_neg: list[Literal]
    add: list[Literal]
    delete: list[Literal]
    cost: list[CostTerm] = field(default_factory=list)  # summed `(increase (total-cost) x)`
    # ADL (see formulas): precondition conjuncts that are not literals, conditional and
    # universal effects, and the name of every variable slot (parameters first)
    pre_complex: list[tuple[Any, ...]] = field(default_factory=list)
    cond_effects: list[CondEffect] = field(default_factory=list)
    slot_names: list[str] = field(default_factory=list)
    # per conjunct of pre_complex, its compiled closure over (slots, state), or None when a
    # quantifier is inside (the evaluator takes it)
    checks: list[Any] = field(default_factory=list)

    def ground(self, literal: Literal, binding: tuple[str, ...]) -> GroundAtom:
        pred, terms = literal
        return (pred, *(binding[t] if isinstance(t, int) else t for t in terms))


@dataclass(slots=True)
class Domain:
    """A STRIPS domain with types (child -> parent), constants and predicate signatures."""

    name: str
    requirements: list[str]
    parents: dict[str, str]
    constants: dict[str, str]
    predicates: dict[str, list[str]]
    schemas: dict[str, Schema]
    functions: dict[str, list[str]] = field(default_factory=dict)  # static cost functions
    either: dict[str, tuple[str, ...]] = field(default_factory=dict)
    span: dict[str, tuple[int, int]] = field(default_factory=dict)  # see index_types
    static: frozenset[str] = frozenset()  # predicates no action changes
    compiled: dict[str, Any] = field(default_factory=dict)  # the simulator's, per schema
    axioms: Any = None  # the compiled `(:derived ...)` rules (axioms.Axioms), if any

    def index_types(self) -> list[str]:
        """Number the type tree depth-first; returns the types no path leads to from
        `object` (members of a cycle), which the reader refuses."""
        children: dict[str, list[str]] = {}
        for child, parent in self.parents.items():
            children.setdefault(parent, []).append(child)
        span: dict[str, tuple[int, int]] = {}
        counter = 0
        stack: list[tuple[str, bool]] = [(ROOT_TYPE, False)]
        start: dict[str, int] = {}
        while stack:
            kind, done = stack.pop()
            if done:
                span[kind] = (start[kind], counter)
                continue
            if kind in start:
                continue
            start[kind] = counter
            counter += 1
            stack.append((kind, True))
            stack.extend((c, False) for c in children.get(kind, ()))
        self.span = span
        return [t for t in self.parents if t not in span]

    def is_a(self, kind: str, wanted: str) -> bool:
        """`kind` is `wanted` or one of its subtypes (every type is an `object`)."""
        if kind == wanted or wanted == ROOT_TYPE:
            return True
        either = self.either
        if either:
            if kind in either:
                return any(self.is_a(k, wanted) for k in either[kind])
            if wanted in either:
                return any(self.is_a(kind, w) for w in either[wanted])
        inner, outer = self.span.get(kind), self.span.get(wanted)
        if inner is None or outer is None:
            return False
        return outer[0] <= inner[0] and inner[1] <= outer[1]


@dataclass(slots=True)
class Problem:
    """Objects (with the domain's constants), the initial atoms and the goal literals."""

    name: str
    objects: dict[str, str]
    init: set[GroundAtom]
    goal_pos: list[GroundAtom]
    goal_neg: list[GroundAtom]
    by_type: dict[str, list[str]] = field(default_factory=dict)
    values: dict[GroundAtom, float] = field(default_factory=dict)  # `(= (f a b) 5)` of :init
    initial_cost: float | None = None  # `(= (total-cost) N)` of :init: where totals start
    goal_complex: list[tuple[Any, ...]] = field(default_factory=list)  # ADL goal conjuncts
    goal_slots: list[str] = field(default_factory=list)  # their variables' names
    static_index: Any = None  # joins.static_index: the static atoms, indexed on first use
    # the fast run's ground actions (by plan line) and compiled schemas, kept for the
    # next plan of this problem (a batch's plans and their mutations share most lines)
    grounded: dict[Any, Any] = field(default_factory=dict)
    compiled: dict[str, Any] = field(default_factory=dict)

    def of_type(self, domain: Domain, kind: str) -> list[str]:
        """Objects of `kind` or a subtype, cached per type."""
        found = self.by_type.get(kind)
        if found is None:
            found = [o for o, t in self.objects.items() if domain.is_a(t, kind)]
            self.by_type[kind] = found
        return found


Grounder = Callable[[Sequence[Any]], GroundAtom]


def grounder(literal: Literal) -> Grounder:
    """The literal's atom under a binding (a sequence indexed by slot), as fast as CPython
    builds a tuple: the hot loops ground millions of atoms, so one, two or three slots
    are indexed directly, more through `itemgetter`, and a literal with constants fills
    a template."""
    pred, terms = literal
    if not any(isinstance(t, int) for t in terms):  # constants only: one atom
        ground = (pred, *(str(t) for t in terms))
        return lambda b: ground
    if not all(isinstance(t, int) for t in terms):
        template: list[Any] = [pred, *(None if isinstance(t, int) else t for t in terms)]
        fill = [(k, t) for k, t in enumerate(terms, start=1) if isinstance(t, int)]

        def mixed(b: Sequence[Any]) -> GroundAtom:
            out = template.copy()
            for k, t in fill:
                out[k] = b[t]
            return tuple(out)
        return mixed
    idx = [int(t) for t in terms]
    if len(idx) == 1:
        i = idx[0]
        return lambda b: (pred, b[i])
    if len(idx) == 2:
        i, j = idx
        return lambda b: (pred, b[i], b[j])
    if len(idx) == 3:
        i, j, k = idx
        return lambda b: (pred, b[i], b[j], b[k])
    head, get = (pred,), itemgetter(*idx)
    return lambda b: head + get(b)


Shower = Callable[[Sequence[Any]], str]


def shower(literal: Literal) -> Shower:
    """The literal's atom under a binding as the report writes it (`show` of the
    grounded atom), built from the binding without the tuple in between."""
    pred, terms = literal
    if not terms:
        shown = f"({pred})"
        return lambda b: shown
    if not all(isinstance(t, int) for t in terms):
        ground = grounder(literal)
        return lambda b: "(" + " ".join(ground(b)) + ")"
    head = f"({pred} "
    idx = [int(t) for t in terms]
    if len(idx) == 1:
        i = idx[0]
        return lambda b: head + b[i] + ")"
    if len(idx) == 2:
        i, j = idx
        return lambda b: head + b[i] + " " + b[j] + ")"
    get = itemgetter(*idx)
    return lambda b: head + " ".join(get(b)) + ")"


def atom_text(atom: GroundAtom | tuple[str, ...]) -> str:
    """`("at", "t1", "l1")` -> `(at t1 l1)`; equality reads `(= a b)`."""
    return "(" + " ".join(atom) + ")"
