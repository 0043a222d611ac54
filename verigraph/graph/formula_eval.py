"""Goal formulas evaluated over a scene: true or false, and why, in plain data.

The evaluator reads a scene through `Facts`: the objects of each kind, the edges by
relation name and each node's states through one accessor (`node_state`), so it needs
nothing of how a `WorldState` stores them. Meanings:

- `(inside a b)`/`(in a b)`: `a` is anywhere within `b`, as BEHAVIOR reads Inside:
  placed `in b`, or placed on, in, under or next to something that is itself within `b`,
  followed down its placements (a pizza on a plate in the fridge, a book on a book in
  the bookcase, a cup beside a bottle in the cabinet are in it);
- `(ontop a b)`/`(on a b)`, `(under a b)`: the direct support, as BEHAVIOR's OnTop needs
  contact: the scene has that edge (`a on b`, `a under b`), or `a` stands next to
  something that is so placed: an object placed `nextto c` stands where `c` stands
  (beside furniture, which stands in its room, is on that room's floor or lawn,
  `GROUND_KINDS`);
- `(nextto a b)`: an edge `nextto` either way, or `a` and `b` (two objects) both placed
  next to one object: `nextto` stays one placement per object (x set next to y), and
  objects set beside one anchor stand side by side around it (chairs around a table),
  so three books pairwise next to each other are two placed beside the third, or all
  three beside a fourth;
- `(inroom a r)`: `a` is in room `r`: furniture by its own `inroom` edge, any other
  object by the room of the furniture its placements lead down to (a cup on a plate on
  the kitchen table is in the kitchen).
- `(open x)`, `(toggled_on x)`: the node's state; a node without that state reads false
  (an openable without a state is closed, a toggleable one is off).
- `forall`/`exists` range over the scene's objects of the kind (the dictionary label,
  synonyms read as the dictionary reads them; `room` takes every room, whatever its room
  kind); over a kind the scene lacks, `forall` is
  true and `exists` false. `forn (N)`: exactly N objects satisfy the body (BDDL's
  reading). `forpairs`: a one-to-one pairing of distinct objects, every object of the
  smaller kind paired; `fornpairs (N)`: N such pairs.

`evaluate` returns a `FormulaResult`: whether it holds, EVERY counterexample (each names
the failing part with its objects filled in and why it fails), and the witnesses of each
`exists` that holds (in a formula that fails too, in its parts that hold).
`check_names` is the check a goal passes before it is stored.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from verigraph.budget import checkpoint
from verigraph.errors import GoalError
from verigraph.graph.dictionary import kind_token
from verigraph.graph.formula import (
    Atom,
    Formula,
    Imply,
    Junction,
    Not,
    Pairs,
    Quantified,
    constants,
    show,
)
from verigraph.reporting import MAX_LISTED

if TYPE_CHECKING:
    from verigraph.graph.state import WorldState

MAX_GROUND = 200_000  # ground instances a formula may expand to on one scene
MAX_KEPT = 1_000  # counterexamples and witnesses kept (all are counted)
SHOWN_CHARS = 160  # a part is shown up to this many characters
LINE_CHARS = 600  # a counterexample or witness, part and reason, up to this many
# What furniture (an object with no placement, standing in its room) stands on: an
# object placed next to furniture is on its room's floor (or lawn, outdoors).
GROUND_KINDS = ("floor", "lawn")
_WORDS = {"on": "on", "in": "in", "under": "under", "nextto": "next to", "inroom": "in room"}
# What a formula means by these words beyond their edge, a line each, for the texts
# a planner or a client reads beside a formula (the module docstring says why).
FORMULA_MEANINGS = {
    "inside": "(inside a b) holds when a is in b, or on, in, under or next to something "
              "that is itself inside b",
    "nextto": "(nextto a b) holds when a is placed next to b, b next to a, or both next to "
              "one object",
}


def one_to_one(fits: dict[str, list[str]]) -> dict[str, str]:
    """A largest one-to-one pairing over `fits` (each first -> the seconds it may pair
    with), as second -> first, by augmenting paths (firsts tried in the dict's order)."""
    partner: dict[str, str] = {}

    def augment(a: str, seen: set[str]) -> bool:
        for b in fits[a]:
            if b in seen:
                continue
            seen.add(b)
            if b not in partner or augment(partner[b], seen):
                partner[b] = a
                return True
        return False

    for a in fits:
        augment(a, set())
    return partner


def meanings_in(formula: str) -> list[str]:
    """The `FORMULA_MEANINGS` lines of the words a formula's text uses, in table order."""
    return [meaning for word, meaning in FORMULA_MEANINGS.items() if f"({word} " in formula]


def node_state(state: WorldState, obj: str) -> Mapping[str, bool]:
    """The state keys a node sets (`open`, `toggled_on`); a key it does not set reads
    false (an openable object is closed, a toggleable one off)."""
    return state.states.get(obj, {})


class Facts:
    """What a formula reads of a scene: kinds, edges by relation name, node states."""

    __slots__ = ("by_kind", "edges", "placed", "states", "resolve", "openable", "_inside")

    def __init__(self, labels: Mapping[str, str], edges: Iterable[tuple[str, str, str]],
                 states: Mapping[str, Mapping[str, bool]],
                 resolve: Callable[[str], str | None],
                 groups: Mapping[str, list[str]] | None = None,
                 openable: frozenset[str] = frozenset()) -> None:
        self.by_kind: dict[str, list[str]] = {}
        for obj, label in labels.items():
            self.by_kind.setdefault(label, []).append(obj)
        for kind, objs in (groups or {}).items():  # `room`: every room, of any room kind
            mine = self.by_kind.setdefault(kind, [])
            mine.extend(o for o in objs if o not in mine)
        self.states = states
        self.resolve = resolve
        self.openable = openable  # nothing goes in or out of one while it is closed
        self.edges: set[tuple[str, str, str]] = set()
        self.placed: dict[str, list[tuple[str, str]]] = {}
        self._index(edges)

    def _index(self, edges: Iterable[tuple[str, str, str]]) -> None:
        """Each edge `(relation, source, target)`, and each source's placements."""
        self._inside: dict[str, set[str]] = {}  # object -> every container it is within
        for relation, source, target in edges:
            self.edges.add((relation, source, target))
            self.placed.setdefault(source, []).append((relation, target))

    def with_edges(self, edges: Iterable[tuple[str, str, str]]) -> Facts:
        """The same objects and states with other edges (a search state)."""
        other = Facts.__new__(Facts)
        other.by_kind, other.states, other.resolve = self.by_kind, self.states, self.resolve
        other.openable = self.openable
        other.edges, other.placed = set(), {}
        other._index(edges)
        return other

    def kind(self, word: str) -> str:
        """The label a kind word names (`mug` -> `cup` where the dictionary says so)."""
        return self.resolve(word) or kind_token(word)

    def objects_of(self, word: str) -> list[str]:
        return self.by_kind.get(self.kind(word), [])

    def knows(self, obj: str) -> bool:
        return any(obj in ids for ids in self.by_kind.values())

    def related(self, relation: str, source: str, target: str) -> bool:
        if (relation, source, target) in self.edges:
            return True
        if relation == "in":
            return self.within(source, target)
        if relation == "inroom":
            return self.room(source) == target
        if relation == "nextto":
            return ("nextto", target, source) in self.edges or self._side_by_side(source, target)
        return self._beside(relation, source, target)

    def within(self, source: str, target: str) -> bool:
        """Whether `source` is anywhere within `target`: placed `in` it, or placed on, in,
        under or next to something that is, followed down (bounded: placements have no
        cycle). Its truth reads only the placements of `source` and what they lead down
        to, none of which a move can change before `source` itself has moved: each of
        them carries the one above, so is not clear (a goal's bound relies on it)."""
        inside = self._inside.get(source)
        if inside is None:  # read many times over one state (every atom, every target)
            inside = self._inside[source] = {
                place for relation, place in self.down(source) if relation == "in"}
        return target in inside

    def down(self, obj: str) -> Iterator[tuple[str, str]]:
        """Every placement `(relation, place)` of `obj` and of what it is placed on, in,
        under or next to, followed down (a room is not followed; each place once, so
        bounded)."""
        stack, seen = [obj], {obj}
        while stack:
            for relation, place in self.placed.get(stack.pop(), ()):
                yield relation, place
                if relation != "inroom" and place not in seen:
                    seen.add(place)
                    stack.append(place)

    def _side_by_side(self, source: str, target: str) -> bool:
        """Whether two distinct objects are both placed next to one object (chairs set
        around a table, books beside a folder: they stand side by side around it)."""
        if source == target:
            return False
        anchors = {t for r, t in self.placed.get(source, []) if r == "nextto"}
        return any(r == "nextto" and t in anchors for r, t in self.placed.get(target, []))

    def _beside(self, relation: str, source: str, target: str) -> bool:
        """Whether `source` stands next to something placed `relation target` (an object
        placed next to another stands where that one stands; next to furniture, on its
        room's ground), followed along `nextto` placements (bounded: no cycle)."""
        current = source
        for _ in range(len(self.placed) + 1):
            beside = next((t for r, t in self.placed.get(current, []) if r == "nextto"), None)
            if beside is None:
                return False
            if (relation, beside, target) in self.edges:
                return True
            if not any(r != "inroom" for r, _ in self.placed.get(beside, [])):
                # furniture stands on the ground of its room
                room = self.room(beside)
                return relation == "on" and room is not None and self.room(target) == room \
                    and any(target in self.by_kind.get(k, ()) for k in GROUND_KINDS)
            current = beside
        return False

    def room(self, obj: str) -> str | None:
        """The room of `obj`: its own `inroom` edge, or that of what it is placed on,
        in, under or next to, followed down (bounded: a placement chain has no cycle)."""
        current: str | None = obj
        for _ in range(len(self.placed) + 1):
            if current is None:
                return None
            places = self.placed.get(current, [])
            room = next((t for r, t in places if r == "inroom"), None)
            if room is not None:
                return room
            current = next((t for r, t in places if r != "inroom"), None)
        return None

    def flag(self, obj: str, key: str) -> bool:
        return bool(self.states.get(obj, {}).get(key, False))

    def closed(self, obj: str) -> bool:
        """An openable object that is closed (no state: closed)."""
        return obj in self.openable and not self.flag(obj, "open")

    def where(self, obj: str) -> str:
        """`cup_1 is on table`, or that it rests on nothing."""
        places = self.placed.get(obj, [])
        places = [(r, t) for r, t in places if r != "inroom"] or places
        if not places:
            return f"{obj} rests on nothing"
        return f"{obj} is " + ", ".join(f"{_WORDS.get(r, r)} {t}" for r, t in places)


def facts_of(state: WorldState) -> Facts:
    """A WorldState's facts: its labels, its placements and furniture's rooms (tangram
    contacts aside), its states; read as plain tuples, so a search can call it often."""
    labels = {o: info.label for o, info in state.objects.items()}
    edges = [(r, o, t) for o, (r, t) in state.support.items()]
    edges += [("inroom", o, r) for o, r in state.rooms.items()]
    states = {o: node_state(state, o) for o in state.states}
    rooms = [o for o, info in state.objects.items() if info.props.room]
    return Facts(labels, edges, states, state.dictionary.resolve,
                 {"room": rooms} if rooms else None, state.openable)


@dataclass
class FormulaResult:
    """Whether a formula holds, every counterexample and the witnesses of its exists."""

    satisfied: bool
    counterexamples: list[str] = field(default_factory=list)
    counterexample_count: int = 0
    witnesses: list[str] = field(default_factory=list)
    witness_count: int = 0

    def kept(self) -> list[str]:
        """The counterexamples (or, when it holds, the witnesses) kept, the last item
        saying "... and N more" when there were more than MAX_KEPT."""
        items, total = ((self.witnesses, self.witness_count) if self.satisfied
                        else (self.counterexamples, self.counterexample_count))
        return items + ([f"... and {total - len(items)} more"] if total > len(items) else [])

    def lines(self, limit: int = MAX_LISTED) -> list[str]:
        """The counterexamples (or, when it holds, the witnesses), with "and N more"."""
        items, total = ((self.witnesses, self.witness_count) if self.satisfied
                        else (self.counterexamples, self.counterexample_count))
        shown = items[:limit]
        if total > len(shown):
            shown = [*shown, f"... and {total - len(shown)} more"]
        return shown


def check_names(formula: Formula, facts: Facts) -> None:
    """Every object id the formula names exists and every kind is known (to the
    dictionary or as a label of the scene), and it grounds to at most MAX_GROUND
    instances: a GoalError lists every problem with the fix."""
    ids, kinds = constants(formula)
    problems: list[str] = []
    every = sorted(o for objs in facts.by_kind.values() for o in objs)
    for obj in sorted(ids):
        if not facts.knows(obj):
            near = difflib.get_close_matches(obj, every[:400], n=1, cutoff=0.6)
            problems.append(f"object '{obj}'" + (f" (did you mean {near[0]}?)" if near else
                                                 " (a ?variable must be bound by forall "
                                                 "or exists)"))
    for word in sorted(kinds):
        if facts.resolve(word) is None and kind_token(word) not in facts.by_kind:
            near = difflib.get_close_matches(kind_token(word), list(facts.by_kind), n=1,
                                             cutoff=0.6)
            problems.append(f"kind '{word}', known neither to the dictionary nor as a label "
                            "of the scene" + (f" (did you mean {near[0]}?)" if near else ""))
    if problems:
        raise GoalError("the formula names what the scene does not have: "
                        + "; ".join(problems[:MAX_LISTED]),
                        field="formula", value=problems[0][:80],
                        fix="name objects by scene id and quantify over kinds the scene "
                            f"has: {', '.join(sorted(facts.by_kind)[:20])}")
    size = _ground_size(formula, facts)
    if size > MAX_GROUND:
        raise GoalError(f"the formula expands to {size} instances on this scene, more than "
                        f"{MAX_GROUND}", field="formula", value=None,
                        fix="nest fewer quantifiers, or quantify over narrower kinds")


def _ground_size(node: Formula, facts: Facts) -> int:
    if isinstance(node, Atom):
        return 1
    if isinstance(node, Not):
        return _ground_size(node.body, facts)
    if isinstance(node, Junction):
        return sum(_ground_size(p, facts) for p in node.parts) + 1
    if isinstance(node, Imply):
        return _ground_size(node.condition, facts) + _ground_size(node.then, facts)
    body = _ground_size(node.body, facts)
    if isinstance(node, Quantified):
        return max(1, len(facts.objects_of(node.param.kind))) * body
    return max(1, len(facts.objects_of(node.first.kind))
               * len(facts.objects_of(node.second.kind))) * body


def holds(formula: Formula, facts: Facts) -> bool:
    """Whether the formula holds (short-circuit; the goal test of a search)."""
    return _Evaluator(facts).holds(formula, {})


def holds_in(formula: Formula, facts: Facts, binding: dict[str, str]) -> bool:
    """Whether a part holds with its free variables bound to objects."""
    return _Evaluator(facts).holds(formula, binding)


def pairing(node: Pairs, facts: Facts, binding: dict[str, str]
            ) -> tuple[list[tuple[str, str]], list[str], list[str], int]:
    """A largest one-to-one pairing for which a pair quantifier's body holds, the objects
    of each kind left unpaired, and how many pairs the quantifier needs."""
    evaluator = _Evaluator(facts)
    pairs, left_first, left_second = evaluator.pairing(node, binding)
    return pairs, left_first, left_second, evaluator.pairs_needed(node)


def evaluate(formula: Formula, facts: Facts) -> FormulaResult:
    """Whether the formula holds, every counterexample when it does not, and the
    witnesses of each `exists` in the parts that hold."""
    ev = _Evaluator(facts)
    witnesses = _Found()
    ev.witnesses(formula, {}, witnesses)
    if ev.holds(formula, {}):
        return FormulaResult(True, witnesses=witnesses.items, witness_count=witnesses.total)
    failures = _Found()
    ev.failures(formula, {}, failures)
    return FormulaResult(False, counterexamples=failures.items,
                         counterexample_count=failures.total, witnesses=witnesses.items,
                         witness_count=witnesses.total)


@dataclass
class _Found:
    """Findings kept up to MAX_KEPT, all counted."""

    items: list[str] = field(default_factory=list)
    total: int = 0

    def add(self, text: str) -> None:
        self.total += 1
        if len(self.items) < MAX_KEPT:
            self.items.append(text if len(text) <= LINE_CHARS
                              else text[:LINE_CHARS - 3] + "...")


def _joined(parts: list[str], sep: str = "; ") -> str:
    shown = parts[:MAX_LISTED]
    more = f"{sep}and {len(parts) - len(shown)} more" if len(parts) > len(shown) else ""
    return sep.join(shown) + more


def _bound(env: dict[str, str], name: str, obj: str) -> dict[str, str]:
    new = dict(env)
    new[name] = obj
    return new


class _Evaluator:
    """Truth and explanations of one formula over one scene's facts."""

    def __init__(self, facts: Facts) -> None:
        self.facts = facts
        self.steps = 0

    def part(self, node: Formula, env: dict[str, str]) -> str:
        text = show(node, env)
        return text if len(text) <= SHOWN_CHARS else text[:SHOWN_CHARS - 3] + "..."

    # -- truth -------------------------------------------------------------------------
    def holds(self, node: Formula, env: dict[str, str]) -> bool:
        self.steps += 1
        if self.steps % 1024 == 0:
            checkpoint()
        if isinstance(node, Atom):
            return self.atom(node, env)
        if isinstance(node, Not):
            return not self.holds(node.body, env)
        if isinstance(node, Junction):
            if node.op == "and":
                return all(self.holds(p, env) for p in node.parts)
            return any(self.holds(p, env) for p in node.parts)
        if isinstance(node, Imply):
            return not self.holds(node.condition, env) or self.holds(node.then, env)
        if isinstance(node, Quantified):
            objs = self.facts.objects_of(node.param.kind)
            name = node.param.name
            if node.op == "forall":
                return all(self.holds(node.body, _bound(env, name, o)) for o in objs)
            if node.op == "exists":
                return any(self.holds(node.body, _bound(env, name, o)) for o in objs)
            return len(self.satisfying(node, env)) == node.count
        return len(self.pairing(node, env)[0]) >= self.pairs_needed(node)

    def atom(self, node: Atom, env: dict[str, str]) -> bool:
        terms = [env.get(t, t) for t in node.terms]
        if len(terms) == 1:
            return self.facts.flag(terms[0], node.relation)
        return self.facts.related(node.relation, terms[0], terms[1])

    def satisfying(self, node: Quantified, env: dict[str, str]) -> list[str]:
        name = node.param.name
        return [o for o in self.facts.objects_of(node.param.kind)
                if self.holds(node.body, _bound(env, name, o))]

    def pairs_needed(self, node: Pairs) -> int:
        if node.count is not None:
            return node.count
        return min(len(self.facts.objects_of(node.first.kind)),
                   len(self.facts.objects_of(node.second.kind)))

    def pairing(self, node: Pairs, env: dict[str, str]
                ) -> tuple[list[tuple[str, str]], list[str], list[str]]:
        """A largest one-to-one pairing of distinct objects for which the body holds
        (augmenting paths), and the objects of each kind left unpaired."""
        firsts = self.facts.objects_of(node.first.kind)
        seconds = self.facts.objects_of(node.second.kind)
        fits: dict[str, list[str]] = {
            a: [b for b in seconds if b != a and self.holds(
                node.body, _bound(_bound(env, node.first.name, a), node.second.name, b))]
            for a in firsts}
        partner = one_to_one(fits)  # second -> first
        pairs = sorted((a, b) for b, a in partner.items())
        paired_first = {a for a, _ in pairs}
        return (pairs, [a for a in firsts if a not in paired_first],
                [b for b in seconds if b not in partner])

    # -- explanations --------------------------------------------------------------------
    def why_true(self, node: Formula, env: dict[str, str]) -> str:
        """One plain sentence: why a node that holds holds."""
        if isinstance(node, Atom):
            terms = [env.get(t, t) for t in node.terms]
            if len(terms) == 1:
                return f"{terms[0]} is {_state_word(node.relation, True)}"
            return f"{terms[0]} is {_WORDS.get(node.relation, node.relation)} {terms[1]}"
        if isinstance(node, Not):
            return self.why_false(node.body, env)
        if isinstance(node, Junction):
            if node.op == "and":
                return _joined([self.why_true(p, env) for p in node.parts]) or "nothing asked"
            first = next(p for p in node.parts if self.holds(p, env))
            return self.why_true(first, env)
        if isinstance(node, Imply):
            if not self.holds(node.condition, env):
                return f"{self.why_false(node.condition, env)}, so nothing is required"
            return self.why_true(node.then, env)
        if isinstance(node, Quantified):
            objs = self.facts.objects_of(node.param.kind)
            if node.op == "forall":
                return (f"every {node.param.kind} ({_joined(objs, ', ')}) satisfies it"
                        if objs else f"there is no {node.param.kind} in the scene")
            found = self.satisfying(node, env)
            if node.op == "exists":
                return _joined([self.why_true(node.body, _bound(env, node.param.name, o))
                                for o in found])
            return f"exactly {node.count} {node.param.kind}(s) satisfy it: " \
                   f"{_joined(found, ', ') or 'none'}"
        pairs, _, _ = self.pairing(node, env)
        return "paired: " + (_joined([f"{a} with {b}" for a, b in pairs], ", ") or "none needed")

    def why_false(self, node: Formula, env: dict[str, str]) -> str:
        """One plain sentence: why a node that fails fails."""
        if isinstance(node, Atom):
            terms = [env.get(t, t) for t in node.terms]
            if len(terms) == 1:
                given = node.relation in self.facts.states.get(terms[0], {})
                return (f"{terms[0]} is {_state_word(node.relation, False)}"
                        + ("" if given else " (no state given: that is the default)"))
            return (f"{terms[0]} is not {_WORDS.get(node.relation, node.relation)} "
                    f"{terms[1]} ({self.facts.where(terms[0])})")
        if isinstance(node, Not):
            return self.why_true(node.body, env)
        if isinstance(node, Junction):
            if node.op == "and":
                return _joined([self.why_false(p, env) for p in node.parts
                                if not self.holds(p, env)])
            if not node.parts:
                return "(or) with no alternative never holds"
            return "none holds: " + _joined([self.why_false(p, env) for p in node.parts],
                                            " / ")
        if isinstance(node, Imply):
            return (f"{self.why_true(node.condition, env)}, but "
                    f"{self.why_false(node.then, env)}")
        if isinstance(node, Quantified):
            return self.quantified_false(node, env)
        return self.pairs_false(node, env)

    def quantified_false(self, node: Quantified, env: dict[str, str]) -> str:
        kind, name = node.param.kind, node.param.name
        objs = self.facts.objects_of(kind)
        if node.op == "forall":
            return _joined([self.why_false(node.body, _bound(env, name, o)) for o in objs
                            if not self.holds(node.body, _bound(env, name, o))])
        if node.op == "exists":
            if not objs:
                return f"missing: there is no {kind} in the scene"
            tried = [self.why_false(node.body, _bound(env, name, o)) for o in objs]
            return (f"missing: no {kind} as {name} makes {self.part(node.body, env)} "
                    f"hold; of the {len(objs)} {kind}(s): {_joined(tried)}")
        found = self.satisfying(node, env)
        return (f"{len(found)} {kind}(s) satisfy it ({_joined(found, ', ') or 'none'}); "
                f"exactly {node.count} wanted")

    def pairs_false(self, node: Pairs, env: dict[str, str]) -> str:
        pairs, left_first, left_second = self.pairing(node, env)
        needed = self.pairs_needed(node)
        shown = _joined([f"{a} with {b}" for a, b in pairs], ", ") or "none"
        unpaired = [*left_first, *left_second]
        return (f"only {len(pairs)} of {needed} one-to-one pairs ({node.first.kind} with "
                f"{node.second.kind}) hold: {shown}; unpaired: "
                f"{_joined(unpaired, ', ') or 'none'}")

    def failures(self, node: Formula, env: dict[str, str], found: _Found) -> None:
        """Every counterexample of a failing node: `part fails: why`, descending through
        `and` and `forall` so each failing object is its own counterexample."""
        if isinstance(node, Junction) and node.op == "and":
            for p in node.parts:
                if not self.holds(p, env):
                    self.failures(p, env, found)
            return
        if isinstance(node, Quantified) and node.op == "forall":
            for o in self.facts.objects_of(node.param.kind):
                inner = _bound(env, node.param.name, o)
                if not self.holds(node.body, inner):
                    self.failures(node.body, inner, found)
            return
        found.add(f"{self.part(node, env)} fails: {self.why_false(node, env)}")

    def witnesses(self, node: Formula, env: dict[str, str], found: _Found) -> None:
        """The witnesses of every `exists` that holds, reached through the parts that hold
        (of an `and` or a `forall` that fails too: its parts that hold)."""
        if isinstance(node, Junction):
            for p in node.parts:
                if self.holds(p, env):
                    self.witnesses(p, env, found)
                    if node.op == "or":
                        return
        elif isinstance(node, Imply):
            if self.holds(node.condition, env) and self.holds(node.then, env):
                self.witnesses(node.then, env, found)
        elif isinstance(node, Quantified):
            name = node.param.name
            if node.op == "exists":
                objs = self.satisfying(node, env)
                if objs:
                    found.add(f"{self.part(node, env)} holds with {name} = "
                              f"{_joined(objs, ', ')}")
                return
            if node.op == "forall":
                for o in self.facts.objects_of(node.param.kind):
                    if self.holds(node.body, _bound(env, name, o)):
                        self.witnesses(node.body, _bound(env, name, o), found)


def _state_word(key: str, value: bool) -> str:
    if key == "open":
        return "open" if value else "closed"
    if key == "toggled_on":
        return "on" if value else "off"
    return key if value else f"not {key}"
