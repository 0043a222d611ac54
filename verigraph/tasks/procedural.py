"""Procedural tasks with a difficulty knob: a seeded generator per family, in levels.

The stored suites (`groups`, bundled as verigraph/env/data/*.jsonl) stay the fixed test
sets; these generators draw as many fresh tasks as training needs. A family's generator
reads a `LevelConfig` (how many objects the goal is about, distractors, constraints, and
for the kitchen the plan length aimed at) and `LEVELS[family][level]` holds the presets:
every knob rises (or stays) from one level to the next, and so does the optimal length.

- **blocks**: the goal is one or two towers (a partial goal: only their edges must hold)
  built from blocks spread on the table; `distractors` extra blocks are in the scene and
  not in the goal, and `constraints` of them sit on goal blocks (in piles), so those must
  be cleared first (`object_not_clear`). The optimal length is known by construction:
  every goal block but a tower's bottom must move, and every block piled on a goal block
  must move once (each goal block has to be clear at some point), and moving the piles to
  the table and then building the towers achieves that bound, so it is
  `goal blocks - towers + constraints` (tests check it against the reference solver).
- **kitchen**: the sim2d kitchen with `objects` movable objects; a seeded random walk of
  valid moves (with room in the simulator) until the reference solver, under a bounded
  budget, needs `length` to `length + 2` moves to the walk's end. The goal is partial: only the
  objects whose place changed; the others are distractors (at least `distractors`), and
  at least `constraints` goal objects carry something at the start (clear them first).
- **tangram**: a target figure of `objects` pieces with `length` pieces taken out (one
  align each to put back); `constraints` of them were attached to a piece also taken
  out (the order matters), and `distractors` of them are left touching the figure in a
  contact it does not have. The optimal length comes from the bounded breadth-first
  search of `verigraph.planning.tangram_plan`.
- **household** (verigraph.tasks.procedural_household): a home in the household
  dictionary with `objects` food and dishes, a formula goal of parts (food into the
  fridge, a dish out of a closed cabinet, food cooked on the stove, a dish moved, and
  `quantified` parts over a kind); `constraints` closed containers to open or
  appliances to switch on, `distractors` objects not in the goal; the optimal length is
  the reference solver's, `length` to `length + 2`.

A family is one `register_generator(FamilyGenerator(...))` call (its group, draw function
and level presets); `generate_tasks(family, level, n, seed)` gives `Task`s (kind
`level_L`, id `family-L<level>/<seed>/<index>`) that the environment, the curriculum and
the datasets use like any other task. Draws are quick: no search is unbounded, and a
draw that misses its level's bounds is drawn again (at most `MAX_DRAWS` times).
"""

from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from verigraph.errors import VeriGraphError
from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.tasks.suite_blocks import COLOURS
from verigraph.tasks.task import GroupName, Task

MAX_DRAWS = 60
KITCHEN_BUDGET = 30_000  # solver expansions per kitchen draw (bounded search)
KITCHEN_WALK = 16


class LevelConfig(BaseModel):
    """The knobs of one draw. What each means per family: see the module docstring."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    objects: int = Field(ge=1, le=12, description="goal objects (blocks: goal blocks; "
                         "kitchen: movable objects in the scene; tangram: figure pieces)")
    distractors: int = Field(ge=0, le=8, description="objects or contacts not in the goal")
    constraints: int = Field(ge=0, le=8, description="orderings the plan must respect "
                             "(things to clear first, pieces that go back after another)")
    length: int = Field(default=0, ge=0, le=12, description="kitchen: optimal length aimed "
                        "at; tangram: pieces out; blocks: unused (it follows)")
    towers: int = Field(default=1, ge=1, le=3, description="blocks: goal towers")
    quantified: int = Field(default=0, ge=0, le=3, description="household: goal parts "
                            "stated over a kind (forall, exists) instead of by id")


@dataclass(frozen=True)
class DrawnTask:
    """One drawn task before it becomes a `Task`."""

    graph: SceneGraph
    goal: Goal
    optimal_length: int
    distractors: int
    constraints: int


Draw = Callable[[random.Random, LevelConfig], DrawnTask | None]


@dataclass(frozen=True)
class FamilyGenerator:
    """A family's procedural generator: its task group, draw function and level presets."""

    family: str
    group: GroupName
    draw: Draw
    levels: tuple[LevelConfig, ...]  # level 1 first
    # the LevelConfig fields this family reads: a curriculum's attributes
    knobs: tuple[str, ...] = ("objects", "distractors", "constraints", "length", "towers")

    def config(self, level: int) -> LevelConfig:
        if not 1 <= level <= len(self.levels):
            raise VeriGraphError(f"{self.family} has levels 1 to {len(self.levels)}, not "
                                 f"{level}", field="level", value=level,
                                 fix=f"use a level from 1 to {len(self.levels)}")
        return self.levels[level - 1]


