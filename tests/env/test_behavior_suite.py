"""verigraph/behavior-v0: BEHAVIOR-1K activities as tasks, one per activity, bundled and
hash-checked, split by activity; the environment needs no `bddl` to serve them. (That
the oracle solves every task of both splits: tests/env/test_env_gym.py.)"""

from __future__ import annotations

from collections import Counter

from optional import require

gym = require("gymnasium", "pip install 'verigraph-mcp[env]'")

from verigraph.env import check_disjoint, split_tasks  # noqa: E402
from verigraph.env.dataset import suite_tasks  # noqa: E402
from verigraph.graph.formula import parse_formula  # noqa: E402


def test_one_task_per_activity_split_by_activity() -> None:
    tasks = suite_tasks("behavior")
    activities = [t.task_id.rsplit("/", 1)[-1] for t in tasks]
    assert len(tasks) >= 100 and len(set(activities)) == len(tasks)
    assert all(t.family == "behavior" and t.group == "behavior" for t in tasks)
    assert set(Counter(t.kind for t in tasks)) == {"spatial", "household", "thermal"}
    for task in tasks:
        assert task.load["graph"]["dictionary"] == "behavior"
        assert task.set_goal is not None
        parse_formula(task.set_goal["formula"])
        assert task.optimal_length >= 1
    train, test = split_tasks(tasks, "train"), split_tasks(tasks, "test")
    check_disjoint(train, test)
    assert train and test and len(train) + len(test) == len(tasks)


def test_the_environment_serves_a_behavior_task_with_its_formula() -> None:
    env = gym.make("verigraph/behavior-v0", split="test")
    try:
        obs, info = env.reset(seed=0)
        assert info["family"] == "behavior"
        assert "(" in obs  # the goal formula is shown
    finally:
        env.close()
