"""An admissible lower bound on the actions a goal formula still needs.

Every action changes one thing about one object: a move changes where its object rests,
`open`/`close` one object's `open` state, `toggle_on`/`toggle_off` its `toggled_on`
state. The bound walks the formula once, computing each part's truth and, for the truth
wanted, requirements of the form "one of these things must change" (a set of
`(aspect, object)`, aspect `place`, `open` or `toggled_on`) that every solution meets:

- an atom with the wrong truth: its thing must change (`on`/`in`/`under`: the source's
  placement, even where `in` reads the whole way down, a pizza on a plate in the fridge
  (the atom reads only the placements from the source down, and the first move that
  changes one of them moves the source: each object below carries the one above, so is
  not clear); `open`, `toggled_on`: that state of the object); `nextto` (either placed
  next to the other, or both next to one object): the placement of one of the two
  (but furniture, standing `inroom`, never moves), since its truth reads only theirs
  (moving one next to a third may make it);
  `inroom` (a room follows what the object stands on) only says that some action is
  needed, since moving the object, or what it stands on, may change it;
- all parts wanted (and, forall; or, exists wanted false; ...): every part's
  requirements;
- one part wanted (or, exists; and, forall wanted false; ...): each part's
  requirements thinned to pairwise disjoint ones, and the j-th of every part joined
  into one, for as many j as the poorest part has (whichever part a solution makes
  true, it meets each joined one with a distinct action);
- `forn` and the pair quantifiers: some action, when their truth is wrong (for the
  additive guide, `forn` wanted true: the requirements of the fewest parts that must
  change; a pair quantifier wanted true: those of the cheapest pairing of each
  unpaired object, as many as pairs are missing).

A closed container that must be opened and that the formula wants closed at the end
(`(not (open x))` under `and`/`forall` alone) must be closed again: one more action (an
open one wanted closed needs only the closing).

An object that must move must first be clear, so whatever stands on, in, under or next
to it (and so on up) must move too; nothing goes into or comes out of a closed container,
so one that must be entered or left (directly or with what carries the object) must be
opened. Requirements with no thing in common need distinct actions, so the size of a
family of pairwise disjoint requirements (picked greedily, smallest first) is a lower
bound; it is 0 exactly at the goal.
Admissible, so A* over it stays optimal.
"""

from __future__ import annotations

from collections.abc import Callable

from verigraph.graph.formula import (
    STATE_KEYS,
    Atom,
    Formula,
    Imply,
    Junction,
    Not,
    Pairs,
    Quantified,
    parse_formula,
)
from verigraph.graph.formula import parts as every_part
from verigraph.graph.formula_eval import Facts, holds_in, pairing
from verigraph.graph.goal import Goal

Thing = tuple[str, str]
Need = tuple[bool, list[frozenset[Thing]], bool]  # truth, requirements, some action needed
PLACE_RELATIONS = ("on", "in", "under")  # the source's placement: only moving it changes


def formula_needs_table(goal: Goal) -> bool:
    """Whether a goal formula speaks of what only the action table's search can change:
    a state (`open`, `toggled_on`) or an `under`/`nextto` placement (the encoded search
    moves objects on and in only)."""
    if goal.formula is None:
        return False
    return any(isinstance(node, Atom) and node.relation in (*STATE_KEYS, "under", "nextto")
               for node in every_part(parse_formula(goal.formula)))


# What else a state atom needs (object, state key, truth wanted) -> more requirements,
# e.g. a heat source turned on before `cooked` (verigraph.actions.processes).
StateNeeds = Callable[[str, str, bool], list[frozenset[Thing]]]


def formula_bound(formula: Formula, facts: Facts, state_needs: StateNeeds | None = None, *,
                  additive: bool = False, things: set[Thing] | None = None) -> int:
    """Actions the formula needs at least, from the state `facts` describe.
    `state_needs`: the other requirements of changing a state (each met by an action
    other than the one that changes the state).

    `additive`: the number of distinct requirements instead, not a lower bound (shared
    actions are counted once per requirement) but a sharper guide for a search that
    does not promise optimal plans (greedy, weighted A*); there an object cleared out of
    a mover's way, or one a process needs at its source, counts once more (it must also
    come back or go on to its goal place), so emptying a container before it moves, or
    heating before placing, lowers the guide instead of leaving a plateau. `things`:
    filled with every thing the requirements name (what a helpful action changes)."""
    truth, needs, some = _Bound(facts, state_needs, additive).need(formula, {}, True)
    if truth:
        return 0
    freed = _made_free(needs, facts)
    needs = [*needs, *freed]
    if additive:  # a guide: what is cleared out of the way must also come back or go on
        needs += [frozenset({("back", o)}) for need in freed for kind, o in need
                  if kind == "place"]
    opened = {n for need in needs if len(need) == 1 for n in need
              if n[0] == "open" and facts.closed(n[1])}  # closed now: it must be opened
    if opened:  # opened now, closed at the end: closed again, one more action each
        closed = _closed_at_the_end(formula, facts)
        needs += [frozenset({("close", c)}) for _, c in opened if c in closed]
    if things is not None:
        things.update(thing for need in needs for thing in need)
    if additive:
        return max(len(set(needs)), 1)
    taken: set[Thing] = set()
    count = 0
    for need in sorted(needs, key=len):
        if taken.isdisjoint(need):
            taken |= need
            count += 1
    return max(count, 1 if some or needs else 0)


