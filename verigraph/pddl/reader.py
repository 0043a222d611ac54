"""Read a STRIPS domain and problem (PDDL text) into the model, refusing what it cannot judge.

Supported: `:strips`, `:typing` (with `(either ...)` types in parameter, predicate,
constant and object lists), `:negative-preconditions`, `:equality` and `:action-costs`
(`(increase (total-cost) N)` and `(increase (total-cost) (f ?x ?y))` over functions
whose values the problem's `:init` gives; the report sums the plan's cost, as VAL
does), ADL (`or`, `imply`, `not`, `exists`, `forall` in preconditions and goals;
`when` and `forall` in effects) and derived predicates (`(:derived ...)`, compiled and
stratified by `axioms`). Conjunctions may nest (`(and (and ...))`) in preconditions,
effects and goals. Anything else (numeric fluents beyond action costs, durative actions,
preferences, ...) is refused with the requirement named, and so is a construct that
needs one, so a plan is never judged under rules this model does not implement.

Nothing is skipped silently: every section of a domain or problem and every part of an
action is read or refused by name. A misspelt keyword (`:precondtion`, `:efect`,
`:predicate`) is an error naming it with the closest correct keyword; a keyword with no
value, a requirement that is not a `:keyword`, and a section that is not a list are
errors naming what was found. Static errors (an undeclared predicate, type, object,
function or parameter; a wrong arity; an initial atom whose objects have the wrong type;
a type that is its own ancestor) are refused with the name at fault. The S-expression
reader bounds nesting depth and refuses non-ASCII names with the line.
"""

from __future__ import annotations

import difflib
import math
import re
from operator import itemgetter
from typing import Any

from verigraph.errors import VeriGraphError
from verigraph.pddl.axioms import Definition, compile_axioms, head_types_for
from verigraph.pddl.formulas import Formula, compile_condition
from verigraph.pddl.joins import conjunction, plan
from verigraph.pddl.model import (
    ROOT_TYPE,
    SUPPORTED_REQUIREMENTS,
    CondEffect,
    CostTerm,
    Domain,
    GroundAtom,
    Literal,
    Problem,
    Schema,
    Term,
)
from verigraph.pddl.syntax import SExpr, define_body

MAX_OBJECTS = 100_000
TOTAL_COST: GroundAtom = ("total-cost",)
MAX_INIT_ATOMS = 2_000_000
# constructs outside STRIPS -> the requirement a domain would need for them
NEEDS = {"assign": ":numeric-fluents", "increase": ":numeric-fluents",
         "decrease": ":numeric-fluents", "scale-up": ":numeric-fluents",
         "scale-down": ":numeric-fluents", "at": ":durative-actions", "over": ":durative-actions",
         "<": ":numeric-fluents", ">": ":numeric-fluents", "<=": ":numeric-fluents",
         ">=": ":numeric-fluents", "preference": ":preferences"}
ADL_HEADS = ("and", "or", "not", "imply", "exists", "forall", "when")
SUPPORTED_TEXT = " ".join(SUPPORTED_REQUIREMENTS)
# every requirement PDDL 1.2-3.1 defines: one outside this list is a misspelling
KNOWN_REQUIREMENTS = SUPPORTED_REQUIREMENTS + (
    ":disjunctive-preconditions", ":existential-preconditions", ":universal-preconditions",
    ":quantified-preconditions", ":conditional-effects", ":fluents", ":numeric-fluents",
    ":object-fluents", ":adl", ":durative-actions", ":duration-inequalities",
    ":continuous-effects", ":derived-predicates", ":timed-initial-literals", ":preferences",
    ":constraints", ":domain-axioms", ":expression-evaluation", ":open-world", ":true-negation",
    ":ucpop", ":safety-constraints", ":action-expansions", ":foreach-expansions",
    ":dag-expansions", ":subgoals-through-axioms", ":time", ":timed-initial-fluents")
DOMAIN_SECTIONS = (":requirements", ":types", ":constants", ":predicates", ":functions",
                   ":action", ":derived")
UNSUPPORTED_DOMAIN_SECTIONS = {":durative-action": ":durative-actions", ":process": ":time",
                               ":event": ":time", ":constraints": ":constraints",
                               ":axiom": ":domain-axioms", ":timeless": ":strips (PDDL 1.2)",
                               ":extends": ":strips (PDDL 1.2 domain extension)"}
PROBLEM_SECTIONS = (":domain", ":requirements", ":objects", ":init", ":goal", ":metric")
UNSUPPORTED_PROBLEM_SECTIONS = {":constraints": ":constraints", ":length": ":strips (PDDL 1.2)",
                                ":situation": ":strips (PDDL 1.2)"}
ACTION_KEYS = (":parameters", ":precondition", ":effect")
UNSUPPORTED_ACTION_KEYS = {":vars": ":strips (PDDL 1.2 :vars)",
                           ":expansion": ":action-expansions", ":duration": ":durative-actions",
                           ":condition": ":durative-actions"}
ACTION_FORM = "(:action NAME :parameters (?x - type ...) :precondition (and ...) :effect (and ...))"


# a name with a variable glued on: `(aircraft?a)`; the `?` is matched first and what
# precedes it looked behind at, so the scan jumps from `?` to `?` (25x a plain class)
_GLUED = re.compile(r"\?(?<=[^\s()?]\?)")
_VARIABLE_PARTS = re.compile(r"\??[^?]+|\?")


# a PDDL number: decimal digits with an optional fraction and exponent (no `nan`, `inf`,
# `0x10` or `1_000`, which Python's float() would take)
_NUMBER = re.compile(r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:e[-+]?[0-9]+)?")


def number(text: str) -> float | None:
    """The value of a PDDL number (the text lower-cased, as the reader gives it), or None
    for text that is no decimal number or is beyond a double's range (`1e999`)."""
    if _NUMBER.fullmatch(text) is None:
        return None
    value = float(text)
    return value if math.isfinite(value) else None


