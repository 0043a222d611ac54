"""Derived predicates (PDDL 2.2 `:derived-predicates`): stratified rules, evaluated per state.

`(:derived (p ?x - t) formula)` makes `(p a)` true in a state exactly when the formula
holds for `?x = a`; several rules for one predicate are a disjunction, and a rule may
use derived predicates, itself included (least fixpoint: `upstream` in psr is a
transitive closure). Actions never change a derived predicate and the initial state
never lists one (the reader refuses both by name): after the initial state and after
every step the simulator recomputes all derived atoms from the basic ones
(`refresh`), so preconditions, conditions of conditional effects and goals read them as
ordinary atoms of the state.

Each rule body (any ADL formula: and, or, not, imply, exists, forall, equality) is
compiled once per domain into conjunctive rules, as Fast Downward's translator does:
negation is pushed to the literals, `or` splits a rule into several, an `exists`
binds body variables, and a `forall` becomes the negation of an auxiliary derived
predicate (`forall x. f` is `not exists x. not f`) over the variables it shares with the
rule. Negation must be stratified: a derived predicate (auxiliaries included) may be
negated only in a rule of a predicate in a higher stratum, never in one it feeds, else
the rules have no single meaning and the domain is refused by name (`field="domain"`,
with the predicates at fault). A stratum is evaluated by joins over the atoms that hold
(bound variables first, each body literal checked as soon as its variables are bound;
a variable no positive literal binds ranges over the objects of its type) and repeated
until nothing new is derived; strata run bottom-up.

Limits: one recomputation may try at most `MAX_DERIVED_BINDINGS` bindings (a
VeriGraphError beyond, never a half-computed state), and a rule body may expand into
at most `MAX_CONJUNCTIONS` conjunctions.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from verigraph.actions.pddl.formulas import Evaluator, Formula, text
from verigraph.actions.pddl.model import ROOT_TYPE, Domain, GroundAtom, Problem, Term, show
from verigraph.budget import checkpoint
from verigraph.errors import VeriGraphError

MAX_DERIVED_BINDINGS = 5_000_000
MAX_CONJUNCTIONS = 4_096
AUX = "#forall"  # auxiliary predicate names: `p#forall1` (no PDDL name has '#')

BodyLiteral = tuple[bool, str, tuple[Term, ...]]  # (positive, predicate, terms)


class DerivedPredicateError(VeriGraphError):
    """Derived-predicate rules that cannot be given a meaning (unstratifiable, too big)."""


@dataclass(slots=True)
class Definition:
    """One `(:derived (p ?x ...) formula)` as written: for explanations and compiling."""

    predicate: str
    formula: Formula
    slot_names: list[str]  # head variables first, then every quantified variable
    head_types: list[str]


@dataclass(slots=True)
class Rule:
    """`head(terms) :- literals`, with a join order (`ops`) fixed at compile time."""

    head: str
    head_terms: tuple[Term, ...]
    body: list[BodyLiteral]
    types: dict[int, str]
    slots: int
    ops: list[tuple[Any, ...]] = field(default_factory=list)
    # semi-naive evaluation: one join order per body literal of the rule's own stratum,
    # that literal joined first over the atoms the last round derived
    delta_ops: list[list[tuple[Any, ...]]] = field(default_factory=list)


@dataclass(slots=True)
class Axioms:
    """A domain's compiled derived predicates."""

    predicates: frozenset[str]  # the declared derived predicates
    definitions: dict[str, list[Definition]]
    strata: list[tuple[list[Rule], bool]]  # rules per stratum, and whether it recurses
    used_basic: frozenset[str]  # basic predicates some rule reads


# ---------------------------------------------------------------- compiling

def _slots_in(f: Formula) -> set[int]:
    kind = f[0]
    if kind == "atom":
        return {t for t in f[1][1] if isinstance(t, int)}
    if kind == "not":
        return _slots_in(f[1])
    if kind in ("and", "or"):
        return set().union(*(_slots_in(g) for g in f[1])) if f[1] else set()
    if kind == "imply":
        return _slots_in(f[1]) | _slots_in(f[2])
    return _slots_in(f[2]) - {slot for slot, _, _ in f[1]}


