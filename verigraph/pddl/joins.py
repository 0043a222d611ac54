"""Joins: every binding of a conjunction's variables under which it holds.

A conjunction of literals (`BodyLiteral`: sign, predicate, terms) is planned once into a
list of ops and then run on a state. The plan binds variables by joining a positive
literal with an `Index` of atoms (the literal with the most bound terms first), checks
each literal as soon as its variables are bound, binds a variable from an equality with
one side bound, and lets a variable no joinable literal binds range over the objects of
its type (`enum`). So a conjunction costs what its matching atoms cost, not the product
of its variables' types.

Two users: the derived predicates (`axioms`: every positive literal is joinable, over
the atoms that hold in the state being derived), and the conditions of quantified
conditional effects (`forall (?old ?new - level) (when (and (available ?p ?old) (DIFF
?old l1 ?new)) ...)`): there only static predicates are joinable (no action changes
them, so one index of the initial state serves every state of a problem,
`static_index`), and the few DIFF atoms with `l1` in second place are tried instead of
every pair of levels.

Ops, run left to right:
    ("check", positive, pred, ground, derived)  the literal, fully bound (`ground` makes
                                                its atom from the binding), has its sign
    ("some", type)                              the type has an object (else no binding)
    ("bind", slot, source, type)                slot := a bound slot or a constant
    ("enum", slot, type)                        slot ranges over the objects of type
    ("join", pred, fixed, free, same, derived, delta)
        atoms of pred whose `fixed` positions equal their bound terms; each binds the
        `free` slots (type-checked where the signature does not imply the type); `same`
        pairs of positions hold one variable
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable
from typing import Any

from verigraph.budget import checkpoint
from verigraph.errors import VeriGraphError
from verigraph.pddl.model import (
    ROOT_TYPE,
    Domain,
    GroundAtom,
    Problem,
    Term,
    grounder,
)

BodyLiteral = tuple[bool, str, tuple[Term, ...]]  # (positive, predicate, terms)
Op = tuple[Any, ...]


class Index:
    """Atoms by predicate, and by (predicate, position) -> object (tables built on first
    use); atoms may join and leave it (each group is an insertion-ordered dict). An
    explanation reads one state through `explain.StateIndex` instead, which sorts its
    answers and builds a position's table only after a few lookups."""

    __slots__ = ("by_pred", "by_arg")

    def __init__(self, atoms: Iterable[GroundAtom] = ()) -> None:
        by_pred: dict[str, dict[GroundAtom, None]] = {}
        for atom in atoms:  # no position table exists yet: by predicate only
            found = by_pred.get(atom[0])
            if found is None:
                by_pred[atom[0]] = {atom: None}
            else:
                found[atom] = None
        self.by_pred = by_pred
        self.by_arg: dict[tuple[str, int], dict[str, dict[GroundAtom, None]]] = {}

    def add(self, atom: GroundAtom) -> None:
        self.by_pred.setdefault(atom[0], {})[atom] = None
        by_arg = self.by_arg
        if by_arg:
            for pos in range(1, len(atom)):
                table = by_arg.get((atom[0], pos))
                if table is not None:
                    table.setdefault(atom[pos], {})[atom] = None

    def discard(self, atom: GroundAtom) -> None:
        group = self.by_pred.get(atom[0])
        if group is None or group.pop(atom, 0) is not None:
            return  # not indexed
        by_arg = self.by_arg
        if by_arg:
            for pos in range(1, len(atom)):
                table = by_arg.get((atom[0], pos))
                if table is not None:
                    table[atom[pos]].pop(atom)

    def matching(self, pred: str, pos: int, obj: str) -> Collection[GroundAtom]:
        table = self.by_arg.get((pred, pos))
        if table is None:
            table = {}
            for atom in self.by_pred.get(pred, ()):
                table.setdefault(atom[pos], {})[atom] = None
            self.by_arg[(pred, pos)] = table
        return table.get(obj, ())


