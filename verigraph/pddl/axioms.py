"""Derived predicates (PDDL 2.2 `:derived-predicates`): stratified rules, evaluated per state.

`(:derived (p ?x - t) formula)` makes `(p a)` true in a state exactly when the formula
holds for `?x = a`; several rules for one predicate are a disjunction, and a rule may
use derived predicates, itself included (least fixpoint: `upstream` in psr is a
transitive closure). Actions never change a derived predicate and the initial state
never lists one (the reader refuses both by name): in the initial state and after every
step the simulator brings the derived atoms up to date with the basic ones
(`Derivation`), so preconditions, conditions of conditional effects and goals read them
as ordinary atoms of the state.

Each rule body (any ADL formula: and, or, not, imply, exists, forall, equality) is
compiled once per domain into conjunctive rules, as Fast Downward's translator does:
negation is pushed to the literals, `or` splits a rule into several, an `exists`
binds body variables, and a `forall` becomes the negation of an auxiliary derived
predicate (`forall x. f` is `not exists x. not f`) over the variables it shares with the
rule. Negation must be stratified: a derived predicate (auxiliaries included) may be
negated only in a rule of a predicate in a higher stratum, never in one it feeds, else
the rules have no single meaning and the domain is refused by name (`field="domain"`,
with the predicates at fault). A stratum is evaluated by joins over the atoms that hold
(`joins`: bound variables first, each body literal checked as soon as its variables are
bound; a variable no positive literal binds ranges over the objects of its type, and a
quantified variable no literal mentions, as in `(exists (?t - tool) (ready))`, still
needs an object of its type: PDDL's exists over no objects is false, its forall true) and
repeated until nothing new is derived; strata run bottom-up, and after a step only
those that read a predicate the step changed.

Limits: one recomputation may try at most `MAX_DERIVED_BINDINGS` bindings (a
VeriGraphError beyond, never a half-computed state), a rule body (or a forall's) may
expand into at most `MAX_CONJUNCTIONS` conjunctions, refused before they are built, and
a domain's rules into at most `MAX_RULES` (a forall is compiled once, however many
conjunctions it is part of).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import chain, product
from typing import Any

from verigraph.errors import VeriGraphError
from verigraph.pddl.formulas import Evaluator, Formula, text
from verigraph.pddl.joins import BodyLiteral, Index, Joiner, plan
from verigraph.pddl.model import (
    ROOT_TYPE,
    Domain,
    GroundAtom,
    Grounder,
    Problem,
    Term,
    atom_text,
    grounder,
)

MAX_DERIVED_BINDINGS = 1_000_000
MAX_CONJUNCTIONS = 4_096
MAX_RULES = 16_384  # conjunctive rules of a whole domain (auxiliaries' included)
AUX = "#forall"  # auxiliary predicate names: `p#forall1` (no PDDL name has '#')


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
    # types that must have an object: those of quantified variables no body literal
    # mentions (`exists (?t - tool) (ready)` is false when there is no tool)
    nonempty: tuple[str, ...] = ()
    ops: list[tuple[Any, ...]] = field(default_factory=list)
    ground: Grounder = field(init=False)  # the head's atom under a binding
    # semi-naive evaluation: one join order per body literal of the rule's own stratum,
    # that literal joined first over the atoms the last round derived
    delta_ops: list[list[tuple[Any, ...]]] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.ground = grounder((self.head, self.head_terms))


@dataclass(slots=True)
class Axioms:
    """A domain's compiled derived predicates."""

    predicates: frozenset[str]  # the declared derived predicates
    definitions: dict[str, list[Definition]]
    strata: list[tuple[list[Rule], bool]]  # rules per stratum, and whether it recurses
    used_basic: frozenset[str]  # basic predicates some rule reads
    reads: list[frozenset[str]]  # per stratum: the predicates its rules read
    heads: list[frozenset[str]]  # per stratum: the predicates it derives
    joined: frozenset[str] = frozenset()  # derived predicates a rule joins on (indexed)


# ---------------------------------------------------------------- compiling

