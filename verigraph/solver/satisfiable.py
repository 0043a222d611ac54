"""Whether any state at all satisfies a goal formula, however a plan would reach it.

A movable object has exactly one placement (docs/worlds.md, Placements), so a formula
may ask for what no state has: six logs each on the table or on a log, exactly two on
the table and exactly two on a log. A search would spend its whole budget before it
could say so; this check says it first, and why.

It looks for ANY state where the formula holds, ignoring how it is reached: each movable
object gets one placement `(relation, target)` the world allows (the target fits the
relation as `move` asks: `on` a surface, `in` a container, `under` furniture, `nextto`
anything but a room; `on` and `in` within the target's capacity; never itself, never a
cycle; its current placement is always allowed, and so is resting on nothing when it
does now), and each state key the formula reads is free, true or false (a relaxation:
some states no action can change, so "satisfiable" here promises no plan; only
"unsatisfiable" is an answer). Fixed objects keep their placements.

The search is depth-first over those choices, made lazily: only objects whose placement
some atom still needs get one (an object the formula names, and whatever stands below
it as far as its atoms read). The formula is grounded on the scene's objects once
(`forall`, `exists`, `forn`, `forpairs`, `fornpairs` over the objects of their kind; one
ground part per distinct part) and read in three values (true, false, unknown): each
atom is read once it is known, and its truth is propagated up (`and`: false at its
first false part; `or` the dual; `forn (N)`: false once more than N parts hold or fewer
than N still can; a pair quantifier: false once a largest pairing over the pairs that
still can hold is too small). Beside what is known, what every satisfying state must
have is implied from the formula wanted true, down (an `and` wanted: each part; an `or`
wanted whose parts all fail but one: that one; `not`: the opposite; `forn (N)` wanted
with N parts true: the others false, with N that can still hold: those true) and up
again; a part implied both true and false abandons the choice that led there: with two
logs on the table, every other log must be on a log, more than `forn (2)` allows.

An atom is read through formula_eval's `Facts` (its meaning is the evaluator's) once it
is known: a relation atom once the placements down the chain of its first object are
chosen (what it stands on, in, under or next to, and so on down to what is fixed or
rests on nothing), for `nextto` those of both objects; a state atom once its key is
chosen. This rests on the evaluator reading `(on a b)`, `(inside a b)`, `(under a b)`
and `(inroom a r)` from where `a` is (b only as the place named), and `(nextto a b)`
from where both are.

Objects of one label and properties that the formula treats alike (swapping the two
leaves it the same, the parts of `and` and `or` in any order) are interchangeable: of
those neither placed yet, nor a target of a placement, nor with a state chosen, only the
first is tried as a target.

`unsatisfiable_reason` returns the reason when the search proves that no state satisfies
the formula (the top-level conjuncts that cannot hold together, as few as it finds), and
None when it finds a state or its share of the solve's budget runs out.
"""

from __future__ import annotations

import time
from collections.abc import Iterator

from verigraph.actions.schemas import fits
from verigraph.graph.dictionary import PLACEMENT_RELATIONS, SUPPORT_RELATIONS
from verigraph.graph.formula import (
    Atom,
    Formula,
    Imply,
    Junction,
    Not,
    Quantified,
    constants,
    show,
)
from verigraph.graph.formula_eval import SHOWN_CHARS, Facts, facts_of, one_to_one
from verigraph.graph.state import WorldState
from verigraph.solver.budget import SearchBudget

MAX_GROUND = 20_000  # ground parts the check builds; beyond, it says nothing
MAX_CHOICES = 200  # placements and states chosen at once (the depth of the search)
SHARE = 0.2  # of the solve's CPU time limit, at most MAX_SECONDS
MAX_SECONDS = 1.0
TRIAL_NODES = 2_000  # at least, for each trial without one conjunct (the reason's core)
MAX_SHOWN = 4  # conjuncts shown in the reason
QUICK_NODES = 500  # the quick search for a state, before the whole search

