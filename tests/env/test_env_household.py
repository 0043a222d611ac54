"""verigraph/household-v0: a household task through the Gymnasium interface."""

from __future__ import annotations

import gymnasium as gym
import pytest

import verigraph.env  # noqa: F401  (registers the ids)
from verigraph.env.dataset import suite_tasks
from verigraph.env.registration import ENV_IDS
from verigraph.graph import SceneGraph
from verigraph.solver import solve

pytestmark = pytest.mark.fast


def test_the_household_id_serves_its_suite_and_a_solved_plan_succeeds() -> None:
    assert ENV_IDS["verigraph/household-v0"] == "household"
    tasks = suite_tasks("household")
    assert len(tasks) >= 30 and all(t.group == "household" for t in tasks)
    env = gym.make("verigraph/household-v0", k=10)
    obs, info = env.reset(seed=3)
    assert "open(object)" in obs and "container_closed" in obs and "rooms: kitchen:" in obs
    task = next(t for t in tasks if t.task_id == info["task_id"])
    assert task.goal is not None
    plan = solve(_graph(task.load["graph"]), task.goal).plan
    assert len(plan) == task.optimal_length
    answer = "\n".join([*(a.text() for a in plan), "done"])
    _, reward, terminated, _, info = env.step(answer)
    assert terminated and info["success"] is True and reward > 0


def _graph(data: dict[str, object]) -> SceneGraph:
    return SceneGraph.model_validate(data)