def _split_glued(expr: SExpr) -> SExpr:
    """`aircraft?a` -> `aircraft`, `?a`: `?` cannot occur in a PDDL name, so it starts a
    variable wherever it stands (VAL's and Fast Downward's lexers read it so; zenotravel
    of IPC 2002 writes `(aircraft?a)`)."""
    if isinstance(expr, str):
        return expr
    out: list[SExpr] = []
    for item in expr:
        if isinstance(item, str) and "?" in item[1:]:
            out.extend(_VARIABLE_PARTS.findall(item))
        else:
            out.append(_split_glued(item))
    return out


def _define_sections(text: str, *, what: str, kind: str) -> tuple[str, list[SExpr]]:
    """`(define (KIND name) sections...)` -> (name, sections), glued variables split
    (see `_split_glued`; a regex scan decides whether the walk is needed)."""
    name, sections = define_body(text, what=what, kind=kind)
    if _GLUED.search(text):
        sections = [_split_glued(s) for s in sections]
    return name, sections


class PddlInputError(VeriGraphError):
    """A domain or problem that is readable but wrong (undeclared name, arity, type)."""


class UnsupportedRequirementError(VeriGraphError):
    """PDDL outside the supported STRIPS fragment; names the requirement."""

    def __init__(self, requirement: str, where: str, what: str) -> None:
        super().__init__(f"unsupported requirement {requirement} ({what} in the {where}); "
                         f"supported: {SUPPORTED_TEXT}", field=where, value=requirement,
                         fix="give a STRIPS domain with typing, negative preconditions and "
                             "equality, or compile the feature away")


def _show(expr: SExpr) -> str:
    if isinstance(expr, str):
        return expr
    return "(" + " ".join(_show(e) for e in expr) + ")"


def _closest(word: str, choices: tuple[str, ...] | list[str]) -> str:
    near = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.6)
    return f"did you mean {near[0]}?" if near else f"use one of {', '.join(choices)}"


def _unknown_keyword(word: SExpr, choices: tuple[str, ...], where: str, context: str
                     ) -> PddlInputError:
    shown = _show(word)[:40]
    return PddlInputError(f"unknown {context} {shown}", field=where, value=shown,
                          fix=_closest(shown, choices) if isinstance(word, str) else
                          f"write one of {', '.join(choices)}")


def _requirements(items: list[SExpr], where: str) -> list[str]:
    """The `:keyword` items of a `(:requirements ...)`; anything else is refused by name."""
    out = []
    for req in items:
        if not isinstance(req, str) or not req.startswith(":"):
            shown = _show(req)[:40]
            fixed = ":" + (req if isinstance(req, str) else _show(req).strip("()").split(" ")[0])
            raise PddlInputError(f"requirement {shown} is not a :keyword", field=where,
                                 value=shown, fix=f"write requirements as keywords, e.g. {fixed}")
        if req not in KNOWN_REQUIREMENTS:
            raise _unknown_keyword(req, SUPPORTED_REQUIREMENTS, where, "requirement")
        if req not in SUPPORTED_REQUIREMENTS:
            raise UnsupportedRequirementError(req, where, "declared")
        out.append(req)
    return out


def _type_name(domain: Domain, item: SExpr, where: str, name: str) -> str:
    """A declared type, or `(either a b ...)` as a type of its own (see model)."""
    if isinstance(item, list):
        if len(item) < 2 or item[0] != "either" or not all(isinstance(t, str) for t in item[1:]):
            raise PddlInputError(f"the type of {name} is {_show(item)[:60]}, which is neither "
                                 "a type name nor (either type ...)", field=where,
                                 value=_show(item)[:60], fix="write `name - type` or "
                                                             "`name - (either t1 t2)`")
        members = tuple(str(t) for t in item[1:])
        for kind in members:
            _type_name(domain, kind, where, name)
        key = "either " + " ".join(members)
        domain.either[key] = members
        return key
    if item != ROOT_TYPE and item not in domain.parents:
        raise PddlInputError(f"type '{item}' (of {name}) is not declared in (:types ...)",
                             field=where, value=item, fix=f"declare {item} in :types")
    return item


def _typed(items: list[SExpr]) -> list[tuple[SExpr, SExpr | None]]:
    """`a b - t c - (either u v) d` -> [(a, t), (b, t), (c, [either, u, v]), (d, None)]."""
    out: list[tuple[SExpr, SExpr | None]] = []
    pending: list[SExpr] = []
    i = 0
    while i < len(items):
        if items[i] == "-" and i + 1 < len(items):
            out.extend((n, items[i + 1]) for n in pending)
            pending = []
            i += 2
            continue
        pending.append(items[i])
        i += 1
    out.extend((n, None) for n in pending)
    return out


def _types(domain: Domain, items: list[SExpr], where: str) -> list[tuple[str, str]]:
    if items and items[-1] == "-":
        raise PddlInputError(f"'-' ends the list {_show(items)[:60]} with no type after it",
                             field=where, value=None, fix="write names as `a b - type`")
    out = []
    for name, kind in _typed(items):
        if not isinstance(name, str) or name == "-":
            raise PddlInputError(f"expected a name in a typed list, got {_show(name)[:60]}",
                                 field=where, value=_show(name)[:60],
                                 fix="write names as `a b - type`")
        out.append((name, ROOT_TYPE if kind is None else _type_name(domain, kind, where, name)))
    return out


def declared_twice(what: str, name: str, where: str, first: str = "", second: str = ""
                   ) -> PddlInputError:
    """The refusal of a name declared twice (the later one never silently wins)."""
    kinds = f" (as {first} and as {second})" if first and second and first != second else ""
    return PddlInputError(f"{what} {name} is declared twice{kinds}", field=where, value=name,
                          fix=f"declare {name} once: remove or rename the second {name}")


def _once(names: list[str], what: str, where: str) -> None:
    """Refuse the first name of `names` that occurs twice."""
    if len(set(names)) != len(names):
        seen: set[str] = set()
        for name in names:
            if name in seen:
                raise declared_twice(what, name, where)
            seen.add(name)