Placement = tuple[str, str] | None  # (relation, target), or resting on nothing
Var = str | tuple[str, str]  # an object's placement, or (object, state key)
# The relations whose reading follows both objects' placements (`nextto` holds from
# either side); the others read where the first object is, the second only as a place.
BOTH_CHAINS = ("nextto",)
_WAYS = {"on": "on a surface", "in": "in a container", "under": "under furniture",
         "nextto": "next to one object"}
_AND, _OR, _NOT, _COUNT, _PAIRS, _ATOM = range(6)


class _Undecided(Exception):  # noqa: N818 - a control-flow signal, not an error
    """The check's share of the budget ran out, or the formula is too large for it."""


def unsatisfiable_reason(state: WorldState, formula: Formula, budget: SearchBudget
                         ) -> str | None:
    """Why no state satisfies `formula` (whatever the plan), or None: a state found, or
    the check's share of `budget` spent. Only the solve's own limits reaching their end
    stop it with SearchBudgetSpent."""
    seconds = min(MAX_SECONDS, SHARE * budget.time_limit_s)
    clock = _Clock(budget, time.thread_time() + seconds)
    world = _World(state)
    parts = _conjuncts(formula)
    try:
        if _satisfiable(world, parts, clock):
            return None
    except _Undecided:
        return None
    core = list(parts)
    trial_nodes = max(TRIAL_NODES, 4 * clock.ticks)
    for part in parts:  # fewer conjuncts that still cannot hold together say more
        if len(core) == 1:
            break
        rest = [p for p in core if p is not part]
        clock.stop_at = clock.ticks + trial_nodes
        try:
            if not _satisfiable(world, rest, clock):
                core = rest
        except _Undecided:
            if clock.late():
                break
    return _reason(core, world.relations)


def _conjuncts(formula: Formula) -> list[Formula]:
    """The parts of the top-level `and` (nested ones flattened), or the formula."""
    if isinstance(formula, Junction) and formula.op == "and" and formula.parts:
        return [p for part in formula.parts for p in _conjuncts(part)]
    return [formula]


def _reason(core: list[Formula], relations: list[str]) -> str:
    shown = [_shown(p) for p in core[:MAX_SHOWN]]
    if len(core) > len(shown):
        asked = f"{', '.join(shown)} and {len(core) - len(shown)} more part(s)"
    else:
        asked = " and ".join(shown) if len(shown) <= 2 else \
            f"{', '.join(shown[:-1])} and {shown[-1]}"
    verb = "cannot hold" if len(core) == 1 else "cannot hold together"
    ways = [_WAYS[r] for r in relations if r in _WAYS]
    how = ", ".join(ways[:-1]) + f" or {ways[-1]}" if len(ways) > 1 else "".join(ways)
    return (f"no state satisfies the goal, whatever the plan: {asked} {verb} (each object "
            f"has one placement: {how}, within capacities)")


def _shown(part: Formula) -> str:
    text = " ".join(show(part).split())
    return text if len(text) <= SHOWN_CHARS else text[:SHOWN_CHARS - 4] + "...)"


class _Clock:
    """The check's share of the CPU time, the nodes one trial may take, and the solve's
    budget checked now and then."""

    def __init__(self, budget: SearchBudget, deadline: float) -> None:
        self.budget = budget
        self.deadline = deadline
        self.ticks = 0
        self.stop_at = -1  # a trial's last node (-1: no limit)

    def late(self) -> bool:
        return time.thread_time() > self.deadline

    def tick(self) -> None:
        self.ticks += 1
        if self.ticks == self.stop_at:
            raise _Undecided
        if self.ticks % 64 == 1:
            self.budget.check()
            if self.late():
                raise _Undecided


