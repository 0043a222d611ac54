"""Goal formulas in BDDL's syntax: the grammar, one function per rule, into a small tree.

BDDL is the goal language of BEHAVIOR's activity definitions: PDDL's `and or not imply
forall exists` plus `forn forpairs fornpairs`, over atoms such as `(ontop cup plate)`.
A goal formula names objects by scene id and quantifies over kinds (a dictionary label
is the type: `(forall (?c - cup) (not (exists (?p - plate) (ontop ?c ?p))))`).

    formula  := atom | (and formula*) | (or formula*) | (not formula)
              | (imply formula formula)
              | (forall (param+) formula) | (exists (param+) formula)
              | (forn (N) (param) formula)
              | (forpairs (param) (param) formula)
              | (fornpairs (N) (param) (param) formula)
    param    := ?var - kind
    atom     := (predicate term+)       term := ?var | object-id

A whole `(:goal formula)` section is read as its formula. As in BDDL, a `?name` that no
quantifier binds names an object (`?cup.n.01_1` is the object `cup.n.01_1`).
Predicates: `ontop`/`on`, `inside`/`in`, `under`, `nextto`, `inroom` (two terms),
`open`, `toggled_on`, and the thermal states `cooked`, `hot`, `frozen` (one).
Parsing is one pass over the tokens, with the text's length, the nesting depth and the
number of parts bounded; every error names the character position and the fix. Whether
the ids and kinds exist is the evaluator's question (`formula_eval.check_names`): the
grammar needs no scene.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from functools import lru_cache

from verigraph.errors import GoalError

MAX_FORMULA_CHARS = 20_000
MAX_DEPTH = 32  # nested parentheses
MAX_PARTS = 2_000  # atoms, connectives and quantifiers together
MAX_COUNT = 1_000  # the N of forn and fornpairs
MAX_WORD = 128  # characters of an id, a kind or a variable (a node id's limit)

# BDDL's predicate -> (the relation or state it reads, how many terms).
PREDICATES: dict[str, tuple[str, int]] = {
    "ontop": ("on", 2), "on": ("on", 2), "inside": ("in", 2), "in": ("in", 2),
    "under": ("under", 2), "nextto": ("nextto", 2), "inroom": ("inroom", 2),
    "open": ("open", 1), "toggled_on": ("toggled_on", 1),
    "cooked": ("cooked", 1), "hot": ("hot", 1), "frozen": ("frozen", 1),
}
STATE_KEYS = ("open", "toggled_on", "cooked", "hot", "frozen")
CONNECTIVES = ("and", "or", "not", "imply")
QUANTIFIERS = ("forall", "exists", "forn", "forpairs", "fornpairs")
FORMULA_EXAMPLE = "(forall (?c - cup) (not (exists (?p - plate) (ontop ?c ?p))))"
_SYNSET = re.compile(r"\.n\.\d+$")  # BDDL's `cup.n.01` names the kind `cup`
_TOKEN = re.compile(r"\s+|;[^\n]*|\(|\)|[^\s();]+")
_VARIABLE = re.compile(r"\?[A-Za-z_][A-Za-z0-9_.\-]*")
_ID = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.\-]*")


@dataclass(frozen=True, slots=True)
class Param:
    """`?c - cup`: a variable ranging over the scene's objects of one kind."""

    name: str
    kind: str


@dataclass(frozen=True, slots=True)
class Atom:
    """`(ontop ?c plate_1)`: `relation` is the scene's word (`on`), `terms` are variables
    (`?c`) or object ids."""

    predicate: str
    relation: str
    terms: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class Not:
    body: Formula


@dataclass(frozen=True, slots=True)
class Junction:
    """`and` (every part holds) or `or` (some part holds); empty `and` is true."""

    op: str
    parts: tuple[Formula, ...]


@dataclass(frozen=True, slots=True)
class Imply:
    condition: Formula
    then: Formula


@dataclass(frozen=True, slots=True)
class Quantified:
    """`forall`, `exists` or `forn` (`count`: exactly that many objects satisfy it)."""

    op: str
    param: Param
    body: Formula
    count: int | None = None


