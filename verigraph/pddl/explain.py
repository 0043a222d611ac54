"""Why a literal does not hold, and which actions would make it hold: bounded searches.

`history` says which step last changed an atom (or that it never held) and, for an atom
that is false, what holds instead (`(at a0 l0-0)`, true since the start, for a wanted
`(at a0 l1-0)`): the atoms of the same predicate that share its first argument (or, failing
that, another argument).

`Explainer.achievers` lists the actions whose effects would give an atom the wanted value.
Each is lifted from the atom (`(unload-truck p0 ?truck ap)`) and then grounded by a
search for its *closest* binding: the one with the fewest unsatisfied preconditions, zero
meaning applicable now. The search joins the action's preconditions with the atoms that
hold (an index by predicate, argument position and object), the one with the most bound
terms first, so it is bounded by the state the plan reached and the atom being explained,
not by the number of groundings:

- preconditions on static predicates (no action changes them), equalities and types are
  hard: an achiever none of whose bindings satisfies them can never apply and is not
  listed (a truck that is a package, a road that does not exist);
- the others cost one each when unsatisfied, so the grounding shown says what is still
  needed (`needs (at ?truck ap)`) and the list is ordered by that count: applicable now
  first, then the ones the plan is closest to reaching;
- an ADL precondition (or, forall, ...) is checked once a binding is complete and counts
  one when false; achievers come from unconditional effects only (an effect under `when`
  or `forall` is not searched);
- once `MAX_ACHIEVERS` are found, a later action is searched only for a grounding that
  needs less than the last of them (the list is the same as if every achiever were
  searched in full);
- every search is bounded: `ACHIEVER_NODES` candidate bindings per achiever and
  `REPORT_NODES` per report (an achiever whose search ran out is listed as unsearched,
  after the others), `REPORT_QUANTIFIED` bindings for the quantifiers of the ADL
  preconditions of every candidate of a report (beyond, such a precondition counts as
  unsatisfied: 1,000 candidates of an action whose forall spans a million bindings took
  minutes; now they cost one step's worth), and it checks the call's budget (`verigraph.budget`)
  as it goes, so a server can stop it. Explaining 20 unmet goals of a domain of 10
  six-parameter actions over 40 objects takes a few milliseconds, and no search takes
  more than about 50 ms.
"""

from __future__ import annotations

from typing import Any

from verigraph.budget import checkpoint
from verigraph.pddl.formulas import MAX_QUANTIFIED, Evaluator, QuantifierLimitError
from verigraph.pddl.formulas import text as formula_text
from verigraph.pddl.model import (
    Domain,
    GroundAtom,
    Literal,
    Problem,
    Schema,
    atom_text,
    grounder,
)

Changed = dict[GroundAtom, tuple[int, str]]  # atom -> (step, action) that last changed it
ACHIEVER_NODES = 1_000
REPORT_NODES = 8_000
MAX_ACHIEVERS = 4
REPORT_QUANTIFIED = MAX_QUANTIFIED  # see Explainer.quantified
MAX_INSTEAD = 2


def literal_text(atom: GroundAtom, expected: bool) -> str:
    return atom_text(atom) if expected else f"(not {atom_text(atom)})"


def atom_holds(atom: GroundAtom, state: set[GroundAtom]) -> bool:
    """Whether a ground atom holds in `state` (equality by its terms)."""
    if atom[0] == "=":
        return atom[1] == atom[2]
    return atom in state


def _since(atom: GroundAtom, changed: Changed) -> str:
    last = changed.get(atom)
    return "true since the start" if last is None else \
        f"made true at step {last[0]} by {last[1]}"


def instead(atom: GroundAtom, state: set[GroundAtom], index: StateIndex | None = None
            ) -> list[GroundAtom]:
    """Atoms that hold in place of a false `atom`: same predicate, sharing its first
    argument (else any other argument at the same position)."""
    if atom[0] == "=" or len(atom) < 2:
        return []
    index = index or StateIndex(state)
    for position in range(1, len(atom)):
        found = [a for a in index.matching(atom[0], position, atom[position]) if a != atom]
        if found:
            return sorted(found)[:MAX_INSTEAD]
    return []