class _Compiler:
    def __init__(self, domain: Domain) -> None:
        self.domain = domain
        self.rules: list[Rule] = []
        self.aux_count: dict[str, int] = {}
        self.origin: dict[str, str] = {}  # auxiliary -> the derived predicate it serves

    def _product(self, parts: list[list[list[Any]]], owner: str) -> list[list[Any]]:
        out: list[list[Any]] = [[]]
        for options in parts:
            out = [a + b for a in out for b in options]
            if len(out) > MAX_CONJUNCTIONS:
                raise DerivedPredicateError(
                    f"the rule of derived predicate {owner} expands into more than "
                    f"{MAX_CONJUNCTIONS:,} conjunctions", field="domain", value=owner,
                    fix="split the rule into several (:derived ...) rules or simplify "
                        "its disjunctions")
        return out

    def dnf(self, f: Formula, positive: bool, types: dict[int, str], owner: str
            ) -> list[list[Any]]:
        """Disjunctive normal form of `f` (negated when not `positive`): a list of
        conjunctions of ("lit", positive, pred, terms) and ("forall", vars, f, positive)."""
        kind = f[0]
        if kind == "atom":
            return [[("lit", positive, f[1][0], f[1][1])]]
        if kind == "not":
            return self.dnf(f[1], not positive, types, owner)
        if kind in ("and", "or"):
            parts = [self.dnf(g, positive, types, owner) for g in f[1]]
            if (kind == "and") == positive:
                return self._product(parts, owner)
            return [c for p in parts for c in p]
        if kind == "imply":
            if positive:
                return self.dnf(f[1], False, types, owner) + self.dnf(f[2], True, types, owner)
            return self._product([self.dnf(f[1], True, types, owner),
                                  self.dnf(f[2], False, types, owner)], owner)
        for slot, _, kind_name in f[1]:
            types[slot] = kind_name
        if (kind == "exists") == positive:
            return self.dnf(f[2], positive, types, owner)
        return [[("forall", f[1], f[2], positive)]]

    def add_rules(self, head: str, head_terms: tuple[Term, ...], f: Formula, positive: bool,
                  types: dict[int, str], slots: int, owner: str) -> None:
        for conj in self.dnf(f, positive, types, owner):
            body: list[BodyLiteral] = []
            for item in conj:
                if item[0] == "lit":
                    body.append((item[1], item[2], item[3]))
                    continue
                _, variables, inner, sign = item
                bound = {slot for slot, _, _ in variables}
                free = tuple(sorted(_slots_in(inner) - bound))
                n = self.aux_count[owner] = self.aux_count.get(owner, 0) + 1
                aux = f"{owner}{AUX}{n}"
                self.origin[aux] = owner
                # forall v. g  ==  not aux(free), aux(free) := exists v. not g
                self.add_rules(aux, free, inner, not sign, types, slots, owner)
                body.append((False, aux, free))
            self.rules.append(Rule(head, head_terms, body, dict(types), slots))


def _plan(domain: Domain, rule: Rule, derived: set[str], first: int | None = None
          ) -> list[tuple[Any, ...]]:
    """The join order of one rule: ops ("join" | "bind" | "enum" | "check", ...); with
    `first`, that body literal is joined first, over the last round's new atoms."""
    pending = list(rule.body)
    bound: set[int] = set()
    ops: list[tuple[Any, ...]] = []
    needed = {t for t in rule.head_terms if isinstance(t, int)}
    for _, _, terms in pending:
        needed.update(t for t in terms if isinstance(t, int))

    def is_bound(t: Term) -> bool:
        return not isinstance(t, int) or t in bound

    def admits(slot: int, given: str | None) -> str | None:
        wanted = rule.types.get(slot, ROOT_TYPE)
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
        bound.update(seen)
        pending.remove(lit)

    if first is not None:
        join(rule.body[first], True)
    while pending or needed - bound:
        progress = False
        for lit in list(pending):  # checks as soon as their variables are bound
            positive, pred, terms = lit
            if all(is_bound(t) for t in terms):
                ops.append(("check", positive, pred, terms, pred in derived))
                pending.remove(lit)
                progress = True
        for lit in list(pending):  # (= ?x c) with one side bound binds the other
            positive, pred, terms = lit
            if positive and pred == "=":
                a, b = terms
                if is_bound(a) != is_bound(b):
                    target, source = (b, a) if is_bound(a) else (a, b)
                    assert isinstance(target, int)
                    ops.append(("bind", target, source, admits(target, None)))
                    bound.add(target)
                    pending.remove(lit)
                    progress = True
        if progress:
            continue
        joins = [lit for lit in pending if lit[0] and lit[1] != "="]
        if joins:
            join(max(joins, key=lambda x: sum(is_bound(t) for t in x[2])), False)
            continue
        slot = min(needed - bound)
        ops.append(("enum", slot, rule.types.get(slot, ROOT_TYPE)))
        bound.add(slot)
    return ops


