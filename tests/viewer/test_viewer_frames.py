"""Simulator pictures per step: replayed on a rebuilt copy of the world as loaded, one per
step, the blockers of a refused step framed (tabletop and tangram), the live episode
untouched."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
from test_viewer_views import count, picture

from verigraph.actions.feedback import Violation
from verigraph.graph.builtin_scenes import cup_on_book
from verigraph.sim2d import generate_scene, world_for_graph
from verigraph.sim2d.persist import world_from_state, world_state
from verigraph.sim2d.render import tangram_boxes
from verigraph.tools import Toolbox
from verigraph.tools.context import ToolConfig
from verigraph.tools.drawing import OUTLINE_COLOR
from verigraph.tools.records import from_record, to_record
from verigraph.viewer import ViewInput, frames, view

pytestmark = pytest.mark.fast

MOVES = ["move(cup, on, desk)", "move(book, on, shelf)", "move(cup, on, book)"]


def simulated_cup_on_book(box: Toolbox, moves: list[str]) -> str:
    eid: str = box.call("load_scene", {"scene_id": "cup_on_book",  # type: ignore[union-attr]
                                       "simulate": True}).episode_id
    for move in moves:
        assert box.call("execute_actions", {"episode_id": eid,  # type: ignore[union-attr]
                                            "actions": [move]}).ok
    return eid


def test_each_executed_step_has_its_own_simulator_picture_and_the_episode_is_untouched(
) -> None:
    box = Toolbox()
    eid = simulated_cup_on_book(box, MOVES)
    with box.context.store.use(eid) as episode:
        live_world = world_state(episode.world)  # type: ignore[arg-type]
        live = (copy.deepcopy(episode.executed), copy.deepcopy(episode.trace),
                episode.require_state().to_graph(), episode.changes)
        live_picture = episode.world.render(width=frames.FRAME_WIDTH)  # type: ignore[union-attr]

    result = view(box.context, ViewInput(episode_id=eid))

    assert [s.text for s in result.steps] == MOVES and all(s.ok for s in result.steps)
    pictures = [s.scene_render for s in result.steps]
    assert all(p is not None for p in pictures)
    assert result.initial_scene_render is not None
    assert len({result.initial_scene_render, *pictures}) == len(MOVES) + 1  # all different
    # The first picture is the scene as loaded (an independently built world), the last
    # is the live world now.
    loaded = world_for_graph(cup_on_book()).render(width=frames.FRAME_WIDTH)
    assert np.array_equal(picture(result.initial_scene_render), loaded)
    assert np.array_equal(picture(pictures[-1] or ""), live_picture)
    assert all(count(picture(p or ""), OUTLINE_COLOR) == 0 for p in pictures)
    with box.context.store.use(eid) as episode:
        assert world_state(episode.world) == live_world  # type: ignore[arg-type]
        assert (episode.executed, episode.trace, episode.require_state().to_graph(),
                episode.changes) == live


def test_a_refused_step_shows_the_unchanged_scene_with_the_blocker_framed() -> None:
    box = Toolbox()
    eid = simulated_cup_on_book(box, MOVES[:1])
    box.call("execute_actions", {"episode_id": eid, "actions": ["move(desk, on, shelf)",
                                                                "move(cup, on, book)"]})
    box.call("execute_actions", {"episode_id": eid, "actions": ["move(cup, on, book)",
                                                                "move(book, on, shelf)"]})
    result = view(box.context, ViewInput(episode_id=eid))
    assert [s.ok for s in result.steps] == [True, True, False]
    before, refused = (picture(s.scene_render or "") for s in result.steps[1:])
    assert result.steps[2].outlined == ["cup"]
    assert count(before, OUTLINE_COLOR) == 0 and count(refused, OUTLINE_COLOR) > 200
    changed = (refused != before).any(axis=2)
    # Nothing moved: the pictures differ only by the thin frame around the cup.
    assert 200 < changed.sum() < 0.03 * changed.size
    ys, xs = np.nonzero(changed)
    assert (ys.max() - ys.min()) * (xs.max() - xs.min()) < 0.2 * changed.size


def test_tangram_pieces_get_boxes_around_their_polygons() -> None:
    world = generate_scene("tangram", 3).world
    image = world.render()
    boxes = tangram_boxes(world)
    assert set(boxes) == {n.id for n in world.nodes}
    drawn = (image != image[0, 0]).any(axis=2)  # everything but the background
    covered = np.zeros_like(drawn)
    for x0, y0, x1, y1 in boxes.values():
        assert 0 <= x0 < x1 < image.shape[1] and 0 <= y0 < y1 < image.shape[0]
        covered[max(0, y0 - 2):y1 + 3, max(0, x0 - 2):x1 + 3] = True
    assert drawn.sum() > 1000 and not (drawn & ~covered).any()
    one = next(iter(boxes.values()))
    assert (one[2] - one[0]) * (one[3] - one[1]) < drawn.size / 4  # a piece, not the scene


def test_a_tangram_overlap_frames_the_piece_in_the_way() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"generator": {"family": "tangram",  # type: ignore[union-attr]
                                                "seed": 3}, "executor": "sim2d"}).episode_id
    assert box.call("execute_actions", {"episode_id": eid,  # type: ignore[union-attr]
                                        "actions": ["align(parallelogram, 0, square, 1)"]}).ok
    refused = box.call("execute_actions", {"episode_id": eid,
                                           "actions": ["align(square, 2, small_triangle_1, 0)"]})
    assert refused.violation.constraint == "overlap"  # type: ignore[union-attr]
    result = view(box.context, ViewInput(episode_id=eid))
    first, last = result.steps
    assert last.outlined == ["large_triangle_2"]
    assert count(picture(first.scene_render or ""), OUTLINE_COLOR) == 0
    assert count(picture(last.scene_render or ""), OUTLINE_COLOR) > 200
    assert count(picture(result.scene_render or ""), OUTLINE_COLOR) > 200  # current scene
    assert first.scene_render != result.initial_scene_render


def test_pictures_stop_at_the_cap(monkeypatch: pytest.MonkeyPatch) -> None:
    box = Toolbox()
    eid = simulated_cup_on_book(box, MOVES)
    monkeypatch.setattr(frames, "MAX_SIMULATED_STEPS", 2)
    result = view(box.context, ViewInput(episode_id=eid))
    assert [s.scene_render is not None for s in result.steps] == [True, True, False]
    assert all(s.render is not None for s in result.steps)  # drawings are kept


def test_graph_episodes_have_no_simulator_pictures() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"scene_id": "cup_on_book"}).episode_id  # type: ignore[union-attr]
    box.call("execute_actions", {"episode_id": eid, "actions": MOVES[:1]})
    result = view(box.context, ViewInput(episode_id=eid))
    assert result.initial_scene_render is None and result.steps[0].scene_render is None


def test_the_world_as_loaded_is_kept_in_the_stored_record() -> None:
    box = Toolbox()
    eid = simulated_cup_on_book(box, MOVES[:1])
    with box.context.store.use(eid) as episode:
        record = to_record(episode, version=1, created_at=0.0, updated_at=0.0)
        loaded = episode.initial_world
    assert loaded is not None and len(str(loaded)) < 16_000  # a few KiB
    restored = from_record(type(record).model_validate_json(record.model_dump_json()))
    assert restored.initial_world == loaded
    assert np.array_equal(world_from_state(loaded).render(),
                          world_for_graph(cup_on_book()).render())


def test_another_host_on_a_durable_store_pictures_the_same_steps(tmp_path: Path) -> None:
    url = f"sqlite:///{tmp_path / 'episodes.db'}"
    here, there = (Toolbox(config=ToolConfig(store=url)) for _ in range(2))
    eid = simulated_cup_on_book(here, MOVES)
    local = view(here.context, ViewInput(episode_id=eid))
    remote = view(there.context, ViewInput(episode_id=eid))
    assert remote.initial_scene_render == local.initial_scene_render
    assert [s.scene_render for s in remote.steps] == [s.scene_render for s in local.steps]
    with there.context.store.use(eid) as episode:  # rebuilt from the record
        now = episode.world.render(width=frames.FRAME_WIDTH)  # type: ignore[union-attr]
    assert np.array_equal(picture(remote.steps[-1].scene_render or ""), now)


def test_a_step_the_world_did_not_carry_out_as_predicted_shows_the_world_after_it() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"scene_id": "cup_on_book",  # type: ignore[union-attr]
                                  "simulate": True}).episode_id
    assert box.call("execute_actions", {"episode_id": eid,  # type: ignore[union-attr]
                                        "actions": MOVES[:2]}).ok
    failed = Violation(step=2, action={"action": "move", "object": "book", "relation": "on",
                                       "target": "shelf"}, constraint="execution_failed",
                       message="the world did not end as predicted", blocking=["book"],
                       suggestion="re-plan from the observed graph")
    with box.context.store.use(eid) as episode:  # as execute_in_world records a mismatch
        episode.trace[-1] = episode.trace[-1].model_copy(update={"violation": failed})
        episode.last_violation = failed
    result = view(box.context, ViewInput(episode_id=eid))
    assert [(s.text, s.ok) for s in result.steps] == [(MOVES[0], True), (MOVES[1], False)]
    assert result.steps[1].violation == failed and result.steps[1].outlined == ["book"]
    moved, framed = (picture(s.scene_render or "") for s in result.steps)
    assert count(framed, OUTLINE_COLOR) > 200
    assert (moved != framed).any(axis=2).sum() > 0.01 * moved.shape[0] * moved.shape[1]
