"""Random household scenes and the agreement check of random valid household actions.

`household_scene(seed)` draws a kitchen and a dining room (counter, stove, sink, fridge,
cabinet, table, each in its room), food and dishes on the counter and the table, and
random door and switch states; `household_agreement` runs random valid actions
(`actions.schemas.valid_actions`: every action of the table the validator accepts, in
a stable order) on them in the simulator.
"""

from __future__ import annotations

import random

from verigraph.actions.execution import execute_in_world
from verigraph.actions.schemas import valid_actions
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.sim2d.layout import build_tabletop
from verigraph.sim2d.room_household import household_room_violation
from verigraph.sim2d.tabletop import TabletopWorld

ROOMS = {"counter": "kitchen", "stove": "kitchen", "sink": "kitchen", "fridge": "kitchen",
         "cabinet": "kitchen", "table": "dining_room"}
ITEMS = ("milk", "bread", "cheese", "butter", "pot", "pan", "plate", "cup", "bowl", "lid",
         "spoon", "kettle", "lamp")
STATES = {"fridge": "open", "cabinet": "open", "stove": "toggled_on", "sink": "toggled_on"}


def household_scene(seed: int, n_objects: int | None = None
                    ) -> tuple[SceneGraph, TabletopWorld]:
    """A random household graph (household dictionary) and its simulated world."""
    rng = random.Random(f"household:{seed}")
    n = n_objects if n_objects is not None else rng.randint(4, 7)
    labels = rng.sample(ITEMS, min(n, len(ITEMS)))
    nodes = [Node(id="kitchen", label="kitchen"), Node(id="dining_room", label="dining_room")]
    nodes += [Node(id=f, label=f) for f in ROOMS]
    nodes += [Node(id=lab, label=lab) for lab in labels]
    for node in nodes:
        key = STATES.get(node.id) or ("toggled_on" if node.id == "lamp" else None)
        if key is not None and rng.random() < 0.5:
            node.state = {key: rng.random() < 0.5}
    edges = [Edge(source=f, relation="inroom", target=room) for f, room in ROOMS.items()]
    edges += [Edge(source=lab, relation="on", target=rng.choice(["counter", "table"]))
              for lab in labels]
    graph = SceneGraph(nodes=nodes, edges=edges, dictionary="household")
    return graph, build_tabletop(graph, seed)


def household_agreement(n: int, first_seed: int = 0, per_scene: int = 15
                        ) -> tuple[int, int, list[str]]:
    """(executed, refused, failures) over `n` random valid household actions.

    Actions are drawn uniformly from `valid_actions` (the action table's order) on
    `household_scene`s (seeds from `first_seed`, `per_scene` draws each). One the room check
    (`room_household.household_room_violation`) refuses is counted as refused and not
    run; every other one goes through `execute_in_world`, must be carried out, and the
    observed graph (placements, rooms and states) must equal the prediction. A failure
    names the scene, the step and what differed.
    """
    executed = refused = 0
    failures: list[str] = []
    seed = first_seed
    while executed + refused < n:
        graph, world = household_scene(seed)
        state = WorldState.from_graph(graph)
        rng = random.Random(seed)
        for step in range(per_scene):
            if executed + refused >= n:
                break
            action = rng.choice(valid_actions(state))
            if household_room_violation(state, action) is not None:
                refused += 1
                continue
            _, _, violation, _, new_state = execute_in_world(state, [action], world)
            where = f"household:{seed} step {step} {action.text()}"
            seen = world.observe()
            if violation is not None:
                failures.append(f"{where}: {violation.constraint}: {violation.message}")
                state = WorldState.from_graph(seen, state.dictionary, partial=True)
                continue
            executed += 1
            state = new_state
            if seen != new_state.to_graph().canonical():
                failures.append(f"{where}: observed {seen.sentences()}")
        seed += 1
    return executed, refused, failures