@dataclass(frozen=True, slots=True)
class Pairs:
    """`forpairs` (every object of the smaller kind paired one-to-one with a distinct
    object of the other) or `fornpairs` (`count` such pairs)."""

    op: str
    first: Param
    second: Param
    body: Formula
    count: int | None = None


Formula = Atom | Not | Junction | Imply | Quantified | Pairs


@dataclass(frozen=True, slots=True)
class _Token:
    text: str
    at: int  # character offset in the formula text


@lru_cache(maxsize=128)
def parse_formula(text: str) -> Formula:
    """The formula tree of `text`, or a GoalError naming the position and the fix."""
    if len(text) > MAX_FORMULA_CHARS:
        raise GoalError(f"the formula has {len(text)} characters, more than "
                        f"{MAX_FORMULA_CHARS}", field="formula", value=text[:80],
                        fix="split the goal, or quantify over a kind instead of naming "
                            "every object")
    parser = _Parser(text, _tokens(text))
    formula = parser.formula(depth=0, scope=())
    if parser.i < len(parser.tokens):
        extra = parser.tokens[parser.i]
        if extra.text == ")":
            raise parser.fail(extra, "a ')' closes nothing", "remove it")
        raise parser.fail(extra, "text after the end of the formula",
                          "give one formula; join several with (and ...)")
    return formula


def _tokens(text: str) -> list[_Token]:
    """`(`, `)` and words with their offsets; whitespace and `;` comments dropped."""
    tokens = []
    for m in _TOKEN.finditer(text):
        word = m.group()
        if len(word) > MAX_WORD and word[0] != ";" and not word[0].isspace():
            raise GoalError(f"character {m.start() + 1}: a name of {len(word)} characters, "
                            f"more than {MAX_WORD} (at '{word[:40]}')", field="formula",
                            value=word[:40], fix="use the object's scene id or a kind's label")
        if not word[0].isspace() and word[0] != ";":
            tokens.append(_Token(word, m.start()))
    return tokens


