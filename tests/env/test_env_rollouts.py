"""Rollouts serially and on a local Ray, trajectories as JSONL, and their replay."""

from __future__ import annotations

import io
import json
import os
import sys
from pathlib import Path
from typing import Any

import pytest

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")

from verigraph.env import VeriGraphEnv, build_tasks  # noqa: E402
from verigraph.env.rollout import (  # noqa: E402
    RolloutJob,
    RolloutResult,
    RolloutWorker,
    pass_rates,
    run_rollouts,
)
from verigraph.env.trajectory import read_lines, replay, write_lines  # noqa: E402
from verigraph.jobs.ray_runner import QUEUE_PER_SLOT  # noqa: E402


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


def test_rollouts_resume_from_their_trajectory_file(tmp_path: Path) -> None:
    tasks = build_tasks("blocks", 4)
    jobs = jobs_for([t.task_id for t in tasks[:3]])
    kwargs = {"tasks": tasks}
    path = tmp_path / "trajectories.jsonl"
    first = run_rollouts(jobs[:5], kwargs, trajectories=path)
    assert all(r.worker == os.getpid() for r in first)
    # killed while writing: the last episode's end is lost and a line is cut short
    lines = path.read_text().splitlines(keepends=True)
    path.write_text("".join(lines[:-2]) + lines[-2][:25])
    again = run_rollouts(jobs + jobs[:1], kwargs, trajectories=path)
    assert [r.job for r in again] == jobs + jobs[:1]
    # four whole episodes are read back (no worker), the cut one and the rest run now
    assert [r.worker for r in again] == [None] * 4 + [os.getpid()] * 5 + [None]
    fresh = run_rollouts(jobs, kwargs)

    def outcome(r: RolloutResult) -> dict[str, Any]:
        return r.model_dump(exclude={"worker"})

    assert [outcome(r) for r in again[:len(jobs)]] == [outcome(r) for r in fresh]
    written = read_lines(path)  # every episode exactly once, and each replays
    assert len(written) == sum(r.steps + 1 for r in fresh)
    assert sorted({line.episode for line in written}) == sorted(j.episode() for j in jobs)
    env = VeriGraphEnv(tasks=tasks)
    assert replay(written, env).ok
    edited = [line.model_copy(update={"success": not line.success}) if line.final else line
              for line in written]
    assert not replay(edited, env).ok  # an outcome edited by hand does not survive either
    env.close()


def test_noisy_rollouts_differing_only_in_noise_are_different_episodes() -> None:
    tasks = build_tasks("tangram", 2)
    jobs = [RolloutJob(task_id=tasks[0].task_id, policy="noisy", noise=n) for n in (0.0, 0.9)]
    results = run_rollouts(jobs, {"tasks": tasks, "threshold": 2})
    assert [r.job for r in results] == jobs
    assert len({r.lines[0].episode for r in results}) == 2


def test_the_progress_bar_counts_rollouts_per_suite_and_resumes(tmp_path: Path) -> None:
    tasks = build_tasks("blocks", 1)
    jobs = [RolloutJob(task_id=t.task_id, policy=p) for t in tasks for p in ("oracle", "refuse")]
    path = tmp_path / "run.jsonl"
    first, second, quiet = io.StringIO(), io.StringIO(), io.StringIO()
    run_rollouts(jobs[:2], {"tasks": tasks}, trajectories=path, progress=True, stream=first)
    run_rollouts(jobs, {"tasks": tasks}, trajectories=path, progress=True, stream=second)
    run_rollouts(jobs, {"tasks": tasks}, stream=quiet)
    suite = jobs[0].task_id.split("/")[0]
    assert "2/2 [" in first.getvalue() and f"{suite} 1/2" in first.getvalue()
    shown = second.getvalue()
    assert f"2/{len(jobs)} [" in shown  # starts from what the file already holds
    assert f"{len(jobs)}/{len(jobs)} [" in shown
    assert quiet.getvalue() == ""  # no bar unless asked


ray = pytest.importorskip("ray", reason="the scale extra (ray) is not installed")


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