class _ActionReader:
    """Turns one `(:action ...)` into a Schema, checking names against the domain."""

    def __init__(self, domain: Domain, body: list[SExpr]) -> None:
        self.domain = domain
        if len(body) < 2 or not isinstance(body[1], str) or body[1].startswith(":"):
            raise PddlInputError(f"an action has no name: {_show(body)[:60]}", field="domain",
                                 value=None, fix=f"write {ACTION_FORM}")
        self.name = body[1]
        self.where = f"action {self.name}"
        self.keys: dict[str, SExpr] = {}
        i = 2
        while i < len(body):
            key = body[i]
            if not isinstance(key, str) or not key.startswith(":"):
                raise PddlInputError(f"{self.where}: expected a :keyword, got "
                                     f"{_show(key)[:40]}", field="domain", value=self.name,
                                     fix=f"write {ACTION_FORM}")
            if key in UNSUPPORTED_ACTION_KEYS:
                raise UnsupportedRequirementError(UNSUPPORTED_ACTION_KEYS[key], "domain",
                                                  f"{key} in {self.where}")
            if key not in ACTION_KEYS:
                raise PddlInputError(f"{self.where}: unknown keyword {key}",
                                     field="domain", value=key,
                                     fix=_closest(key, ACTION_KEYS))
            value = body[i + 1] if i + 1 < len(body) else None
            if value is None or (isinstance(value, str) and value.startswith(":")):
                raise PddlInputError(f"{self.where}: keyword {key} has no value",
                                     field="domain", value=key,
                                     fix=f"write {key} (...) or leave the keyword out")
            if key in self.keys:
                raise PddlInputError(f"{self.where} gives {key} twice", field="domain",
                                     value=key, fix=f"merge the two {key} into one (and ...)")
            self.keys[key] = value
            i += 2
        params = self.keys.get(":parameters", [])
        if not isinstance(params, list):
            raise PddlInputError(f"{self.where} has malformed :parameters",
                                 field="domain", value=self.name, fix="write :parameters (?x - t)")
        typed = _types(domain, params, "domain")
        for p, _ in typed:
            if not p.startswith("?"):
                raise PddlInputError(f"{self.where}: parameter {p} does not start with ?",
                                     field="domain", value=p, fix=f"write ?{p}")
        self.params = [p for p, _ in typed]
        self.types = [t for _, t in typed]
        _once(self.params, f"{self.where}: parameter", "domain")
        self.index = {p: i for i, p in enumerate(self.params)}
        self.cost: list[CostTerm] = []

    def term(self, arg: SExpr, literal: SExpr, scope: dict[str, int] | None = None) -> Term:
        scope = self.index if scope is None else scope
        if not isinstance(arg, str):
            raise PddlInputError(f"{self.where}: {_show(literal)[:60]} has a nested "
                                 "term; STRIPS terms are parameters and constants",
                                 field="domain", value=self.name, fix="use ?params or constants")
        if arg.startswith("?"):
            if arg not in scope:
                raise PddlInputError(f"{self.where} uses {arg} in {_show(literal)[:60]} "
                                     "but does not declare it", field="domain", value=arg,
                                     fix=f"add {arg} to the action's :parameters")
            return scope[arg]
        if arg not in self.domain.constants:
            raise PddlInputError(f"{self.where} names '{arg}', which is neither a "
                                 "parameter nor a declared constant", field="domain",
                                 value=arg,
                                 fix=f"declare {arg} in (:constants ...) or write ?{arg}")
        return arg

    def atom(self, expr: SExpr, scope: dict[str, int] | None = None) -> Literal:
        if not (isinstance(expr, list) and expr and isinstance(expr[0], str)):
            raise PddlInputError(f"{self.where}: {_show(expr)[:60]} is not an atom",
                                 field="domain", value=self.name, fix="write (predicate ?x ...)")
        head = expr[0]
        if head in NEEDS and head not in self.domain.predicates:
            raise UnsupportedRequirementError(NEEDS[head], "domain",
                                              f"({head} ...) in {self.where}")
        if head in ADL_HEADS and head not in self.domain.predicates:
            raise PddlInputError(f"{self.where}: {_show(expr)[:60]} is not an atom here",
                                 field="domain", value=head,
                                 fix="(not ...) takes one formula; effects are atoms, "
                                     "(not atom), when, forall and (increase (total-cost) x)")
        terms = tuple(self.term(a, expr, scope) for a in expr[1:])
        if head == "=":
            if len(terms) != 2:
                raise PddlInputError(f"{self.where}: (= ...) takes two terms",
                                     field="domain", value=self.name, fix="write (= ?x ?y)")
            return head, terms
        signature = self.domain.predicates.get(head)
        if signature is None:
            raise PddlInputError(f"{self.where} uses predicate '{head}', which "
                                 "(:predicates ...) does not declare", field="domain",
                                 value=head, fix=f"declare ({head} ...) in :predicates")
        if len(signature) != len(terms):
            raise PddlInputError(f"{self.where}: {_show(expr)[:60]} has {len(terms)} "
                                 f"argument(s); {head} takes {len(signature)}", field="domain",
                                 value=head, fix=f"give {head} {len(signature)} argument(s)")
        return head, terms

    def cost_term(self, expr: SExpr, whole: SExpr) -> CostTerm:
        """The amount of `(increase (total-cost) X)`: a number or a static function."""
        if isinstance(expr, str):
            value = number(expr)
            if value is None or value < 0:
                raise PddlInputError(f"{self.where}: {_show(whole)[:60]} adds "
                                     f"'{expr}', not a finite non-negative decimal number",
                                     field="domain", value=expr,
                                     fix="increase (total-cost) by a number >= 0 (such as 1 "
                                         "or 2.5) or by a function such as (distance ?a ?b)")
            return value
        if expr and isinstance(expr[0], str) and expr[0] in self.domain.functions:
            signature = self.domain.functions[expr[0]]
            if len(signature) != len(expr) - 1:
                raise PddlInputError(f"{self.where}: {_show(expr)[:60]} has "
                                     f"{len(expr) - 1} argument(s); {expr[0]} takes "
                                     f"{len(signature)}", field="domain", value=expr[0],
                                     fix=f"give {expr[0]} {len(signature)} argument(s)")
            return expr[0], tuple(self.term(a, expr) for a in expr[1:])
        raise UnsupportedRequirementError(":numeric-fluents", "domain",
                                          f"{_show(whole)[:60]} in {self.where}")

    def variables(self, expr: SExpr, scope: dict[str, int]
                  ) -> tuple[list[tuple[int, str, str]], dict[str, int]]:
        """The typed variables of a quantifier, each with a slot of its own."""
        if not isinstance(expr, list):
            raise PddlInputError(f"{self.where}: a quantifier's variables are "
                                 f"{_show(expr)[:40]}", field="domain", value=self.name,
                                 fix="write (forall (?x - type) ...)")
        out = []
        inner = dict(scope)
        typed = _types(self.domain, expr, "domain")
        _once([name for name, _ in typed], f"{self.where}: quantified variable", "domain")
        for name, kind in typed:
            if not name.startswith("?"):
                raise PddlInputError(f"{self.where}: quantified {name} does not start "
                                     "with ?", field="domain", value=name, fix=f"write ?{name}")
            slot = len(self.slot_names)
            self.slot_names.append(name)
            out.append((slot, name, kind))
            inner[name] = slot
        return out, inner

    def condition(self, expr: SExpr, scope: dict[str, int]) -> Formula:
        """A precondition formula (see formulas): literals, and, or, not, imply, quantifiers."""
        if expr == [] or expr == ["and"]:
            return ("and", [])
        head = expr[0] if isinstance(expr, list) and expr else None
        if head in self.domain.predicates or head not in ADL_HEADS:
            return ("atom", self.atom(expr, scope))
        assert isinstance(expr, list)
        if head in ("and", "or"):
            return (head, [self.condition(e, scope) for e in expr[1:]])
        if head == "not" and len(expr) == 2:
            return ("not", self.condition(expr[1], scope))
        if head == "imply" and len(expr) == 3:
            return ("imply", self.condition(expr[1], scope), self.condition(expr[2], scope))
        if head in ("exists", "forall") and len(expr) == 3:
            variables, inner = self.variables(expr[1], scope)
            return (head, variables, self.condition(expr[2], inner))
        raise PddlInputError(f"{self.where}: malformed {_show(expr)[:60]}",
                             field="domain", value=str(head),
                             fix="(not f), (imply f g), (exists (?x - t) f), (forall (?x - t) f)")

    def precondition(self, expr: SExpr) -> tuple[list[Literal], list[Literal], list[Formula]]:
        """Top-level literals (the fast path) and the other conjuncts (ADL)."""
        pos: list[Literal] = []
        neg: list[Literal] = []
        complex_: list[Formula] = []
        stack = [self.condition(expr, self.index)]
        while stack:
            f = stack.pop()
            if f[0] == "and":
                stack.extend(reversed(f[1]))
            elif f[0] == "atom":
                pos.append(f[1])
            elif f[0] == "not" and f[1][0] == "atom":
                neg.append(f[1][1])
            else:
                complex_.append(f)
        return pos, neg, complex_

    def effect(self, expr: SExpr, scope: dict[str, int], effect: CondEffect) -> None:
        """Add the effect's literals to `effect` (a when or forall opens a new one)."""
        stack = [expr]
        while stack:
            item = stack.pop()
            if item == [] or item == ["and"]:
                continue
            head = item[0] if isinstance(item, list) and item else None
            if not isinstance(item, list) or head in self.domain.predicates \
                    or head not in ADL_HEADS + ("increase",):
                effect.add.append(self.atom(item, scope))
            elif head == "and":
                stack.extend(reversed(item[1:]))
            elif head == "not":
                if len(item) != 2:
                    raise PddlInputError(f"{self.where}: {_show(item)[:60]} - not takes "
                                         "one atom", field="domain", value=self.name,
                                         fix="write (not (predicate ?x ...))")
                effect.delete.append(self.atom(item[1], scope))
            elif head == "increase" and len(item) == 3 and item[1] == ["total-cost"]:
                if effect.variables or effect.condition is not None:
                    raise UnsupportedRequirementError(":numeric-fluents", "domain",
                                                      f"a conditional cost in {self.name}")
                self.cost.append(self.cost_term(item[2], item))
            elif head == "when" and len(item) == 3:
                condition = self.condition(item[1], scope)
                if effect.condition is not None:
                    condition = ("and", [effect.condition, condition])
                inner = CondEffect(list(effect.variables), condition, [], [])
                self.effects.append(inner)
                self.effect(item[2], scope, inner)
            elif head == "forall" and len(item) == 3:
                variables, inner_scope = self.variables(item[1], scope)
                inner = CondEffect(effect.variables + variables, effect.condition, [], [])
                self.effects.append(inner)
                self.effect(item[2], inner_scope, inner)
            elif head == "increase":
                raise UnsupportedRequirementError(":numeric-fluents", "domain",
                                                  f"{_show(item)[:60]} in {self.where}")
            else:
                raise PddlInputError(f"{self.where}: {_show(item)[:60]} is not an effect",
                                     field="domain", value=str(head),
                                     fix="effects are atoms, (not atom), (when c e), "
                                         "(forall (?x - t) e), (increase (total-cost) x)")

    def schema(self) -> Schema:
        self.slot_names = list(self.params)
        pre_pos, pre_neg, pre_complex = self.precondition(self.keys.get(":precondition", []))
        plain = CondEffect([], None, [], [])
        self.effects: list[CondEffect] = []
        self.effect(self.keys.get(":effect", []), self.index, plain)
        for lit in plain.add + plain.delete + [x for e in self.effects for x in e.add + e.delete]:
            if lit[0] == "=":
                raise PddlInputError(f"{self.where} has an equality effect",
                                     field="domain", value=self.name,
                                     fix="effects are atoms and (not atom)")
        return Schema(self.name, self.params, self.types, pre_pos, pre_neg, plain.add,
                      plain.delete, self.cost, pre_complex,
                      [e for e in self.effects if e.add or e.delete], self.slot_names)


