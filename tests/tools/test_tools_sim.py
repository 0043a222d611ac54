"""Episodes backed by the sim2d simulator: load with simulate, execute, render, generate."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

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