def compile_axioms(domain: Domain, definitions: dict[str, list[Definition]]) -> Axioms:
    """Compile and stratify a domain's derived predicates (module docstring)."""
    compiler = _Compiler(domain)
    for pred, defs in definitions.items():
        for d in defs:
            types = dict(enumerate(d.head_types))
            compiler.add_rules(pred, tuple(range(len(d.head_types))), d.formula, True, types,
                               len(d.slot_names), pred)
    rules = compiler.rules
    heads = set(definitions) | set(compiler.origin)
    stratum = dict.fromkeys(heads, 0)
    limit = len(heads)
    changed = True
    while changed:
        changed = False
        for rule in rules:
            for positive, pred, _ in rule.body:
                if pred not in heads:
                    continue
                need = stratum[pred] + (0 if positive else 1)
                if stratum[rule.head] < need:
                    stratum[rule.head] = need
                    changed = True
                    if need > limit:
                        _unstratifiable(rules, heads, stratum, compiler.origin, rule.head)
    derived = set(heads)
    levels = sorted(set(stratum.values()))
    strata = []
    for level in levels:
        group = [r for r in rules if stratum[r.head] == level]
        for rule in group:
            rule.ops = _plan(domain, rule, derived)
            rule.delta_ops = [_plan(domain, rule, derived, j)
                              for j, (positive, pred, _) in enumerate(rule.body)
                              if positive and pred in heads and stratum[pred] == level]
        strata.append((group, any(r.delta_ops for r in group)))
    used = frozenset(pred for r in rules for _, pred, _ in r.body
                     if pred not in heads and pred != "=")
    return Axioms(frozenset(definitions), definitions, strata, used)


def _unstratifiable(rules: list[Rule], heads: set[str], stratum: dict[str, int],
                    origin: dict[str, str], at: str) -> None:
    """Raise the refusal, naming a negation that lies on a cycle of dependencies."""
    deps: dict[str, set[str]] = {}
    for r in rules:
        deps.setdefault(r.head, set()).update(p for _, p, _ in r.body if p in heads)

    def feeds(start: str, target: str) -> bool:  # target depends on start? (start ->* target)
        seen, todo = set(), [target]
        while todo:
            p = todo.pop()
            if p == start:
                return True
            if p not in seen:
                seen.add(p)
                todo.extend(deps.get(p, ()))
        return False

    def name(p: str) -> str:
        return origin.get(p, p)

    culprits = [(r.head, pred) for r in rules for positive, pred, _ in r.body
                if not positive and pred in heads and feeds(r.head, pred)]
    culprits.sort(key=lambda c: (c[0] in origin, c[1] in origin))
    head, negated = culprits[0] if culprits else (at, at)
    via = " (inside a forall)" if negated in origin else ""
    shown_head, shown_negated = name(head), name(negated)
    cycle = "itself" if shown_negated == shown_head else f"{shown_head}"
    raise DerivedPredicateError(
        f"the derived predicates cannot be stratified: the rule of {shown_head} negates "
        f"{shown_negated}{via}, which depends on {cycle}", field="domain", value=shown_head,
        fix=f"negate {shown_negated} only in rules of predicates it does not feed "
            "(stratified negation), or make one of them a basic predicate set by actions")


# ---------------------------------------------------------------- evaluation