class _World:
    """What a state may be: each movable object's placements, capacities, fixed edges,
    and the classes of interchangeable objects (filled per formula)."""

    def __init__(self, state: WorldState) -> None:
        self.state = state
        self.facts = facts_of(state)
        objects = state.objects
        self.movable = {o for o, info in objects.items() if info.props.movable}
        self.fixed_place = {o: p for o, p in state.support.items() if o not in self.movable}
        self.fixed_edges = [e for e in self.facts.edges if e[1] not in self.movable]
        self.capacity = {o: info.props.capacity for o, info in objects.items()
                         if info.props.capacity is not None}
        self.fixed_load: dict[str, int] = {}
        for relation, target in self.fixed_place.values():
            if relation in SUPPORT_RELATIONS:
                self.fixed_load[target] = self.fixed_load.get(target, 0) + 1
        self.relations = [r for r in state.move_relations if r in PLACEMENT_RELATIONS]
        self._allowed: dict[str, list[Placement]] = {}

    def allowed(self, obj: str) -> list[Placement]:
        """The placements `obj` may have: every one the rules allow, and its current
        one (or resting on nothing, where it rests on nothing now)."""
        if obj not in self._allowed:
            objects = self.state.objects
            allowed: list[Placement] = [(r, t) for r in self.relations for t in objects
                                        if t != obj and fits(objects[t].props, r)]
            current = self.state.support.get(obj)
            if current not in allowed:
                allowed.append(current)
            self._allowed[obj] = allowed
        return self._allowed[obj]

    def regular(self, obj: str) -> bool:
        """Whether `obj` rests on nothing or as the rules allow (so two such objects of
        one kind may take the same placements, each but on itself)."""
        current = self.state.support.get(obj)
        return current is None or (current[0] in self.relations and current[1] != obj
                                   and fits(self.state.objects[current[1]].props,
                                            current[0]))

    def classes(self, formula: Formula) -> dict[str, list[str]]:
        """Object -> its class of interchangeable movable objects (same label and
        properties, a current placement the rules allow or none in both, the target of
        no fixed object's placement nor of one the rules would not allow, and the
        formula the same with the two swapped)."""
        objects, support = self.state.objects, self.state.support
        named = constants(formula)[0]
        # what a fixed object, or a placement the rules would not allow, names as its
        # target is not interchangeable with another (only it is in those placements)
        fixed_targets = {t for _, t in self.fixed_place.values()}
        fixed_targets |= {support[o][1] for o in self.movable if not self.regular(o)}
        groups: dict[tuple[object, ...], list[list[str]]] = {}
        plain = show(formula, ordered=True) if named else ""
        for o in sorted(self.movable):
            if o in fixed_targets or not self.regular(o):
                continue
            key = (objects[o].label, objects[o].props, o in support)
            for members in groups.setdefault(key, []):
                first = members[0]
                if (o not in named and first not in named) \
                        or show(formula, {first: o, o: first}, ordered=True) == plain:
                    members.append(o)
                    break
            else:
                groups[key].append([o])
        return {o: members for classes in groups.values() for members in classes
                if len(members) > 1 for o in members}


def _satisfiable(world: _World, parts: list[Formula], clock: _Clock) -> bool:
    """Whether some state makes every part hold (raises _Undecided): a quick search for
    a state first, where an object goes only where an atom names or onto what is fixed
    or placed already (no chain of objects yet to be placed beneath it), then the whole
    search."""
    formula = parts[0] if len(parts) == 1 else Junction("and", tuple(parts))
    limit = clock.stop_at
    clock.stop_at = clock.ticks + QUICK_NODES if limit < 0 else \
        min(limit, clock.ticks + QUICK_NODES)
    try:
        if _Search(world, formula, clock, quick=True).run():
            return True
    except _Undecided:
        if clock.late() or clock.ticks == limit:
            raise
    finally:
        clock.stop_at = limit
    return _Search(world, formula, clock).run()


