"""Procedural household tasks: a home's kitchen, dining and living room, in levels.

The household family of `verigraph.tasks.procedural` (docs/env.md, "Levels"). A draw
assembles a scene in the household dictionary (docs/worlds.md, "Household worlds"):
rooms, furniture standing `inroom` them (a counter, a stove that is off and heats what
stands on it, a closed fridge that cools, a closed cabinet, a sink, a table; a closed
drawer and a living-room shelf in the bigger levels) and `objects` movable objects,
food and dishes. Its goal is a formula (docs/worlds.md, "Goals as formulas") made of
parts, each about one or two objects:

- `store`: food into the fridge (`(inside milk fridge)`), sometimes with the fridge
  closed again afterwards (`(not (open fridge))`): open it first;
- `fetch`: a dish out of a closed cabinet or drawer onto a surface: open it first;
- `cook`: food cooked (`(cooked bread)`): onto the stove, switch the stove on, cook;
- `place`: a dish on another surface or in the sink;
- `all` / `some` (the `quantified` knob): every object of a kind somewhere
  (`(forall (?c - cup) (ontop ?c table))`, one of the two shut away in the cabinet or
  drawer), or one of them (`(exists ...)`, both shut away).

The quantified parts come first, then `store`, `fetch` and `cook` (distinct ones; a
quantified part stands for `fetch`) up to `constraints`, so the plan must open that
many closed containers or switch on that many appliances;
`distractors` further objects are not in the goal, some of them sitting on or in a goal
object (clear it first). The reference solver (bounded) gives the optimal length, and a
draw is kept when it is `length` to `length + LENGTH_SLACK` and its optimal plan opens
or switches on at least `constraints` things (the count reported as its constraints).
"""

from __future__ import annotations

import random

from verigraph.errors import VeriGraphError
from verigraph.graph.dictionary import builtin_dictionary
from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.tasks.procedural import (
    DrawnTask,
    FamilyGenerator,
    LevelConfig,
    register_generator,
)

HOUSEHOLD_BUDGET = 400  # solver expansions per draw (bounded search)
LENGTH_SLACK = 2
# furniture: its room, its start state, the roles it gets beyond the dictionary's
FURNITURE: dict[str, tuple[str, dict[str, bool], dict[str, bool]]] = {
    "counter": ("kitchen", {}, {}),
    "stove": ("kitchen", {"toggled_on": False}, {"heat_source": True}),
    "fridge": ("kitchen", {"open": False}, {"cold_source": True}),
    "cabinet": ("kitchen", {"open": False}, {}),
    "sink": ("kitchen", {}, {}),
    "table": ("dining_room", {}, {}),
    "drawer": ("kitchen", {"open": False}, {}),  # from DRAWER_AT objects
    "shelf": ("living_room", {}, {}),  # from SHELF_AT objects
}
DRAWER_AT, SHELF_AT = 6, 7
SURFACES = ("counter", "table", "shelf")
FOOD = ("milk", "butter", "cheese", "bread")
COOKABLE = ("bread", "cheese")  # toast, a grilled cheese
DISHES = ("cup", "plate", "bowl", "mug", "pot", "pan")
CARRIERS = ("plate", "bowl", "pot")  # dishes a distractor may sit on or in
CONSTRAINED = ("store", "fetch", "cook")
FREE_PARTS = ("store", "fetch", "cook", "place", "place")


