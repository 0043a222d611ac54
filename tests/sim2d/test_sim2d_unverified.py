"""Unverified execution: an action the validator would refuse really changes the scene
the way physics dictates (the cup on the book falls when the book is moved)."""

from __future__ import annotations

import math

import pytest

from verigraph.actions import AlignAction, MoveAction, validate_action
from verigraph.actions.execution import execute_in_world
from verigraph.graph.builtin_scenes import cup_on_book, three_blocks
from verigraph.graph.state import WorldState
from verigraph.sim2d import SimError, TabletopWorld, generate_scene, world_for_graph


def tabletop(graph_factory: object) -> TabletopWorld:
    world = world_for_graph(graph_factory())  # type: ignore[operator]
    assert isinstance(world, TabletopWorld)
    return world


def test_moving_the_book_from_under_the_cup_makes_the_cup_fall() -> None:
    state = WorldState.from_graph(cup_on_book())
    action = MoveAction(object="book", target="shelf")
    assert validate_action(state, action).constraint == "object_not_clear"  # type: ignore[union-attr]
    world = tabletop(cup_on_book)
    cup = world.scene.things["cup"]
    height_before = cup.bounds()[1]
    observed = world.perform_unverified(action)
    edges = observed.edge_keys()
    assert ("book", "on", "shelf", None, None) in edges
    assert ("cup", "on", "book", None, None) not in edges
    assert cup.bounds()[1] < height_before - 2.0  # it came down by the book's thickness
    assert world.tipped() == ["cup"]  # and it lies on its side
    assert abs(abs(math.remainder(cup.body.angle, math.pi)) - math.pi / 2) < 0.3


def test_the_verified_path_refuses_the_same_move_and_nothing_changes() -> None:
    world = tabletop(cup_on_book)
    state = WorldState.from_graph(cup_on_book())
    before = world.scene.snapshot()
    executed, _, violation, _, after = execute_in_world(
        state, [MoveAction(object="book", target="shelf")], world)
    assert executed == [] and violation is not None
    assert violation.constraint == "object_not_clear" and violation.blocking == ["cup"]
    assert world.scene.snapshot() == before and after.to_graph() == state.to_graph()


def test_unverified_move_off_a_tower_knocks_the_top_block_down() -> None:
    world = tabletop(three_blocks)
    observed = world.perform_unverified(MoveAction(object="blue_block", target="green_block"))
    edges = observed.edge_keys()
    assert ("blue_block", "on", "green_block", None, None) in edges
    assert ("red_block", "on", "blue_block", None, None) not in edges


def test_unverified_valid_move_behaves_like_a_verified_one() -> None:
    world = tabletop(cup_on_book)
    observed = world.perform_unverified(MoveAction(object="cup", target="desk"))
    assert observed.edge_keys() == {("book", "on", "desk", None, None),
                                    ("cup", "on", "desk", None, None)}
    assert world.tipped() == []


def test_unverified_mode_still_refuses_what_no_arm_can_do() -> None:
    world = tabletop(cup_on_book)
    with pytest.raises(SimError) as err:
        world.perform_unverified(MoveAction(object="desk", target="shelf"))
    assert err.value.field == "object" and "fixed" in err.value.message
    with pytest.raises(SimError) as err:
        world.perform_unverified(MoveAction(object="saucer", target="desk"))
    assert err.value.field == "object" and err.value.fix


def test_unverified_align_may_overlap_pieces() -> None:
    scene = generate_scene("tangram", 1)
    world = scene.world
    ids = [n.id for n in world.nodes]
    refused = None
    for p in ids:
        for q in ids:
            if p != q:
                action = AlignAction(object=p, side=0, target=q, target_side=0)
                trial = world.copy()
                if trial.perform(action) is not None:
                    refused = action
                    break
        if refused:
            break
    assert refused is not None
    world.perform_unverified(refused)
    assert world.overlapping(refused.object)  # type: ignore[attr-defined]