class _Ground:
    """The formula grounded on the scene's objects: parts numbered children first, one
    number per distinct part (the same atom, or the same `or` of the same atoms, read
    in two places is one part, so what one place implies the other sees)."""

    def __init__(self, world: _World, formula: Formula) -> None:
        self.world = world
        self.op: list[int] = []
        self.count: list[int] = []
        self.children: list[tuple[int, ...]] = []
        self.parents: list[list[int]] = []
        self.pairs: dict[int, list[tuple[str, str, int]]] = {}
        self.atoms: dict[int, tuple[str, tuple[str, ...]]] = {}
        self.seen: dict[tuple[object, ...], int] = {}
        self.root = self.ground(formula, {})

    def node(self, op: int, children: list[int], count: int = 0,
             key: tuple[object, ...] | None = None) -> int:
        key = key if key is not None else (op, tuple(children), count)
        if key in self.seen:
            return self.seen[key]
        index = len(self.op)
        if index >= MAX_GROUND:
            raise _Undecided
        self.seen[key] = index
        self.op.append(op)
        self.count.append(count)
        self.children.append(tuple(children))
        self.parents.append([])
        for child in dict.fromkeys(children):
            self.parents[child].append(index)
        return index

    def ground(self, node: Formula, env: dict[str, str]) -> int:
        if isinstance(node, Atom):
            atom = (node.relation, tuple(env.get(t, t) for t in node.terms))
            index = self.node(_ATOM, [], key=atom)
            self.atoms[index] = atom
            return index
        if isinstance(node, Not):
            return self.node(_NOT, [self.ground(node.body, env)])
        if isinstance(node, Junction):
            return self.node(_AND if node.op == "and" else _OR,
                             [self.ground(p, env) for p in node.parts])
        if isinstance(node, Imply):
            return self.node(_OR, [self.node(_NOT, [self.ground(node.condition, env)]),
                                   self.ground(node.then, env)])
        facts = self.world.facts
        if isinstance(node, Quantified):
            name = node.param.name
            bodies = [self.ground(node.body, {**env, name: o})
                      for o in facts.objects_of(node.param.kind)]
            if node.op == "forn":
                return self.node(_COUNT, bodies, node.count or 0)
            return self.node(_AND if node.op == "forall" else _OR, bodies)
        firsts = facts.objects_of(node.first.kind)
        seconds = facts.objects_of(node.second.kind)
        edges = [(a, b, self.ground(node.body, {**env, node.first.name: a,
                                                 node.second.name: b}))
                 for a in firsts for b in seconds if b != a]
        needed = node.count if node.count is not None else min(len(firsts), len(seconds))
        index = self.node(_PAIRS, [c for _, _, c in edges], needed,
                          key=(_PAIRS, tuple(edges), needed))
        self.pairs[index] = edges
        return index


class _Truths:
    """One truth per ground part (None: not known) and, per part, how many of its parts
    are known true and false; every change on a trail, so a choice is undone exactly.
    `truth` reads a part's truth off its parts' (Kleene's three values)."""

    def __init__(self, ground: _Ground) -> None:
        n = len(ground.op)
        self.g = ground
        self.value: list[bool | None] = [None] * n
        self.yes = [0] * n
        self.no = [0] * n
        self.trail: list[int] = []

    def learn(self, index: int, truth: bool) -> None:
        self.value[index] = truth
        self.trail.append(index)
        counts = self.yes if truth else self.no
        for parent in self.g.parents[index]:
            counts[parent] += self.g.children[parent].count(index)

    def undo(self, mark: int) -> None:
        while len(self.trail) > mark:
            index = self.trail.pop()
            counts = self.yes if self.value[index] else self.no
            self.value[index] = None
            for parent in self.g.parents[index]:
                counts[parent] -= self.g.children[parent].count(index)

    def truth(self, index: int) -> bool | None:
        g = self.g
        op, size, yes, no = g.op[index], len(g.children[index]), self.yes[index], \
            self.no[index]
        if op == _AND:
            return False if no else True if yes == size else None
        if op == _OR:
            return True if yes else False if no == size else None
        if op == _NOT:
            return False if yes else True if no else None
        if op == _COUNT:
            wanted = g.count[index]
            if yes > wanted or size - no < wanted:
                return False
            return True if yes + no == size else None
        if op == _ATOM:
            return None
        edges, needed, value = g.pairs[index], g.count[index], self.value
        if _matching([(a, b) for a, b, c in edges if value[c] is not False]) < needed:
            return False
        if _matching([(a, b) for a, b, c in edges if value[c]]) >= needed:
            return True
        return None


