"""Run a list of episode jobs serially or on Ray, resumably, with a progress bar.

The dispatch itself is the job engine's (`verigraph.jobs.dispatch.run_on_workers`,
generic over the worker: one serial path and one Ray path), shared with environment
rollouts (`verigraph.env.rollout`, `RolloutWorker`).

`run_jobs` is the evaluation engine for episodes, behind `verigraph bench plan` and
every other caller (the public, stable entry point): it reads the results file, skips
every job already recorded there (`plan_resume`, which rollouts share), runs the rest
through `run_on_workers` (serially in this process by default, on Ray with
`RunOptions.ray`), appends each record as it arrives, and returns the records of all
the jobs asked for, in the order asked. Ctrl-C closes the bar, prints what is done and
how to resume, and re-raises. The command-line flags that fill `RunOptions` are parsed
in `verigraph.cli.bench`.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Generator, Sequence
from typing import TextIO

from pydantic import BaseModel, ConfigDict, Field

from verigraph.agent.evaluation.results import BenchRecord, ResultsFile
from verigraph.agent.evaluation.spec import EpisodeJob
from verigraph.agent.evaluation.worker import EngineConfig, episode_factory
from verigraph.jobs.dispatch import plan_resume, run_on_workers
from verigraph.jobs.limiter import BackendLimits, RateLimiter
from verigraph.jobs.progress_bar import EpisodeProgress
from verigraph.tasks.task import Task


class RunOptions(BaseModel):
    """Where and how to run: serial or Ray, the results file, limits, progress."""

    model_config = ConfigDict(extra="forbid")

    ray: str | None = Field(default=None, description="None: serial; local, auto, ray://...")
    results: str | None = None
    concurrency: int | None = Field(default=None, ge=1, description="Ray: episodes at once")
    limits: BackendLimits = Field(default_factory=BackendLimits,
                                  description="every backend's budget, unless named below")
    backend_limits: dict[str, BackendLimits] = Field(
        default_factory=dict, description="budgets of named backends (e.g. openai:gpt-4o)")

    def limiter(self) -> RateLimiter | None:
        """The in-process limiter these limits need (None: nothing is limited)."""
        budgets = [self.limits, *self.backend_limits.values()]
        if not any(b.concurrency or b.requests for b in budgets):
            return None
        return RateLimiter(self.backend_limits, default=self.limits)
    engine: EngineConfig = Field(default_factory=EngineConfig)
    progress: bool = True


def execute(jobs: list[EpisodeJob], tasks: dict[str, Task], options: RunOptions,
            on_ready: Callable[[], None] | None = None
            ) -> Generator[BenchRecord, None, None]:
    """Records of `jobs` as they finish (no resuming, no file: see `run_jobs`).

    `on_ready` is called when the workers are up, before the first episode starts.
    """
    factory = episode_factory(tasks, options.engine, options.limiter())
    yield from run_on_workers(factory, jobs, ray=options.ray,
                              concurrency=options.concurrency, on_ready=on_ready)


def run_jobs(jobs: Sequence[EpisodeJob], tasks: dict[str, Task], options: RunOptions, *,
             stream: TextIO | None = None) -> list[BenchRecord]:
    """Every job's record: from the results file when there, else run now.

    Stable signature: `run_jobs(jobs: Sequence[EpisodeJob], tasks: dict[str, Task],
    options: RunOptions, *, stream: TextIO | None = None) -> list[BenchRecord]`.
    `jobs` come from `spec.jobs_for` (one per task, setting and sample), `tasks` from
    `spec.task_index` of the same groups; `stream` receives the progress bar and the
    resume notes (default stderr). The result has one record per job, in the order of
    `jobs` (a job listed twice is run once). A failed episode is a record with
    `success=False` and `error` set, never an exception.
    """
    stream = stream or sys.stderr
    sink = ResultsFile(options.results) if options.results else None
    known = {r.key: r for r in sink.load(repair=True)} if sink else {}
    unique, done, pending = plan_resume(jobs, EpisodeJob.key, known)
    if done:
        print(f"resuming: {len(done)} of {len(unique)} episodes already in {options.results}; "
              f"running {len(pending)}", file=stream)
    progress = EpisodeProgress(len(unique), done.values(), stream=stream,
                               enabled=options.progress)
    records = execute(pending, tasks, options)
    try:
        for record in records:
            if sink is not None:
                sink.append([record])
            done[record.key] = record
            progress.update(record)
    except KeyboardInterrupt:
        records.close()
        progress.close()
        print(progress.summary(interrupted=True, results=options.results), file=stream)
        raise
    finally:
        progress.close()
    if options.progress:
        print(progress.summary(), file=stream)
    return [done[job.key()] for job in jobs]
