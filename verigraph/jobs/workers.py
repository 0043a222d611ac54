"""What the job engine runs jobs on: the worker protocol, its factory, and how a job
that raised is recorded.

The engine (verigraph.jobs.dispatch) knows no episodes: it runs any `Worker` (ready,
run, close) that a `WorkerFactory` builds, in this process or as Ray actors
(verigraph.jobs.ray_runner). `bench plan`'s `EpisodeWorker`
(verigraph.agent.evaluation.worker) and the environment's `RolloutWorker`
(verigraph.env.rollout) are two such workers, so episodes and rollouts are scheduled,
queued and recorded by the same code.
"""

from __future__ import annotations

import os
import socket
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Generic, Protocol, TypeVar

from verigraph.errors import VeriGraphError
from verigraph.jobs.limiter import RateLimiter

JobT = TypeVar("JobT")
ResultT = TypeVar("ResultT")
JobT_contra = TypeVar("JobT_contra", contravariant=True)
ResultT_co = TypeVar("ResultT_co", covariant=True)


class Worker(Protocol[JobT_contra, ResultT_co]):
    """What the engine runs jobs on, in this process or as a Ray actor.

    `run` must be safe to call from several threads at once (a Ray actor may run a few
    jobs concurrently) and must not raise for a job that merely fails: its outcome is a
    result. `ready` answers once the worker is built, so start-up can be timed apart.
    """

    def ready(self) -> str: ...

    def run(self, job: JobT_contra) -> ResultT_co: ...

    def close(self) -> None: ...


@dataclass(frozen=True)
class WorkerFactory(Generic[JobT, ResultT]):
    """How to build a worker here or on Ray, and what a job whose worker is lost yields.

    `worker` is a class (Ray makes actors of classes) called with `args`, plus
    `limiter=` when `limiter` is set: the limiter itself in this process, a proxy of one
    limiter actor shared by the cluster on Ray. On Ray each argument is put in the
    object store once for all actors. `lost(job, error)` is the failed result of a job
    whose worker process died for good, so a run never ends in an exception for it.
    """

    worker: type[Any]
    args: tuple[Any, ...]
    lost: Callable[[JobT, str], ResultT]
    limiter: RateLimiter | None = None

    def build(self) -> Worker[JobT, ResultT]:
        """The worker in this process (the Ray path builds its actors itself)."""
        extra = {"limiter": self.limiter} if self.limiter is not None else {}
        worker: Worker[JobT, ResultT] = self.worker(*self.args, **extra)
        return worker


def worker_name() -> str:
    """host:pid, the place a result records it ran."""
    return f"{socket.gethostname()}:{os.getpid()}"


def error_kind(exc: Exception) -> str:
    """How a job that raised is recorded: "tool" for a VeriGraphError (bad input, a
    store failure), else "internal" (a bug). Episodes and environment rollouts alike."""
    return "tool" if isinstance(exc, VeriGraphError) else "internal"