GENERATORS: dict[str, FamilyGenerator] = {}


def register_generator(generator: FamilyGenerator) -> None:
    """Add (or replace) a family's generator: the one step that gives a family levels."""
    GENERATORS[generator.family] = generator


def generator_for(family: str) -> FamilyGenerator:
    if family not in GENERATORS:
        raise VeriGraphError(f"no procedural generator for family '{family}'",
                             field="family", value=family,
                             fix=f"use one of {', '.join(GENERATORS)}")
    return GENERATORS[family]


def max_level(family: str) -> int:
    return len(generator_for(family).levels)


# -- blocks -------------------------------------------------------------------------------
def _block_ids(n: int, rng: random.Random) -> list[str]:
    """n distinct block ids named after their colour (a second round gets a suffix)."""
    ids = []
    for round_ in range(1 + (n - 1) // len(COLOURS)):
        suffix = f"_{round_ + 1}" if round_ else ""
        ids += [f"{c}_block{suffix}" for c in rng.sample(COLOURS, len(COLOURS))]
    return ids[:n]


def _blocks_graph(stacks: list[list[str]]) -> SceneGraph:
    nodes = [Node(id="table", label="table")]
    edges = []
    for stack in stacks:
        below = "table"
        for block in stack:
            nodes.append(Node(id=block, label="block", attrs={"color": block.split("_")[0]}))
            edges.append(Edge(source=block, relation="on", target=below))
            below = block
    return SceneGraph(nodes=nodes, edges=edges, dictionary="blocks")


def draw_blocks(rng: random.Random, cfg: LevelConfig) -> DrawnTask | None:
    n, towers = cfg.objects, min(cfg.towers, cfg.objects // 2)
    ids = _block_ids(n + cfg.distractors, rng)
    goal_blocks, extra = ids[:n], ids[n:]
    cuts = sorted(rng.sample(range(2, n - 1), towers - 1)) if towers > 1 else []
    bounds = [0, *cuts, n]
    order = rng.sample(goal_blocks, n)
    goal_towers = [order[a:b] for a, b in zip(bounds, bounds[1:], strict=False)]
    if any(len(t) < 2 for t in goal_towers):
        return None
    # piles of `constraints` distractors on goal blocks; the rest on the table or on
    # each other
    stacks: dict[str, list[str]] = {b: [b] for b in goal_blocks}
    burying, free = extra[:cfg.constraints], extra[cfg.constraints:]
    for block in burying:
        stacks[rng.choice(goal_blocks)].append(block)
    loose: list[list[str]] = []
    for block in free:
        if loose and rng.random() < 0.5:
            rng.choice(loose).append(block)
        else:
            loose.append([block])
    start = [stacks[b] for b in goal_blocks] + loose
    rng.shuffle(start)
    words = "; ".join(", ".join(b.removesuffix("_block") for b in t) for t in goal_towers)
    goal_graph = _blocks_graph(goal_towers)
    goal = Goal(graph=goal_graph, partial=True,
                instruction=f"Build {len(goal_towers)} tower(s), each from the bottom up: "
                            f"{words}. The other blocks may end up anywhere.")
    return DrawnTask(_blocks_graph(start), goal, n - len(goal_towers) + len(burying),
                     len(extra), len(burying))


# -- kitchen ------------------------------------------------------------------------------
def draw_kitchen(rng: random.Random, cfg: LevelConfig) -> DrawnTask | None:
    from verigraph.actions.validator import apply_action
    from verigraph.sim2d.generator import generate_scene, valid_moves
    from verigraph.sim2d.room import room_violation
    from verigraph.solver import solve

    try:
        scene = generate_scene("kitchen", rng.randrange(2**31), cfg.objects)
    except VeriGraphError:
        return None
    start = WorldState.from_graph(scene.graph)
    movable = sorted(o for o, x in start.objects.items() if x.props.movable)
    state = start.copy()
    for _ in range(KITCHEN_WALK):
        moves = [m for m in valid_moves(state) if room_violation(state, m) is None]
        if not moves:
            return None
        apply_action(state, rng.choice(moves))
        moved = [o for o in movable if state.support.get(o) != start.support.get(o)]
        blocked = [o for o in moved if not start.is_clear(o)]
        if len(movable) - len(moved) < cfg.distractors or len(blocked) < cfg.constraints:
            continue
        if 2 * len(moved) < cfg.length:
            continue  # too few goal objects to need `length` moves yet: skip the search
        goal_graph = _kitchen_goal_graph(state, moved)
        goal = Goal(graph=goal_graph, partial=True,
                    instruction="Put each object listed in the goal where the goal graph "
                                "says; the others may stay or move.")
        result = solve(start, goal, max_expansions=KITCHEN_BUDGET)
        if not result.reachable:
            continue
        length = len(result.plan)
        if length > cfg.length + 2:
            return None
        if length >= cfg.length:
            return DrawnTask(scene.graph, goal, length, len(movable) - len(moved),
                             len(blocked))
    return None


def _kitchen_goal_graph(state: WorldState, moved: list[str]) -> SceneGraph:
    full = state.to_graph()
    keep = set(moved) | {t for o in moved if (s := state.support.get(o)) for t in [s[1]]}
    return SceneGraph(nodes=[n for n in full.nodes if n.id in keep],
                      edges=[e for e in full.edges if e.source in moved],
                      dictionary=full.dictionary)


# -- tangram ------------------------------------------------------------------------------
def draw_tangram(rng: random.Random, cfg: LevelConfig) -> DrawnTask | None:
    from verigraph.sim2d import world_for_graph
    from verigraph.sim2d.generator import generate_scene
    from verigraph.tasks.suite_tangram import peelable, put_back_goal

    figure = generate_scene("tangram", rng.randrange(2**31), cfg.objects).goal.graph
    if figure is None:
        return None
    contacts = [(e.source, e.target) for e in figure.edges if e.relation == "touches"]
    edges = set(contacts)
    out: list[str] = []
    chained = 0
    for _ in range(cfg.length):
        leaves = peelable(edges)
        if not leaves:
            return None
        # prefer what the level asks for: a leaf hanging on a piece already out or not
        on_out = [p for p in leaves if any(p in (a, b) and ({a, b} - {p}) & set(out)
                                           for a, b in contacts)]
        want_chain = chained < cfg.constraints
        pool = [p for p in leaves if (p in on_out) == want_chain] or leaves
        piece = rng.choice(pool)
        chained += piece in on_out
        edges = {(a, b) for a, b in edges if piece not in (a, b)}
        out.append(piece)
    # a piece is "chained" when a figure partner of it was taken out before it
    chained = sum(1 for i, p in enumerate(out) if any(
        p in (a, b) and ({a, b} - {p}) & set(out[:i]) for a, b in contacts))
    kept = [e for e in figure.edges if e.source not in out and e.target not in out]
    wrong = _wrong_contacts(rng, figure, out, cfg.distractors)
    if chained < cfg.constraints or wrong is None:
        return None
    start = SceneGraph(nodes=list(figure.nodes), edges=kept + wrong,
                       dictionary=figure.dictionary)
    try:  # a start load_scene takes: its pieces can lie with exactly these contacts
        world_for_graph(start)
    except VeriGraphError:
        return None
    put_back = put_back_goal(figure, start, out)
    if put_back is None:
        return None
    goal, length = put_back
    return DrawnTask(start, goal, length, len(wrong), chained)


def _wrong_contacts(rng: random.Random, figure: SceneGraph, out: list[str], count: int
                    ) -> list[Edge] | None:
    """`count` pieces taken out, each left touching a free side of a figure piece that the
    figure does not join it to (or None when there is no such side)."""
    if count > len(out):
        return None
    used = {(e.source, e.source_side) for e in figure.edges} | \
        {(e.target, e.target_side) for e in figure.edges}
    state = WorldState.from_graph(figure)
    inside = [p for p in sorted(state.objects) if p not in out]
    free = [(p, s) for p in inside for s in range(state.objects[p].props.sides or 0)
            if (p, s) not in used]
    partners = {(e.source, e.target) for e in figure.edges} | \
        {(e.target, e.source) for e in figure.edges}
    wrong = []
    for piece in rng.sample(out, count):
        options = [(p, s) for p, s in free if (piece, p) not in partners]
        if not options:
            return None
        target, side = rng.choice(options)
        free.remove((target, side))
        wrong.append(Edge(source=piece, relation="touches", target=target, source_side=0,
                          target_side=side))
    return wrong


# -- registry and tasks -------------------------------------------------------------------
def _levels(*rows: tuple[int, int, int, int, int]) -> tuple[LevelConfig, ...]:
    return tuple(LevelConfig(objects=o, distractors=d, constraints=c, length=n, towers=t)
                 for o, d, c, n, t in rows)


#                 objects distractors constraints length towers
BLOCKS_LEVELS = _levels((3, 0, 0, 0, 1), (4, 1, 0, 0, 1), (5, 1, 1, 0, 1),
                        (6, 2, 2, 0, 2), (7, 3, 2, 0, 2), (8, 3, 3, 0, 2))
KITCHEN_LEVELS = _levels((4, 0, 0, 2, 1), (5, 1, 0, 3, 1), (6, 1, 1, 4, 1),
                         (7, 2, 1, 5, 1), (8, 2, 2, 6, 1), (9, 3, 2, 6, 1))
TANGRAM_LEVELS = _levels((3, 0, 0, 1, 1), (4, 0, 0, 2, 1), (5, 1, 1, 3, 1),
                         (6, 1, 1, 4, 1), (7, 2, 2, 5, 1), (7, 3, 3, 5, 1))

register_generator(FamilyGenerator("blocks", "stacking", draw_blocks, BLOCKS_LEVELS))
register_generator(FamilyGenerator("kitchen", "ref_image_kitchen", draw_kitchen,
                                   KITCHEN_LEVELS))
register_generator(FamilyGenerator("tangram", "tangram", draw_tangram, TANGRAM_LEVELS))


def _graph_json(graph: SceneGraph) -> dict[str, Any]:
    return graph.model_dump(mode="json", exclude_none=True)


def _seed_text(cfg: LevelConfig) -> str:
    """The knobs as the seed reads them: a knob added later (`quantified`) only when set,
    so the tasks drawn before it existed keep their seeds."""
    return cfg.model_dump_json(exclude=set() if cfg.quantified else {"quantified"})


def generate_task(family: str, level: int, index: int, seed: int = 0,
                  config: LevelConfig | None = None) -> Task:
    """Task `index` of a family's level (or of an explicit `config`), fixed by the
    seed: the same arguments give the same task in every process."""
    generator = generator_for(family)
    cfg = config or generator.config(level)
    for draw in range(MAX_DRAWS):
        rng = random.Random(f"verigraph-procedural:{family}:{_seed_text(cfg)}:"
                            f"{seed}:{index}:{draw}")
        made = generator.draw(rng, cfg)
        if made is None or (made.goal.graph is None and made.goal.formula is None):
            continue
        set_goal: dict[str, Any] = {"instruction": made.goal.instruction}
        if made.goal.graph is not None:
            set_goal["graph"] = _graph_json(made.goal.graph)
        if made.goal.formula is not None:
            set_goal["formula"] = made.goal.formula
        if made.goal.partial:
            set_goal["partial"] = True
        return Task.create(task_id=f"{family}-L{level}/{seed}/{index}",
                           load={"graph": _graph_json(made.graph)}, set_goal=set_goal,
                           family=family, group=generator.group, kind=f"level_{level}",
                           optimal_length=made.optimal_length, show_goal_graph=True,
                           instruction=made.goal.instruction,
                           category=f"distractors={made.distractors},"
                                    f"constraints={made.constraints}")
    raise VeriGraphError(f"no {family} task drawn for level {level} in {MAX_DRAWS} draws",
                         field="level", value=level,
                         fix="use another seed or index, or a config with fewer "
                             "constraints")


def generate_tasks(family: str, level: int, n: int, seed: int = 0,
                   config: LevelConfig | None = None) -> list[Task]:
    """n tasks of a family's level: indexes 0..n-1 of `generate_task`."""
    if not 1 <= n <= 100_000:
        raise VeriGraphError("n must be between 1 and 100000", field="n", value=n,
                             fix="use e.g. 200")
    return [generate_task(family, level, i, seed, config) for i in range(n)]


# the household family registers itself (its generator lives in its own module)
import verigraph.tasks.procedural_household  # noqa: E402,F401