def static_index(domain: Domain, problem: Problem) -> Index:
    """The initial atoms of the domain's static predicates, indexed once per problem (in
    sorted order: an effect's atoms come out in the same order in every process)."""
    found = problem.static_index
    if found is None:
        static = domain.static
        found = problem.static_index = Index(sorted(a for a in problem.init if a[0] in static))
    assert isinstance(found, Index)
    return found


def conjunction(formula: Any) -> list[BodyLiteral] | None:
    """A condition that is a conjunction of literals (atoms, negated atoms, equalities;
    `and`s may nest), as body literals; None for anything else (or, imply, a quantifier)."""
    out: list[BodyLiteral] = []
    stack = [formula]
    while stack:
        f = stack.pop()
        if f[0] == "and":
            stack.extend(f[1])
        elif f[0] == "atom":
            out.append((True, f[1][0], f[1][1]))
        elif f[0] == "not" and f[1][0] == "atom":
            out.append((False, f[1][1][0], f[1][1][1]))
        else:
            return None
    return out


def plan(domain: Domain, body: list[BodyLiteral], types: dict[int, str], needed: set[int],
         *, joinable: Callable[[str], bool], derived: frozenset[str] | set[str] = frozenset(),
         bound: Iterable[int] = (), first: int | None = None,
         nonempty: Iterable[str] = ()) -> list[Op]:
    """The join order of a conjunction (module docstring). `needed` are the slots to
    bind (with every variable of the body), `bound` the ones bound before it runs;
    with `first`, that body literal is joined first, over the `delta` index;
    `nonempty`: types that must have an object (checked first)."""
    pending = list(body)
    is_bound_slot = set(bound)
    ops: list[Op] = [("some", kind) for kind in nonempty]
    needed = set(needed)
    for _, _, terms in pending:
        needed.update(t for t in terms if isinstance(t, int))

    def is_bound(t: Term) -> bool:
        return not isinstance(t, int) or t in is_bound_slot

    def admits(slot: int, given: str | None) -> str | None:
        wanted = types.get(slot, ROOT_TYPE)
        if wanted == ROOT_TYPE or (given is not None and domain.is_a(given, wanted)):
            return None
        return wanted

    def join(lit: BodyLiteral, delta: bool) -> None:
        _, pred, terms = lit
        signature = domain.predicates.get(pred)
        fixed = [(pos, t) for pos, t in enumerate(terms, start=1) if is_bound(t)]
        free: list[tuple[int, int, str | None]] = []
        same: list[tuple[int, int]] = []
        seen: dict[int, int] = {}
        for pos, t in enumerate(terms, start=1):
            if is_bound(t):
                continue
            assert isinstance(t, int)
            if t in seen:
                same.append((pos, seen[t]))
                continue
            seen[t] = pos
            given = signature[pos - 1] if signature is not None else None
            free.append((pos, t, admits(t, given)))
        ops.append(("join", pred, fixed, free, same, pred in derived, delta))
        is_bound_slot.update(seen)
        pending.remove(lit)

    if first is not None:
        join(body[first], True)
    while pending or needed - is_bound_slot:
        progress = False
        kept = []  # (a new list, not list.remove: a body of 100,000 literals stays linear)
        for lit in pending:  # checks as soon as their variables are bound
            positive, pred, terms = lit
            if all(is_bound(t) for t in terms):
                ops.append(("check", positive, pred, grounder((pred, terms)), pred in derived))
                progress = True
            else:
                kept.append(lit)
        pending[:] = []
        for lit in kept:  # (= ?x c) with one side bound binds the other
            positive, pred, terms = lit
            if positive and pred == "=":
                a, b = terms
                if is_bound(a) != is_bound(b):
                    target, source = (b, a) if is_bound(a) else (a, b)
                    assert isinstance(target, int)
                    ops.append(("bind", target, source, admits(target, None)))
                    is_bound_slot.add(target)
                    progress = True
                    continue
            pending.append(lit)
        if progress:
            continue
        joins = [lit for lit in pending if lit[0] and lit[1] != "=" and joinable(lit[1])]
        if joins:
            join(max(joins, key=lambda x: sum(is_bound(t) for t in x[2])), False)
            continue
        slot = min(needed - is_bound_slot)
        ops.append(("enum", slot, types.get(slot, ROOT_TYPE)))
        is_bound_slot.add(slot)
    return ops