class _Parser:
    """Recursive descent over the tokens: one method per grammar rule."""

    def __init__(self, text: str, tokens: list[_Token]) -> None:
        self.text = text
        self.tokens = tokens
        self.i = 0
        self.parts = 0

    # -- tokens ------------------------------------------------------------------------
    def fail(self, token: _Token | None, what: str, fix: str) -> GoalError:
        at = token.at if token is not None else len(self.text)
        near = self.text[at:at + 40] if token is not None else "the end of the text"
        return GoalError(f"character {at + 1}: {what} (at '{near}')",
                        field="formula", value=near, fix=fix)

    def peek(self) -> _Token | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self) -> _Token:
        token = self.peek()
        if token is None and not self.tokens:
            raise self.fail(None, "the formula is empty", f"write one, e.g. {FORMULA_EXAMPLE}")
        if token is None:
            opened = sum(t.text == "(" for t in self.tokens) - sum(
                t.text == ")" for t in self.tokens)
            raise self.fail(None, f"the formula ends with {opened} parenthesis(es) open",
                            f"close it with {')' * max(opened, 1)}")
        self.i += 1
        return token

    def expect(self, word: str, fix: str) -> _Token:
        token = self.take()
        if token.text != word:
            raise self.fail(token, f"expected '{word}', found '{token.text}'", fix)
        return token

    def word(self, what: str, fix: str) -> _Token:
        token = self.take()
        if token.text in "()":
            raise self.fail(token, f"expected {what}, found '{token.text}'", fix)
        return token

    def count_part(self, token: _Token) -> None:
        self.parts += 1
        if self.parts > MAX_PARTS:
            raise self.fail(token, f"more than {MAX_PARTS} parts",
                            "quantify over a kind instead of listing objects one by one")

    # -- rules -------------------------------------------------------------------------
    def formula(self, depth: int, scope: tuple[str, ...]) -> Formula:
        """formula := atom | (connective ...) | (quantifier ...) | (:goal formula)."""
        start = self.expect("(", f"a formula starts with '(', e.g. {FORMULA_EXAMPLE}")
        if depth >= MAX_DEPTH:
            raise self.fail(start, f"nested deeper than {MAX_DEPTH} levels",
                            "flatten the formula: (and a b c) instead of (and a (and b c))")
        self.count_part(start)
        head = self.word("a connective, quantifier or predicate",
                         "write (and ...), (forall (?x - kind) ...) or (ontop a b)")
        name = head.text.lower()
        if name == ":goal" and depth == 0:
            formula = self.formula(depth + 1, scope)
        elif name in ("and", "or"):
            formula = self.junction(name, depth, scope)
        elif name == "not":
            formula = Not(self.formula(depth + 1, scope))
        elif name == "imply":
            formula = Imply(self.formula(depth + 1, scope), self.formula(depth + 1, scope))
        elif name in ("forall", "exists"):
            formula = self.quantified(name, depth, scope)
        elif name == "forn":
            formula = self.forn(depth, scope)
        elif name in ("forpairs", "fornpairs"):
            formula = self.pairs(name, depth, scope)
        elif name in PREDICATES:
            formula = self.atom(head, name, scope)
        else:
            raise self.fail(head, f"'{head.text}' is not a connective, quantifier or "
                                  "predicate this goal language reads",
                            f"use {', '.join(CONNECTIVES + QUANTIFIERS)} or a predicate: "
                            f"{', '.join(PREDICATES)}")
        self.expect(")", f"close ({head.text} ...) here")
        return formula

    def junction(self, op: str, depth: int, scope: tuple[str, ...]) -> Junction:
        """(and formula*) | (or formula*)."""
        parts = []
        while (token := self.peek()) is not None and token.text == "(":
            parts.append(self.formula(depth + 1, scope))
        return Junction(op, tuple(parts))

    def param(self, scope: tuple[str, ...]) -> Param:
        """param := ?var - kind (inside its own parentheses, read by the caller)."""
        var = self.word("a variable such as ?c", "write (?c - cup)")
        if not _VARIABLE.fullmatch(var.text):
            raise self.fail(var, f"'{var.text}' is not a variable",
                            "a variable starts with '?', e.g. (?c - cup)")
        if var.text in scope:
            raise self.fail(var, f"{var.text} is already bound by an enclosing quantifier",
                            "give the inner variable another name")
        self.expect("-", f"write ({var.text} - kind), the kind a dictionary label")
        kind = self.word("a kind", f"write ({var.text} - cup), a dictionary label")
        if not _ID.fullmatch(kind.text):
            raise self.fail(kind, f"'{kind.text}' is not a kind", "use a dictionary label")
        return Param(var.text, _SYNSET.sub("", kind.text))

    def params(self, scope: tuple[str, ...], *, several: bool) -> list[Param]:
        """(param) or, for forall and exists, (param+)."""
        self.expect("(", "write the variable in parentheses: (?c - cup)")
        found = [self.param(scope)]
        while several and (token := self.peek()) is not None and token.text != ")":
            found.append(self.param((*scope, *(p.name for p in found))))
        self.expect(")", "one variable here: (?c - cup)" if not several else
                    "close the variable list: (?c - cup ?p - plate)")
        return found

    def quantified(self, op: str, depth: int, scope: tuple[str, ...]) -> Formula:
        """(forall (param+) formula) | (exists (param+) formula); several variables
        read as nested quantifiers."""
        params = self.params(scope, several=True)
        body = self.formula(depth + 1, (*scope, *(p.name for p in params)))
        for param in reversed(params):
            body = Quantified(op, param, body)
        return body

    def number(self) -> int:
        """(N), a whole number from 0 to MAX_COUNT."""
        self.expect("(", "write the number in parentheses: (forn (2) (?c - cup) ...)")
        token = self.word("a number", "write (2)")
        if not token.text.isdigit() or int(token.text) > MAX_COUNT:
            raise self.fail(token, f"'{token.text}' is not a whole number up to {MAX_COUNT}",
                            "write (2)")
        self.expect(")", "close the number: (2)")
        return int(token.text)

    def forn(self, depth: int, scope: tuple[str, ...]) -> Quantified:
        """(forn (N) (param) formula): exactly N objects of the kind satisfy it."""
        count = self.number()
        param = self.params(scope, several=False)[0]
        return Quantified("forn", param, self.formula(depth + 1, (*scope, param.name)), count)

    def pairs(self, op: str, depth: int, scope: tuple[str, ...]) -> Pairs:
        """(forpairs (param) (param) formula) | (fornpairs (N) (param) (param) formula)."""
        count = self.number() if op == "fornpairs" else None
        first = self.params(scope, several=False)[0]
        second = self.params((*scope, first.name), several=False)[0]
        body = self.formula(depth + 1, (*scope, first.name, second.name))
        return Pairs(op, first, second, body, count)

    def atom(self, head: _Token, name: str, scope: tuple[str, ...]) -> Atom:
        """atom := (predicate term+), a term a bound variable or an object id."""
        relation, arity = PREDICATES[name]
        terms = []
        while (token := self.peek()) is not None and token.text not in "()":
            self.i += 1
            word = token.text
            if word.startswith("?") and word not in scope:
                word = word[1:]  # BDDL's `?cup.n.01_1`: an unbound name is an object's id
            if not word.startswith("?") and not _ID.fullmatch(word):
                raise self.fail(token, f"'{token.text}' is not an object id or a variable",
                                "name an object by its scene id, or a variable ?x")
            terms.append(word)
        if self.peek() is None:
            self.take()  # raises: the formula ends with parentheses open
        if len(terms) != arity:
            example = f"({name} cup plate)" if arity == 2 else f"({name} fridge)"
            raise self.fail(head, f"({name} ...) takes {arity} term(s), got {len(terms)}",
                            f"write {example}")
        return Atom(name, relation, tuple(terms))