def history(atom: GroundAtom, expected: bool, changed: Changed, state: set[GroundAtom],
            index: StateIndex | None = None, static: frozenset[str] = frozenset()
            ) -> dict[str, Any]:
    """Why `atom` does not have the value `expected`: the step that last changed it, and
    for a false atom what holds instead; a fact of a predicate no action changes is said
    to be fixed (no step can change it)."""
    if atom[0] == "=":
        same = "the same object" if atom[1] == atom[2] else "different objects"
        return {"last_changed": None, "explanation": f"{atom[1]} and {atom[2]} are {same}"}
    last = changed.get(atom)
    if last is not None:
        made = "false" if expected else "true"
        text = f"made {made} at step {last[0]} by {last[1]}"
        out: dict[str, Any] = {"last_changed": {"step": last[0], "action": last[1]}}
    elif atom[0] in static:
        fixed = "false" if expected else "true"
        return {"last_changed": None, "fixed": True,
                "explanation": f"{fixed} in the initial state and no action changes "
                               f"{atom[0]}"}
    elif expected:
        text, out = "never true", {"last_changed": None}
    else:
        return {"last_changed": None, "explanation": "true in the initial state, never made "
                                                     "false"}
    if expected:
        others = instead(atom, state, index)
        if others:
            out["instead"] = [{"literal": atom_text(a), "since": _since(a, changed)}
                              for a in others]
            text += "; instead " + ", ".join(f"{atom_text(a)} holds ({_since(a, changed)})"
                                             for a in others)
    out["explanation"] = text
    return out


class StateIndex:
    """The atoms of one state by predicate (sorted: the same explanation in every
    process), and by (predicate, position, object): the first lookups of a (predicate,
    position) filter its atoms, later ones get a table of them all, built once (a
    search looks up many objects at one position; `instead` looks up one). A read-only
    view of one state, for explanations; `joins.Index` is the index atoms join and
    leave as a plan runs (derived predicates, quantified effects)."""

    __slots__ = ("state", "by_pred", "by_arg", "sorted", "found", "lookups")

    def __init__(self, state: set[GroundAtom]) -> None:
        self.state = state
        self.by_pred: dict[str, list[GroundAtom]] | None = None
        self.by_arg: dict[tuple[str, int], dict[str, list[GroundAtom]]] = {}
        self.sorted: set[str] = set()
        self.found: dict[tuple[str, int, str], list[GroundAtom]] = {}
        self.lookups: dict[tuple[str, int], int] = {}

    def of(self, pred: str) -> list[GroundAtom]:
        """The atoms of `pred` that hold, sorted."""
        by_pred = self.by_pred
        if by_pred is None:
            by_pred = self.by_pred = {}
            for atom in self.state:
                by_pred.setdefault(atom[0], []).append(atom)
        found = by_pred.get(pred, [])
        if pred not in self.sorted:
            found.sort()
            self.sorted.add(pred)
        return found

    def matching(self, pred: str, position: int, obj: str) -> list[GroundAtom]:
        """The atoms of `pred` with `obj` at `position`, sorted."""
        table = self.by_arg.get((pred, position))
        if table is not None:
            return table.get(obj, [])
        key = (pred, position, obj)
        found = self.found.get(key)
        if found is not None:
            return found
        seen = self.lookups.get((pred, position), 0)
        if seen < 2:
            self.lookups[(pred, position)] = seen + 1
            found = self.found[key] = [a for a in self.of(pred)
                                       if len(a) > position and a[position] == obj]
            return found
        table = {}
        for atom in self.of(pred):
            if len(atom) > position:
                table.setdefault(atom[position], []).append(atom)
        self.by_arg[(pred, position)] = table
        return table.get(obj, [])


class _SchemaPlan:
    """What every search of one schema shares, built once per domain: its precondition
    literals (with their sign and whether they are hard), the literals each slot
    appears in, and the positive literals that can drive a join."""

    __slots__ = ("literals", "by_slot", "joins", "tests")

    def __init__(self, domain: Domain, schema: Schema) -> None:
        static = domain.static
        lits = [(lit, True) for lit in schema.pre_pos] + [(lit, False) for lit in schema.pre_neg]
        self.literals = [(lit, expected, lit[0] == "=" or lit[0] in static)
                         for lit, expected in lits]
        # per literal: its slots (all bound: it can be decided) and its atom's grounder
        self.tests = [(tuple(dict.fromkeys(t for t in lit[1] if isinstance(t, int))),
                       grounder(lit)) for lit, _ in lits]
        # binding a slot decides only the literals it appears in
        self.by_slot: dict[int, list[int]] = {}
        for k, ((_, terms), _) in enumerate(lits):
            for t in dict.fromkeys(t for t in terms if isinstance(t, int)):
                self.by_slot.setdefault(t, []).append(k)
        # hard (static) ones first where the search must choose between equals
        self.joins = sorted([k for k, (lit, expected, _) in enumerate(self.literals)
                             if expected and lit[0] != "="],
                            key=lambda k: not self.literals[k][2])

    @staticmethod
    def of(domain: Domain, schema: Schema) -> _SchemaPlan:
        key = f"explain {schema.name}"  # beside the schemas' names (no name has a space)
        found = domain.compiled.get(key)
        if found is None:
            found = domain.compiled[key] = _SchemaPlan(domain, schema)
        assert isinstance(found, _SchemaPlan)
        return found


