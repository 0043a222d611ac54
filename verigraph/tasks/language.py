"""Language-instruction episodes: block scenes with colours, and instructions that need
colours, quantifiers, relations and negation to be understood.

Scenes have 6 to 8 blocks in 2 or 3 towers, in four colours, so some colours repeat
(quantifiers have something to range over) and some are unique (so "the green block"
names one block). Every instruction comes with its ground-truth goal: a partial goal
graph holding exactly the edges the words ask for (the rest of the scene may end up
anywhere), computed here from the scene, independently of the rule-based translator.
A binding is kept only if the solver reaches the goal in at least 3 moves.

Each template has wordings inside the rule-based translator's grammar and one
colloquial wording outside it ("Take the red blocks down and set them on the table"),
so the translator's accuracy measures coverage of real phrasing, not only parsing.

Templates, by what they exercise (`CATEGORIES`):

- colours: a three-block tower in a named order;
- quantifier: "all the red blocks", "every red block";
- relation: "the block under the green one", "the block on top of the green one";
- negation: "every block that is not red", "all blocks except the red ones";
- compound: two clauses, one of the above with a plain colour move.
"""

from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass

from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.solver import solve
from verigraph.tasks.suite_blocks import block_graph, random_towers

PALETTE = ("red", "blue", "green", "yellow", "purple")
SOLVER_BUDGET = 60_000
MIN_LENGTH = 3
Wanted = dict[str, str]  # block -> what it must be on


@dataclass(frozen=True)
class Instruction:
    """One generated instruction, its ground-truth goal and the template it came from."""

    template: str
    category: str
    text: str
    goal: Goal
    optimal_length: int


class _Scene:
    def __init__(self, towers: list[list[str]]) -> None:
        self.towers = towers
        self.graph = block_graph(towers)
        self.state = WorldState.from_graph(self.graph)
        self.colour = {b: b.split("_")[0] for t in towers for b in t}

    def of(self, colour: str) -> list[str]:
        return sorted(b for b, c in self.colour.items() if c == colour)

    def unique(self) -> list[str]:
        return sorted(c for c in set(self.colour.values()) if len(self.of(c)) == 1)

    def repeated(self) -> list[str]:
        return sorted(c for c in set(self.colour.values()) if len(self.of(c)) > 1)

    def below(self, block: str) -> str:
        return self.state.support[block][1]

    def above(self, block: str) -> str | None:
        return next(iter(self.state.carried[block]), None)


Option = tuple[str, Wanted]
Builder = Callable[[_Scene, random.Random], Option | None]


def _tower3(s: _Scene, rng: random.Random) -> Option | None:
    colours = s.unique()
    if len(colours) < 3:
        return None
    a, b, c = rng.sample(colours, 3)
    ids = [s.of(x)[0] for x in (a, b, c)]
    text = rng.choice([
        f"Build a tower of the {a}, {b} and {c} blocks with the {a} one at the bottom and the "
        f"{c} one on top.",
        f"Put the {a} block on the table, then put the {b} block on the {a} block, then "
        f"stack the {c} block on the {b} block.",
        f"I'd like the {a}, {b} and {c} blocks stacked in that order, starting from the "
        "table."])
    return text, {ids[0]: "table", ids[1]: ids[0], ids[2]: ids[1]}


def _all_to(s: _Scene, rng: random.Random) -> Option | None:
    if not s.repeated():
        return None
    c = rng.choice(s.repeated())
    others = [u for u in s.unique() if u != c]
    if others and rng.random() < 0.5:
        # "all the red blocks on the green block" would need room for all: a tower is
        # not a place, so quantified moves go to the table; a second clause adds an on-block
        d, e = rng.sample(others, 2) if len(others) >= 2 else (others[0], None)
        if e is not None:
            text = f"Put all the {c} blocks on the table, then put the {d} block on the {e} block."
            return text, {**dict.fromkeys(s.of(c), "table"), s.of(d)[0]: s.of(e)[0]}
    text = rng.choice([f"Put all the {c} blocks on the table.",
                       f"Every {c} block should be on the table.",
                       f"Take the {c} blocks down and set them on the table."])
    return text, dict.fromkeys(s.of(c), "table")


