"""Scene builders and hypothesis strategies shared by the core tests."""

from __future__ import annotations

import random

from hypothesis import strategies as st

from verigraph.actions import MoveAction, apply_action, validate_action
from verigraph.actions.model import StateAction
from verigraph.actions.schemas import SCHEMAS, valid_actions
from verigraph.graph import Edge, Node, SceneGraph, WorldState

TABLEWARE_MOVABLE = ["plate", "bowl", "cup", "mug", "book", "tray", "spoon", "fork"]


def graph(dictionary: str | None, nodes: list[tuple[str, str]],
          edges: list[tuple[str, str, str]]) -> SceneGraph:
    return SceneGraph(nodes=[Node(id=i, label=lab) for i, lab in nodes],
                      edges=[Edge(source=s, relation=r, target=t) for s, r, t in edges],
                      dictionary=dictionary)


def random_blocks(n: int, seed: int, p_stack: float = 0.6) -> SceneGraph:
    """n blocks in random towers on a table."""
    rng = random.Random(seed)
    ids = [f"b{i}" for i in range(n)]
    rng.shuffle(ids)
    edges, tops = [], []
    for b in ids:
        if tops and rng.random() < p_stack:
            t = rng.choice(tops)
            tops.remove(t)
            edges.append((b, "on", t))
        else:
            edges.append((b, "on", "table"))
        tops.append(b)
    return graph("blocks", [("table", "table")] + [(b, "block") for b in sorted(ids)], edges)


def random_tableware(n: int, seed: int, labels_seed: int | None = None) -> SceneGraph:
    """n tableware objects placed randomly where properties and capacities allow.

    The objects come from `labels_seed` (default `seed`), so two calls with the same
    labels_seed and different seeds give the same objects in different places.
    """
    from verigraph.graph import builtin_dictionary

    d = builtin_dictionary("tableware")
    rng = random.Random(seed)
    label_rng = random.Random(seed if labels_seed is None else labels_seed)
    nodes = [("table", "table"), ("shelf", "shelf")]
    load = {"table": 0, "shelf": 0}
    edges = []
    for i in range(n):
        label = label_rng.choice(TABLEWARE_MOVABLE)
        oid = f"{label}_{i}"
        options = []
        for target, _ in nodes:
            tp = d.objects[dict(nodes)[target]]
            room = tp.capacity is None or load[target] < tp.capacity
            if tp.surface and room:
                options.append((target, "on"))
            if tp.container and room:
                options.append((target, "in"))
        target, rel = rng.choice(options)
        load[target] += 1
        load[oid] = 0
        nodes.append((oid, label))
        edges.append((oid, rel, target))
    return graph("tableware", nodes, edges)


@st.composite
def scene_and_seed(draw: st.DrawFn) -> SceneGraph:
    kind = draw(st.sampled_from(["blocks", "tableware"]))
    n = draw(st.integers(min_value=1, max_value=8))
    seed = draw(st.integers(min_value=0, max_value=10_000))
    return random_blocks(n, seed) if kind == "blocks" else random_tableware(n, seed)


@st.composite
def raw_move(draw: st.DrawFn, graph_: SceneGraph) -> dict[str, str]:
    """A move drawn from the scene's ids plus a few wrong names: valid and invalid ones."""
    ids = graph_.node_ids() + ["ghost"]
    return {"action": "move", "object": draw(st.sampled_from(ids)),
            "relation": draw(st.sampled_from(["on", "in", "under"])),
            "target": draw(st.sampled_from(ids))}


def walk_checking_valid_actions(state: WorldState, seed: int, steps: int) -> int:
    """Walk `steps` random actions of `valid_actions` from `state` (in place), checking at
    each state that the list is, as a set and without repeats, exactly the definition:
    every move of every object by every relation onto every object, and every other row
    of the table on every object, that `validate_action` accepts. Returns how many
    actions were listed in all (so a caller can see the walk was not empty)."""
    rng = random.Random(seed)
    listed = 0
    for _ in range(steps):
        ids = sorted(state.objects)
        tried = [*(MoveAction(object=o, relation=r, target=t)
                   for o in ids for r in state.move_relations for t in ids),
                 *(StateAction(action=name, object=o)  # type: ignore[arg-type]
                   for name in SCHEMAS if name != "move" for o in ids)]
        wanted = {a.text() for a in tried if validate_action(state, a) is None}
        found = [a.text() for a in valid_actions(state)]
        assert len(found) == len(set(found))
        assert set(found) == wanted
        listed += len(found)
        if not found:
            break
        apply_action(state, rng.choice(valid_actions(state)))
    return listed
