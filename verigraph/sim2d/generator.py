"""Seeded scene generator: `generate_scene("kitchen", 7)` is the same scene on every machine.

Families: `blocks` (equal blocks of distinct colours in towers of varied height),
`kitchen` and `tableware` (furniture plus 3-7 objects, some stacked, some in
containers; tableware often has the paper's cup on a book), `tangram` (a target
figure and a single-move perturbation of it), and `user`: a dictionary of its own
(kinds that no built-in has, with random roles, sizes and colours, given inline as a
client gives one) on a bench and a side table, to check that generic bodies behave as
the verifier predicts. Tabletop graphs are drawn so that they
are physically plausible (things fit where they are put) and then laid out in the
simulator, which checks them; a draw the physics rejects is replaced by the next draw
of the same random stream. Tabletop goals are the graph after 2-4 random valid moves
(with room, see room.py) carried out in a copy of the world, so every goal is
physically reachable.
"""

from __future__ import annotations

import random
from dataclasses import dataclass

from verigraph.actions.execution import execute_in_world
from verigraph.actions.model import MoveAction
from verigraph.actions.validator import validate_action
from verigraph.graph.dictionary import (
    InlineDictionary,
    ObjectProperties,
    builtin_dictionary,
    canonical_token,
)
from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.sim2d.bodies import movable_spec
from verigraph.sim2d.errors import SimError
from verigraph.sim2d.layout import build_tabletop
from verigraph.sim2d.palette import BLOCK_COLORS
from verigraph.sim2d.room import room_violation
from verigraph.sim2d.tabletop import TabletopWorld
from verigraph.sim2d.tangram_figures import perturb, random_pieces, target_figure
from verigraph.sim2d.world import SimWorld

FAMILIES = ("blocks", "kitchen", "tableware", "tangram")
USER_FAMILY = "user"  # generated on demand; not one of the built-in families above
MIN_OBJECTS, MAX_OBJECTS = 3, 7
TABLETOP_LIMIT = 12
DRAWS = 30

KITCHEN_ITEMS = ("pan", "pot", "lid", "kettle", "cutting_board", "spoon", "knife")
TABLEWARE_ITEMS = ("tray", "plate", "bowl", "cup", "mug", "spoon", "fork", "knife", "book")


@dataclass(slots=True)
class GeneratedScene:
    """A generated scene: its graph, a world in that state, and a goal to plan towards.

    `goal.graph` is the target graph (tangram: the target figure) and `goal_world` a
    world in the goal state, for rendering it.
    """

    family: str
    seed: int
    graph: SceneGraph
    world: SimWorld
    goal: Goal
    goal_world: SimWorld | None = None

    @property
    def scene_id(self) -> str:
        return f"{self.family}:{self.seed}"


def generate_scene(family: str, seed: int, n_objects: int | None = None) -> GeneratedScene:
    """A reproducible scene of `family` (see FAMILIES); `n_objects` movable objects
    (default: 3-7 drawn from the seed; tangram: 7 pieces)."""
    if family not in FAMILIES and family != USER_FAMILY:
        raise SimError(f"unknown scene family '{family}'", field="family", value=family,
                       fix=f"use one of {', '.join(FAMILIES)} or {USER_FAMILY}")
    rng = random.Random(f"verigraph-sim2d:{family}:{seed}")
    if family == "tangram":
        target = target_figure(rng, random_pieces(rng, n_objects))
        start, moved = perturb(rng, target)
        goal = Goal(graph=target.observe(), instruction=f"Put {moved} back into the figure: "
                    "make every contact of the target figure hold.")
        return GeneratedScene(family, seed, start.observe(), start, goal, target)
    n = n_objects if n_objects is not None else rng.randint(MIN_OBJECTS, MAX_OBJECTS)
    if not 1 <= n <= TABLETOP_LIMIT:
        raise SimError(f"a {family} scene has 1 to {TABLETOP_LIMIT} objects, not {n}",
                       field="n_objects", value=n, fix="use a number from 3 to 7")
    for _ in range(DRAWS):
        graph = _draw_tabletop(family, rng, n)
        state = WorldState.from_graph(graph)
        if not any(room_violation(state, a) is None for a in valid_moves(state)):
            continue  # nothing can be moved anywhere (three spoons on a table)
        try:
            world = build_tabletop(graph, rng.randrange(2**31))
        except SimError:
            continue
        goal_world = _random_goal(world, graph, rng)
        goal = Goal(graph=goal_world.observe(),
                    instruction="Rearrange the objects so that the scene matches the goal graph.")
        return GeneratedScene(family, seed, world.observe(), world, goal, goal_world)
    raise SimError(f"no physically valid {family} scene with {n} objects for seed {seed}",
                   field="seed", value=seed, fix="use another seed or fewer objects")