class _RuleReader(_ActionReader):
    """The body of one `(:derived (p ?x ...) formula)`: the head's variables are its scope."""

    def __init__(self, domain: Domain, section: list[SExpr]) -> None:
        self.domain = domain
        head = section[1] if len(section) == 3 else None
        if not (isinstance(head, list) and head and isinstance(head[0], str)):
            raise PddlInputError(f"malformed {_show(section)[:60]}", field="domain",
                                 value=_show(section)[:60],
                                 fix="write (:derived (predicate ?x - type ...) formula)")
        pred = head[0]
        self.name, self.where = pred, f"the rule of derived predicate {pred}"
        if pred not in domain.predicates:
            raise PddlInputError(f"derived predicate '{pred}' is not declared in "
                                 "(:predicates ...)", field="domain", value=pred,
                                 fix=f"declare ({pred} ...) in :predicates")
        typed = _types(domain, head[1:], "domain")
        if len(typed) != len(domain.predicates[pred]):
            raise PddlInputError(f"{self.where} has {len(typed)} variable(s); {pred} takes "
                                 f"{len(domain.predicates[pred])}", field="domain", value=pred,
                                 fix=f"give {pred} {len(domain.predicates[pred])} variable(s)")
        for name, _ in typed:
            if not name.startswith("?"):
                raise PddlInputError(f"{self.where}: {name} in its head is not a variable",
                                     field="domain", value=name, fix=f"write ?{name}")
        self.params = [n for n, _ in typed]
        _once(self.params, f"{self.where}: head variable", "domain")
        self.index = {n: i for i, n in enumerate(self.params)}
        self.slot_names = list(self.params)
        self.cost = []
        self.types = head_types_for(domain, pred, [t for _, t in typed])
        self.formula = self.condition(section[2], self.index)

    def definition(self) -> Definition:
        return Definition(self.name, self.formula, self.slot_names, self.types)


