"""Random aligns in the tangram world end exactly in the predicted graph.

The state holds every contact of a side (a long side can touch two pieces), and an
aligned piece that also lands against new neighbours has those contacts added to the
prediction as observed. Seeded; `verigraph bench sim2d` runs the same check at 500.
"""

from __future__ import annotations

import random

from verigraph.actions.execution import execute_in_world
from verigraph.actions.validator import validate_action
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.sim2d import generate_scene
from verigraph.sim2d.sampling import random_align

ALIGNS = 200


def random_aligns(aligns: int, first_seed: int = 0) -> tuple[int, list[str]]:
    """(aligns carried out, mismatches) over seeded random valid aligns."""
    mismatches: list[str] = []
    done = 0
    seed = first_seed
    while done < aligns:
        scene = generate_scene("tangram", seed)
        world, state = scene.world, WorldState.from_graph(scene.graph)
        rng = random.Random(seed)
        ids = sorted(state.objects)
        for _ in range(30):
            action = random_align(rng, ids)
            if validate_action(state, action) is not None:
                continue
            _, _, violation, _, new_state = execute_in_world(state, [action], world)
            if violation is not None:
                assert violation.constraint == "overlap", violation.message
                continue
            observed = world.observe().edge_keys()
            if observed != new_state.to_graph().edge_keys():
                mismatches.append(f"seed {seed}: {action.text()}")
            state = new_state
            done += 1
            if done >= aligns:
                break
        seed += 1
    return done, mismatches


def test_random_aligns_end_in_the_predicted_graph() -> None:
    done, mismatches = random_aligns(ALIGNS)
    assert done == ALIGNS
    assert not mismatches, mismatches


def test_a_side_keeps_both_pieces_it_touches() -> None:
    """A large triangle's long side can touch two small triangles at once; the state
    keeps both, and moving one away leaves the other."""
    graph = SceneGraph(nodes=[Node(id=p, label=p) for p in
                              ("large_triangle_1", "small_triangle_1", "small_triangle_2")],
                       edges=[Edge(source="small_triangle_1", relation="touches",
                                   target="large_triangle_1", source_side=2, target_side=2),
                              Edge(source="small_triangle_2", relation="touches",
                                   target="large_triangle_1", source_side=2, target_side=2)],
                       dictionary="tangram")
    state = WorldState.from_graph(graph)
    assert sorted(state.partners(("large_triangle_1", 2))) == [("small_triangle_1", 2),
                                                             ("small_triangle_2", 2)]
    assert len(state.to_graph().edges) == 2
    state.detach_contacts("small_triangle_1")
    assert state.partners(("large_triangle_1", 2)) == [("small_triangle_2", 2)]
