"""The Gymnasium environment: API conformance, seeding, termination and truncation.

Every registered id passes Gymnasium's own `check_env`; the same seed and actions give
identical observations, rewards and infos; the reference solver reaches reward 1 on
every task of every family; a policy of refused actions is truncated at the threshold
with the violations in `info`; the MCP path gives the same episode as the in-process one.
"""

from __future__ import annotations

import warnings
from typing import Any

import pytest

from optional import require

gym = require("gymnasium", "pip install 'verigraph-mcp[env]'")

from gymnasium.utils.env_checker import check_env  # noqa: E402

from verigraph.agent import McpTools  # noqa: E402
from verigraph.env import ENV_IDS, VeriGraphEnv  # noqa: E402
from verigraph.env.rollout import REFUSED_ACTION, RolloutJob, make_policy, run_rollout  # noqa: E402
from verigraph.errors import VeriGraphError  # noqa: E402


@pytest.mark.parametrize("env_id", sorted(ENV_IDS))
def test_check_env_passes_on_every_registered_id(env_id: str) -> None:
    env = gym.make(env_id)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # a warning from the checker fails the test
            check_env(env.unwrapped)
        assert env.unwrapped.family == ENV_IDS[env_id]
        obs, info = env.reset(seed=3)
        assert obs in env.observation_space and info["family"] == ENV_IDS[env_id]
    finally:
        env.close()


def episode(env: VeriGraphEnv, seed: int, actions: list[str]) -> list[Any]:
    obs, info = env.reset(seed=seed)
    out: list[Any] = [obs, info]
    for action in actions:
        step = env.step(action)
        out.append(step)
        if step[2] or step[3]:
            break
    return out


def test_same_seed_and_actions_give_identical_episodes() -> None:
    env = VeriGraphEnv("blocks")
    policy = make_policy("noisy", seed=4, noise=0.5)
    # Record the noisy policy's answers once, then feed the same text twice.
    obs, _ = env.reset(seed=11)
    answers = []
    while True:
        answer = policy(env, obs, {})
        answers.append(answer)
        obs, _, terminated, truncated, _ = env.step(answer)
        if terminated or truncated:
            break
    first, second = episode(env, 11, answers), episode(env, 11, answers)
    assert first == second
    assert len(first) >= 3
    other = VeriGraphEnv("blocks")
    assert episode(other, 11, answers) == first  # a fresh environment too
    assert env.reset(seed=12)[0] != first[0] or env.reset(seed=13)[0] != first[0]
    env.close()
    other.close()


def test_reset_picks_tasks_by_id_index_or_record_and_refuses_unknown_ones() -> None:
    env = VeriGraphEnv("tangram")
    task = env.tasks[2]
    by_id = env.reset(options={"task": task.task_id})
    by_index = env.reset(options={"task": 2})
    by_record = env.reset(options={"task": task})
    assert by_id == by_index == by_record and by_id[1]["task_id"] == task.task_id
    with pytest.raises(VeriGraphError) as err:
        env.reset(options={"task": "stacking/0/999"})
    assert err.value.field == "options.task" and "task id" in (err.value.fix or "")
    with pytest.raises(VeriGraphError):
        env.reset(options={"task": len(env.tasks)})
    env.close()


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tangram", "behavior"])
def test_the_reference_solver_reaches_reward_one_on_every_task(family: str) -> None:
    for split in ("train", "test"):
        env = VeriGraphEnv(family, split=split)
        policy = make_policy("oracle")
        for task in env.tasks:
            result = run_rollout(env, policy, RolloutJob(task_id=task.task_id))
            assert result.success and result.episode_return == 1.0, task.task_id
            assert result.stop_reason in ("goal_reached", "end_token")
            assert result.moves == task.optimal_length  # the solver's plans are optimal
        env.close()


def test_refused_actions_are_truncated_at_the_threshold_with_the_violations() -> None:
    env = VeriGraphEnv("kitchen", threshold=4)
    env.reset(seed=0)
    infos = []
    for _ in range(4):
        obs, reward, terminated, truncated, info = env.step(REFUSED_ACTION)
        infos.append(info)
        assert reward == 0.0 and not terminated
    assert truncated and not any(i["success"] for i in infos[:-1])
    assert [i["tau"] for i in infos] == [1, 2, 3, 4]
    assert all(i["violation"]["constraint"] == "unknown_object" for i in infos)
    assert infos[-1]["stop_reason"] == "threshold" and infos[-1]["success"] is False
    assert "[unknown_object]" in obs  # the feedback is in the observation text
    with pytest.raises(VeriGraphError) as err:
        env.step("done")
    assert "reset()" in (err.value.fix or "")
    env.close()


def test_malformed_answers_and_premature_done_count_and_the_step_limit_truncates() -> None:
    env = VeriGraphEnv("blocks", k=1, threshold=10, max_steps=3)
    long_task = next(t for t in env.tasks if t.optimal_length >= 3)
    env.reset(options={"task": long_task.task_id})
    obs, _, _, truncated, info = env.step("I would move the red block, I think")
    assert info["verdict"] == "malformed" and info["tau"] == 1 and not truncated
    assert "[malformed_action]" in obs and info["parsed"] == []
    obs, _, terminated, truncated, info = env.step("done")
    assert info["verdict"] == "premature_done" and info["tau"] == 2
    assert not (terminated or truncated) and "[premature_done]" in obs
    obs, reward, terminated, truncated, info = env.step(make_policy("oracle")(env, obs, info))
    assert info["verdict"] == "clean" and info["tau"] == 0 and len(info["executed"]) == 1
    assert truncated and not terminated and reward == 0.0
    assert info["stop_reason"] == "step_limit" and info["success"] is False
    env.close()


def test_at_most_k_actions_are_sent_and_the_rest_reported_dropped() -> None:
    env = VeriGraphEnv("blocks", k=1)
    obs, info = env.reset(seed=0)
    plan = make_policy("oracle")
    # The oracle answers one action at k=1; ask it at k=3 through a second env.
    wide = VeriGraphEnv("blocks", k=3)
    wide.reset(seed=0)
    answer = plan(wide, obs, info)
    assert len(answer.splitlines()) >= 2
    _, _, _, _, info = env.step(answer)
    assert len(info["executed"]) == 1 and info["dropped"] == answer.splitlines()[1:]
    env.close()
    wide.close()


def test_the_mcp_path_gives_the_same_episode_as_in_process() -> None:
    task = VeriGraphEnv("blocks").tasks[0]
    answers = ["move(no_such_object, on, table)", "not an action"]
    local = VeriGraphEnv(tasks=[task])
    obs, _ = local.reset(options={"task": 0})
    oracle = make_policy("oracle")
    expected = episode(local, 0, answers)
    # continue with the oracle to the end, recording its answers
    while not local.over:
        answer = oracle(local, local.observation, {})
        answers.append(answer)
        local.step(answer)
    expected = episode(local, 0, answers)
    tools = McpTools.stdio()
    try:
        remote = VeriGraphEnv(tasks=[task], tools=tools)
        assert episode(remote, 0, answers) == expected
        assert expected[-1][1] == 1.0 and expected[-1][2] is True
        remote.close()
    finally:
        tools.close()
    local.close()