def _derived(domain: Domain, sections: list[list[SExpr]]) -> None:
    """Read and compile the `(:derived ...)` rules (see axioms); actions may not change a
    derived predicate."""
    definitions: dict[str, list[Definition]] = {}
    for section in sections:
        d = _RuleReader(domain, section).definition()
        definitions.setdefault(d.predicate, []).append(d)
    for schema in domain.schemas.values():
        for lit in schema.add + schema.delete + [x for e in schema.cond_effects
                                                 for x in e.add + e.delete]:
            if lit[0] in definitions:
                raise PddlInputError(f"action {schema.name} changes derived predicate "
                                     f"{lit[0]}", field="domain", value=lit[0],
                                     fix=f"only the (:derived ...) rules decide {lit[0]}: "
                                         "remove it from the effect, or make it a basic "
                                         "predicate without rules")
    domain.axioms = compile_axioms(domain, definitions)


class _GoalReader(_ActionReader):
    """A goal's formulas: names are the problem's objects, variables are quantified."""

    def __init__(self, domain: Domain, objects: dict[str, str]) -> None:
        self.domain, self.objects = domain, objects
        self.name, self.where, self.index = "goal", "the goal", {}
        self.slot_names: list[str] = []
        self.cost = []

    def term(self, arg: SExpr, literal: SExpr, scope: dict[str, int] | None = None) -> Term:
        if isinstance(arg, str) and not arg.startswith("?"):
            if arg not in self.objects:
                raise PddlInputError(f"{_show(literal)[:60]} in the goal names '{arg}', which "
                                     "(:objects ...) does not declare", field="problem",
                                     value=arg, fix=f"declare {arg} in :objects")
            return arg
        return super().term(arg, literal, scope)


def _functions(domain: Domain, items: list[SExpr]) -> None:
    """`(:functions (total-cost) - number (road-length ?a ?b - place) - number)`."""
    i = 0
    seen_total = False
    while i < len(items):
        item = items[i]
        if item == "-":
            kind = items[i + 1] if i + 1 < len(items) else None
            if kind != "number":
                raise UnsupportedRequirementError(":object-fluents", "domain",
                                                  f"function type {_show(kind or '')[:30]}")
            i += 2
            continue
        if not (isinstance(item, list) and item and isinstance(item[0], str)):
            raise PddlInputError(f"malformed function {_show(item)[:60]}", field="domain",
                                 value=_show(item)[:60], fix="write (:functions (name ?x - t) "
                                                             "- number)")
        if item[0] in domain.functions or item[0] == "total-cost" and seen_total:
            raise declared_twice("function", item[0], "domain")
        seen_total = seen_total or item[0] == "total-cost"
        if item[0] != "total-cost":
            domain.functions[item[0]] = [t for _, t in _types(domain, item[1:], "domain")]
        i += 1


def _check_types(domain: Domain) -> None:
    for parent in set(domain.parents.values()) - set(domain.parents) - {ROOT_TYPE}:
        domain.parents[parent] = ROOT_TYPE  # a parent used but not listed is an object
    cycle = domain.index_types()
    if cycle:
        shown = ", ".join(f"{t} - {domain.parents[t]}" for t in cycle[:4])
        raise PddlInputError(f"type {cycle[0]} is its own ancestor ({shown})", field="domain",
                             value=cycle[0], fix="give each type a parent that leads to object")