def _bounded(conjunctions: int, owner: str) -> None:
    if conjunctions > MAX_CONJUNCTIONS:
        raise DerivedPredicateError(
            f"the rule of derived predicate {owner} expands into more than "
            f"{MAX_CONJUNCTIONS:,} conjunctions", field="domain", value=owner,
            fix="split the rule into several (:derived ...) rules or simplify its "
                "disjunctions")


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
        # a forall item (by identity: a product copies it into many conjunctions) -> its
        # auxiliary and free variables, compiled once; the item is kept alive with it
        self.aux_of: dict[int, tuple[Any, str, tuple[int, ...]]] = {}

    def _product(self, parts: list[list[list[Any]]], owner: str) -> list[list[Any]]:
        """The conjunctions of a conjunction of DNFs, refused before it is built when it
        would have more than MAX_CONJUNCTIONS (two halves of 4,096 make 16.7 million)."""
        total = 1
        for options in parts:
            total *= len(options)
            _bounded(total, owner)
        # each conjunction built once (growing them part by part was quadratic in a long
        # `and`: 200,000 literals took 36 s)
        return [list(chain.from_iterable(combo)) for combo in product(*parts)]

    def _union(self, parts: list[list[list[Any]]], owner: str) -> list[list[Any]]:
        """The conjunctions of a disjunction of DNFs, bounded as `_product`'s."""
        _bounded(sum(map(len, parts)), owner)
        return [c for p in parts for c in p]

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
            return self._union(parts, owner)
        if kind == "imply":
            if positive:
                return self._union([self.dnf(f[1], False, types, owner),
                                    self.dnf(f[2], True, types, owner)], owner)
            return self._product([self.dnf(f[1], True, types, owner),
                                  self.dnf(f[2], False, types, owner)], owner)
        for slot, _, kind_name in f[1]:
            types[slot] = kind_name
        if (kind == "exists") == positive:
            # ("some", vars): the variables range over their types even where no literal
            # of the body mentions them (exists over a type with no objects is false)
            return [[*c, ("some", f[1])] for c in self.dnf(f[2], positive, types, owner)]
        return [[("forall", f[1], f[2], positive)]]

    def add_rules(self, head: str, head_terms: tuple[Term, ...], f: Formula, positive: bool,
                  types: dict[int, str], slots: int, owner: str,
                  quantified: tuple[tuple[int, str, str], ...] = ()) -> None:
        """The rules of `head(head_terms) :- f` (negated when not `positive`);
        `quantified`: the variables the body is existentially quantified over besides
        its own `exists` (an auxiliary's: those of the forall it stands for)."""
        for conj in self.dnf(f, positive, types, owner):
            body: list[BodyLiteral] = []
            witnesses = list(quantified)
            for item in conj:
                if item[0] == "lit":
                    body.append((item[1], item[2], item[3]))
                    continue
                if item[0] == "some":
                    witnesses.extend(item[1])
                    continue
                known = self.aux_of.get(id(item))
                if known is None:
                    _, variables, inner, sign = item
                    bound = {slot for slot, _, _ in variables}
                    free = tuple(sorted(_slots_in(inner) - bound))
                    n = self.aux_count[owner] = self.aux_count.get(owner, 0) + 1
                    aux = f"{owner}{AUX}{n}"
                    self.origin[aux] = owner
                    self.aux_of[id(item)] = (item, aux, free)
                    # forall v. g  ==  not aux(free), aux(free) := exists v. not g
                    self.add_rules(aux, free, inner, not sign, types, slots, owner,
                                   tuple(variables))
                else:
                    _, aux, free = known
                body.append((False, aux, free))
            mentioned = {t for _, _, terms in body for t in terms if isinstance(t, int)}
            # a quantified variable no literal mentions: its type needs an object, no more
            nonempty = tuple(dict.fromkeys(kind for slot, _, kind in witnesses
                                           if slot not in mentioned))
            self.rules.append(Rule(head, head_terms, body, dict(types), slots,
                                   nonempty=nonempty))
            if len(self.rules) > MAX_RULES:
                raise DerivedPredicateError(
                    f"the derived predicates compile into more than {MAX_RULES:,} "
                    f"conjunctive rules (at the rule of {owner})", field="domain",
                    value=owner, fix="write fewer or simpler (:derived ...) rules: fewer "
                                     "disjunctions, and foralls over simpler formulas")