class _House:
    """A scene being assembled: furniture, movable objects, their places, goal parts."""

    def __init__(self, rng: random.Random, objects: int) -> None:
        self.rng = rng
        self.furniture = [f for f in FURNITURE if (f != "drawer" or objects >= DRAWER_AT)
                          and (f != "shelf" or objects >= SHELF_AT)]
        self.places: dict[str, tuple[str, str]] = {}  # movable id -> (relation, target)
        self.labels: dict[str, str] = {}
        self.attrs: dict[str, dict[str, bool]] = {}
        self.kinds_used: set[str] = set()
        self.literals: list[str] = []
        self.words: list[str] = []
        self.goal_objects: list[str] = []
        self.wanted: dict[str, int] = {}  # target -> goal objects that must end on or in it

    # -- places and capacity
    def _capacity(self, target: str) -> int | None:
        label = self.labels.get(target, target)
        return builtin_dictionary("household").properties(label).capacity

    def has_room(self, target: str) -> bool:
        capacity = self._capacity(target)
        used = sum(1 for rel, t in self.places.values() if t == target and rel in ("on", "in"))
        return capacity is None or used < capacity

    def takes(self, target: str, count: int = 1) -> bool:
        """Whether `count` more goal objects may end on or in `target` (its capacity)."""
        capacity = self._capacity(target)
        return capacity is None or self.wanted.get(target, 0) + count <= capacity

    def want(self, target: str, count: int = 1) -> None:
        self.wanted[target] = self.wanted.get(target, 0) + count

    def spot(self, options: list[tuple[str, str]]) -> tuple[str, str] | None:
        free = [o for o in options if o[1] in self.furniture + list(self.labels)
                and self.has_room(o[1])]
        return self.rng.choice(free) if free else None

    def surfaces(self, but: str | None = None) -> list[tuple[str, str]]:
        return [("on", s) for s in SURFACES if s in self.furniture and s != but]

    def new_object(self, kind: str, place: tuple[str, str], attrs: dict[str, bool] | None
                   = None, suffix: str = "") -> str:
        obj = f"{kind}{suffix}"
        self.labels[obj] = kind
        self.places[obj] = place
        self.kinds_used.add(kind)
        if attrs:
            self.attrs[obj] = attrs
        return obj

    def fresh_kind(self, pool: tuple[str, ...]) -> str | None:
        left = [k for k in pool if k not in self.kinds_used]
        return self.rng.choice(left) if left else None

    def goal(self, literal: str, words: str, *objects: str) -> None:
        if literal not in self.literals:
            self.literals.append(literal)
            self.words.append(words)
        self.goal_objects += [o for o in objects if o not in self.goal_objects]

    # -- goal parts (each returns False when the scene has no room for it)
    def store(self) -> bool:
        kind = self.fresh_kind(FOOD)
        place = self.spot(self.surfaces())
        if kind is None or place is None or not self.takes("fridge"):
            return False
        obj = self.new_object(kind, place)
        self.want("fridge")
        self.goal(f"(inside {obj} fridge)", f"put the {obj} in the fridge", obj)
        if self.rng.random() < 0.5:
            self.goal("(not (open fridge))", "leave the fridge closed")
        return True

    def fetch(self) -> bool:
        kind = self.fresh_kind(DISHES)
        shut = self.spot([("in", c) for c in ("cabinet", "drawer")])
        if kind is None or shut is None:
            return False
        surface = self.rng.choice([s for _, s in self.surfaces()])
        obj = self.new_object(kind, shut)
        self.goal(f"(ontop {obj} {surface})", f"take the {obj} out of the {shut[1]} and put "
                  f"it on the {surface}", obj)
        return True

    def cook(self) -> bool:
        kind = self.fresh_kind(COOKABLE)
        place = self.spot([*self.surfaces(), ("in", "fridge")])
        if kind is None or place is None:
            return False
        obj = self.new_object(kind, place, {"cookable": True})
        self.goal(f"(cooked {obj})", f"cook the {obj}", obj)
        return True

    def place(self) -> bool:
        kind = self.fresh_kind(DISHES)
        start = self.spot(self.surfaces())
        if kind is None or start is None:
            return False
        obj = self.new_object(kind, start)
        targets = [("on", s) for _, s in self.surfaces(but=start[1])] + [("in", "sink")]
        relation, target = self.rng.choice([t for t in targets if self.takes(t[1])])
        self.want(target)
        literal = "ontop" if relation == "on" else "inside"
        self.goal(f"({literal} {obj} {target})", f"put the {obj} {relation} the {target}",
                  obj)
        return True

    def quantified(self, every: bool) -> bool:
        kind = self.fresh_kind(DISHES)
        if kind is None:
            return False
        relation, target = self.rng.choice([t for t in [*self.surfaces(), ("in", "sink")]
                                            if self.takes(t[1], 2)])
        self.want(target, 2)
        shut = [("in", c) for c in ("cabinet", "drawer")]
        made = []
        for i in (1, 2):  # one shut away (`every`: the other elsewhere; `a`: both)
            start = self.spot(shut if i == 1 or not every else self.surfaces(but=target))
            if start is None:
                return False
            made.append(self.new_object(kind, start, suffix=f"_{i}"))
        literal = "ontop" if relation == "on" else "inside"
        quantifier, word = ("forall", "every") if every else ("exists", "a")
        self.goal(f"({quantifier} (?x - {kind}) ({literal} ?x {target}))",
                  f"put {word} {kind} {relation} the {target}", *made)
        return True

    def distractor(self) -> bool:
        kind = self.fresh_kind(FOOD + DISHES)
        if kind is None:
            return False
        carriers = [("on" if self.labels[o] == "plate" else "in", o) for o in
                    self.goal_objects if self.labels[o] in CARRIERS]
        if carriers and self.rng.random() < 0.4:
            start = self.spot(carriers)
        else:
            start = self.spot([*self.surfaces(), ("in", "cabinet"), ("in", "fridge")])
        if start is None:
            return False
        self.new_object(kind, start)
        return True

    # -- the scene
    def graph(self) -> SceneGraph:
        rooms = sorted({FURNITURE[f][0] for f in self.furniture})
        nodes = [Node(id=r, label=r) for r in rooms]
        edges = []
        for f in self.furniture:
            room, state, attrs = FURNITURE[f]
            nodes.append(Node(id=f, label=f, attrs=dict(attrs), state=dict(state)))
            edges.append(Edge(source=f, relation="inroom", target=room))
        for obj, (relation, target) in self.places.items():
            nodes.append(Node(id=obj, label=self.labels[obj], attrs=dict(self.attrs.get(obj,
                                                                                    {}))))
            edges.append(Edge(source=obj, relation=relation, target=target))
        return SceneGraph(nodes=nodes, edges=edges, dictionary="household")