def read_domain(text: str) -> Domain:
    """The STRIPS domain in `text`, or an error naming the requirement or name at fault."""
    name, sections = _define_sections(text, what="domain", kind="domain")
    domain = Domain(name, [], {}, {}, {}, {})
    actions: list[list[SExpr]] = []
    rules: list[list[SExpr]] = []
    checked: list[list[SExpr]] = []
    for section in sections:  # types first, wherever they are written: the rest uses them
        if not isinstance(section, list) or not section or not isinstance(section[0], str):
            raise PddlInputError(f"unexpected {_show(section)[:60]} in the domain",
                                 field="domain", value=_show(section)[:60],
                                 fix="sections are lists that start with a :keyword, e.g. "
                                     "(:predicates ...)")
        checked.append(section)
        if section[0] == ":types":
            for child, parent in _typed(section[1:]):
                if not isinstance(child, str) or child == "-":
                    raise PddlInputError(f"expected a type name, got {_show(child)[:60]}",
                                         field="domain", value=_show(child)[:60],
                                         fix="write (:types a b - parent)")
                if isinstance(parent, list):
                    raise UnsupportedRequirementError(":typing with (either ...) as a "
                                                      "supertype", "domain", _show(parent))
                # `t - t` (seen in the wild) declares t, under object
                parent = ROOT_TYPE if parent in (None, child) else parent
                before = domain.parents.get(child, ROOT_TYPE)
                if before != ROOT_TYPE and parent not in (ROOT_TYPE, before):
                    # under two parents: no tree. Under object and then another type (IPC
                    # storage: `area - object` ... `area crate - surface`) it is the other
                    raise declared_twice("type", child, "domain", before, str(parent))
                domain.parents[child] = parent if before == ROOT_TYPE else before
            domain.parents.pop(ROOT_TYPE, None)
    _check_types(domain)
    for section in checked:
        head, rest = section[0], section[1:]
        if head == ":requirements":
            domain.requirements.extend(_requirements(rest, "domain"))
        elif head == ":types":
            continue
        elif head == ":constants":
            for name, kind in _types(domain, rest, "domain"):
                if name in domain.constants:
                    raise declared_twice("constant", name, "domain", domain.constants[name],
                                         kind)
                domain.constants[name] = kind
        elif head == ":predicates":
            for pred in rest:
                if not isinstance(pred, list) or not pred or not isinstance(pred[0], str):
                    raise PddlInputError(f"malformed predicate {_show(pred)[:60]}",
                                         field="domain", value=None,
                                         fix="write (name ?x - type ...)")
                if pred[0] in domain.predicates:
                    raise declared_twice("predicate", pred[0], "domain")
                domain.predicates[pred[0]] = [t for _, t in _types(domain, pred[1:], "domain")]
        elif head == ":functions":
            _functions(domain, rest)
        elif head == ":action":
            actions.append(section)
        elif head == ":derived":
            rules.append(section)
        elif head in UNSUPPORTED_DOMAIN_SECTIONS:
            raise UnsupportedRequirementError(UNSUPPORTED_DOMAIN_SECTIONS[head], "domain",
                                              f"section {head}")
        else:
            raise _unknown_keyword(head, DOMAIN_SECTIONS, "domain", "domain section")
    for body in actions:
        schema = _ActionReader(domain, body).schema()
        if schema.name in domain.schemas:
            raise PddlInputError(f"action {schema.name} is defined twice", field="domain",
                                 value=schema.name,
                                 fix=f"define {schema.name} once: rename or remove the second")
        domain.schemas[schema.name] = schema
    if rules:
        _derived(domain, rules)
    changed = {lit[0] for s in domain.schemas.values()
               for lit in s.add + s.delete + [x for e in s.cond_effects for x in e.add + e.delete]}
    if domain.axioms is not None:
        changed |= domain.axioms.predicates  # recomputed in every state, never fixed
    domain.static = frozenset(domain.predicates) - changed
    _plan_effect_joins(domain)
    return domain


def _plan_effect_joins(domain: Domain) -> None:
    """Compile each ADL condition once (a closure, see formulas.compile_condition) and plan
    each quantified conditional effect whose condition is a conjunction of literals as a
    join over the static predicates (see joins)."""
    static = domain.static
    for schema in domain.schemas.values():
        schema.checks = [compile_condition(f) for f in schema.pre_complex]
        types = dict(enumerate(schema.types))
        for effect in schema.cond_effects:
            if effect.condition is not None:
                effect.check = compile_condition(effect.condition)
            if not effect.variables or effect.condition is None:
                continue
            body = conjunction(effect.condition)
            if body is None:
                continue
            slots = {slot for slot, _, _ in effect.variables}
            if any(isinstance(t, int) and t >= len(schema.params) and t not in slots
                   for _, _, terms in body for t in terms):
                continue  # a slot bound elsewhere: the general evaluator takes it
            effect.join = plan(domain, body, {**types, **{s: k for s, _, k in effect.variables}},
                               slots, joinable=static.__contains__,
                               bound=range(len(schema.params)))


def _ground(domain: Domain, objects: dict[str, str], expr: SExpr, where: str) -> GroundAtom:
    if not (isinstance(expr, list) and expr and all(isinstance(a, str) for a in expr)):
        head = expr[0] if isinstance(expr, list) and expr and isinstance(expr[0], str) else ""
        if head in NEEDS:
            raise UnsupportedRequirementError(NEEDS[head], "problem",
                                              f"({head} ...) in the {where}")
        raise PddlInputError(f"the {where} holds {_show(expr)[:60]}, which is not a ground atom",
                             field="problem", value=None, fix="write (predicate obj ...)")
    head, args = str(expr[0]), [str(a) for a in expr[1:]]
    if head == "=":
        if len(args) != 2:
            raise PddlInputError(f"the {where}: (= ...) takes two objects", field="problem",
                                 value=None, fix="write (= a b)")
    else:
        signature = domain.predicates.get(head)
        if signature is None:
            raise PddlInputError(f"the {where} uses predicate '{head}', which the domain does "
                                 "not declare", field="problem", value=head,
                                 fix=f"declare ({head} ...) in the domain's :predicates")
        if len(signature) != len(args):
            raise PddlInputError(f"the {where}: {_show(expr)[:60]} has {len(args)} argument(s); "
                                 f"{head} takes {len(signature)}", field="problem", value=head,
                                 fix=f"give {head} {len(signature)} argument(s)")
    for i, a in enumerate(args):
        kind = objects.get(a)
        if kind is None:
            raise PddlInputError(f"{_show(expr)[:60]} in the {where} names '{a}', which "
                                 "(:objects ...) does not declare", field="problem", value=a,
                                 fix=f"declare {a} in :objects")
        if head != "=" and not domain.is_a(kind, domain.predicates[head][i]):
            raise PddlInputError(f"{_show(expr)[:60]} in the {where}: {a} is a {kind}, but "
                                 f"argument {i + 1} of {head} is a {domain.predicates[head][i]}",
                                 field="problem", value=a,
                                 fix=f"give {head} an object of type {domain.predicates[head][i]}")
    return (head, *args)