def _closed_at_the_end(formula: Formula, facts: Facts) -> set[str]:
    """Objects every solution must leave closed: `(not (open x))` reached from the top
    through `and` and `forall` alone (x an id, or each object of the forall's kind)."""
    closed: set[str] = set()
    stack: list[tuple[Formula, dict[str, str]]] = [(formula, {})]
    while stack:
        node, env = stack.pop()
        if isinstance(node, Junction) and node.op == "and":
            stack.extend((p, env) for p in node.parts)
        elif isinstance(node, Quantified) and node.op == "forall":
            stack.extend((node.body, {**env, node.param.name: o})
                         for o in facts.objects_of(node.param.kind))
        elif isinstance(node, Not) and isinstance(node.body, Atom) \
                and node.body.relation == "open":
            closed.add(env.get(node.body.terms[0], node.body.terms[0]))
    return closed


def _made_free(needs: list[frozenset[Thing]], facts: Facts) -> list[frozenset[Thing]]:
    """An object that must move must be clear first: whatever is placed on, in, under or
    next to it, and so on up, must move too (once each, at least); and nothing comes out
    of a closed container, so each closed one that holds a mover (directly or through
    what carries it) must be opened."""
    must_move = [next(iter(n))[1] for n in needs if len(n) == 1 and next(iter(n))[0] == "place"]
    if not must_move:
        return []
    above: dict[str, list[str]] = {}
    for source, places in facts.placed.items():
        for relation, target in places:
            if relation != "inroom":
                above.setdefault(target, []).append(source)
    found: set[str] = set()
    stack = list(must_move)
    while stack:
        for other in above.get(stack.pop(), []):
            if other not in found:
                found.add(other)
                stack.append(other)
    boxes = {box for o in (*must_move, *found) for box in _closed_around(o, facts)}
    return [*(frozenset({("place", o)}) for o in sorted(found)),
            *(frozenset({("open", box)}) for box in sorted(boxes))]


def _closed_around(obj: str, facts: Facts) -> set[str]:
    """The closed containers `obj` is within, directly or through what carries it (a
    pizza on a plate in a closed fridge): each must be opened before `obj` moves."""
    return {place for relation, place in facts.down(obj)
            if relation == "in" and facts.closed(place)}


def _in_a_room(facts: Facts, obj: str) -> bool:
    """Whether an object stands in a room by its own `inroom` edge: only furniture (a
    fixed object) does, so it never moves."""
    return any(relation == "inroom" for relation, _ in facts.placed.get(obj, []))


def _every(truth: bool, parts: list[Need]) -> Need:
    """All parts must reach the wanted truth: every part's requirements."""
    return truth, [n for part in parts for n in part[1]], any(part[2] for part in parts)


def _one(truth: bool, parts: list[Need]) -> Need:
    """One part must: when every part has requirements, each part's thinned to pairwise
    disjoint ones, and the j-th of every part joined into one (met whichever part a
    solution makes true, each by a distinct action), for as many j as the poorest part
    has (one part alone keeps all of its own); else only that some action is needed."""
    if len(parts) == 1:  # the one way: all its requirements
        return truth, parts[0][1], True
    if not parts or any(not part[1] for part in parts):
        return truth, [], True
    families = [_disjoint(part[1]) for part in parts]
    depth = min(len(family) for family in families)
    return truth, [frozenset().union(*(family[j] for family in families))
                   for j in range(depth)], True


def _disjoint(needs: list[frozenset[Thing]]) -> list[frozenset[Thing]]:
    """Pairwise disjoint requirements, picked greedily, smallest first."""
    taken: set[Thing] = set()
    kept = []
    for need in sorted(needs, key=len):
        if taken.isdisjoint(need):
            taken |= need
            kept.append(need)
    return kept