# -- tabletop graphs ------------------------------------------------------------------------
def _draw_tabletop(family: str, rng: random.Random, n: int) -> SceneGraph:
    if family == "blocks":
        return _draw_blocks(rng, n)
    if family == USER_FAMILY:
        return _draw_user(rng, n)
    d = builtin_dictionary(family)
    pool: tuple[str, ...]
    if family == "kitchen":
        fixed = ["counter"] + (["stove"] if rng.random() < 0.75 else []) + \
            (["shelf"] if rng.random() < 0.25 else [])
        pool = KITCHEN_ITEMS
    else:
        fixed = [rng.choice(["table", "desk"])] + (["shelf"] if rng.random() < 0.35 else [])
        pool = TABLEWARE_ITEMS
    labels = _sample_labels(rng, pool, n)
    forced: dict[str, tuple[str, str]] = {}
    if family == "tableware" and n >= 2 and rng.random() < 0.5:
        # The paper's motivating case: a cup on a book.
        labels = ["book", "cup"] + [x for x in labels if x not in ("book", "cup")][:n - 2]
        forced["cup"] = ("on", "book")
    nodes = [Node(id=f, label=f) for f in fixed]
    ids = _unique_ids(labels)
    nodes += [Node(id=i, label=lab) for i, lab in zip(ids, labels, strict=True)]
    props = {node.id: d.objects[node.label] for node in nodes}
    return SceneGraph(nodes=nodes, edges=_draw_supports(rng, fixed, ids, props, forced),
                      dictionary=family)


# Kinds a user might bring, by role; sizes and capacities are drawn per scene.
USER_SURFACES = ("laptop", "tablet", "cutting_mat", "sketchbook", "placemat")
USER_CONTAINERS = ("pen_holder", "basket", "tin", "planter", "caddy")
USER_THINGS = ("stapler", "phone", "mouse", "charger", "candle", "figurine")


def user_dictionary(rng: random.Random, n: int) -> InlineDictionary:
    """A random inline dictionary: a fixed bench and side table, then n movable kinds."""
    objects: dict[str, dict[str, object]] = {
        "bench": {"movable": False, "surface": True, "width": 60, "height": 4,
                  "color": "walnut"},
        "side_table": {"movable": False, "surface": True, "capacity": 3, "width": 30,
                       "height": 3, "color": "gray"}}
    pools = {"surface": list(USER_SURFACES), "container": list(USER_CONTAINERS),
             "thing": list(USER_THINGS)}
    for pool in pools.values():
        rng.shuffle(pool)
    for _ in range(n):
        role = rng.choice([r for r, pool in pools.items() if pool])
        label = pools[role].pop()
        color = rng.choice(BLOCK_COLORS)
        if role == "surface":
            objects[label] = {"surface": True, "capacity": rng.randint(1, 2),
                              "width": rng.randint(10, 18), "height": rng.randint(1, 3),
                              "color": color}
        elif role == "container":
            objects[label] = {"container": True, "capacity": rng.randint(1, 2),
                              "width": rng.randint(9, 14), "height": rng.randint(4, 8),
                              "color": color}
        else:
            objects[label] = {"width": rng.randint(3, 7), "height": rng.randint(2, 5),
                              "color": color}
    return InlineDictionary.model_validate({"name": "generated", "objects": objects})


def _draw_user(rng: random.Random, n: int) -> SceneGraph:
    spec = user_dictionary(rng, n)
    d = spec.build()
    fixed = ["bench", "side_table"]
    ids = [canonical_token(label) for label in spec.objects if label not in fixed]
    nodes = [Node(id=i, label=i) for i in [*fixed, *ids]]
    props = {i: d.objects[i] for i in [*fixed, *ids]}
    return SceneGraph(nodes=nodes, edges=_draw_supports(rng, fixed, ids, props, {}),
                      dictionary=spec)


def _draw_blocks(rng: random.Random, n: int) -> SceneGraph:
    if n > len(BLOCK_COLORS):
        raise SimError(f"at most {len(BLOCK_COLORS)} blocks have distinct colours",
                       field="n_objects", value=n, fix=f"use at most {len(BLOCK_COLORS)}")
    colors = rng.sample(BLOCK_COLORS[:max(7, n)], n)
    nodes = [Node(id="table", label="table")] + [
        Node(id=f"{c}_block", label="block", attrs={"color": c}) for c in colors]
    tops: list[str] = []
    edges = []
    for c in colors:
        block = f"{c}_block"
        if not tops or rng.random() < 0.4:
            edges.append(Edge(source=block, relation="on", target="table"))
            tops.append(block)
        else:
            k = rng.randrange(len(tops))
            edges.append(Edge(source=block, relation="on", target=tops[k]))
            tops[k] = block
    return SceneGraph(nodes=nodes, edges=edges, dictionary="blocks")


