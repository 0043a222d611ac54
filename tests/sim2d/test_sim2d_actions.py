"""Every valid action executed in sim2d ends in the predicted graph.

Random valid moves (uniform over what the validator accepts) on generated scenes of
the built-in tabletop families go through `execute_in_world`. A move the symbolic room
check (`room_violation`) accepts must end exactly as predicted; a move it rejects may
still succeed, or the world refuses it before anything moves. Nothing may ever end in
a graph other than the prediction.
"""

from __future__ import annotations

import random

import pytest

from verigraph.actions import MoveAction
from verigraph.actions.execution import execute_in_world
from verigraph.graph.builtin_scenes import cup_on_book, kitchen_pan
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.sim2d import generate_scene, world_for_graph
from verigraph.sim2d.generator import valid_moves
from verigraph.sim2d.room import room_violation
from verigraph.sim2d.tabletop import TabletopWorld

SCENES_PER_FAMILY = 30
MOVES_PER_SCENE = 15


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware"])
def test_random_valid_moves_end_in_the_predicted_graph(family: str) -> None:
    failures: list[str] = []
    executed = refused = 0
    for seed in range(SCENES_PER_FAMILY):
        scene = generate_scene(family, seed)
        world = scene.world
        state = WorldState.from_graph(scene.graph)
        rng = random.Random(f"{family}:{seed}")
        for step in range(MOVES_PER_SCENE):
            action = rng.choice(valid_moves(state))
            roomy = room_violation(state, action) is None
            before = world.observe()
            done, _, violation, _, new_state = execute_in_world(state, [action], world)
            where = f"{family}:{seed} step {step} {action.text()}"
            if violation is None:
                observed = world.observe()
                if observed.edge_keys() != new_state.to_graph().edge_keys():
                    failures.append(f"{where}: observed {observed.sentences()}")
                executed += 1
                state = new_state
            elif done:  # performed, but the world ended elsewhere
                failures.append(f"{where}: {violation.message}")
                state = new_state
            elif roomy:
                failures.append(f"{where}: refused although the room check passed: "
                                f"{violation.message}")
            else:
                refused += 1
                assert violation.constraint == "no_room", where
                assert world.observe() == before, f"{where}: a refusal moved something"
    assert not failures, "\n".join(failures)
    total = SCENES_PER_FAMILY * MOVES_PER_SCENE
    assert executed + refused == total
    assert executed >= 0.8 * total  # the room check rejects a minority of valid moves


def _state_and_world(graph: SceneGraph) -> tuple[WorldState, TabletopWorld]:
    world = world_for_graph(graph)
    assert isinstance(world, TabletopWorld)
    return WorldState.from_graph(graph), world


def test_move_lands_on_the_free_part_of_the_target() -> None:
    state, world = _state_and_world(cup_on_book())
    _, _, violation, _, state = execute_in_world(
        state, [MoveAction(object="cup", target="desk"), MoveAction(object="book",
                                                                    target="shelf")], world)
    assert violation is None
    things = world.scene.things
    cup, book, shelf = (things[i].bounds() for i in ("cup", "book", "shelf"))
    assert cup[1] == pytest.approx(14.0, abs=0.1)  # standing on the desk top
    assert shelf[0] <= book[0] and book[2] <= shelf[2]  # wholly on the shelf
    # Moving the cup onto the book again centres it on the book's free part.
    _, _, violation, _, state = execute_in_world(
        state, [MoveAction(object="cup", target="book")], world)
    assert violation is None
    cup = things["cup"].bounds()
    assert book[0] <= cup[0] and cup[2] <= book[2] and cup[1] == pytest.approx(book[3], abs=0.1)


def test_containment_is_real_the_spoon_lies_between_the_walls() -> None:
    state, world = _state_and_world(kitchen_pan())
    _, _, violation, _, state = execute_in_world(
        state, [MoveAction(object="spoon", relation="in", target="pan")], world)
    assert violation is None
    spoon, pan = world.scene.things["spoon"], world.scene.things["pan"]
    left, bottom, right, top = pan.bounds()
    s_left, s_bottom, s_right, s_top = spoon.bounds()
    assert left < s_left and s_right < right and bottom < s_bottom < top


