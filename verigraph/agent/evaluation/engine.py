"""Run a list of episode jobs serially or on Ray, resumably, with a progress bar.

`run_jobs` is the engine behind `verigraph bench plan`: it reads the results file,
skips every job already recorded there, runs the rest (serially in this process by
default, on Ray with `--ray`), appends each record as it arrives, and returns the
records of all the jobs asked for, in the order asked. Ctrl-C closes the bar, prints
what is done and how to resume, and re-raises.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Generator, Sequence
from typing import TextIO

from pydantic import BaseModel, ConfigDict, Field

from verigraph.agent.evaluation.episode import EngineConfig, EpisodeWorker
from verigraph.agent.evaluation.guard import RetryPolicy
from verigraph.agent.evaluation.limiter import BackendLimits, RateLimiter
from verigraph.agent.evaluation.progress import EpisodeProgress
from verigraph.agent.evaluation.results import EpisodeRecord, ResultsFile
from verigraph.agent.evaluation.spec import EpisodeJob
from verigraph.agent.evaluation.tasks import Task
from verigraph.agent.factory import PlannerOptions
from verigraph.errors import VeriGraphError


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


def add_engine_arguments(p: argparse.ArgumentParser) -> None:
    """The options of the execution engine, shared by every benchmark that uses it."""
    g = p.add_argument_group("execution (serial by default; Ray with --ray)")
    g.add_argument("--ray", nargs="?", const="local", metavar="ADDRESS",
                   help="run episodes on Ray: without ADDRESS a local Ray with this "
                        "machine's cores; 'auto', 'HOST:PORT' or 'ray://HOST:10001' joins "
                        "a running cluster")
    g.add_argument("--results", metavar="FILE.jsonl",
                   help="append one JSON line per finished episode; a rerun skips the "
                        "episodes already there (render with `verigraph bench report`)")
    g.add_argument("--concurrency", type=int,
                   help="with --ray: episodes in flight (default: the cluster's cores)")
    g.add_argument("--rpm", type=int, help="requests per minute allowed per planner backend, "
                                           "shared by every worker")
    g.add_argument("--max-concurrent", type=int,
                   help="planner requests in flight allowed per backend")
    g.add_argument("--limit", action="append", default=[], metavar="BACKEND=RPM[/IN_FLIGHT]",
                   help="a named backend's own budget, e.g. openai:gpt-4o-mini=500/16 "
                        "(repeatable; the backend name is the record's `planner`)")
    g.add_argument("--retries", type=int, default=4,
                   help="retries of a planner request on HTTP 429/5xx (default 4)")
    g.add_argument("--backoff", type=float, default=0.5,
                   help="first retry delay in seconds, doubled each retry (default 0.5)")
    g.add_argument("--simulated-latency", type=float, default=0.0, metavar="SECONDS",
                   help="wait this long before every planner answer (a stand-in for a "
                        "model API, to measure concurrency)")
    g.add_argument("--traces", metavar="DIR", help="write each episode's trace JSON here")
    g.add_argument("--no-progress-bar", action="store_true", help="no progress bar on stderr")


def _check_flags(args: argparse.Namespace) -> None:
    checks = (("--concurrency", args.concurrency, 1), ("--rpm", args.rpm, 1),
              ("--max-concurrent", args.max_concurrent, 1), ("--retries", args.retries, 0),
              ("--backoff", args.backoff, 0), ("--simulated-latency", args.simulated_latency, 0))
    for flag, value, least in checks:
        if value is not None and value < least:
            raise VeriGraphError(f"{flag} must be at least {least}", field=flag, value=value,
                                 fix=f"give {flag} a value >= {least}, or leave it out")
    if args.retries > 20:
        raise VeriGraphError("--retries must be at most 20", field="--retries",
                             value=args.retries, fix="use e.g. --retries 4")


def parse_limit(text: str) -> tuple[str, BackendLimits]:
    """`NAME=RPM` or `NAME=RPM/IN_FLIGHT` (RPM may be empty: `NAME=/4`)."""
    name, sep, budget = text.rpartition("=")
    rpm, _, in_flight = budget.partition("/")
    try:
        if not (sep and name) or not (rpm or in_flight):
            raise ValueError(text)
        return name, BackendLimits(requests=int(rpm) if rpm else None,
                                   concurrency=int(in_flight) if in_flight else None)
    except ValueError:
        raise VeriGraphError(f"not a backend limit: {text!r}", field="--limit", value=text,
                             fix="write BACKEND=RPM or BACKEND=RPM/IN_FLIGHT with positive "
                                 "whole numbers, e.g. openai:gpt-4o-mini=500/16") from None


def options_from_args(args: argparse.Namespace) -> RunOptions:
    """The engine options of parsed `add_engine_arguments` flags (bad values: exit 2)."""
    _check_flags(args)
    return RunOptions(
        ray=args.ray, results=args.results, concurrency=args.concurrency,
        limits=BackendLimits(concurrency=args.max_concurrent, requests=args.rpm),
        backend_limits=dict(parse_limit(text) for text in args.limit),
        engine=EngineConfig(retry=RetryPolicy(retries=args.retries, backoff_s=args.backoff),
                            latency_s=args.simulated_latency, traces_dir=args.traces,
                            planner_options=PlannerOptions()),
        progress=not args.no_progress_bar)


def execute(jobs: list[EpisodeJob], tasks: dict[str, Task], options: RunOptions,
            on_ready: Callable[[], None] | None = None
            ) -> Generator[EpisodeRecord, None, None]:
    """Records of `jobs` as they finish (no resuming, no file: see `run_jobs`).

    `on_ready` is called when the workers are up, before the first episode starts.
    """
    if options.ray is not None:
        from verigraph.agent.evaluation.ray_runner import run_on_ray

        yield from run_on_ray(jobs, tasks, options.engine, address=options.ray,
                              concurrency=options.concurrency, limiter=options.limiter(),
                              on_ready=on_ready)
        return
    worker = EpisodeWorker(tasks, options.engine, options.limiter())
    if on_ready is not None:
        on_ready()
    try:
        for job in jobs:
            yield worker.run(job)
    finally:
        worker.close()


def run_jobs(jobs: Sequence[EpisodeJob], tasks: dict[str, Task], options: RunOptions, *,
             stream: TextIO | None = None) -> list[EpisodeRecord]:
    """Every job's record: from the results file when there, else run now."""
    stream = stream or sys.stderr
    unique = list({job.key(): job for job in jobs}.values())
    sink = ResultsFile(options.results) if options.results else None
    known = {r.key: r for r in sink.load(repair=True)} if sink else {}
    done = {job.key(): known[job.key()] for job in unique if job.key() in known}
    pending = [job for job in unique if job.key() not in done]
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
