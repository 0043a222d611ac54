"""The evaluation engine on a local Ray: same records as the serial path, and the
cluster-wide limiter keeps a backend under its request rate (measured at the server)."""

from __future__ import annotations

import json
import os
import sys
import time
from collections import deque
from typing import Any

import pytest
from planning_doubles import RecordedResponse as R
from planning_doubles import RecordedResponseServerForTests, chat_completion

from verigraph.agent.evaluation import Setting
from verigraph.agent.evaluation.engine import RunOptions, run_jobs
from verigraph.agent.evaluation.guard import RetryPolicy
from verigraph.agent.evaluation.results import BenchRecord
from verigraph.agent.evaluation.spec import EpisodeJob, jobs_for, task_index
from verigraph.agent.evaluation.worker import EngineConfig, EpisodeWorker, lost_record
from verigraph.jobs.dispatch import run_on_workers
from verigraph.jobs.limiter import BackendLimits
from verigraph.jobs.ray_runner import QUEUE_PER_SLOT
from verigraph.jobs.workers import WorkerFactory
from verigraph.planning.factory import PlannerOptions
from verigraph.tasks import build_groups
from verigraph.tasks.task import Task

ray = pytest.importorskip("ray", reason="the scale extra (ray) is not installed")
pytest.importorskip("verigraph.sim2d.generator", reason="sim2d not installed")


def test_ray_and_serial_give_identical_episodes(local_ray: None) -> None:
    groups = build_groups(("stacking", "language", "tangram"), 4, 0, ground_truth=True)
    settings = [Setting(planner="noisy", noise=0.5), Setting(planner="noisy", mode="direct"),
                Setting(planner="oracle", k=2)]
    jobs = [j for s in settings for j in jobs_for(s, groups, "suite")]
    tasks = task_index(groups)
    serial = run_jobs(jobs, tasks, RunOptions(progress=False))
    # 4 episodes at once on 2 cores: two actors with two threads each.
    on_ray = run_jobs(jobs, tasks, RunOptions(ray="local", concurrency=4, progress=False))
    assert [r.key for r in on_ray] == [j.key() for j in jobs]
    assert [r.outcome() for r in on_ray] == [r.outcome() for r in serial]
    assert len({r.worker for r in on_ray}) >= 2  # really spread over worker processes
    assert {r.worker for r in serial} != {r.worker for r in on_ray}
    assert 0 < sum(r.success for r in on_ray) < len(jobs)  # the noise really bites


class TimedQueue(deque[Any]):
    """The recorded responses, noting when each request reached the server."""

    def __init__(self, items: list[Any]) -> None:
        super().__init__(items)
        self.times: list[float] = []

    def popleft(self) -> Any:
        self.times.append(time.monotonic())
        return super().popleft()


def test_limiter_actor_keeps_the_backend_under_its_rate(local_ray: None) -> None:
    groups = build_groups(("stacking",), 16, 0, ground_truth=True)
    done = chat_completion(json.dumps({"actions": [{"action": "done"}]}))
    limit, window = 4, 1.0
    with RecordedResponseServerForTests() as server:
        server.responses = TimedQueue([R(done, delay_s=0.05)] * 16)
        options = RunOptions(
            ray="local", concurrency=8, progress=False,
            limits=BackendLimits(requests=limit, window_s=window, concurrency=3),
            engine=EngineConfig(planner_options=PlannerOptions(
                base_url=f"{server.url}/v1", model="recorded", api_key="sk-test"),
                retry=RetryPolicy(retries=0)))
        jobs = jobs_for(Setting(planner="openai", mode="direct"), groups, "suite")
        records = run_jobs(jobs, task_index(groups), options)
        times = sorted(server.responses.times)
    assert len(times) == 16 and all(r.error is None for r in records)
    assert all(r.stop_reason == "single_shot" and r.requests == 1 for r in records)
    # At most `limit` arrivals in any window (less a margin for network jitter) ...
    margin = 0.15
    for i, start in enumerate(times):
        in_window = [t for t in times[i:] if t < start + window - margin]
        assert len(in_window) <= limit, (i, [round(t - times[0], 3) for t in times])
    # ... and the limiter did bind: 16 requests need at least 3 further windows.
    assert times[limit] - times[0] >= window - margin
    assert times[-1] - times[0] >= 3 * window - margin


def test_a_killed_worker_is_restarted_and_no_episode_is_lost(local_ray: None) -> None:
    import os
    import signal

    from verigraph.agent.evaluation.engine import execute

    groups = build_groups(("stacking",), 8, 0, ground_truth=True)
    jobs = jobs_for(Setting(planner="noisy", noise=0.5), groups, "suite")
    tasks = task_index(groups)
    serial = {r.key: r.outcome() for r in run_jobs(jobs, tasks, RunOptions(progress=False))}
    options = RunOptions(ray="local", concurrency=2, progress=False,
                         engine=EngineConfig(latency_s=0.2))
    records = []
    for record in execute(jobs, tasks, options):
        if not records:  # the first episode is done: kill the process that ran it
            os.kill(int((record.worker or "").rsplit(":", 1)[1]), signal.SIGKILL)
        records.append(record)
    assert sorted(r.key for r in records) == sorted(serial)
    assert all(r.error is None for r in records)
    assert {r.key: r.outcome() for r in records} == serial
    assert len({r.worker for r in records}) >= 3  # the restarted actor is a new process


class DyingEpisodeWorkerForTests(EpisodeWorker):
    """A worker whose process exits on one task: a stand-in for a machine that crashes
    on an episode every time it is retried (so its restarts run out)."""

    def __init__(self, tasks: dict[str, Task], config: EngineConfig, doomed: str) -> None:
        super().__init__(tasks, config)
        self.doomed = doomed

    def run(self, job: EpisodeJob) -> BenchRecord:
        if job.task_id == self.doomed:
            os._exit(1)
        return super().run(job)


def test_an_episode_whose_worker_dies_for_good_is_a_failed_record(local_ray: None) -> None:
    groups = build_groups(("stacking",), 8, 0, ground_truth=True)
    jobs = jobs_for(Setting(planner="noisy", noise=0.5), groups, "suite")
    tasks = task_index(groups)
    serial = {r.key: r.outcome() for r in run_jobs(jobs, tasks, RunOptions(progress=False))}
    # the worker class travels by value: Ray's workers need not import this test module
    ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
    factory = WorkerFactory(DyingEpisodeWorkerForTests,
                            (tasks, EngineConfig(), jobs[0].task_id), lost=lost_record)
    records = list(run_on_workers(factory, jobs, ray="local", concurrency=2))
    assert sorted(r.key for r in records) == sorted(serial)  # one record per job, no raise
    doomed = next(r for r in records if r.key == jobs[0].key())
    assert not doomed.success and doomed.error_kind == "worker"
    assert doomed.stop_reason == "worker_error"
    assert (doomed.error or "").startswith("ActorDiedError")
    lost = [r for r in records if r.error_kind == "worker" and r is not doomed]
    # the dead worker took at most its other queued episode with it; the rest ran on
    # the surviving worker, exactly as serially
    assert len(lost) <= QUEUE_PER_SLOT - 1
    ran = [r for r in records if r.error_kind != "worker"]
    assert len(ran) >= len(jobs) - QUEUE_PER_SLOT
    assert all(r.outcome() == serial[r.key] for r in ran)