def _sample_labels(rng: random.Random, pool: tuple[str, ...], n: int) -> list[str]:
    if n <= len(pool):
        return rng.sample(pool, n)
    return list(pool) + [rng.choice(pool) for _ in range(n - len(pool))]


def _unique_ids(labels: list[str]) -> list[str]:
    seen: dict[str, int] = {}
    out = []
    for lab in labels:
        seen[lab] = seen.get(lab, 0) + 1
        out.append(lab if seen[lab] == 1 else f"{lab}_{seen[lab]}")
    return out


def _fits(obj: ObjectProperties, label: str, relation: str, target: ObjectProperties,
          target_label: str, carried: list[ObjectProperties]) -> bool:
    """Plausible at a glance: things fit inside containers, nothing overhangs a surface."""
    w = float(obj.width or 6)
    if relation == "on":
        return w + sum(float(c.width or 6) for c in carried) <= float(target.width or 6)
    spec = movable_spec(target_label, target)
    assert spec.cavity is not None
    inner = spec.cavity[1] - spec.cavity[0]
    if carried:
        return False
    item = movable_spec(label, obj)
    return w <= inner - 0.4 or (item.thin and item.height < inner - 0.4
                                and item.width <= 1.6 * (spec.cavity[3] - spec.cavity[2]))


def _draw_supports(rng: random.Random, fixed: list[str], ids: list[str],
                   props: dict[str, ObjectProperties],
                   forced: dict[str, tuple[str, str]]) -> list[Edge]:
    order = list(ids)
    rng.shuffle(order)
    # Carriers first, so that smaller things can end up on or in them.
    order.sort(key=lambda i: 0 if i in ("book",) and "cup" in forced else (
        1 if props[i].surface or props[i].container else 2))
    placed: list[str] = []
    carried: dict[str, list[str]] = {f: [] for f in fixed}
    depth: dict[str, int] = dict.fromkeys(fixed, 0)
    edges = []
    for obj in order:
        if obj in forced and forced[obj][1] in placed:
            relation, target = forced[obj]
        else:
            options: list[tuple[float, str, str]] = []
            for f in fixed:
                cap = props[f].capacity
                if cap is None or len(carried[f]) < cap:
                    options.append((1.0, "on", f))
            for t in placed:
                p = props[t]
                if depth[t] >= 3 or (p.capacity is not None and len(carried[t]) >= p.capacity):
                    continue
                label_t, label_o = _label(t), _label(obj)
                held = [props[c] for c in carried[t]]
                if p.container and _fits(props[obj], label_o, "in", p, label_t, held):
                    options.append((2.5, "in", t))
                elif p.surface and _fits(props[obj], label_o, "on", p, label_t, held):
                    options.append((1.5, "on", t))
            total = sum(w for w, _, _ in options)
            pick = rng.random() * total
            relation, target = options[-1][1], options[-1][2]
            for w, rel, tgt in options:
                pick -= w
                if pick <= 0:
                    relation, target = rel, tgt
                    break
        edges.append(Edge(source=obj, relation=relation, target=target))
        carried.setdefault(target, []).append(obj)
        carried.setdefault(obj, [])
        depth[obj] = depth.get(target, 0) + 1
        placed.append(obj)
    return edges


def _label(node_id: str) -> str:
    base, _, suffix = node_id.rpartition("_")
    return base if suffix.isdigit() and base else node_id


def _random_goal(world: TabletopWorld, graph: SceneGraph, rng: random.Random
                 ) -> TabletopWorld:
    """A copy of the world after 2-4 random valid moves that have room (more if those
    happened to lead back to the start)."""
    sim = world.copy()
    state = WorldState.from_graph(graph)
    start = graph.edge_keys()
    wanted, done = rng.randint(2, 4), 0
    for _ in range(4 * wanted):
        if done >= wanted and sim.observe().edge_keys() != start:
            break
        actions = [a for a in valid_moves(state) if room_violation(state, a) is None]
        rng.shuffle(actions)
        for action in actions[:8]:
            _, _, violation, _, state = execute_in_world(state, [action], sim)
            if violation is None:
                done += 1
                break
    return sim


def valid_moves(state: WorldState) -> list[MoveAction]:
    """Every move the validator accepts in `state`, in a stable order."""
    moves = []
    for obj in sorted(state.objects):
        if not state.objects[obj].props.movable:
            continue
        for target in sorted(state.objects):
            for relation in ("on", "in"):
                action = MoveAction(object=obj, relation=relation, target=target)
                if validate_action(state, action) is None:
                    moves.append(action)
    return moves
