"""Language-instruction tasks: templates of both kinds with their ground-truth goal graphs.

The paper's language group mixes direct commands ("Move the pan to the stovetop") and
goal descriptions ("I need the pan and the pot swapped"). Each template here pairs a
wording with an edit of the scene's supports; the goal graph is the start graph with
that edit applied and everything else left where it was (the instruction says so), so
the ground truth is unique. A binding is kept only if the goal graph is well formed
and the reference solver reaches it, so every task is solvable.
"""

from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import check_well_formed
from verigraph.solver import solve

Support = dict[str, tuple[str, str]]
Kind = Literal["command", "goal_description"]
KEEP_REST = " Leave everything else as it is."
SOLVER_BUDGET = 20_000


@dataclass(frozen=True)
class Instruction:
    """One generated instruction, its ground-truth goal and the template it came from."""

    template: str
    kind: Kind
    text: str
    goal: Goal
    optimal_length: int


class _Scene:
    """The start state with helpers for naming objects and choosing edit arguments."""

    def __init__(self, graph: SceneGraph, rng: random.Random) -> None:
        self.graph = graph
        self.state = WorldState.from_graph(graph)
        self.rng = rng
        self.support: Support = dict(self.state.support)

    def name(self, obj: str) -> str:
        """How the instruction refers to an object: its id in words, sometimes a synonym."""
        info = self.state.objects[obj]
        synonyms = info.props.synonyms
        if obj == info.label and synonyms and self.rng.random() < 0.3:
            return synonyms[0]
        return obj.replace("_", " ")

    def movable(self) -> list[str]:
        return sorted(o for o, i in self.state.objects.items() if i.props.movable)

    def above(self, obj: str) -> set[str]:
        return {o for o in self.state.objects if obj in self.state.supports_chain(o)}

    def targets(self, obj: str, relation: str) -> list[str]:
        """Targets `obj` could go `relation` without a cycle (room is checked later)."""
        kind = "surface" if relation == "on" else "container"
        banned = self.above(obj) | {obj}
        return sorted(t for t, i in self.state.objects.items()
                      if t not in banned and getattr(i.props, kind)
                      and self.support.get(obj) != (relation, t))

    def carried(self, obj: str) -> list[str]:
        return sorted(self.state.carried[obj])


Edit = tuple[str, Support]  # (instruction text, new supports)
Builder = Callable[[_Scene], list[Edit]]


def _edited(scene: _Scene, changes: Support) -> Support:
    return {**scene.support, **changes}


# -- edits, each returning every (text, supports) binding it allows ---------------------------
def _place(relation: str, wording: str) -> Builder:
    def build(s: _Scene) -> list[Edit]:
        out = []
        for x in s.movable():
            for t in s.targets(x, relation):
                out.append((wording.format(x=s.name(x), t=s.name(t)),
                            _edited(s, {x: (relation, t)})))
        return out
    return build


def _take_out(wording: str) -> Builder:
    def build(s: _Scene) -> list[Edit]:
        out = []
        for x in s.movable():
            rel_s = s.support.get(x)
            if rel_s is None or not s.state.objects[rel_s[1]].props.movable:
                continue
            for t in s.targets(x, "on"):
                if t == rel_s[1]:
                    continue
                word = "in" if rel_s[0] == "in" else "on"
                out.append((wording.format(x=s.name(x), s=s.name(rel_s[1]), t=s.name(t),
                                           rel=word), _edited(s, {x: ("on", t)})))
        return out
    return build


def _swap(wording: str) -> Builder:
    def build(s: _Scene) -> list[Edit]:
        out = []
        movable = s.movable()
        for i, x in enumerate(movable):
            for y in movable[i + 1:]:
                sx, sy = s.support.get(x), s.support.get(y)
                if sx is None or sy is None or sx == sy or y in s.above(x) | {sx[1]} \
                        or x in s.above(y) | {sy[1]}:
                    continue
                out.append((wording.format(x=s.name(x), y=s.name(y)),
                            _edited(s, {x: sy, y: sx})))
        return out
    return build


def _clear(wording: str, relation: str) -> Builder:
    def build(s: _Scene) -> list[Edit]:
        out = []
        for t in sorted(s.state.objects):
            items = [o for o in s.carried(t) if s.support[o][0] == relation]
            if not items or len(items) != len(s.carried(t)):
                continue
            for u in sorted(s.state.objects):
                if u == t or not s.state.objects[u].props.surface or u in items \
                        or any(u in s.above(o) for o in items):
                    continue
                out.append((wording.format(t=s.name(t), u=s.name(u)),
                            _edited(s, dict.fromkeys(items, ("on", u)))))
        return out
    return build


def _two_places(wording: str) -> Builder:
    def build(s: _Scene) -> list[Edit]:
        out = []
        movable = s.movable()
        for x in movable:
            for y in movable:
                if y == x or y in s.above(x) or x in s.above(y):
                    continue
                for t in s.targets(x, "on")[:4]:
                    for u in s.targets(y, "on")[:4]:
                        if x in (u,) or y in (t,):
                            continue
                        out.append((wording.format(x=s.name(x), t=s.name(t), y=s.name(y),
                                                   u=s.name(u)),
                                    _edited(s, {x: ("on", t), y: ("on", u)})))
        return out
    return build


