"""Episodes on Ray: a pool of `EpisodeWorker` actors and one shared limiter actor.

Each actor holds the task table (put in the object store once) and runs jobs with
the same `EpisodeWorker.run` the serial path calls, so results do not depend on the
scheduler. An actor may run several episodes at once on threads (`max_concurrency`):
episodes spend most of their time waiting on a model API, not on a core. Jobs are
submitted a few at a time per slot and collected with `ray.wait` as they finish, so
a record reaches the results file the moment its episode is done.

A worker process that dies is restarted by Ray and its episodes retried (they are
idempotent: same seed, same record); an episode whose worker is lost for good is
recorded with `error_kind` "worker" and the run goes on.

`address`: "local" starts a private Ray instance with this machine's cores (and stops
it afterwards); "auto", "HOST:PORT" or "ray://HOST:10001" join a running cluster, to
which the verigraph package is shipped as a `py_modules` runtime environment (the
cluster's Python still needs verigraph's dependencies). An already initialised Ray
(a notebook, a test fixture) is used as it is.
"""

from __future__ import annotations

import logging
import math
import os
import socket
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import verigraph
from verigraph.agent.evaluation.limiter import RateLimiter
from verigraph.agent.evaluation.results import BenchRecord, blank_record
from verigraph.agent.evaluation.spec import EpisodeJob
from verigraph.agent.evaluation.tasks import Task
from verigraph.agent.evaluation.worker import EngineConfig, EpisodeWorker
from verigraph.errors import VeriGraphError
from verigraph.extras import require

QUEUE_PER_SLOT = 2  # jobs queued per concurrent slot: workers never idle, Ctrl-C stays quick
WORKER_RESTARTS = 2  # a dead worker actor is restarted and its episodes retried (idempotent)


def _ray() -> Any:
    require("scale", "ray")
    import ray

    return ray


def _check_reachable(address: str) -> None:
    """Fail fast on a HOST:PORT nobody listens on (Ray itself keeps retrying for minutes)."""
    if address == "auto" or "://" in address:
        return
    host, _, port = address.rpartition(":")
    if not host or not port.isdigit():
        raise VeriGraphError(f"not a Ray address: {address!r}", field="--ray", value=address,
                             fix="use auto, HOST:PORT or ray://HOST:10001")
    try:
        socket.create_connection((host.strip("[]"), int(port)), timeout=5).close()
    except OSError as exc:
        raise VeriGraphError(f"nothing answers at {address} ({exc})", field="--ray",
                             value=address,
                             fix="start the head with `ray start --head` and pass the "
                                 "address it prints, or use --ray auto on a cluster node"
                             ) from None


def connect(address: str) -> bool:
    """Initialise Ray for `address`; True when this call started it (and must stop it)."""
    ray = _ray()
    if ray.is_initialized():
        return False
    if address == "local":
        ray.init(num_cpus=os.cpu_count() or 1, include_dashboard=False, log_to_driver=False,
                 logging_level=logging.WARNING)
    else:
        _check_reachable(address)
        package = str(Path(verigraph.__file__).parent)
        try:
            ray.init(address=address, log_to_driver=False, logging_level=logging.WARNING,
                     runtime_env={"py_modules": [package]})
        except (ConnectionError, RuntimeError) as exc:
            raise VeriGraphError(
                f"cannot join the Ray cluster at {address}: {str(exc).splitlines()[0]}",
                field="--ray", value=address,
                fix="check the address ('auto' on a cluster node, HOST:6379 of the head, or "
                    "ray://HOST:10001, which needs ray[client]); a cluster with token "
                    "authentication needs RAY_AUTH_MODE=token and its token "
                    "(~/.ray/auth_token or RAY_AUTH_TOKEN)") from None
    return True


class ActorLimiter:
    """The `LimiterLike` side of the limiter actor, picklable into every worker."""

    def __init__(self, handle: Any) -> None:
        self.handle = handle

    def try_acquire(self, backend: str) -> float:
        return float(_ray().get(self.handle.try_acquire.remote(backend)))

    def release(self, backend: str) -> None:
        self.handle.release.remote(backend)


def _lost(job: EpisodeJob, exc: Exception) -> BenchRecord:
    record = blank_record(job, job.setting.planner)
    record.error_kind = "worker"
    record.stop_reason = "worker_error"
    record.error = f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}"[:500]
    return record


def _dispatch(ray: Any, workers: list[Any], jobs: list[EpisodeJob],
              budget: int) -> Iterator[BenchRecord]:
    """Keep `budget` jobs queued over the workers (round robin); yield as they finish."""
    queue = iter(jobs)
    in_flight: dict[Any, EpisodeJob] = {}
    turn = 0
    while True:
        while len(in_flight) < budget and (job := next(queue, None)) is not None:
            in_flight[workers[turn % len(workers)].run.remote(job)] = job
            turn += 1
        if not in_flight:
            return
        ready, _ = ray.wait(list(in_flight), num_returns=1)
        for ref in ready:
            job = in_flight.pop(ref)
            try:
                yield ray.get(ref)
            except ray.exceptions.RayError as exc:
                yield _lost(job, exc)


def run_on_ray(jobs: list[EpisodeJob], tasks: dict[str, Task], config: EngineConfig, *,
               address: str = "local", concurrency: int | None = None,
               limiter: RateLimiter | None = None,
               on_ready: Callable[[], None] | None = None) -> Iterator[BenchRecord]:
    """Yield one record per job, in the order they finish.

    `on_ready` is called once every worker actor is up (its process started and the
    task table loaded), before the first job is submitted: start-up is then separable
    from throughput.
    """
    ray = _ray()
    started = connect(address)
    actors: list[Any] = []
    try:
        cpus = max(1, int(ray.cluster_resources().get("CPU", 1)))
        slots = max(1, concurrency or cpus)
        n_actors = min(cpus, slots)
        threads = math.ceil(slots / n_actors)
        shared = None
        if limiter is not None:  # the same budgets, held by one actor for the cluster
            limiter_actor = ray.remote(RateLimiter).options(num_cpus=0).remote(
                limiter.limits, default=limiter.default)
            actors.append(limiter_actor)
            shared = ActorLimiter(limiter_actor)
        remote_worker = ray.remote(EpisodeWorker).options(
            num_cpus=1, max_concurrency=threads, max_restarts=WORKER_RESTARTS,
            max_task_retries=WORKER_RESTARTS)
        # Held until the run ends, so a restarted worker can still read it (Ray warns
        # about restartable actors with object-store arguments; this is the remedy).
        tasks_ref = ray.put(tasks)
        workers = [remote_worker.remote(tasks_ref, config, shared) for _ in range(n_actors)]
        actors.extend(workers)
        ray.get([worker.ready.remote() for worker in workers])
        if on_ready is not None:
            on_ready()
        yield from _dispatch(ray, workers, jobs, n_actors * threads * QUEUE_PER_SLOT)
    finally:
        for actor in actors:
            ray.kill(actor)
        if started:
            ray.shutdown()
