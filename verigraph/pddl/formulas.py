"""ADL conditions as plain tuples: evaluation (interpreted, or compiled into a closure for
the conditions of conditional effects and the bodies of quantifiers over many bindings),
the reason one is false, and its text.

A formula is one of
    ("atom", (pred, terms))          terms: int (a variable slot) or str (an object)
    ("not", f)   ("and", [f, ...])   ("or", [f, ...])   ("imply", f, g)
    ("exists", vars, f)   ("forall", vars, f)      vars: [(slot, name, type), ...]
evaluated over a binding list whose slots are an action's parameters followed by every
variable its quantifiers introduce (each quantifier has slots of its own). Quantifiers
range over the problem's objects of the variable's type (constants included), as in
PDDL: over a type with no objects `exists` is false and `forall` true. One evaluation
may try at most `MAX_QUANTIFIED` bindings (a VeriGraphError beyond: a quantifier over a
product of large types is refused, never judged half-way); from `COMPILE_FROM` bindings
a quantifier's body, when it has no quantifier inside, is compiled once per evaluator
(`compile_condition`) and run with its last variable in the inner loop, about ten
times faster than the interpreted walk.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from itertools import product
from typing import Any

from verigraph.budget import checkpoint
from verigraph.errors import VeriGraphError
from verigraph.pddl.model import Domain, GroundAtom, Problem

Formula = tuple[Any, ...]
MAX_QUANTIFIED = 1_000_000
COMPILE_FROM = 256  # a quantifier over this many bindings has its body compiled
# A goal forall not reached names at most this many counterexamples (then how many more).
MAX_COUNTEREXAMPLES = 20
_UNSET: Any = object()


class QuantifierLimitError(VeriGraphError):
    """A quantifier ranges over more bindings than one check may try."""


def _atom(lit: tuple[str, tuple[Any, ...]], binding: list[str | None]) -> GroundAtom:
    pred, terms = lit
    return (pred, *(str(binding[t]) if isinstance(t, int) else t for t in terms))


def _holds(atom: GroundAtom, state: set[GroundAtom]) -> bool:
    return atom[1] == atom[2] if atom[0] == "=" else atom in state


class Evaluator:
    """Evaluates formulas in one state for one problem, counting quantified bindings."""

    def __init__(self, domain: Domain, problem: Problem, state: set[GroundAtom],
                 limit: int = MAX_QUANTIFIED) -> None:
        self.domain = domain
        self.problem = problem
        self.state = state
        self.tried = 0
        self.limit = limit  # bindings one check may try (QuantifierLimitError beyond)
        # a quantifier's body compiled into a closure (compile_condition), by the body's
        # id, made once per evaluator for a quantifier over many bindings
        self.compiled: dict[int, Check | None] = {}

    def bindings(self, variables: list[tuple[int, str, str]]) -> Any:
        lists = [self.problem.of_type(self.domain, kind) for _, _, kind in variables]
        total = 1
        for objs in lists:
            total *= len(objs)
        self.tried += total
        if self.tried > self.limit:
            names = " ".join(name for _, name, _ in variables)
            raise QuantifierLimitError(
                f"a quantifier over {names} ranges over more than {self.limit:,} "
                "bindings in one check", field="domain", value=names,
                fix="quantify over smaller types, or compile the quantifier away")
        return product(*lists)

    def holds(self, f: Formula, binding: list[str | None]) -> bool:
        kind = f[0]
        if kind == "atom":
            return _holds(_atom(f[1], binding), self.state)
        if kind == "not":
            return not self.holds(f[1], binding)
        if kind == "and":
            return all(self.holds(g, binding) for g in f[1])
        if kind == "or":
            return any(self.holds(g, binding) for g in f[1])
        if kind == "imply":
            return not self.holds(f[1], binding) or self.holds(f[2], binding)
        found = self.search(f[1], f[2], binding, kind == "forall")
        return (found is None) == (kind == "forall")

    def search(self, variables: list[tuple[int, str, str]], body: Formula,
               binding: list[str | None], want: bool) -> tuple[str, ...] | None:
        """The first objects for `variables` under which `body` does not have the truth
        value `want` (a forall's counterexample, an exists' witness), left bound in
        `binding`; None when there are none. Over many bindings the body is compiled into
        a closure (`compile_condition`, about ten times faster) and the last variable is the
        inner loop."""
        before = self.tried
        combos = self.bindings(variables)
        check = None
        if self.tried - before >= COMPILE_FROM:
            check = self.compiled.get(id(body), _UNSET)
            if check is _UNSET:
                check = self.compiled[id(body)] = compile_condition(body)
        if check is None:
            for n, objs in enumerate(combos):
                if not n & 1023:
                    checkpoint()
                for (slot, _, _), obj in zip(variables, objs, strict=True):
                    binding[slot] = obj
                if self.holds(body, binding) != want:
                    return tuple(objs)
            return None
        state = self.state
        *outer, (last, _, kind) = variables
        inner = self.problem.of_type(self.domain, kind)
        places = [slot for slot, _, _ in outer]
        lists = [self.problem.of_type(self.domain, k) for _, _, k in outer]
        tried = 0
        for objs in product(*lists):
            tried += len(inner)
            if tried >= 1024:
                tried = 0
                checkpoint()
            for slot, obj in zip(places, objs, strict=True):
                binding[slot] = obj
            for obj in inner:
                binding[last] = obj
                if check(binding, state) != want:
                    return (*objs, obj)
        return None

    def why_goal_false(self, f: Formula, binding: list[str | None], names: list[str]) -> str:
        """`why_false` for a goal formula, except that a goal `forall` names every
        counterexample (the first MAX_COUNTEREXAMPLES, then how many more): a goal not
        reached says all that is missing, not only the first passenger not served."""
        if f[0] != "forall":
            return self.why_false(f, binding, names)
        self.tried = 0
        variables, body = f[1], f[2]
        found: list[str] = []
        total = 0
        for n, objs in enumerate(self.bindings(variables)):
            if not n & 1023:
                checkpoint()
            for (slot, _, _), obj in zip(variables, objs, strict=True):
                binding[slot] = obj
            if not self.holds(body, binding):
                total += 1
                if len(found) < MAX_COUNTEREXAMPLES:
                    where = ", ".join(f"{name} = {o}"
                                      for (_, name, _), o in zip(variables, objs, strict=True))
                    found.append(f"for {where}: {self.why_false(body, binding, names, 1)}")
        for slot, _, _ in variables:
            binding[slot] = None
        if total <= 1:
            return self.why_false(f, binding, names)
        more = f"; ... and {total - len(found)} more" if total > len(found) else ""
        return f"{total} counterexamples: " + "; ".join(found) + more

    def why_false(self, f: Formula, binding: list[str | None], names: list[str],
                  depth: int = 0) -> str:
        """A short reason `f` is false under `binding` (the first counterexample). An
        explanation is a check of its own: it may try `MAX_QUANTIFIED` bindings anew."""
        if depth == 0:
            self.tried = 0
        kind = f[0]
        if kind == "atom":
            return f"{text(f, binding, names)} is false"
        if kind == "not":
            return f"{text(f[1], binding, names)} holds"
        if kind == "and":
            for g in f[1]:
                if not self.holds(g, binding):
                    return self.why_false(g, binding, names, depth + 1)
        if kind == "or":
            return "none of " + ", ".join(text(g, binding, names) for g in f[1][:4]) + " holds"
        if kind == "imply":
            return (f"{text(f[1], binding, names)} holds but "
                    + self.why_false(f[2], binding, names, depth + 1))
        if kind == "exists":  # its variables unbound: the text names them, not the last tried
            for slot, _, _ in f[1]:
                binding[slot] = None
            tried = [self.problem.of_type(self.domain, t) for _, _, t in f[1]]
            among = f" (tried: {', '.join(tried[0])})" if len(tried) == 1 and \
                0 < len(tried[0]) <= MAX_COUNTEREXAMPLES else ""
            return "no " + ", ".join(f"{n} - {t}" for _, n, t in f[1]) + " makes " \
                + text(f[2], binding, names) + " true" + among
        if kind == "forall":
            objs = self.search(f[1], f[2], binding, True)
            if objs is not None:
                where = ", ".join(f"{n} = {o}" for (_, n, _), o in zip(f[1], objs, strict=True))
                reason = self.why_false(f[2], binding, names, depth + 1) if depth < 3 \
                    else "false"
                for slot, _, _ in f[1]:
                    binding[slot] = None
                return f"for {where}: {reason}"
        return "false"


Check = Callable[[Sequence[Any], set[GroundAtom]], bool]


def compile_condition(f: Any) -> Check | None:
    """A condition as a closure over (slots, state) with `Evaluator.holds`'s truth value
    on a full binding: atoms, equality, not, and, or and imply; None when a quantifier is
    inside (the evaluator takes it)."""
    kind = f[0]
    if kind == "atom":
        pred, terms = f[1]
        if pred == "=":
            a, b = terms
            if isinstance(a, int) and isinstance(b, int):
                return lambda s, st: s[a] == s[b]
            if isinstance(a, int):
                return lambda s, st: s[a] == b
            if isinstance(b, int):
                return lambda s, st: a == s[b]
            return lambda s, st: a == b
        if len(terms) == 1 and isinstance(terms[0], int):
            one = terms[0]
            return lambda s, st: (pred, s[one]) in st
        if len(terms) == 2 and all(isinstance(t, int) for t in terms):
            i, j = terms
            return lambda s, st: (pred, s[i], s[j]) in st
        fixed = tuple(terms)
        return lambda s, st: (pred, *[s[t] if isinstance(t, int) else t for t in fixed]) in st
    if kind == "not":
        inner = compile_condition(f[1])
        if inner is None:
            return None
        return lambda s, st: not inner(s, st)
    if kind in ("and", "or"):
        parts = [compile_condition(g) for g in f[1]]
        if any(p is None for p in parts):
            return None
        checks = [p for p in parts if p is not None]
        if kind == "and":
            def every(s: Sequence[Any], st: set[GroundAtom]) -> bool:
                for c in checks:  # noqa: SIM110 - a loop: no generator per test
                    if not c(s, st):
                        return False
                return True
            return every

        def some(s: Sequence[Any], st: set[GroundAtom]) -> bool:
            for c in checks:  # noqa: SIM110 - a loop: no generator per test
                if c(s, st):
                    return True
            return False
        return some
    if kind == "imply":
        first, then = compile_condition(f[1]), compile_condition(f[2])
        if first is None or then is None:
            return None
        return lambda s, st: not first(s, st) or then(s, st)
    return None  # exists / forall: the evaluator


def text(f: Formula, binding: list[str | None], names: list[str]) -> str:
    """The formula in PDDL, bound slots written as their objects."""
    kind = f[0]
    if kind == "atom":
        pred, terms = f[1]
        shown = [(binding[t] or names[t]) if isinstance(t, int) else t for t in terms]
        return "(" + " ".join((pred, *shown)) + ")"
    if kind == "not":
        return f"(not {text(f[1], binding, names)})"
    if kind in ("and", "or"):
        return "(" + " ".join((kind, *(text(g, binding, names) for g in f[1]))) + ")"
    if kind == "imply":
        return f"(imply {text(f[1], binding, names)} {text(f[2], binding, names)})"
    saved = [binding[slot] for slot, _, _ in f[1]]
    for slot, _, _ in f[1]:
        binding[slot] = None
    head = " ".join(f"{n} - {t}" for _, n, t in f[1])
    out = f"({kind} ({head}) {text(f[2], binding, names)})"
    for (slot, _, _), value in zip(f[1], saved, strict=True):
        binding[slot] = value
    return out
