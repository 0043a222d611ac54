"""Procedural environment ids and the Reasoning Gym-style curriculum: a family and a
level through `gymnasium.make`, seeded streams, the split cut, a level moved between
episodes, and `score_answer` computed by the verifier (never by comparing strings)."""

from __future__ import annotations

import pytest

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")

import gymnasium as gym  # noqa: E402
from gymnasium.utils.env_checker import check_env  # noqa: E402

import verigraph.env  # noqa: E402,F401
from verigraph.env.curriculum import (  # noqa: E402
    VeriGraphCurriculum,
    VeriGraphDataset,
    score_answer,
)
from verigraph.env.dataset import split_of  # noqa: E402
from verigraph.env.procedural import procedural_id  # noqa: E402
from verigraph.env.rollout import RolloutJob, run_rollouts  # noqa: E402
from verigraph.errors import VeriGraphError  # noqa: E402
from verigraph.tasks.procedural import generate_tasks, max_level  # noqa: E402

FAMILIES = ("blocks", "kitchen", "tangram")


@pytest.mark.parametrize("family", FAMILIES)
def test_make_with_a_level_passes_check_env(family: str) -> None:
    env = gym.make(procedural_id(family), level=2)
    check_env(env.unwrapped)
    _, info = env.reset(seed=11)
    assert info["level"] == 2 and info["kind"] == "level_2" and info["family"] == family
    assert env.reset(seed=11)[1]["task_id"] == info["task_id"]
    env.close()


def test_a_stream_is_seeded_stays_in_its_split_and_moves_with_the_level() -> None:
    env = gym.make(procedural_id("blocks"), level=1).unwrapped
    seen = set()
    for seed in range(12):
        env.reset(seed=seed)
        assert env.task is not None and split_of(env.task.content_hash) == "train"
        seen.add(env.task.content_hash)
    assert len(seen) > 6  # fresh tasks, not a small pool
    short = env.task.optimal_length
    env.set_level(5)
    _, info = env.reset(seed=0)
    assert info["level"] == 5 and info["optimal_length"] > short
    test_env = gym.make(procedural_id("blocks"), level=1, split="test").unwrapped
    test_env.reset(seed=0)
    assert test_env.task is not None and split_of(test_env.task.content_hash) == "test"


def test_a_sized_pool_is_addressed_by_id() -> None:
    env = gym.make(procedural_id("tangram"), level=3, size=6).unwrapped
    ids = [t.task_id for t in env.tasks]
    assert ids and all(i.startswith("tangram-L3/0/") for i in ids)
    _, info = env.reset(options={"task": ids[-1]})
    assert info["task_id"] == ids[-1]


def test_bad_arguments_are_structured_errors() -> None:
    with pytest.raises(VeriGraphError) as err:
        gym.make(procedural_id("kitchen"), level=0)
    assert err.value.field == "level"
    with pytest.raises(VeriGraphError) as err:
        gym.make(procedural_id("blocks"), tasks=[])
    assert err.value.field == "tasks"


@pytest.mark.parametrize("family", FAMILIES)
def test_the_oracle_solves_every_level(family: str) -> None:
    for level in range(1, max_level(family) + 1):
        tasks = generate_tasks(family, level, 1, seed=2)
        [result] = run_rollouts([RolloutJob(task_id=tasks[0].task_id)], {"tasks": tasks})
        assert result.success, (family, level, result.stop_reason)
        assert result.moves == tasks[0].optimal_length


def test_curriculum_attributes_move_and_configure() -> None:
    curriculum = VeriGraphCurriculum("blocks")
    assert curriculum.generate_configuration().level == 1
    assert curriculum.increment_attr_level("level") and curriculum.get_attr_value("level") == 2
    assert curriculum.get_attr_level("distractors") == 1
    config = curriculum.generate_configuration(size=4, seed=3)
    assert (config.level, config.size, config.seed, config.knobs) == (2, 4, 3, None)
    assert curriculum.increment_attr_level("constraints")
    knobs = curriculum.generate_configuration().knobs
    assert knobs is not None and knobs.constraints == 1 and knobs.objects == 4
    curriculum.set_attr_level("level", max_level("blocks") - 1)
    assert not curriculum.increment_attr_level("level")
    curriculum.set_attr_level("level", 0)
    assert not curriculum.decrement_attr_level("level")
    with pytest.raises(VeriGraphError):
        curriculum.set_attr_level("objects", 40)
    with pytest.raises(VeriGraphError):
        curriculum.get_attr_level("colour")


@pytest.mark.parametrize("family", FAMILIES)
def test_dataset_entries_are_scored_by_the_verifier(family: str) -> None:
    curriculum = VeriGraphCurriculum(family)
    curriculum.set_attr_level("level", 2)
    data = VeriGraphDataset(curriculum.generate_configuration(size=2, seed=1))
    assert len(data) == 2 and len(list(data)) == 2
    entry = data[0]
    assert set(entry) == {"question", "answer", "metadata"}
    assert entry["metadata"]["level"] == 3 and "## Goal" in entry["question"]
    lines = entry["answer"].splitlines()
    assert len(lines) == entry["metadata"]["optimal_length"]
    assert data.score_answer(entry["answer"], entry) == 1.0
    # the same plan in another form the parser reads: still the verifier's 1.0
    fenced = "Here is my plan:\n```\n" + "\n".join(lines) + "\ndone\n```"
    assert score_answer(fenced, entry) == 1.0
    first = score_answer(lines[0], entry)
    assert 0.0 < first < 0.5 + 1e-9  # a prefix closes part of the distance: partial credit
    assert score_answer("", entry) == 0.0
    assert score_answer("I cannot do that", entry) == 0.0
    assert score_answer("move(no_such_thing, on, table)", entry) == 0.0
    # a plan that reaches the goal by another route scores the same
    assert score_answer("\n".join([*lines, "done"]), entry) == 1.0