def _under(s: _Scene, rng: random.Random) -> Option | None:
    options = [(c, d) for c in s.unique() for d in s.unique() if c != d
               and s.below(s.of(c)[0]) in s.colour and s.below(s.of(c)[0]) != s.of(d)[0]]
    if not options:
        return None
    c, d = rng.choice(options)
    x = s.below(s.of(c)[0])
    text = rng.choice([f"Put the block under the {c} block on top of the {d} block.",
                       f"Move the block beneath the {c} one onto the {d} block.",
                       f"Grab whatever is below the {c} block and put it on the {d} block."])
    return text, {x: s.of(d)[0]}


def _above(s: _Scene, rng: random.Random) -> Option | None:
    options = [(c, d) for c in s.unique() for d in s.unique() if c != d
               and s.above(s.of(c)[0]) not in (None, s.of(d)[0])]
    if not options:
        return None
    c, d = rng.choice(options)
    x = s.above(s.of(c)[0])
    assert x is not None
    text = rng.choice([f"Move the block on top of the {c} block onto the {d} block.",
                       f"The block that is on the {c} block should be on the {d} block.",
                       f"Lift the block sitting on the {c} block over to the {d} block."])
    return text, {x: s.of(d)[0]}


def _negation(s: _Scene, rng: random.Random) -> Option | None:
    c = rng.choice(sorted(set(s.colour.values())))
    text = rng.choice([f"Move every block that is not {c} to the table.",
                       f"Put all blocks except the {c} ones on the table.",
                       f"Everything that isn't {c} goes on the table."])
    return text, {b: "table" for b, col in s.colour.items() if col != c}


def _compound(s: _Scene, rng: random.Random) -> Option | None:
    first = _under(s, rng) or _above(s, rng)
    colours = s.unique()
    if first is None or len(colours) < 2:
        return None
    text, wanted = first
    for _ in range(6):
        a, b = rng.sample(colours, 2)
        x, y = s.of(a)[0], s.of(b)[0]
        if x not in wanted and y not in wanted and x not in wanted.values():
            return (f"{text[:-1]}, then put the {a} block on the {b} block.",
                    {**wanted, x: y})
    return None


TEMPLATES: dict[str, tuple[str, Builder]] = {
    "tower_in_order": ("colours", _tower3),
    "all_of_colour": ("quantifier", _all_to),
    "block_under": ("relation", _under),
    "block_above": ("relation", _above),
    "all_but_colour": ("negation", _negation),
    "relation_then_colour": ("compound", _compound),
}
CATEGORIES = ("colours", "quantifier", "relation", "negation", "compound")


def draw_scene(rng: random.Random) -> list[list[str]]:
    """6-8 blocks in four colours (some repeated), in 2 or 3 towers."""
    n = rng.randint(6, 8)
    colours = rng.sample(PALETTE, 4)
    counts: dict[str, int] = {}
    blocks = []
    for i in range(n):
        c = colours[i] if i < 4 else rng.choice(colours[:2])
        counts[c] = counts.get(c, 0) + 1
        blocks.append(f"{c}_block" if counts[c] == 1 else f"{c}_block_{counts[c]}")
    return random_towers(rng, blocks, rng.randint(2, 3))


def _goal(scene: _Scene, wanted: Wanted, text: str) -> Goal:
    table = "table"
    edges = [Edge(source=o, relation="on", target=t if t != "table" else table)
             for o, t in sorted(wanted.items())]
    return Goal(graph=SceneGraph(nodes=list(scene.graph.nodes), edges=edges,
                                 dictionary="blocks"), partial=True, instruction=text)


def instruction_for(towers: list[list[str]], template: str, rng: random.Random
                    ) -> Instruction | None:
    """A binding of `template` on the scene with a goal at least MIN_LENGTH moves away."""
    category, build = TEMPLATES[template]
    scene = _Scene(towers)
    for _ in range(8):
        made = build(scene, rng)
        if made is None:
            return None
        text, wanted = made
        goal = _goal(scene, wanted, text)
        result = solve(scene.state, goal, max_expansions=SOLVER_BUDGET)
        if result.reachable and len(result.plan) >= MIN_LENGTH:
            return Instruction(template, category, text, goal, len(result.plan))
    return None
