"""Episodes backed by the sim2d simulator: load with simulate, execute, render, generate."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from mcp_helpers import png_b64

from verigraph.errors import VeriGraphError
from verigraph.tools import Toolbox


def picture(box: Toolbox, eid: str, view: str = "current") -> np.ndarray:
    png = box.call("render_scene", {"episode_id": eid, "view": view, "width": 320,
                                    "height": 240}).png
    image = cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_COLOR)
    assert image is not None and image.shape == (240, 320, 3)
    return image


def test_simulated_episode_executes_in_the_world_and_renders_it() -> None:
    box = Toolbox()
    sim = box.call("load_scene", {"scene_id": "cup_on_book", "simulate": True})
    plain = box.call("load_scene", {"scene_id": "cup_on_book"})
    assert sim.simulated and not plain.simulated
    before = picture(box, sim.episode_id)
    assert not np.array_equal(before, picture(box, plain.episode_id))  # render, not drawing
    out = box.call("execute_actions", {"episode_id": sim.episode_id,
                                       "actions": ["move(cup, desk)", "move(book, shelf)"]})
    assert out.ok and out.goal_satisfied
    assert not np.array_equal(before, picture(box, sim.episode_id))
    refused = box.call("execute_actions", {"episode_id": sim.episode_id,
                                           "actions": ["move(shelf, desk)"]})
    assert refused.violation.constraint == "not_movable"  # the validator guards the world


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware", "tangram"])
def test_generated_scene_with_goal_is_solvable_in_the_simulator(family: str) -> None:
    box = Toolbox()
    state = box.call("load_scene", {"generator": {"family": family, "seed": 3},
                                    "simulate": True})
    assert state.simulated and state.goal is not None
    assert state.source == f"generator:{family}/seed=3"
    plan = box.call("solve", {"episode_id": state.episode_id})
    assert plan.reachable and plan.verified
    for start in range(0, plan.length, state.k):
        out = box.call("execute_actions", {"episode_id": state.episode_id,
                                           "actions": plan.plan[start:start + state.k]})
        assert out.ok, out.summary()
    assert box.call("end_episode", {"episode_id": state.episode_id}).success
    goal = box.call("load_scene", {"generator": {"family": family, "seed": 3},
                                   "simulate": True}).episode_id
    assert picture(box, goal, "goal").std() > 5  # a real picture of the goal state


def test_generator_errors_name_the_field() -> None:
    with pytest.raises(VeriGraphError) as err:
        Toolbox().call("load_scene", {"generator": {"family": "garden"}})
    assert err.value.field == "family" and "tangram" in (err.value.fix or "")


TANGRAM_START = [  # (contacts, valid): one rule of a valid start for every executor
    ([("large_triangle_2", 1, "medium_triangle", 0)], True),  # the model's start
    ([("large_triangle_1", 1, "small_triangle_1", 1),
      ("large_triangle_1", 1, "small_triangle_2", 1)], False),  # two pieces on one side
    ([("square", 0, "small_triangle_1", 0), ("square", 1, "small_triangle_1", 1)], False),
    ([("square", 0, "small_triangle_1", 0), ("square", 2, "small_triangle_2", 0),
      ("small_triangle_1", 1, "small_triangle_2", 1)], False),
]


@pytest.mark.fast
@pytest.mark.parametrize("contacts,valid", TANGRAM_START)
def test_graph_and_sim2d_accept_and_refuse_the_same_tangram_starts(
        contacts: list[tuple[str, int, str, int]], valid: bool) -> None:
    """The graph executor lays a tangram start out as sim2d does (the one rule: pieces
    as align lays them, exactly the listed contacts, no overlap), so both answer alike,
    and a refusal names the piece, the contact tried and what went wrong."""
    pieces = ["large_triangle_1", "large_triangle_2", "medium_triangle", "parallelogram",
              "small_triangle_1", "small_triangle_2", "square"]
    graph = {"nodes": [{"id": p, "label": p} for p in pieces], "dictionary": "tangram",
             "edges": [{"source": a, "relation": "touches", "target": b, "source_side": sa,
                        "target_side": sb} for a, sa, b, sb in contacts]}
    box = Toolbox()
    answers = []
    for executor in ("graph", "sim2d"):
        try:
            box.call("load_scene", {"graph": graph, "executor": executor})
            answers.append("accepted")
        except VeriGraphError as exc:
            assert exc.field == "edges" and "cannot" in exc.message and exc.fix
            assert "laid with side" in exc.message or "not list" in exc.message
            answers.append(exc.message)
    photo = box.call("load_scene", {"image": png_b64(), "dictionary": "tangram"})
    try:  # an image episode adopting the graph follows the same rule
        box.call("submit_scene_graph", {"episode_id": photo.episode_id, "graph": graph})
        answers.append("accepted")
    except VeriGraphError as exc:
        answers.append(exc.message)
    assert answers[0] == answers[1] == answers[2]
    assert (answers[0] == "accepted") == valid, answers[0]