class _Search:
    """The depth-first search over placements and states, with two layers of truths
    over the ground formula: `known`, read off the atoms read so far (the formula known
    true there: a state found), and `implied`, what every satisfying state must have,
    from the formula wanted true down (an `and` wanted: each part; an `or` wanted with
    all parts but one false: that one; `forn (N)` wanted with N parts true: the others
    false, ...) and from what is known up; a part implied both true and false ends the
    choice that led there."""

    def __init__(self, world: _World, formula: Formula, clock: _Clock, *,
                 quick: bool = False) -> None:
        self.world = world
        self.clock = clock
        self.quick = quick  # only the placements an atom names, or onto what is placed
        self.facts_now: Facts | None = None
        self.g = _Ground(world, formula)
        self.root = self.g.root
        self.known = _Truths(self.g)
        self.implied = _Truths(self.g)
        self.place: dict[str, Placement] = {}
        self.states: dict[tuple[str, str], bool] = {}
        self.load = dict(world.fixed_load)
        self.targeted: dict[str, int] = {}
        self.watch: dict[Var, list[int]] = {}
        self.watch_trail: list[Var] = []
        self.classes = world.classes(formula)
        self.wanted = self.wanted_places()
        self.consistent = self.start()

    def wanted_places(self) -> dict[str, list[Placement]]:
        """Each object's placements the atoms name (tried first)."""
        wanted: dict[str, list[Placement]] = {}
        for relation, terms in self.g.atoms.values():
            if relation not in PLACEMENT_RELATIONS or len(terms) != 2:
                continue
            pairs = [(terms[0], terms[1])] + ([(terms[1], terms[0])]
                                               if relation == "nextto" else [])
            for obj, target in pairs:
                places = wanted.setdefault(obj, [])
                if (relation, target) not in places:
                    places.append((relation, target))
        return wanted

    # -- truths --------------------------------------------------------------------------
    def start(self) -> bool:
        """The truths before any choice (children come before their parents), and the
        formula wanted true; False when that is already contradictory."""
        for index, op in enumerate(self.g.op):
            if op == _ATOM:
                truth, blocker = self.read(index)
                if blocker is not None:
                    self.watch.setdefault(blocker, []).append(index)
            else:
                truth = self.known.truth(index)
            if truth is not None:
                self.known.learn(index, truth)
                self.implied.learn(index, truth)
        return self.imply([(self.root, True)])

    def found(self, index: int, truth: bool) -> bool:
        """An atom read: known up as far as it goes, and implied (False: a
        contradiction)."""
        known = self.known
        stack = [(index, truth)]
        while stack:
            part, value = stack.pop()
            if known.value[part] is not None:
                continue
            known.learn(part, value)
            for parent in self.g.parents[part]:
                if known.value[parent] is None:
                    up = known.truth(parent)
                    if up is not None:
                        stack.append((parent, up))
        return self.imply([(index, truth)])

    def imply(self, queue: list[tuple[int, bool]]) -> bool:
        """Parts every satisfying state has with these truths, up and down the formula;
        False when a part is implied both true and false."""
        implied, g = self.implied, self.g
        while queue:
            index, truth = queue.pop()
            now = implied.value[index]
            if now is not None:
                if now != truth:
                    return False
                continue
            implied.learn(index, truth)
            for parent in g.parents[index]:
                up = implied.truth(parent)
                if up is not None:
                    queue.append((parent, up))
                if implied.value[parent] is not None and not self.down(parent, queue):
                    return False
            if not self.down(index, queue):
                return False
        return True

    def down(self, index: int, queue: list[tuple[int, bool]]) -> bool:
        """What a part's implied truth implies of its parts (False: contradictory)."""
        implied, g = self.implied, self.g
        op, value, children = g.op[index], implied.value, g.children[index]
        truth = bool(value[index])
        if op in (_AND, _OR):
            every = truth if op == _AND else not truth  # each part must be `every`
            if every:
                queue.extend((c, truth) for c in children if value[c] is None)
                return not (implied.no if op == _AND else implied.yes)[index]
            open_ = [c for c in children if value[c] is None]
            if (implied.yes if op == _AND else implied.no)[index] == len(children):
                return False  # all parts hold (or all fail) where one must not
            if len(open_) == 1 and not (implied.no if op == _AND else implied.yes)[index]:
                queue.append((open_[0], truth))
            return True
        if op == _NOT:
            queue.append((children[0], not truth))
            return True
        if op == _COUNT and truth:
            wanted, yes, no = g.count[index], implied.yes[index], implied.no[index]
            if yes > wanted or len(children) - no < wanted:
                return False
            if yes == wanted or len(children) - no == wanted:
                queue.extend((c, yes != wanted) for c in children if value[c] is None)
        return True

    def read(self, index: int) -> tuple[bool | None, Var | None]:
        """An atom's truth through the evaluator's Facts once it is known, else the
        choice it waits for."""
        relation, terms = self.g.atoms[index]
        if len(terms) == 1:
            key = (terms[0], relation)
            return (self.states[key], None) if key in self.states else (None, key)
        for term in terms if relation in BOTH_CHAINS else terms[:1]:
            blocker = self.blocker(term)
            if blocker is not None:
                return None, blocker
        if self.facts_now is None:
            self.facts_now = self.world.facts.with_edges(
                [*self.world.fixed_edges,
                 *((p[0], o, p[1]) for o, p in self.place.items() if p is not None)])
        return self.facts_now.related(relation, terms[0], terms[1]), None

    def blocker(self, obj: str) -> str | None:
        """The first object down `obj`'s placements whose placement is not chosen."""
        return next((o for o in self.chain(obj)
                     if o in self.world.movable and o not in self.place), None)

    def chain(self, obj: str) -> Iterator[str]:
        """`obj` and each object down its placements as far as they are known: chosen
        for a movable object, fixed for the rest (bounded: placements form no cycle)."""
        current: str | None = obj
        for _ in range(len(self.world.state.objects) + 1):
            if current is None:
                return
            yield current
            if current in self.world.movable:
                placement = self.place.get(current)
            else:
                placement = self.world.fixed_place.get(current)
            current = placement[1] if placement is not None else None

    # -- choices -------------------------------------------------------------------------
    def run(self) -> bool:
        """Whether some choice of the placements and states makes the formula hold."""
        if not self.consistent:
            return False
        self.clock.tick()
        if self.known.value[self.root]:
            return True
        var = self.choose()
        if var is None or len(self.place) + len(self.states) >= MAX_CHOICES:
            raise _Undecided  # nothing left to choose, yet unknown: not a proof
        for choice in self.choices(var):
            mark = self.assign(var, choice)
            if mark is None:
                continue
            if self.consistent and self.run():
                return True
            self.undo(var, choice, mark)
        return False

    def choose(self) -> Var | None:
        """The choice the first atom still unknown and still needed waits for."""
        for index in self.g.atoms:
            if self.known.value[index] is None and self.needed(index):
                return self.read(index)[1]
        return None

    def needed(self, index: int) -> bool:
        """Whether a part's truth still matters: some path up to the root is unknown."""
        if index == self.root:
            return True
        value = self.known.value
        return any(value[p] is None and self.needed(p) for p in self.g.parents[index])

    def choices(self, var: Var) -> Iterator[Placement | bool]:
        if not isinstance(var, str):
            yield from (True, False)
            return
        allowed = self.world.allowed(var)
        first = sorted((p for p in self.wanted.get(var, []) if p in allowed),
                       key=lambda p: self.rank(var, p))
        current = self.world.state.support.get(var)
        ordered = [*first, *([current] if current not in first else [])]
        ordered += [p for p in allowed if p not in ordered]
        stand_in: dict[int, str | None] = {}  # class -> its one untouched member tried
        movable = self.world.movable
        for placement in ordered:
            target = placement[1] if placement is not None else None
            if self.quick and placement not in first and target in movable \
                    and target not in self.place:
                continue
            members = self.classes.get(target) if target is not None else None
            if members is not None and target is not None and self.untouched(target, var):
                if id(members) not in stand_in:
                    stand_in[id(members)] = next(
                        (m for m in members if self.untouched(m, var)), None)
                if stand_in[id(members)] != target:
                    continue  # an interchangeable object was tried in its place
            yield placement

    def rank(self, obj: str, placement: Placement) -> int:
        """A placement whose own atom every satisfying state has first, one whose atom
        must fail last."""
        assert placement is not None
        relation, target = placement
        index = self.g.seen.get((relation, (obj, target)))
        if index is None and relation in BOTH_CHAINS:
            index = self.g.seen.get((relation, (target, obj)))
        truth = self.implied.value[index] if index is not None else None
        return 0 if truth else 1 if truth is None else 2

    def untouched(self, obj: str, var: Var) -> bool:
        """Neither chosen for, nor a target, nor with a state chosen (nor `var`)."""
        return obj != var and obj not in self.place and not self.targeted.get(obj) \
            and not any(key[0] == obj for key in self.states)

    def assign(self, var: Var, choice: Placement | bool) -> tuple[int, int, int] | None:
        """Make a choice and propagate it (`consistent` says whether it holds up);
        None when the rules forbid it."""
        if isinstance(var, str):
            assert not isinstance(choice, bool)
            if choice is not None:
                relation, target = choice
                capacity = self.world.capacity.get(target)
                if relation in SUPPORT_RELATIONS and capacity is not None \
                        and self.load.get(target, 0) >= capacity:
                    return None
                if self.below(target, var):
                    return None
                self.targeted[target] = self.targeted.get(target, 0) + 1
                if relation in SUPPORT_RELATIONS:
                    self.load[target] = self.load.get(target, 0) + 1
            self.place[var] = choice
        else:
            assert isinstance(choice, bool)
            self.states[var] = choice
        self.facts_now = None
        mark = (len(self.known.trail), len(self.implied.trail), len(self.watch_trail))
        for index in self.watch.get(var, []):
            if self.known.value[index] is not None:
                continue
            truth, blocker = self.read(index)
            if blocker is not None:
                self.watch.setdefault(blocker, []).append(index)
                self.watch_trail.append(blocker)
            elif truth is not None and not self.found(index, truth):
                self.consistent = False
                break
        return mark

    def below(self, target: str, obj: str) -> bool:
        """Whether `obj` is down `target`'s placements (placing obj there: a cycle)."""
        return obj in self.chain(target)

    def undo(self, var: Var, choice: Placement | bool, mark: tuple[int, int, int]) -> None:
        self.consistent = True
        self.known.undo(mark[0])
        self.implied.undo(mark[1])
        while len(self.watch_trail) > mark[2]:
            self.watch[self.watch_trail.pop()].pop()
        if isinstance(var, str):
            del self.place[var]
            if choice is not None:
                assert not isinstance(choice, bool)
                relation, target = choice
                self.targeted[target] -= 1
                if relation in SUPPORT_RELATIONS:
                    self.load[target] -= 1
        else:
            del self.states[var]
        self.facts_now = None


def _matching(edges: list[tuple[str, str]]) -> int:
    """The size of a largest one-to-one pairing over `edges`."""
    fits: dict[str, list[str]] = {}
    for a, b in edges:
        fits.setdefault(a, []).append(b)
    return len(one_to_one(fits))