def _plan(domain: Domain, rule: Rule, derived: set[str], first: int | None = None
          ) -> list[tuple[Any, ...]]:
    """The join order of one rule (see joins.plan); with `first`, that body literal is
    joined first, over the last round's new atoms."""
    needed = {t for t in rule.head_terms if isinstance(t, int)}
    return plan(domain, rule.body, rule.types, needed, joinable=lambda pred: True,
                derived=derived, first=first, nonempty=rule.nonempty)


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
    reads = [frozenset(pred for r in group for _, pred, _ in r.body) for group, _ in strata]
    derives = [frozenset(r.head for r in group) for group, _ in strata]
    joined = frozenset(pred for r in rules for positive, pred, _ in r.body
                       if positive and pred in heads)
    return Axioms(frozenset(definitions), definitions, strata, used, reads, derives, joined)


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

def _too_many(tried: int) -> VeriGraphError:
    return DerivedPredicateError(
        f"computing the derived predicates of one state tries more than "
        f"{MAX_DERIVED_BINDINGS:,} bindings", field="domain", value=tried,
        fix="give the rules' variables smaller types or fewer objects")


class Derivation:
    """The derived atoms of a simulation's states, kept up to date step by step.

    The basic atoms the rules read are indexed once and the index follows each step's
    edit (`follow`); a stratum is evaluated again only when a predicate it reads
    changed (a basic one in the step's edit, or a derived one whose atoms a lower
    stratum changed), else its atoms carry over from the state before, at no cost: the
    set of every derived atom (auxiliaries included, which checks read) and the index of
    those some rule joins on are kept too, and only an evaluated stratum's old atoms
    leave them and its new ones join them (a step that changes nothing the rules read
    costs nothing however many atoms are derived). Each evaluated stratum joins its
    rules over the atoms that hold; a recursive one semi-naively (see `_stratum`).
    `atoms` are the derived atoms of the declared predicates (auxiliaries left out):
    what the state holds of them."""

    def __init__(self, domain: Domain, problem: Problem, state: set[GroundAtom]) -> None:
        axioms = domain.axioms
        assert axioms is not None
        self.domain, self.problem, self.axioms = domain, problem, axioms
        used = axioms.used_basic
        self.basic = Index(atom for atom in state if atom[0] in used)
        self.by_stratum: list[set[GroundAtom]] = [set() for _ in axioms.strata]
        self.derived: set[GroundAtom] = set()  # every stratum's atoms
        self.index = Index()  # those of predicates a rule joins on (`Axioms.joined`)
        self.atoms: set[GroundAtom] = set()
        self._evaluate(state, None)

    def follow(self, state: set[GroundAtom], removed: list[GroundAtom],
               added: list[GroundAtom], changed: dict[GroundAtom, tuple[int, str]],
               step: int, action: str) -> None:
        """Update the derived atoms of `state` after a step removed and added these
        basic atoms: the ones no longer derived leave it, the new ones join it, each flip
        recorded in `changed` as made by `step` (the step whose effects caused it)."""
        used, basic = self.axioms.used_basic, self.basic
        touched = set()
        for atom in removed:
            touched.add(atom[0])
            if atom[0] in used:
                basic.discard(atom)
        for atom in added:
            touched.add(atom[0])
            if atom[0] in used:
                basic.add(atom)
        gone, new = self._evaluate(state, touched)
        state.difference_update(gone)
        state.update(new)
        for atom in gone:
            changed[atom] = (step, action)
        for atom in new:
            changed[atom] = (step, action)

    def _evaluate(self, state: set[GroundAtom], touched: set[str] | None
                  ) -> tuple[list[GroundAtom], list[GroundAtom]]:
        """Strata bottom-up; with `touched`, only those that read a changed predicate.
        Returns the atoms of declared predicates that stopped and started to hold."""
        axioms = self.axioms
        keep, joined, derived, index = axioms.predicates, axioms.joined, self.derived, \
            self.index
        joiner = Joiner(self.domain, self.problem, state, self.basic,
                        limit=MAX_DERIVED_BINDINGS, error=_too_many, derived=derived,
                        derived_index=index)
        gone: list[GroundAtom] = []
        new: list[GroundAtom] = []
        for k, (rules, recursive) in enumerate(axioms.strata):
            if touched is not None and touched.isdisjoint(axioms.reads[k]):
                continue  # its atoms carry over
            before = self.by_stratum[k]
            derived.difference_update(before)  # a rule reads no higher stratum's atoms
            if not joined.isdisjoint(axioms.heads[k]):
                for atom in before:
                    if atom[0] in joined:
                        index.discard(atom)
            atoms = _stratum(joiner, rules, recursive, index, joined)
            self.by_stratum[k] = atoms
            if atoms != before:
                if touched is not None:
                    touched.update(axioms.heads[k])
                gone += [a for a in before - atoms if a[0] in keep]
                new += [a for a in atoms - before if a[0] in keep]
        self.atoms.difference_update(gone)
        self.atoms.update(new)
        return gone, new


