"""Jobs on Ray: a pool of worker actors and one shared limiter actor.

The actors are built by a `WorkerFactory` (`EpisodeWorker` for `bench plan`,
`RolloutWorker` for environment rollouts): each holds the factory's arguments (the
task table, put in the object store once) and runs jobs with the same `run` the serial
path calls, so results do not depend on the scheduler. An actor may run several jobs at
once on threads (`max_concurrency`): episodes spend most of their time waiting on a
model API, not on a core. Jobs are submitted a few at a time per slot and collected
with `ray.wait` as they finish, so a result reaches the results file the moment its
job is done.

A worker process that dies is restarted by Ray and its jobs retried (they are
idempotent: same seed, same result); a job whose worker is lost for good gets the
factory's `lost` result (for an episode, `error_kind` "worker") and the run goes on on
the remaining workers.

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
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

import verigraph
from verigraph.errors import VeriGraphError
from verigraph.extras import require
from verigraph.jobs.limiter import RateLimiter
from verigraph.jobs.workers import JobT, ResultT, WorkerFactory

# Jobs queued per concurrent slot: workers never idle, Ctrl-C stays quick, and a worker
# that dies for good takes at most this many jobs per thread with it.
QUEUE_PER_SLOT = 2
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


def _error_text(exc: Exception) -> str:
    first = str(exc).splitlines()[0] if str(exc) else ""
    return f"{type(exc).__name__}: {first}"[:500]


def _dispatch(ray: Any, workers: list[Any], jobs: Sequence[JobT], per_worker: int,
              lost: Callable[[JobT, str], ResultT]) -> Iterator[ResultT]:
    """Keep up to `per_worker` jobs queued on each live worker; yield as they finish.

    A new job goes to the live worker with the fewest jobs in flight (ties in round robin
    order), so a worker that is being restarted holds no more than its share. A worker
    whose actor died for good (its restarts used up) leaves the rotation and the jobs
    after it go to the others; its jobs in flight come back as `lost` results, and when
    no worker is left every job still waiting does too.
    """
    queue = iter(jobs)
    load = [0] * len(workers)
    live = list(range(len(workers)))
    in_flight: dict[Any, tuple[JobT, int]] = {}
    turn = 0
    exhausted = False
    while True:
        while not exhausted and (free := [i for i in live if load[i] < per_worker]):
            job = next(queue, None)
            if job is None:
                exhausted = True
                break
            index = min(free, key=lambda i: (load[i], (i - turn) % len(workers)))
            in_flight[workers[index].run.remote(job)] = (job, index)
            load[index] += 1
            turn = index + 1
        if not in_flight:
            break
        ready, _ = ray.wait(list(in_flight), num_returns=1)
        for ref in ready:
            job, index = in_flight.pop(ref)
            load[index] -= 1
            try:
                result = ray.get(ref)
            except ray.exceptions.RayError as exc:
                if isinstance(exc, ray.exceptions.ActorDiedError) and index in live:
                    live.remove(index)
                result = lost(job, _error_text(exc))
            yield result
    for job in queue:
        yield lost(job, "ActorDiedError: every worker was lost before this job started")


def run_on_ray(factory: WorkerFactory[JobT, ResultT], jobs: Sequence[JobT], *,
               address: str = "local", concurrency: int | None = None,
               on_ready: Callable[[], None] | None = None) -> Iterator[ResultT]:
    """Yield one result per job, in the order they finish, from actors of `factory`.

    `concurrency` is how many jobs run at once (default: one per core); there are at
    most one actor per core (and per job), each running `concurrency / actors` jobs on
    threads. `on_ready` is called once every worker actor is up (its process started
    and its arguments loaded), before the first job is submitted: start-up is then
    separable from throughput.
    """
    ray = _ray()
    started = connect(address)
    actors: list[Any] = []
    try:
        cpus = max(1, int(ray.cluster_resources().get("CPU", 1)))
        slots = max(1, concurrency or cpus)
        n_actors = max(1, min(cpus, slots, len(jobs)))
        threads = math.ceil(slots / n_actors)
        extra: dict[str, Any] = {}
        if factory.limiter is not None:  # the same budgets, held by one actor for the cluster
            limiter = factory.limiter
            limiter_actor = ray.remote(RateLimiter).options(num_cpus=0).remote(
                limiter.limits, default=limiter.default)
            actors.append(limiter_actor)
            extra["limiter"] = ActorLimiter(limiter_actor)
        remote_worker = ray.remote(factory.worker).options(
            num_cpus=1, max_concurrency=threads, max_restarts=WORKER_RESTARTS,
            max_task_retries=WORKER_RESTARTS)
        # Held until the run ends, so a restarted worker can still read them (Ray warns
        # about restartable actors with object-store arguments; this is the remedy).
        refs = [ray.put(arg) for arg in factory.args]
        workers = [remote_worker.remote(*refs, **extra) for _ in range(n_actors)]
        actors.extend(workers)
        ray.get([worker.ready.remote() for worker in workers])
        if on_ready is not None:
            on_ready()
        yield from _dispatch(ray, workers, jobs, threads * QUEUE_PER_SLOT, factory.lost)
    finally:
        for actor in actors:
            ray.kill(actor)
        if started:
            ray.shutdown()