def draw_household(rng: random.Random, cfg: LevelConfig) -> DrawnTask | None:
    """One household task at the knobs of `cfg`, or None (module docstring)."""
    from verigraph.actions.model import StateAction
    from verigraph.solver import solve

    house = _House(rng, cfg.objects)
    for _ in range(cfg.quantified):
        if not house.quantified(every=rng.random() < 0.6):
            return None
    # a quantified part opens the cabinet or drawer already: it is the `fetch`
    kinds = [p for p in CONSTRAINED if not (cfg.quantified and p == "fetch")]
    for part in rng.sample(kinds, min(cfg.constraints - bool(cfg.quantified), len(kinds))):
        if not getattr(house, part)():
            return None
    while len(house.goal_objects) < cfg.objects - cfg.distractors:
        if not getattr(house, rng.choice(FREE_PARTS))():
            return None
    for _ in range(cfg.distractors):
        if not house.distractor():
            return None
    if len(house.places) != cfg.objects:
        return None
    try:
        graph = house.graph()
        start = WorldState.from_graph(graph)
    except VeriGraphError:
        return None
    goal = Goal(formula=f"(and {' '.join(house.literals)})",
                instruction=_sentence(house.words))
    result = solve(start, goal, max_expansions=HOUSEHOLD_BUDGET)
    if not result.reachable or not result.optimal:
        return None
    length = len(result.plan)
    switched = sum(isinstance(a, StateAction) and a.action in ("open", "toggle_on")
                   for a in result.plan)
    if not cfg.length <= length <= cfg.length + LENGTH_SLACK or switched < cfg.constraints:
        return None
    return DrawnTask(graph, goal, length, cfg.distractors, switched)


def _sentence(words: list[str]) -> str:
    text = "; ".join(words)
    return text[0].upper() + text[1:] + ". Anything else may end up anywhere."


#                    objects distractors constraints length quantified
HOUSEHOLD_LEVELS = tuple(
    LevelConfig(objects=o, distractors=d, constraints=c, length=n, quantified=q)
    for o, d, c, n, q in ((1, 0, 1, 2, 0), (3, 1, 1, 4, 0), (4, 1, 2, 6, 0),
                          (6, 1, 2, 7, 1), (7, 1, 3, 8, 2)))

register_generator(FamilyGenerator("household", "household", draw_household,
                                   HOUSEHOLD_LEVELS,
                                   knobs=("objects", "distractors", "constraints", "length",
                                          "quantified")))