def test_cutlery_stands_upright_in_a_narrow_cup() -> None:
    graph = SceneGraph(nodes=[Node(id="table", label="table"), Node(id="cup", label="cup"),
                              Node(id="fork", label="fork")],
                       edges=[Edge(source="cup", relation="on", target="table"),
                              Edge(source="fork", relation="on", target="table")],
                       dictionary="tableware")
    state, world = _state_and_world(graph)
    _, _, violation, _, _ = execute_in_world(
        state, [MoveAction(object="fork", relation="in", target="cup")], world)
    assert violation is None
    left, bottom, right, top = world.scene.things["fork"].bounds()
    assert top - bottom > 4 * (right - left)  # upright
    assert world.observe().edge_keys() >= {("fork", "in", "cup", None, None)}


def test_no_room_is_refused_before_anything_moves_and_explained() -> None:
    graph = SceneGraph(nodes=[Node(id="table", label="table"), Node(id="plate", label="plate"),
                              Node(id="tray", label="tray"), Node(id="cup", label="cup")],
                       edges=[Edge(source="plate", relation="on", target="table"),
                              Edge(source="tray", relation="on", target="plate"),
                              Edge(source="cup", relation="on", target="table")],
                       dictionary="tableware")
    state, world = _state_and_world(graph)
    action = MoveAction(object="cup", target="plate")  # valid: the plate carries 2
    room = room_violation(state, action)
    assert room is not None and room.blocking == ["tray"] and "tray" in room.suggestion
    before = world.scene.snapshot()
    executed, _, violation, _, after = execute_in_world(state, [action], world)
    assert executed == [] and violation is not None
    assert violation.constraint == "no_room" and violation.blocking == ["tray"]
    assert "nothing was moved" in violation.message
    assert world.scene.snapshot() == before and after.to_graph() == state.to_graph()


def test_room_check_explains_a_blocked_container() -> None:
    state = WorldState.from_graph(kitchen_pan())
    state.set_support("pan", "in", "pot")  # the pan lies across the pot's rim
    violation = room_violation(state, MoveAction(object="lid", relation="in", target="pot"))
    assert violation is not None and violation.blocking == ["pan"]
    assert "rim" in violation.message


@pytest.mark.parametrize(("seed", "blocked", "blockers"), [
    (50151, "move(tray, in, cup)", ["bowl"]),  # the cup stands in a mug, a bowl next door
    (50199, "move(bowl, in, mug)", ["cup", "plate"]),  # a plate across a cup hangs over
    (10071, "move(bowl, in, cup)", ["book", "mug"]),  # a book across a mug, same tray
])
def test_room_check_sees_neighbours_beside_a_raised_target(
        seed: int, blocked: str, blockers: list[str]) -> None:
    """Random valid moves replayed as the agreement benchmark samples them: the move
    that once passed the room check and was refused by the simulator is now predicted,
    and no move the check passes is refused."""
    scene = generate_scene("tableware", seed)
    world, state = scene.world, WorldState.from_graph(scene.graph)
    rng = random.Random(f"tableware:{seed}")
    seen = False
    for _ in range(MOVES_PER_SCENE):
        action = rng.choice(valid_moves(state))
        room = room_violation(state, action)
        before = world.observe()
        _, _, violation, _, new_state = execute_in_world(state, [action], world)
        if action.text() == blocked:
            seen = True
            assert room is not None and room.blocking == blockers, room
            assert violation is not None and violation.constraint == "no_room"
        if violation is None:
            assert world.observe().edge_keys() == new_state.to_graph().edge_keys()
            state = new_state
        else:
            assert room is not None, f"{action.text()}: {violation.message}"
            assert world.observe() == before
    assert seen


def test_clearance_counts_only_neighbours_that_can_be_in_the_way() -> None:
    """A bowl raised on a tray, a cup on a book beside it: a plate resting on the bowl's
    rim may meet the cup, a spoon going through the opening cannot (the cup stands
    lower than the bowl's top, so it cannot hang over it)."""
    nodes = [Node(id=i, label=i) for i in ("table", "tray", "bowl", "book", "cup", "plate",
                                            "spoon")]
    edges = [Edge(source="tray", relation="on", target="table"),
             Edge(source="bowl", relation="on", target="tray"),
             Edge(source="book", relation="on", target="table"),
             Edge(source="cup", relation="on", target="book"),
             Edge(source="plate", relation="on", target="table"),
             Edge(source="spoon", relation="on", target="table")]
    state = WorldState.from_graph(SceneGraph(nodes=nodes, edges=edges, dictionary="tableware"))
    wide = room_violation(state, MoveAction(object="plate", relation="in", target="bowl"))
    assert wide is not None and wide.blocking == ["cup"]  # the book is too low
    assert room_violation(state, MoveAction(object="spoon", relation="in", target="bowl")) is None