class _Bound:
    def __init__(self, facts: Facts, state_needs: StateNeeds | None = None,
                 additive: bool = False) -> None:
        self.facts = facts
        self.state_needs = state_needs
        self.additive = additive

    def need(self, node: Formula, env: dict[str, str], want: bool) -> Need:
        """(truth now, requirements to reach `want`, some action needed)."""
        if isinstance(node, Atom):
            return self.atom(node, env, want)
        if isinstance(node, Not):
            truth, needs, some = self.need(node.body, env, not want)
            return not truth, needs, some
        if isinstance(node, Junction):
            parts = [self.need(p, env, want) for p in node.parts]
            every = node.op == "and"
            truth = all(p[0] for p in parts) if every else any(p[0] for p in parts)
            return self.combine(truth, want, parts, every == want)
        if isinstance(node, Imply):  # (or (not condition) then)
            condition = self.need(node.condition, env, not want)
            then = self.need(node.then, env, want)
            truth = not condition[0] or then[0]
            return self.combine(truth, want, [condition, then], not want)
        if isinstance(node, Quantified) and node.op in ("forall", "exists"):
            name = node.param.name
            parts = [self.need(node.body, {**env, name: o}, want)
                     for o in self.facts.objects_of(node.param.kind)]
            every = node.op == "forall"
            truth = all(p[0] for p in parts) if every else any(p[0] for p in parts)
            return self.combine(truth, want, parts, every == want)
        assert isinstance(node, Quantified | Pairs)
        truth = holds_in(node, self.facts, env)
        if truth != want and want and self.additive:
            if isinstance(node, Quantified):
                return self.count_guide(node, env)
            return self.pairs_guide(node, env)
        return truth, [], truth != want

    def pairs_guide(self, node: Pairs, env: dict[str, str]) -> Need:
        """`forpairs`/`fornpairs` wanted true, for a guide: for each pair still missing,
        the requirements of the cheapest way to pair an unpaired object of the first
        kind with an unpaired one of the second not yet taken (greedily, one to one)."""
        pairs, left_first, left_second, needed = pairing(node, self.facts, env)
        missing = max(needed - len(pairs), 0)
        ways = sorted(
            (len(needs), a, b, needs) for a in left_first for b in left_second if b != a
            for needs in [self.need(node.body, {**env, node.first.name: a,
                                                node.second.name: b}, True)[1]])
        chosen: list[frozenset[Thing]] = []
        taken: set[str] = set()
        for _, a, b, needs in ways:
            if len(taken) >= 2 * missing:
                break
            if a not in taken and b not in taken:
                taken |= {a, b}
                chosen += needs
        return False, chosen, True

    def count_guide(self, node: Quantified, env: dict[str, str]) -> Need:
        """`forn (N)` wanted true, for a guide (not a bound: one action may change two
        parts): the requirements of the fewest parts that must change, those that must
        become true while fewer than N hold, those that must become false while more do."""
        name, count = node.param.name, node.count or 0
        truths = [(o, holds_in(node.body, self.facts, {**env, name: o}))
                  for o in self.facts.objects_of(node.param.kind)]
        held = sum(truth for _, truth in truths)
        flip = held < count
        options = sorted((self.need(node.body, {**env, name: o}, flip)[1]
                          for o, truth in truths if truth != flip), key=len)
        changes = options[:abs(held - count)]
        return False, [n for needs in changes for n in needs], True

    @staticmethod
    def combine(truth: bool, want: bool, parts: list[Need], all_parts: bool) -> Need:
        if truth == want:
            return truth, [], False
        return _every(truth, parts) if all_parts else _one(truth, parts)

    def atom(self, node: Atom, env: dict[str, str], want: bool) -> Need:
        terms = [env.get(t, t) for t in node.terms]
        if len(terms) == 1:
            truth = self.facts.flag(terms[0], node.relation)
            thing = (node.relation, terms[0])
        else:
            truth = self.facts.related(node.relation, terms[0], terms[1])
            thing = ("place", terms[0])
        if truth == want:
            return truth, [], False
        if node.relation == "nextto":  # only moving one of the two changes it (one
            # beside the other, or beside what the other is beside: both their places),
            # and furniture (standing inroom) never moves; the guide keeps both names, so
            # one object asked next to two pieces of furniture stays two requirements
            movers = {("place", t) for t in terms
                      if self.additive or not _in_a_room(self.facts, t)}
            return truth, [frozenset(movers)] if movers else [], True
        if len(terms) == 2 and node.relation not in PLACE_RELATIONS:
            return truth, [], True
        if len(terms) == 1 and self.state_needs is not None:
            more = self.state_needs(terms[0], node.relation, want)
            if self.additive and any(kind == "place" for need in more for kind, _ in need):
                # a guide: what goes to a source must also leave it for its goal place
                more.append(frozenset({("back", terms[0])}))
            return truth, [frozenset({thing}), *more], True
        if want and node.relation == "in" and self.facts.closed(terms[1]):
            # nothing goes into a closed container, nor onto what is in it: opened too
            return truth, [frozenset({thing}), frozenset({("open", terms[1])})], True
        return truth, [frozenset({thing})], True