class _Index:
    """Atoms by predicate, and by (predicate, position) -> object, growing as rules fire."""

    __slots__ = ("by_pred", "by_arg")

    def __init__(self) -> None:
        self.by_pred: dict[str, list[GroundAtom]] = {}
        self.by_arg: dict[tuple[str, int], dict[str, list[GroundAtom]]] = {}

    def add(self, atom: GroundAtom) -> None:
        self.by_pred.setdefault(atom[0], []).append(atom)
        for pos in range(1, len(atom)):
            table = self.by_arg.get((atom[0], pos))
            if table is not None:
                table.setdefault(atom[pos], []).append(atom)

    def matching(self, pred: str, pos: int, obj: str) -> list[GroundAtom]:
        table = self.by_arg.get((pred, pos))
        if table is None:
            table = {}
            for atom in self.by_pred.get(pred, ()):
                table.setdefault(atom[pos], []).append(atom)
            self.by_arg[(pred, pos)] = table
        return table.get(obj, [])


class _Run:
    """One recomputation: the basic state, the derived atoms so far, the binding budget."""

    def __init__(self, domain: Domain, problem: Problem, state: set[GroundAtom],
                 axioms: Axioms) -> None:
        self.domain, self.problem, self.state = domain, problem, state
        self.derived: set[GroundAtom] = set()
        self.index = _Index()
        used = axioms.used_basic
        for atom in state:
            if atom[0] in used:
                self.index.add(atom)
        self.tried = 0
        self.types: dict[str, frozenset[str]] = {}
        self.delta = _Index()

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
            if self.tried > MAX_DERIVED_BINDINGS:
                raise DerivedPredicateError(
                    f"computing the derived predicates of one state tries more than "
                    f"{MAX_DERIVED_BINDINGS:,} bindings", field="domain",
                    value=self.tried, fix="give the rules' variables smaller types or "
                                          "fewer objects")

    def fire(self, rule: Rule, ops: list[tuple[Any, ...]]) -> list[GroundAtom]:
        out: list[GroundAtom] = []
        binding: list[str | None] = [None] * rule.slots
        self._step(rule, ops, 0, binding, out)
        return out

    def _step(self, rule: Rule, ops: list[tuple[Any, ...]], k: int, b: list[str | None],
              out: list[GroundAtom]) -> None:
        while k < len(ops):
            op = ops[k]
            kind = op[0]
            if kind == "check":
                _, positive, pred, terms, is_derived = op
                atom = (pred, *(b[t] if isinstance(t, int) else t for t in terms))
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
            if kind == "enum":
                _, slot, kind_name = op
                objs = self.problem.of_type(self.domain, kind_name)
                self.tick(len(objs))
                for obj in objs:
                    b[slot] = obj
                    self._step(rule, ops, k + 1, b, out)
                b[slot] = None
                return
            _, pred, fixed, free, same, _, delta = op
            index = self.delta if delta else self.index
            if fixed:
                pos, t = fixed[0]
                candidates = index.matching(pred, pos, str(b[t] if isinstance(t, int) else t))
                rest = fixed[1:]
            else:
                candidates = index.by_pred.get(pred, [])
                rest = fixed
            self.tick(len(candidates))
            for atom in candidates:
                if any(atom[pos] != (b[t] if isinstance(t, int) else t) for pos, t in rest):
                    continue
                if any(atom[p] != atom[q] for p, q in same):
                    continue
                ok = True
                for pos, slot, wanted in free:
                    if wanted is not None and atom[pos] not in self.admits(wanted):
                        ok = False
                        break
                    b[slot] = atom[pos]
                if ok:
                    self._step(rule, ops, k + 1, b, out)
            for _, slot, _ in free:
                b[slot] = None
            return
        out.append((rule.head, *(str(b[t]) if isinstance(t, int) else t
                                 for t in rule.head_terms)))

    def run(self, axioms: Axioms) -> set[GroundAtom]:
        """Strata bottom-up; a recursive one semi-naively: first its rules that need none
        of its own atoms, then, round by round, every derivation that uses an atom the
        last round found (joined first, from `delta`) until a round finds nothing new."""
        derived, index = self.derived, self.index
        for rules, recursive in axioms.strata:
            new: list[GroundAtom] = []
            for rule in rules:
                if not rule.delta_ops:
                    for atom in self.fire(rule, rule.ops):
                        if atom not in derived:
                            derived.add(atom)
                            index.add(atom)
                            new.append(atom)
            while recursive and new:
                self.delta = _Index()
                for atom in new:
                    self.delta.add(atom)
                new = []
                for rule in rules:
                    for ops in rule.delta_ops:
                        for atom in self.fire(rule, ops):
                            if atom not in derived:
                                derived.add(atom)
                                index.add(atom)
                                new.append(atom)
        keep = axioms.predicates
        return {a for a in derived if a[0] in keep}