def show(formula: Formula, binding: dict[str, str] | None = None, *,
         ordered: bool = False) -> str:
    """The formula as text, with bound variables replaced by their objects. `ordered`:
    the parts of each `and`/`or` sorted, so formulas equal up to their order read the
    same (a key)."""
    env = binding or {}

    def term(t: str) -> str:
        return env.get(t, t)

    def sub(node: Formula) -> str:
        return show(node, env, ordered=ordered)

    if isinstance(formula, Atom):
        return f"({formula.predicate} {' '.join(term(t) for t in formula.terms)})"
    if isinstance(formula, Not):
        return f"(not {sub(formula.body)})"
    if isinstance(formula, Junction):
        shown = [sub(p) for p in formula.parts]
        return f"({' '.join([formula.op, *(sorted(shown) if ordered else shown)])})"
    if isinstance(formula, Imply):
        return f"(imply {sub(formula.condition)} {sub(formula.then)})"
    if isinstance(formula, Quantified):
        count = f" ({formula.count})" if formula.count is not None else ""
        return f"({formula.op}{count} ({_param(formula.param)}) {sub(formula.body)})"
    count = f" ({formula.count})" if formula.count is not None else ""
    return (f"({formula.op}{count} ({_param(formula.first)}) ({_param(formula.second)}) "
            f"{sub(formula.body)})")


def _param(param: Param) -> str:
    return f"{param.name} - {param.kind}"


def parts(formula: Formula) -> Iterator[Formula]:
    """Every part of a formula, itself included (iteratively: no recursion limit)."""
    stack: list[Formula] = [formula]
    while stack:
        node = stack.pop()
        yield node
        if isinstance(node, Not | Quantified | Pairs):
            stack.append(node.body)
        elif isinstance(node, Junction):
            stack.extend(node.parts)
        elif isinstance(node, Imply):
            stack.extend((node.condition, node.then))


def constants(formula: Formula) -> tuple[set[str], set[str]]:
    """The object ids and the kinds a formula names (for the check against a scene)."""
    ids: set[str] = set()
    kinds: set[str] = set()
    for node in parts(formula):
        if isinstance(node, Atom):
            ids.update(t for t in node.terms if not t.startswith("?"))
        elif isinstance(node, Quantified):
            kinds.add(node.param.kind)
        elif isinstance(node, Pairs):
            kinds.update((node.first.kind, node.second.kind))
    return ids, kinds