class _Search:
    """The closest binding of one schema extending a partial binding (module docstring).

    A branch and bound over bindings: each step joins the undecided positive literal
    with the most bound terms (a hard one first among equals) with the atoms that hold,
    or, for a literal that is not hard, leaves it unsatisfied at a cost of one; a
    literal is decided as soon as its slots are bound."""

    def __init__(self, explainer: Explainer, schema: Schema, binding: list[str | None],
                 index: StateIndex, exact: bool, below: int | None = None) -> None:
        self.e = explainer
        self.schema = schema
        self.values = list(binding)
        self.index = index
        self.exact = exact  # cost 0 only (applicable now), no skipped literal
        plan = _SchemaPlan.of(explainer.domain, schema)
        self.literals, self.by_slot, self.joins = plan.literals, plan.by_slot, plan.joins
        self.tests = plan.tests
        # with `below`, only a grounding of lower cost is wanted: the bound prunes from
        # the start, and a search that finds none ends with this placeholder
        self.bound: tuple[int, tuple[str, ...], list[int]] | None = \
            None if below is None else (below, (), [])
        self.best: tuple[int, tuple[str, ...], list[int]] | None = self.bound
        self.nodes = ACHIEVER_NODES
        self.exhausted = False

    def _score(self, decided: list[bool], touched: list[int] | None = None
               ) -> tuple[int, list[int]] | None:
        """Cost of the literals decidable now (None: a hard literal fails); with
        `touched`, only the literals of those newly bound slots can have become so."""
        cost, failed = 0, []
        if touched is None:
            candidates: Any = range(len(self.literals))
        elif len(touched) == 1:
            candidates = self.by_slot.get(touched[0], ())
        else:
            by_slot = self.by_slot
            candidates = sorted({k for t in touched for k in by_slot.get(t, ())})
        state, literals, exact, values = self.index.state, self.literals, self.exact, self.values
        tests = self.tests
        for k in candidates:
            if decided[k]:
                continue
            slots, ground = tests[k]
            for t in slots:
                if values[t] is None:
                    break
            else:
                _, expected, hard = literals[k]
                atom = ground(values)
                if (atom[1] == atom[2] if atom[0] == "=" else atom in state) != expected:
                    if hard or exact:
                        return None
                    cost += 1
                    failed.append(k)
                decided[k] = True
        return cost, failed

    def _tick(self) -> bool:
        self.nodes -= 1
        self.e.nodes -= 1
        if self.nodes & 63 == 0:
            checkpoint()
        if self.nodes < 0 or self.e.nodes < 0:
            self.exhausted = True
            return False
        return True

    def run(self) -> None:
        decided = [False] * len(self.literals)
        scored = self._score(decided)
        if scored is None:
            return
        cost, failed = scored
        for k, (lit, expected, hard) in enumerate(self.literals):
            if decided[k] or not expected or lit[0] == "=" \
                    or self._candidates(lit)[1] is not None:
                continue
            if hard or self.exact:  # no atom that holds can match it: no grounding can
                return
            decided[k] = True  # unsatisfied whatever the binding: counted once, not searched
            cost += 1
            failed = [*failed, k]
        self._step(decided, cost, failed)

    def _candidates(self, lit: Literal
                    ) -> tuple[list[tuple[int, str]], list[GroundAtom] | None]:
        """The literal's bound (position, object) pairs, and the atoms that hold of its
        predicate with the rarest of them in place (None: no atom fits them all)."""
        pred, terms = lit
        values = self.values
        bound = [(pos, str(values[t]) if isinstance(t, int) else t)
                 for pos, t in enumerate(terms, start=1)
                 if not isinstance(t, int) or values[t] is not None]
        if not bound:
            found = self.index.of(pred)
            return bound, found or None
        found = min((self.index.matching(pred, pos, obj) for pos, obj in bound), key=len)
        if len(bound) > 1:
            found = [a for a in found if all(a[pos] == obj for pos, obj in bound)]
        return bound, found or None

    def _done(self) -> bool:
        return self.exhausted or (self.best is not None and self.best[0] == 0)

    def _pick(self, decided: list[bool]) -> int | None:
        """The undecided join literal with the most bound terms (the joins list puts
        hard ones first, and the first of equals wins)."""
        values = self.values
        pick, most = None, -1
        for k in self.joins:
            if decided[k]:
                continue
            bound = sum(1 for t in self.literals[k][0][1]
                        if not isinstance(t, int) or values[t] is not None)
            if bound > most:
                pick, most = k, bound
        return pick

    def _step(self, decided: list[bool], cost: int, failed: list[int]) -> None:
        if self._done() or (self.best is not None and cost >= self.best[0]):
            return
        k = self._pick(decided)
        if k is not None:
            lit, _, hard = self.literals[k]
            self._join(k, lit, decided, cost, failed)
            if not hard and not self.exact and not self._done():  # or leave it unsatisfied
                skipped = list(decided)
                skipped[k] = True
                self._step(skipped, cost + 1, [*failed, k])
            return
        free = [i for i, v in enumerate(self.values) if v is None]
        if free:
            self._enumerate(free[0], decided, cost, failed)
            return
        if self.schema.pre_complex:  # ADL conjuncts, once the binding is complete
            domain, state = self.e.domain, self.index.state
            ev = Evaluator(domain, self.e.problem, state, limit=self.e.quantified)
            slots = [*self.values, *([None] * (len(self.schema.slot_names) - len(self.values)))]
            extra = []
            for k, (f, check) in enumerate(zip(self.schema.pre_complex, self.schema.checks,
                                               strict=True)):
                if check is not None:
                    ok = check(slots, state)
                else:
                    try:
                        ok = ev.holds(f, slots)
                    except QuantifierLimitError:  # the report's share is spent: unknown,
                        ok = False                # counted as unsatisfied
                if not ok:
                    extra.append(len(self.literals) + k)
            self.e.quantified = max(0, self.e.quantified - ev.tried)
            if extra and self.exact:
                return
            cost, failed = cost + len(extra), failed + extra
            if self.best is not None and cost >= self.best[0]:
                return
        self.best = (cost, tuple(str(v) for v in self.values), failed)

    def _join(self, k: int, lit: Literal, decided: list[bool], cost: int,
              failed: list[int]) -> None:
        _, terms = lit
        _, candidates = self._candidates(lit)
        if candidates is None:
            return
        admits = self.e.admits(self.schema)
        values = self.values
        for atom in candidates:
            if not self._tick():
                return
            saved = list(values)
            ok = True
            touched = []
            for pos, t in enumerate(terms, start=1):
                if isinstance(t, int):
                    v = values[t]
                    if v is None:
                        if atom[pos] not in admits[t]:
                            ok = False
                            break
                        values[t] = atom[pos]
                        touched.append(t)
                    elif v != atom[pos]:
                        ok = False
                        break
            if ok:
                now = list(decided)
                scored = self._score(now, touched)
                if scored is not None:
                    self._step(now, cost + scored[0], failed + scored[1])
            values[:] = saved
            if self._done():
                return

    def _enumerate(self, i: int, decided: list[bool], cost: int, failed: list[int]) -> None:
        for obj in self.e.problem.of_type(self.e.domain, self.schema.types[i]):
            if not self._tick():
                return
            self.values[i] = obj
            now = list(decided)
            scored = self._score(now, [i])
            if scored is not None:
                self._step(now, cost + scored[0], failed + scored[1])
            if self._done():
                break
        self.values[i] = None