class Joiner:
    """Runs planned ops on one state: `index` for joins on basic predicates,
    `derived_index` on derived ones (and `delta` for the first join of a semi-naive
    round), `state` and `derived` for checks; at most `limit` candidate bindings in all
    (`error(tried)` is raised beyond, never a half-judged answer)."""

    __slots__ = ("domain", "problem", "state", "derived", "index", "derived_index", "delta",
                 "tried", "limit", "error", "types")

    def __init__(self, domain: Domain, problem: Problem, state: set[GroundAtom], index: Index,
                 *, limit: int, error: Callable[[int], VeriGraphError],
                 derived: set[GroundAtom] | None = None,
                 derived_index: Index | None = None) -> None:
        self.domain, self.problem, self.state, self.index = domain, problem, state, index
        self.derived: set[GroundAtom] = set() if derived is None else derived
        self.derived_index = index if derived_index is None else derived_index
        self.delta = Index()
        self.tried = 0
        self.limit, self.error = limit, error
        self.types: dict[str, frozenset[str]] = {}

    def admits(self, kind: str) -> frozenset[str]:
        found = self.types.get(kind)
        if found is None:
            found = self.types[kind] = frozenset(self.problem.of_type(self.domain, kind))
        return found

    def tick(self, n: int = 1) -> None:
        before = self.tried
        self.tried += n
        if self.tried >> 12 != before >> 12:
            checkpoint()
        if self.tried > self.limit:
            raise self.error(self.tried)

    def run(self, ops: list[Op], binding: list[Any], emit: Callable[[list[Any]], None]
            ) -> None:
        """Call `emit(binding)` for every binding under which the ops succeed (the
        slots the ops bind are None again afterwards, but for `bind`'s)."""
        self._step(ops, 0, binding, emit)

    def _step(self, ops: list[Op], k: int, b: list[Any], emit: Callable[[list[Any]], None]
              ) -> None:
        while k < len(ops):
            op = ops[k]
            kind = op[0]
            if kind == "check":
                _, positive, pred, ground, is_derived = op
                atom = ground(b)
                if pred == "=":
                    value = atom[1] == atom[2]
                else:
                    value = atom in (self.derived if is_derived else self.state)
                if value != positive:
                    return
                k += 1
                continue
            if kind == "bind":
                _, target, source, wanted = op
                obj = b[source] if isinstance(source, int) else source
                if wanted is not None and obj not in self.admits(wanted):
                    return
                b[target] = obj
                k += 1
                continue
            if kind == "some":
                if not self.problem.of_type(self.domain, op[1]):
                    return
                k += 1
                continue
            if kind == "enum":
                _, slot, kind_name = op
                objs = self.problem.of_type(self.domain, kind_name)
                self.tick(len(objs))
                for obj in objs:
                    b[slot] = obj
                    self._step(ops, k + 1, b, emit)
                b[slot] = None
                return
            _, pred, fixed, free, same, is_derived, delta = op
            index = self.delta if delta else self.derived_index if is_derived else self.index
            if fixed:
                pos, t = fixed[0]
                candidates = index.matching(pred, pos, str(b[t] if isinstance(t, int) else t))
                rest = [(p, b[t] if isinstance(t, int) else t) for p, t in fixed[1:]]
            else:
                candidates = index.by_pred.get(pred, ())
                rest = []
            self.tick(len(candidates))
            for atom in candidates:
                ok = True
                for pos, obj in rest:
                    if atom[pos] != obj:
                        ok = False
                        break
                if ok:
                    for p, q in same:
                        if atom[p] != atom[q]:
                            ok = False
                            break
                if not ok:
                    continue
                for pos, slot, wanted in free:
                    if wanted is not None and atom[pos] not in self.admits(wanted):
                        ok = False
                        break
                    b[slot] = atom[pos]
                if ok:
                    self._step(ops, k + 1, b, emit)
            for _, slot, _ in free:
                b[slot] = None
            return
        emit(b)