def _value(domain: Domain, objects: dict[str, str], item: list[SExpr],
           values: dict[GroundAtom, float]) -> None:
    """`(= (f a b) 5)` in :init: the value of a cost function (a finite decimal >= 0), or
    total-cost's start (any finite decimal; VAL's `Final value` counts from it)."""
    fn = item[1] if len(item) == 3 else None
    amount = item[2] if len(item) == 3 else None
    if not (isinstance(fn, list) and fn and all(isinstance(a, str) for a in fn)
            and isinstance(amount, str)):
        raise PddlInputError(f"the initial state holds {_show(item)[:60]}, which is neither an "
                             "atom nor (= (function obj ...) number)", field="problem",
                             value=_show(item)[:60], fix="write (= (road-length a b) 10)")
    value = _init_number(item, amount)
    name = str(fn[0])
    if name == "total-cost":
        if len(fn) != 1:
            raise PddlInputError(f"{_show(item)[:60]} in the initial state: total-cost takes "
                                 "no arguments", field="problem", value=name,
                                 fix="write (= (total-cost) 0)")
        values[TOTAL_COST] = value
        return
    if value < 0:
        raise PddlInputError(f"{_show(item)[:60]} in the initial state: '{amount}' is a "
                             "negative cost", field="problem", value=amount,
                             fix="give action costs values >= 0 (PDDL's action costs)")
    signature = domain.functions.get(name)
    if signature is None:
        raise PddlInputError(f"{_show(item)[:60]} in the initial state: the domain declares no "
                             f"function '{name}'", field="problem", value=name,
                             fix=f"declare ({name} ...) in the domain's :functions")
    args = [str(a) for a in fn[1:]]
    if len(args) != len(signature) or any(a not in objects for a in args):
        raise PddlInputError(f"{_show(item)[:60]} in the initial state: {name} takes "
                             f"{len(signature)} declared object(s)", field="problem", value=name,
                             fix="name declared objects, one per argument")
    values[(name, *args)] = value


def _init_number(item: list[SExpr], text: str) -> float:
    """The number of `(= (f ...) text)` in :init, or the error naming it."""
    value = number(text)
    if value is None:
        finite = _NUMBER.fullmatch(text) is not None
        raise PddlInputError(
            f"{_show(item)[:60]} in the initial state: '{text[:40]}' is "
            + ("beyond the range of a double (about 1.8e308)" if finite
               else "not a number"), field="problem", value=text[:40],
            fix="give the function a finite decimal number, such as 4 or 2.5")
    return value


def _read_init(domain: Domain, objects: dict[str, str], items: list[SExpr],
               init: set[GroundAtom], values: dict[GroundAtom, float], fitting: _Fitting
               ) -> None:
    """The initial atoms and function values. The atoms are checked per predicate, a
    column at a time (declared, of its arity, every object of each position one that
    position takes: set operations at C speed, where one check per atom made a large
    :init dominate a short plan's validation); the function values likewise, all at once
    (`_values_fit`). Anything that fails goes through `_ground` / `_value` in the file's
    order, which name what is wrong."""
    plain = [item for item in items if type(item) is list and item and item[0] != "="]
    try:
        atoms = set(map(tuple, plain))
    except TypeError:  # a list where an object should be
        atoms = None
    if atoms is not None and _atoms_fit(domain, fitting, atoms):
        init.update(atoms)  # type: ignore[arg-type]
        rest = [item for item in items if not (type(item) is list and item and item[0] != "=")]
    else:
        rest = items
    if rest is not items:
        fit = _values_fit(domain, objects, rest)
        if fit is not None:
            values.update(fit)
            return
    for item in rest:
        if isinstance(item, list) and item and item[0] == "=" and (
                len(item) != 3 or isinstance(item[1], list)):
            _value(domain, objects, item, values)
            continue
        init.add(_ground(domain, objects, item, "initial state"))


def _values_fit(domain: Domain, objects: dict[str, str], items: list[SExpr]
                ) -> dict[GroundAtom, float] | None:
    """The values of `items`, every one `(= (function obj ...) number)` of a declared
    function, its arity and declared objects, a finite non-negative decimal (total-cost's
    start under `TOTAL_COST`, any finite decimal), checked a function at a time; None
    when one is not (`_value` then names it)."""
    if not all(type(item) is list and len(item) == 3 and type(item[1]) is list and item[1]
               and type(item[2]) is str for item in items):
        return None
    try:  # a list where a name should be: the per-item reading names it
        read: dict[Any, float | None] = {tuple(item[1]): number(item[2])  # type: ignore
                                         for item in items}
    except TypeError:
        return None
    groups: dict[Any, list[tuple[Any, ...]]] = {}
    for key, value in read.items():
        if value is None or value < 0 and key != TOTAL_COST:  # `_value` names it
            return None
        groups.setdefault(key[0], []).append(key)
    named: set[str] = set()
    for name, keys in groups.items():
        if name == "total-cost":
            if keys != [TOTAL_COST]:
                return None
            continue
        signature = domain.functions.get(name) if isinstance(name, str) else None
        if signature is None or set(map(len, keys)) != {len(signature) + 1}:
            return None
        named.update(*(key[1:] for key in keys))
    return read if named <= objects.keys() else None  # type: ignore[return-value]


class _Fitting:
    """The declared objects a type takes (itself and its subtypes), computed once per
    type and problem from the objects grouped by their own type."""

    def __init__(self, domain: Domain, objects: dict[str, str]) -> None:
        self.domain = domain
        self.by_type: dict[str, list[str]] = {}
        for name, kind in objects.items():
            self.by_type.setdefault(kind, []).append(name)
        self.takes: dict[str, frozenset[str]] = {}

    def __call__(self, kind: str) -> frozenset[str]:
        found = self.takes.get(kind)
        if found is None:
            found = self.takes[kind] = frozenset().union(
                *(names for own, names in self.by_type.items() if self.domain.is_a(own, kind)))
        return found


