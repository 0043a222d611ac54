"""The job engine's one dispatch: run jobs on workers, serially or on Ray, resumably.

`run_on_workers` is generic over the worker (`verigraph.jobs.workers.WorkerFactory`):
one serial path and one Ray path (verigraph.jobs.ray_runner), used by `bench plan`
episodes (`verigraph.agent.evaluation.engine.run_jobs`, `EpisodeWorker`) and by
environment rollouts (`verigraph.env.rollout.run_rollouts`, `RolloutWorker`) alike.
`plan_resume` is how both skip the jobs their results file already holds.
"""

from __future__ import annotations

from collections.abc import Callable, Generator, Mapping, Sequence

from verigraph.jobs.ray_runner import run_on_ray
from verigraph.jobs.workers import JobT, ResultT, WorkerFactory


def run_on_workers(factory: WorkerFactory[JobT, ResultT], jobs: Sequence[JobT], *,
                   ray: str | None = None, concurrency: int | None = None,
                   on_ready: Callable[[], None] | None = None
                   ) -> Generator[ResultT, None, None]:
    """Results of `jobs` as they finish, on workers `factory` builds: the one dispatch.

    Without `ray`, one worker in this process runs the jobs in order; with it (local,
    auto, HOST:PORT, ray://...), `verigraph.jobs.ray_runner` runs them on a
    pool of actors of the same worker class. `bench plan` episodes and environment
    rollouts both come through here. `on_ready` is called when the workers are up,
    before the first job starts.
    """
    if ray is not None:
        yield from run_on_ray(factory, jobs, address=ray, concurrency=concurrency,
                              on_ready=on_ready)
        return
    worker = factory.build()
    if on_ready is not None:
        on_ready()
    try:
        for job in jobs:
            yield worker.run(job)
    finally:
        worker.close()


def plan_resume(jobs: Sequence[JobT], key: Callable[[JobT], str],
                known: Mapping[str, ResultT]
                ) -> tuple[list[JobT], dict[str, ResultT], list[JobT]]:
    """(the jobs once each, the results already in the results file, the jobs to run).

    `known` maps a job's key to its result as read back from a results file; a job
    listed twice is one job. `run_jobs` (episodes) and the environment's
    `run_rollouts` (trajectory files) resume the same way.
    """
    unique = list({key(job): job for job in jobs}.values())
    done = {key(job): known[key(job)] for job in unique if key(job) in known}
    pending = [job for job in unique if key(job) not in done]
    return unique, done, pending