def _stack(wording: str) -> Builder:
    def build(s: _Scene) -> list[Edit]:
        out = []
        for x in s.movable():
            if not s.state.objects[x].props.surface or s.carried(x):
                continue
            for y in s.movable():
                if y == x or x in s.above(y):
                    continue
                for t in s.targets(x, "on"):
                    if t == y or t in s.above(y):
                        continue
                    out.append((wording.format(x=s.name(x), t=s.name(t), y=s.name(y)),
                                _edited(s, {x: ("on", t), y: ("on", x)})))
        return out
    return build


TEMPLATES: dict[str, tuple[Kind, Builder]] = {
    # direct commands
    "move_to": ("command", _place("on", "Move the {x} to the {t}.")),
    "put_on": ("command", _place("on", "Put the {x} on the {t}.")),
    "place_on_top": ("command", _place("on", "Place the {x} on top of the {t}.")),
    "set_down": ("command", _place("on", "Set the {x} down on the {t}.")),
    "pick_and_put": ("command", _place("on", "Pick up the {x} and put it on the {t}.")),
    "could_you": ("command", _place("on", "Could you move the {x} onto the {t}?")),
    "please_put": ("command", _place("on", "Please put the {x} on the {t}.")),
    "stack_on": ("command", _place("on", "Stack the {x} on the {t}.")),
    "put_in": ("command", _place("in", "Put the {x} in the {t}.")),
    "place_inside": ("command", _place("in", "Place the {x} inside the {t}.")),
    "drop_into": ("command", _place("in", "Drop the {x} into the {t}.")),
    "take_out": ("command", _take_out("Take the {x} out of the {s} and put it on the {t}.")),
    "take_off": ("command", _take_out("Take the {x} off the {s} and set it on the {t}.")),
    "swap_cmd": ("command", _swap("Swap the {x} and the {y}.")),
    "clear_onto": ("command", _clear("Clear the {t}: put everything on it onto the {u}.",
                                     "on")),
    "empty_onto": ("command", _clear("Empty the {t} onto the {u}.", "in")),
    "two_places_cmd": ("command", _two_places("Put the {x} on the {t} and the {y} on the {u}.")),
    "stack_two_cmd": ("command", _stack("Put the {x} on the {t}, then put the {y} on it.")),
    # goal descriptions
    "want_on": ("goal_description", _place("on", "I want the {x} to end up on the {t}.")),
    "belongs_on": ("goal_description", _place("on", "The {x} belongs on the {t}.")),
    "like_sitting": ("goal_description", _place("on", "I'd like the {x} sitting on the {t}.")),
    "should_be_on": ("goal_description", _place("on", "The {x} should be on the {t}.")),
    "should_be_in": ("goal_description", _place("in", "The {x} should be in the {t}.")),
    "ends_inside": ("goal_description", _place("in", "Make sure the {x} ends up inside the "
                                                     "{t}.")),
    "no_longer": ("goal_description", _take_out("The {x} should not be {rel} the {s} any "
                                                "more; it goes on the {t}.")),
    "swapped": ("goal_description", _swap("I need the {x} and the {y} swapped.")),
    "trade_places": ("goal_description", _swap("The {x} and the {y} should trade places.")),
    "nothing_on": ("goal_description", _clear("Nothing should be left on the {t}; what is "
                                              "there goes on the {u}.", "on")),
    "nothing_in": ("goal_description", _clear("The {t} should be empty, with what was in "
                                              "it on the {u}.", "in")),
    "need_two": ("goal_description", _two_places("I need the {x} on the {t} and the {y} on "
                                                 "the {u}.")),
    "with_on_top": ("goal_description", _stack("The {x} should be on the {t} with the {y} "
                                               "on top of it.")),
}


def _goal_graph(scene: _Scene, support: Support) -> SceneGraph:
    edges = [Edge(source=o, relation=r, target=t) for o, (r, t) in sorted(support.items())]
    return SceneGraph(nodes=list(scene.graph.nodes), edges=edges,
                      dictionary=scene.graph.dictionary)


def instruction_for(graph: SceneGraph, template: str, rng: random.Random
                    ) -> Instruction | None:
    """A random binding of `template` on `graph` with a reachable goal, or None."""
    kind, build = TEMPLATES[template]
    scene = _Scene(graph, rng)
    options = build(scene)
    rng.shuffle(options)
    for text, support in options[:12]:
        goal_graph = _goal_graph(scene, support)
        if goal_graph.edge_keys() == graph.edge_keys():
            continue
        if check_well_formed(goal_graph, scene.state.dictionary):
            continue  # e.g. the target would be over capacity
        goal = Goal(graph=goal_graph, instruction=text + KEEP_REST)
        result = solve(scene.state, goal, max_expansions=SOLVER_BUDGET)
        if result.reachable:
            return Instruction(template, kind, text + KEEP_REST, goal, len(result.plan))
    return None


def template_counts() -> dict[Kind, int]:
    counts: dict[Kind, int] = {"command": 0, "goal_description": 0}
    for kind, _ in TEMPLATES.values():
        counts[kind] += 1
    return counts
