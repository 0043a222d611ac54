"""The STRIPS model: action schemas, domains and problems as plain data.

Plain dataclasses and tuples, not pydantic: a plan of 100,000 steps grounds 100,000
actions, and every atom is a tuple `(predicate, arg, ...)` hashed into a set. A schema's
literal arguments are `int` (the index of a parameter) or `str` (a constant), so
grounding an action is one tuple comprehension per literal.
"""

from __future__ import annotations

from dataclasses import dataclass, field

Term = int | str  # parameter index, or constant / object name
Literal = tuple[str, tuple[Term, ...]]  # (predicate, terms); "=" for equality
GroundAtom = tuple[str, ...]  # (predicate, object, ...)

SUPPORTED_REQUIREMENTS = (":strips", ":typing", ":negative-preconditions", ":equality",
                          ":action-costs")
ROOT_TYPE = "object"


@dataclass(slots=True)
class Schema:
    """One action: typed parameters, precondition literals and effects (lifted)."""

    name: str
    params: list[str]
    types: list[str]
    pre_pos: list[Literal]
    pre_neg: list[Literal]
    add: list[Literal]
    delete: list[Literal]

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

    def is_a(self, kind: str, wanted: str) -> bool:
        """`kind` is `wanted` or one of its subtypes (every type is an `object`)."""
        seen = 0
        while True:
            if kind == wanted or wanted == ROOT_TYPE:
                return True
            parent = self.parents.get(kind)
            if parent is None or seen > len(self.parents):
                return False
            kind, seen = parent, seen + 1


@dataclass(slots=True)
class Problem:
    """Objects (with the domain's constants), the initial atoms and the goal literals."""

    name: str
    objects: dict[str, str]
    init: set[GroundAtom]
    goal_pos: list[GroundAtom]
    goal_neg: list[GroundAtom]
    by_type: dict[str, list[str]] = field(default_factory=dict)

    def of_type(self, domain: Domain, kind: str) -> list[str]:
        """Objects of `kind` or a subtype, cached per type."""
        found = self.by_type.get(kind)
        if found is None:
            found = [o for o, t in self.objects.items() if domain.is_a(t, kind)]
            self.by_type[kind] = found
        return found


def show(atom: GroundAtom | tuple[str, ...]) -> str:
    """`("at", "t1", "l1")` -> `(at t1 l1)`; equality reads `(= a b)`."""
    return "(" + " ".join(atom) + ")"