@pytest.mark.parametrize("workers", [2, 4])
def test_rollouts_run_on_the_engines_threads_as_serially(local_ray: None, workers: int
                                                         ) -> None:
    # 4 at once on 2 cores: the engine's two actors with two threads each
    tasks = build_tasks("blocks", 4)
    jobs = jobs_for([t.task_id for t in tasks])
    kwargs = {"tasks": tasks, "threshold": 3}
    serial = run_rollouts(jobs, kwargs)
    on_ray = run_rollouts(jobs + jobs[:2], kwargs, ray="local", workers=workers)
    assert [r.job for r in on_ray] == jobs + jobs[:2]  # a job listed twice is run once
    assert [r.lines for r in on_ray[:len(jobs)]] == [r.lines for r in serial]
    assert all(r.error is None for r in on_ray)


class DyingRolloutWorkerForTests(RolloutWorker):
    """A rollout worker whose process exits on one task: a stand-in for a machine that
    crashes on an episode every time it is retried (so its restarts run out)."""

    def __init__(self, env_kwargs: dict[str, Any]) -> None:
        kwargs = dict(env_kwargs)
        self.doomed = kwargs.pop("doomed")
        super().__init__(kwargs)

    def run(self, job: RolloutJob) -> RolloutResult:
        if job.task_id == self.doomed:
            os._exit(1)
        return super().run(job)


def test_a_rollout_whose_worker_dies_for_good_is_a_failed_result(local_ray: None) -> None:
    # the same engine as `bench plan` episodes (tests/agent/test_evaluation_ray.py): a lost
    # worker is a failed result, the jobs after it run on the worker left
    tasks = build_tasks("kitchen", 5)
    doomed, rest = RolloutJob(task_id=tasks[4].task_id), jobs_for([t.task_id for t in tasks[:4]])
    kwargs: dict[str, Any] = {"tasks": tasks, "threshold": 3}
    serial = {r.job: r for r in run_rollouts(rest, kwargs)}
    ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
    results = run_rollouts([doomed, *rest], {**kwargs, "doomed": doomed.task_id},
                           ray="local", workers=2, worker=DyingRolloutWorkerForTests)
    assert [r.job for r in results] == [doomed, *rest]  # one result per job, no raise
    failed = results[0]
    assert not failed.success and failed.error_kind == "worker" and failed.lines == []
    assert failed.stop_reason == "worker_error" and failed.worker is None
    assert (failed.error or "").startswith("ActorDiedError")
    lost = [r for r in results[1:] if r.error_kind == "worker"]
    assert len(lost) <= QUEUE_PER_SLOT - 1  # the dead worker took at most one more with it
    ran = [r for r in results[1:] if r.error_kind is None]
    assert len(ran) >= len(rest) - 1
    assert all(r.lines == serial[r.job].lines for r in ran)


class RaisingRolloutWorkerForTests(RolloutWorker):
    """A rollout worker whose policy raises on one task (a bug in a user's policy)."""

    def __init__(self, env_kwargs: dict[str, Any]) -> None:
        kwargs = dict(env_kwargs)
        self.broken = kwargs.pop("broken")
        super().__init__(kwargs)

    def policy(self, job: RolloutJob) -> Any:
        if job.task_id != self.broken:
            return super().policy(job)

        def broken(env: VeriGraphEnv, observation: str, info: dict[str, Any]) -> str:
            raise ZeroDivisionError("the policy divided by zero")

        return broken


def test_a_rollout_that_raises_is_the_same_failed_result_serially_and_on_ray(
        local_ray: None, tmp_path: Path) -> None:
    tasks = build_tasks("blocks", 3)
    jobs = jobs_for([t.task_id for t in tasks])
    kwargs: dict[str, Any] = {"tasks": tasks, "threshold": 3, "broken": tasks[1].task_id}
    ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
    serial = run_rollouts(jobs, kwargs, worker=RaisingRolloutWorkerForTests,
                          trajectories=tmp_path / "serial.jsonl")
    on_ray = run_rollouts(jobs, kwargs, ray="local", worker=RaisingRolloutWorkerForTests)
    for results in (serial, on_ray):
        failed = [r for r in results if r.error_kind is not None]
        assert {r.job.task_id for r in failed} == {tasks[1].task_id}
        assert len(failed) == 3  # its oracle, noisy and refusing rollouts
        assert all(r.error_kind == "internal" and r.stop_reason == "internal_error"
                   and r.error == "ZeroDivisionError: the policy divided by zero"
                   and not r.success and r.lines == [] for r in failed)
    assert [r.lines for r in on_ray] == [r.lines for r in serial]
    written = {line.episode for line in read_lines(tmp_path / "serial.jsonl")}
    assert written == {r.job.episode() for r in serial if r.error_kind is None}