def derive(domain: Domain, problem: Problem, state: set[GroundAtom]) -> set[GroundAtom]:
    """The derived atoms that hold in `state` (whose derived atoms, if any, are ignored)."""
    axioms = domain.axioms
    assert axioms is not None
    return _Run(domain, problem, state, axioms).run(axioms)


def refresh(domain: Domain, problem: Problem, state: set[GroundAtom],
            previous: set[GroundAtom], changed: dict[GroundAtom, tuple[int, str]] | None,
            step: int, action: str) -> set[GroundAtom]:
    """Recompute the derived atoms of `state` in place after a change of its basic atoms:
    the ones no longer derived leave it, the new ones join it, each flip recorded in
    `changed` as made by `step` (the step whose effects caused it). Returns the new set."""
    now = derive(domain, problem, state)
    gone = previous - now
    new = now - previous
    state.difference_update(gone)
    state.update(new)
    if changed is not None and step:
        for atom in gone:
            changed[atom] = (step, action)
        for atom in new:
            changed[atom] = (step, action)
    return now


def explain(domain: Domain, problem: Problem, state: set[GroundAtom], atom: GroundAtom,
            expected: bool) -> str:
    """Why a derived `atom` does not have the value `expected` in `state`: it is derived,
    and for a false one, why each of its rules' bodies fails (the first counterexample)."""
    axioms = domain.axioms
    assert axioms is not None
    if expected is False:
        return f"{show(atom)} is derived and its rule holds in this state"
    reasons = []
    ev = Evaluator(domain, problem, state)
    for d in axioms.definitions.get(atom[0], [])[:3]:
        slots: list[str | None] = [*atom[1:], *([None] * (len(d.slot_names) - len(atom) + 1))]
        if any(not domain.is_a(problem.objects.get(str(o), ""), t)
               for o, t in zip(atom[1:], d.head_types, strict=True)):
            reasons.append("its arguments do not have the rule's types")
            continue
        try:
            why = ev.why_false(d.formula, slots, d.slot_names)
        except VeriGraphError:
            why = "its body is false"
        reasons.append(f"{text(d.formula, slots, d.slot_names)[:160]} fails: {why[:200]}")
    return f"{show(atom)} is derived (:derived {atom[0]}); " + "; ".join(reasons)


def head_types_for(domain: Domain, pred: str, given: list[str]) -> list[str]:
    """The head's variable types: as written, else the predicate's declared ones."""
    signature = domain.predicates[pred]
    return [g if g != ROOT_TYPE else s for g, s in zip(given, signature, strict=True)]


__all__ = ["Axioms", "Definition", "DerivedPredicateError", "compile_axioms", "derive",
           "explain", "head_types_for", "note", "refresh"]


def note(domain: Domain, problem: Problem, state: set[GroundAtom], item: dict[str, Any],
         atom: GroundAtom | None) -> None:
    """Mark an unsatisfied precondition or unmet goal that is (or mentions) a derived
    literal: `derived` lists the derived predicates, and the explanation says why a
    derived atom is false (its rules' bodies) or that its rule holds."""
    axioms = domain.axioms
    if axioms is None:
        return
    if atom is not None:
        if atom[0] not in axioms.predicates:
            return
        item["derived"] = [atom[0]]
        why = explain(domain, problem, state, atom, bool(item.get("expected", True)))
        item["explanation"] = f"{item.get('explanation', '')}; {why}".lstrip("; ")
        return
    literal = str(item.get("literal", ""))
    found = sorted(p for p in axioms.predicates if f"({p} " in literal or f"({p})" in literal)
    if found:
        item["derived"] = found
        item["explanation"] = (f"{item.get('explanation', '')} ("
                               f"{', '.join(found)} derived by the domain's :derived rules)")
