"""Physics round trip: the graph read back from the simulator is the graph it was given."""

from __future__ import annotations

import pytest

from verigraph.errors import MalformedGraphError, VeriGraphError
from verigraph.graph.builtin_scenes import BUILTIN_SCENES
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.sim2d import FAMILIES, SimError, TabletopWorld, generate_scene, world_for_graph

SEEDS = range(12)


def keys(graph: SceneGraph) -> set[tuple[str, str, str, int | None, int | None]]:
    return graph.edge_keys()


@pytest.mark.parametrize("scene_id", sorted(BUILTIN_SCENES))
def test_builtin_scenes_read_back_as_given(scene_id: str) -> None:
    graph = BUILTIN_SCENES[scene_id]()
    observed = world_for_graph(graph).observe()
    assert keys(observed) == keys(graph)
    assert [n.id for n in observed.nodes] == sorted(n.id for n in graph.nodes)


@pytest.mark.parametrize("family", FAMILIES)
def test_generated_scenes_read_back_as_intended(family: str) -> None:
    for seed in SEEDS:
        scene = generate_scene(family, seed)
        intended = scene.graph
        assert keys(scene.world.observe()) == keys(intended), f"{family}:{seed}"
        # A fresh layout of the same graph (another seed) reads back the same too.
        fresh = world_for_graph(intended, seed=seed + 100)
        assert keys(fresh.observe()) == keys(intended), f"{family}:{seed} relaid"
        assert scene.goal.graph is not None
        assert scene.goal_world is not None
        assert keys(scene.goal_world.observe()) == keys(scene.goal.graph)
        assert keys(scene.goal.graph) != keys(intended), f"{family}:{seed} goal is the start"


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware"])
def test_tabletop_scenes_have_three_to_seven_objects_and_the_papers_cases(family: str) -> None:
    counts, contained, stacked = set(), 0, 0
    for seed in range(30):
        scene = generate_scene(family, seed)
        assert isinstance(scene.world, TabletopWorld)
        movable = [t for t in scene.world.scene.movable()]
        counts.add(len(movable))
        relations = {(e.relation, scene.graph.node(e.target).label)  # type: ignore[union-attr]
                     for e in scene.graph.edges}
        contained += any(r == "in" for r, _ in relations)
        stacked += any(lab not in ("table", "desk", "counter", "stove", "shelf")
                       for _, lab in relations)
    assert counts <= set(range(3, 8)) and len(counts) >= 3
    assert stacked >= 10  # incomplete stacks: something stands on a movable object
    if family != "blocks":
        assert contained >= 5  # objects in containers


def test_tableware_generator_includes_the_cup_on_a_book() -> None:
    found = [s for s in range(20)
             if ("cup", "on", "book", None, None) in generate_scene("tableware", s).graph
             .edge_keys()]
    assert len(found) >= 4


def test_generation_is_deterministic_and_seed_dependent() -> None:
    for family in FAMILIES:
        a, b = generate_scene(family, 5), generate_scene(family, 5)
        assert a.graph == b.graph and a.goal == b.goal
        assert (a.world.render(160, 120) == b.world.render(160, 120)).all()
        others = {tuple(sorted(keys(generate_scene(family, s).graph))) for s in range(6)}
        assert len(others) >= 4, family


def test_n_objects_is_honoured_and_checked() -> None:
    for n in (1, 3, 7, 10):
        scene = generate_scene("kitchen", 2, n_objects=n)
        assert len(scene.graph.nodes) - len(
            [x for x in scene.graph.nodes if x.label in ("counter", "stove", "shelf")]) == n
    assert len(generate_scene("tangram", 2, n_objects=4).graph.nodes) == 4
    with pytest.raises(SimError) as err:
        generate_scene("blocks", 0, n_objects=40)
    assert err.value.field == "n_objects" and err.value.fix
    with pytest.raises(SimError, match="unknown scene family"):
        generate_scene("garden", 0)


def test_graph_over_the_union_dictionary_mixes_families() -> None:
    graph = SceneGraph(nodes=[Node(id="table", label="table"), Node(id="b", label="block"),
                              Node(id="bowl", label="bowl"), Node(id="spoon", label="spoon"),
                              Node(id="pan", label="frying pan")],
                       edges=[Edge(source="b", relation="on", target="table"),
                              Edge(source="bowl", relation="on", target="table"),
                              Edge(source="spoon", relation="in", target="bowl"),
                              Edge(source="pan", relation="on", target="table")])
    assert keys(world_for_graph(graph).observe()) == keys(graph)


def test_physically_impossible_graph_is_rejected_with_a_fix() -> None:
    # Two trays (24 wide) cannot both lie on a 14-wide plate, whatever its capacity says.
    graph = SceneGraph(nodes=[Node(id="table", label="table"), Node(id="plate", label="plate"),
                              Node(id="t1", label="tray"), Node(id="t2", label="tray")],
                       edges=[Edge(source="plate", relation="on", target="table"),
                              Edge(source="t1", relation="on", target="plate"),
                              Edge(source="t2", relation="on", target="plate")],
                       dictionary="tableware")
    with pytest.raises(SimError) as err:
        world_for_graph(graph)
    assert isinstance(err.value, VeriGraphError)
    assert err.value.field == "edges" and "plate" in str(err.value.value) and err.value.fix


def test_malformed_graph_is_rejected_naming_the_node() -> None:
    graph = SceneGraph(nodes=[Node(id="table", label="table"), Node(id="cup", label="cup")],
                       edges=[], dictionary="tableware")
    with pytest.raises(MalformedGraphError) as err:
        world_for_graph(graph)
    assert err.value.value == "cup"