def _stratum(joiner: Joiner, rules: list[Rule], recursive: bool, index: Index,
             joined: frozenset[str]) -> set[GroundAtom]:
    """The atoms of one stratum: first its rules that need none of its own atoms, then,
    for a recursive one, round by round every derivation that uses an atom the last
    round found (joined first, from the joiner's `delta`) until a round finds nothing
    new. Each atom joins the joiner's derived set as it is found, and `index` when some
    rule joins on its predicate (`joined`)."""
    derived = joiner.derived
    found: set[GroundAtom] = set()
    new: list[GroundAtom] = []

    def keep(atoms: list[GroundAtom]) -> None:
        for atom in atoms:
            if atom not in derived:
                derived.add(atom)
                found.add(atom)
                if atom[0] in joined:  # a later join reads it
                    index.add(atom)
                new.append(atom)

    for rule in rules:
        if not rule.delta_ops:
            keep(_fire(joiner, rule, rule.ops))
    while recursive and new:
        joiner.delta = Index(new)
        new = []
        for rule in rules:
            for ops in rule.delta_ops:
                keep(_fire(joiner, rule, ops))
    return found


def _fire(joiner: Joiner, rule: Rule, ops: list[tuple[Any, ...]]) -> list[GroundAtom]:
    out: list[GroundAtom] = []
    ground, append = rule.ground, out.append
    joiner.run(ops, [None] * rule.slots, lambda b: append(ground(b)))
    return out


def derive(domain: Domain, problem: Problem, state: set[GroundAtom]) -> set[GroundAtom]:
    """The derived atoms that hold in `state` (whose derived atoms, if any, are ignored)."""
    return Derivation(domain, problem, state).atoms


def explain(domain: Domain, problem: Problem, state: set[GroundAtom], atom: GroundAtom,
            expected: bool) -> str:
    """Why a derived `atom` does not have the value `expected` in `state`: it is derived,
    and for a false one, why each of its rules' bodies fails (the first counterexample)."""
    axioms = domain.axioms
    assert axioms is not None
    if expected is False:
        return f"{atom_text(atom)} is derived and its rule holds in this state"
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
    return f"{atom_text(atom)} is derived (:derived {atom[0]}); " + "; ".join(reasons)


def head_types_for(domain: Domain, pred: str, given: list[str]) -> list[str]:
    """The head's variable types: as written, else the predicate's declared ones."""
    signature = domain.predicates[pred]
    return [g if g != ROOT_TYPE else s for g, s in zip(given, signature, strict=True)]


__all__ = ["Axioms", "Definition", "Derivation", "DerivedPredicateError", "compile_axioms",
           "derive", "explain", "head_types_for", "note"]


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
