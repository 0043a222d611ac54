"""Rollouts serially and on a local Ray, trajectories as JSONL, and their replay."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path

import pytest

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")

from verigraph.env import VeriGraphEnv, build_tasks  # noqa: E402
from verigraph.env.rollout import RolloutJob, pass_rates, run_rollouts  # noqa: E402
from verigraph.env.trajectory import read_lines, replay, write_lines  # noqa: E402


def jobs_for(task_ids: list[str]) -> list[RolloutJob]:
    return [RolloutJob(task_id=t, seed=i, policy=p, policy_seed=i)
            for i, t in enumerate(task_ids) for p in ("oracle", "noisy", "refuse")]


def test_trajectories_are_written_one_line_per_step_and_replay_exactly(tmp_path: Path
                                                                       ) -> None:
    tasks = build_tasks("blocks", 4)
    kwargs = {"tasks": tasks}
    results = run_rollouts(jobs_for([t.task_id for t in tasks[:4]]), kwargs)
    path = tmp_path / "trajectories.jsonl"
    written = write_lines([line for r in results for line in r.lines], path)
    assert written == sum(r.steps + 1 for r in results)
    rows = [json.loads(text) for text in path.read_text().splitlines()]
    step = next(r for r in rows if r["kind"] == "step" and r.get("violation"))
    assert {"observation", "action", "parsed", "reward", "violation", "state_hash"} <= set(step)
    assert step["violation"]["constraint"]
    lines = read_lines(path)
    env = VeriGraphEnv(tasks=tasks)
    report = replay(lines, env)
    assert report.ok, report.mismatches
    assert report.episodes == len(results) and report.steps == written - len(results)
    # a reward edited by hand does not survive the replay
    edited = [line.model_copy(update={"reward": 1.0}) if line.kind == "step"
              and line.reward == 0.0 else line for line in lines]
    bad = replay(edited, env)
    assert not bad.ok and all("reward" in m for m in bad.mismatches)
    env.close()


def test_pass_at_one_and_pass_hat_k() -> None:
    tasks = build_tasks("tangram", 6)
    jobs = [RolloutJob(task_id=t.task_id, policy="noisy", policy_seed=s, noise=0.6)
            for t in tasks for s in range(3)]
    results = run_rollouts(jobs, {"tasks": tasks, "threshold": 2})
    rates = pass_rates(results)
    by_task: dict[str, list[bool]] = {}
    for r in results:
        by_task.setdefault(r.job.task_id, []).append(r.success)
    assert rates["pass@1"] == sum(r.success for r in results) / len(results)
    assert rates["pass^k"] == sum(all(v) for v in by_task.values()) / len(by_task)
    assert rates["pass^k"] <= rates["pass@1"]
    assert 0 < rates["pass@1"] < 1  # the noise really bites at t = 2


ray = pytest.importorskip("ray", reason="the scale extra (ray) is not installed")


@pytest.fixture(scope="module")
def local_ray() -> Iterator[None]:
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        yield
    finally:
        ray.shutdown()


def test_ray_and_serial_rollouts_are_identical(local_ray: None) -> None:
    tasks = build_tasks("kitchen", 4)
    jobs = jobs_for([t.task_id for t in tasks])
    kwargs = {"tasks": tasks, "threshold": 3}
    serial = run_rollouts(jobs, kwargs)
    ready = []
    on_ray = run_rollouts(jobs, kwargs, ray="local", on_ready=lambda: ready.append(True))
    assert ready == [True]
    assert [r.job for r in on_ray] == jobs
    assert [r.lines for r in on_ray] == [r.lines for r in serial]
    assert len({r.worker for r in on_ray}) == 2  # spread over both worker processes
    assert {r.worker for r in on_ray}.isdisjoint({r.worker for r in serial})
    assert {r.success for r in serial} == {True, False}