def _atoms_fit(domain: Domain, fitting: _Fitting, atoms: set[tuple[SExpr, ...]]) -> bool:
    """Every atom is of a declared predicate, of its arity, each object declared with a
    type its position takes."""
    groups: dict[SExpr, list[tuple[SExpr, ...]]] = {}
    for atom in atoms:
        groups.setdefault(atom[0], []).append(atom)
    for pred, group in groups.items():
        signature = domain.predicates.get(pred) if isinstance(pred, str) else None
        if signature is None or set(map(len, group)) != {len(signature) + 1}:
            return False
        for position, kind in enumerate(signature, start=1):
            if not fitting(kind).issuperset(map(itemgetter(position), group)):
                return False
    return True


def _goal_literals(expr: SExpr) -> list[tuple[SExpr, bool]]:
    """The literals of a goal conjunction (`and`s may nest), each with its sign."""
    out: list[tuple[SExpr, bool]] = []
    stack = [expr]
    while stack:
        item = stack.pop()
        if item == [] or item == ["and"]:
            continue
        if isinstance(item, list) and item[0] == "and":
            stack.extend(reversed(item[1:]))
        elif isinstance(item, list) and item[0] == "not" and len(item) == 2:
            out.append((item[1], False))
        else:
            out.append((item, True))
    return out


def read_problem(text: str, domain: Domain) -> Problem:
    """The problem in `text` against `domain`; objects include the domain's constants."""
    name, sections = _define_sections(text, what="problem", kind="problem")
    objects = dict(domain.constants)
    declared: set[str] = set()  # the problem's own objects
    init: set[GroundAtom] = set()
    values: dict[GroundAtom, float] = {}
    goal_pos: list[GroundAtom] = []
    goal_neg: list[GroundAtom] = []
    goal_seen = False
    raw_init: list[SExpr] = []
    raw_goal: SExpr = []
    for section in sections:
        if not isinstance(section, list) or not section or not isinstance(section[0], str):
            raise PddlInputError(f"unexpected {_show(section)[:60]} in the problem",
                                 field="problem", value=_show(section)[:60],
                                 fix="sections are lists that start with a :keyword, e.g. "
                                     "(:init ...)")
        head = section[0]
        if head == ":objects":
            if len(section) - 1 > MAX_OBJECTS:
                raise PddlInputError(f"the problem declares {len(section) - 1:,} objects",
                                     field="problem", value=len(section) - 1,
                                     fix=f"keep it under {MAX_OBJECTS:,} objects")
            for obj, kind in _types(domain, section[1:], "problem"):
                if obj in objects:
                    if obj in domain.constants and obj not in declared:
                        raise PddlInputError(
                            f"{obj} is declared twice: a constant of the domain and an object "
                            "of the problem", field="problem", value=obj,
                            fix=f"leave {obj} out of :objects (the domain's constants are "
                                f"objects of every problem), or rename the object {obj}")
                    raise declared_twice("object", obj, "problem", objects[obj], kind)
                objects[obj] = kind
                declared.add(obj)
        elif head == ":init":
            if len(section) - 1 > MAX_INIT_ATOMS:
                raise PddlInputError(f"the initial state has {len(section) - 1:,} atoms",
                                     field="problem", value=len(section) - 1,
                                     fix=f"keep it under {MAX_INIT_ATOMS:,} atoms")
            raw_init = section[1:]
        elif head == ":goal":
            if len(section) != 2:
                raise PddlInputError(f"(:goal ...) holds {len(section) - 1} formulas",
                                     field="problem", value=len(section) - 1,
                                     fix="write one goal formula: (:goal (and ...))")
            goal_seen = True
            raw_goal = section[1]
        elif head == ":domain":
            if len(section) != 2 or not isinstance(section[1], str):
                raise PddlInputError(f"malformed {_show(section)[:60]}", field="problem",
                                     value=None, fix="write (:domain NAME)")
        elif head == ":requirements":
            _requirements(section[1:], "problem")
        elif head == ":metric":
            if section[1:] not in (["minimize", ["total-cost"]], ["minimize", "total-cost"]):
                raise UnsupportedRequirementError(":numeric-fluents", "problem",
                                                  f"metric {_show(section[1:])[:60]}")
        elif head in UNSUPPORTED_PROBLEM_SECTIONS:
            raise UnsupportedRequirementError(UNSUPPORTED_PROBLEM_SECTIONS[head], "problem",
                                              f"section {head}")
        else:
            raise _unknown_keyword(head, PROBLEM_SECTIONS, "problem", "problem section")
    if not goal_seen:
        raise PddlInputError("the problem has no (:goal ...)", field="problem", value=name,
                             fix="add (:goal (and ...))")
    fitting = _Fitting(domain, objects)
    _read_init(domain, objects, raw_init, init, values, fitting)
    if domain.axioms is not None:
        for atom in init:
            if atom[0] in domain.axioms.predicates:
                raise PddlInputError(f"the initial state lists {_show(list(atom))}, of derived "
                                     f"predicate {atom[0]}", field="problem", value=atom[0],
                                     fix=f"leave {atom[0]} out of :init: the domain's "
                                         "(:derived ...) rules decide it in every state")
    goal_complex: list[Formula] = []
    reader = _GoalReader(domain, objects)
    literals = _goal_literals(raw_goal)
    plain = [item for item, _ in literals if type(item) is list and item and item[0] != "="
             and not (item[0] in ADL_HEADS and item[0] not in domain.predicates)]
    try:  # atoms of declared predicates and fitting objects: checked a column at a time
        fit = _atoms_fit(domain, fitting, set(map(tuple, plain)))
    except TypeError:  # a list where an object should be: `_ground` says so
        fit = False
    for item, positive in literals:
        first = item[0] if isinstance(item, list) and item else None
        if first in ADL_HEADS and first not in domain.predicates:
            formula = reader.condition(item, {})
            goal_complex.append(formula if positive else ("not", formula))
        elif fit and type(item) is list and first != "=":
            (goal_pos if positive else goal_neg).append(tuple(item))  # type: ignore[arg-type]
        else:
            (goal_pos if positive else goal_neg).append(_ground(domain, objects, item, "goal"))
    start = values.pop(TOTAL_COST, None)
    return Problem(name, objects, init, goal_pos, goal_neg, values=values,
                   goal_complex=goal_complex, goal_slots=reader.slot_names, initial_cost=start)