class Explainer:
    """Achiever searches for one report: shared node budget, results cached."""

    def __init__(self, domain: Domain, problem: Problem) -> None:
        self.domain = domain
        self.problem = problem
        self.nodes = REPORT_NODES
        # bindings the quantifiers of ADL preconditions may try in all the searches of
        # one report (each candidate grounding evaluates them): beyond, such a
        # precondition counts as unsatisfied, so explaining costs at most one more step
        self.quantified = REPORT_QUANTIFIED
        self._admits: dict[str, list[frozenset[str]]] = {}
        self._cache: dict[tuple[Any, ...], dict[str, Any] | None] = {}

    def admits(self, schema: Schema) -> list[frozenset[str]]:
        found = self._admits.get(schema.name)
        if found is None:
            found = [frozenset(self.problem.of_type(self.domain, t)) for t in schema.types]
            self._admits[schema.name] = found
        return found

    def closest(self, schema: Schema, binding: list[str | None], index: StateIndex,
                exact: bool = False, below: int | None = None
                ) -> tuple[int, tuple[str, ...], list[int]] | None | str:
        """(cost, grounding, unsatisfied literal positions), None when no grounding can
        satisfy the hard preconditions (or, with `below`, none costs less than that),
        "unsearched" when the budget ran out first."""
        search = _Search(self, schema, binding, index, exact, below)
        search.run()
        if search.best is not None and search.best is not search.bound:
            return search.best
        return "unsearched" if search.exhausted else None

    def achievers(self, index: StateIndex, atom: GroundAtom, make_true: bool
                  ) -> list[dict[str, Any]]:
        """Actions whose effects would give `atom` the value `make_true` (docstring): the
        `MAX_ACHIEVERS` that need least, first in the domain's order among equals. Once
        that many are found, a later action is searched only for a grounding that needs
        less than the last of them (none can beat applicable-now ones: the search ends)."""
        if atom[0] == "=":
            return []
        domain, objects = self.domain, self.problem.objects
        found: list[tuple[tuple[int, int], dict[str, Any]]] = []
        for order, schema, terms in _effects_on(domain, atom[0], make_true):
            binding: list[str | None] = [None] * len(schema.params)
            ok = True
            for term, value in zip(terms, atom[1:], strict=True):
                if isinstance(term, int):
                    ok = ok and binding[term] in (None, value) and domain.is_a(
                        objects[value], schema.types[term])
                    binding[term] = value
                else:
                    ok = ok and term == value
            if not ok:
                continue
            below = None
            if len(found) >= MAX_ACHIEVERS:
                found.sort(key=lambda pair: pair[0])
                del found[MAX_ACHIEVERS:]
                below = found[-1][0][0]
                if below == 0:
                    break
            key = (schema.name, tuple(binding), index, below)  # holds the index: no id reuse
            if key in self._cache:
                item = self._cache[key]
            else:
                item = self._achiever(schema, binding, index, below)
                self._cache[key] = item
            if item is not None and all(i["action"] != item["action"] for _, i in found):
                rank = len(item["needs"]) if item["searched"] else 1_000
                if below is None or rank < below:
                    found.append(((rank, order), item))
        found.sort(key=lambda pair: pair[0])
        return [item for _, item in found[:MAX_ACHIEVERS]]

    def _achiever(self, schema: Schema, binding: list[str | None], index: StateIndex,
                  below: int | None = None) -> dict[str, Any] | None:
        lifted = "(" + " ".join((schema.name, *(b or schema.params[i]
                                                for i, b in enumerate(binding)))) + ")"
        result = self.closest(schema, binding, index, below=below)
        if result is None:
            return None  # can never apply (a static precondition, an equality or a type),
            # or, with `below`, needs as much as the achievers found before it
        item: dict[str, Any] = {"action": lifted, "applicable_now": None, "closest": None,
                                "needs": [], "searched": result != "unsearched"}
        if isinstance(result, tuple):
            cost, ground, failed = result
            text = "(" + " ".join((schema.name, *ground)) + ")"
            if cost == 0:
                item["applicable_now"] = text
            else:
                literals = [(lit, True) for lit in schema.pre_pos] + \
                    [(lit, False) for lit in schema.pre_neg]
                item["closest"] = text
                slots = [*ground, *([None] * (len(schema.slot_names) - len(ground)))]
                item["needs"] = [literal_text(schema.ground(literals[k][0], ground),
                                              literals[k][1]) if k < len(literals) else
                                 formula_text(schema.pre_complex[k - len(literals)], slots,
                                              schema.slot_names) for k in sorted(failed)]
        return item


def _effects_on(domain: Domain, pred: str, add: bool
                ) -> list[tuple[int, Schema, tuple[Any, ...]]]:
    """The unconditional effects that add (or delete) an atom of `pred`, in the domain's
    action order: (that order, the schema, the effect's terms); indexed once per domain."""
    key = "explain effects"  # beside the schemas' names (no name has a space)
    table = domain.compiled.get(key)
    if table is None:
        table = {}
        for order, schema in enumerate(domain.schemas.values()):
            for sign, literals in ((True, schema.add), (False, schema.delete)):
                for lit_pred, terms in literals:
                    table.setdefault((lit_pred, sign), []).append((order, schema, terms))
        domain.compiled[key] = table
    found: list[tuple[int, Schema, tuple[Any, ...]]] = table.get((pred, add), [])
    return found


def complete_binding(domain: Domain, problem: Problem, schema: Schema, binding: list[str | None],
                     state: set[GroundAtom]) -> tuple[str, ...] | None:
    """A full binding extending `binding` whose preconditions hold in `state`, or None
    (bounded as above)."""
    result = Explainer(domain, problem).closest(schema, binding, StateIndex(state), exact=True)
    return result[1] if isinstance(result, tuple) else None
