"""Evaluation engine throughput: serial vs Ray-local, and overlapping slow planner calls.

1. The noisy planner on a 2,000-episode slice (the t and k ablation settings on all
   five groups with ground-truth goal graphs), serial in one process vs on a local Ray
   with this machine's cores; Ray's start-up is timed separately. The per-episode
   records of both runs are compared (they must be identical apart from timing).
2. A simulated-latency backend (every planner call waits 1 s first, like a model API):
   the same episodes with 1 and with 16 in flight on Ray, and 16 in flight behind a
   limiter that allows 4 requests at once.

Run: `verigraph bench scale [--episodes 2000] [--latency-episodes 48]`; writes
results/scale.md.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path
from typing import NamedTuple

sys.path.insert(0, str(Path(__file__).parent))

from common import write_table  # noqa: E402

from verigraph.agent.evaluation import Setting  # noqa: E402
from verigraph.agent.evaluation.engine import RunOptions, execute  # noqa: E402
from verigraph.agent.evaluation.results import BenchRecord  # noqa: E402
from verigraph.agent.evaluation.spec import EpisodeJob, jobs_for, task_index  # noqa: E402
from verigraph.agent.evaluation.worker import EngineConfig  # noqa: E402
from verigraph.jobs.limiter import BackendLimits  # noqa: E402
from verigraph.jobs.ray_runner import connect  # noqa: E402
from verigraph.tasks import build_groups  # noqa: E402
from verigraph.tasks.task import GROUPS, Task  # noqa: E402

SETTINGS = [*(Setting(planner="noisy", threshold=t) for t in (2, 3, 5, 10)),
            *(Setting(planner="noisy", k=k) for k in (2, 3, 5, 10))]


class Timing(NamedTuple):
    wall_s: float  # everything, worker start-up included
    run_s: float  # from the workers being ready to the last record
    records: list[BenchRecord]

    @property
    def rate(self) -> float:
        return len(self.records) / self.run_s


def timed(jobs: list[EpisodeJob], tasks: dict[str, Task], options: RunOptions) -> Timing:
    """Run through the engine, timing worker start-up apart from the episodes."""
    started = time.perf_counter()
    ready = [started]
    records = list(execute(jobs, tasks, options, on_ready=lambda: ready.append(
        time.perf_counter())))
    end = time.perf_counter()
    order = {job.key(): i for i, job in enumerate(jobs)}
    return Timing(end - started, end - ready[-1], sorted(records, key=lambda r: order[r.key]))


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--episodes", type=int, default=2000, help="slice for part 1")
    p.add_argument("--latency-episodes", type=int, default=48, help="episodes for part 2")
    p.add_argument("--latency", type=float, default=1.0, help="seconds per planner call")
    args = p.parse_args(argv)
    import ray

    per_group = -(-args.episodes // (len(SETTINGS) * len(GROUPS)))
    groups = build_groups(GROUPS, per_group, 0, ground_truth=True)
    tasks = task_index(groups)
    jobs = [j for s in SETTINGS for j in jobs_for(s, groups, "scale")][:args.episodes]
    quiet = RunOptions(progress=False)
    serial = timed(jobs, tasks, quiet)

    started = time.perf_counter()
    connect("local")
    ray_start_s = time.perf_counter() - started
    try:
        on_ray = timed(jobs, tasks, quiet.model_copy(update={"ray": "local"}))
        identical = [r.outcome() for r in serial.records] == \
            [r.outcome() for r in on_ray.records]

        slow_jobs = jobs_for(Setting(planner="noisy"), groups, "scale")[:args.latency_episodes]
        engine = EngineConfig(latency_s=args.latency)
        latency_runs = []
        for label, concurrency, limits in (
                ("1 in flight", 1, BackendLimits()),
                ("16 in flight", 16, BackendLimits()),
                ("16 in flight, limiter: 4 requests at once", 16, BackendLimits(concurrency=4))):
            options = RunOptions(ray="local", concurrency=concurrency, limits=limits,
                                 engine=engine, progress=False)
            latency_runs.append((label, timed(slow_jobs, tasks, options)))
    finally:
        ray.shutdown()

    n = len(jobs)
    rows = [
        ["noisy, serial (one process)", str(n), f"{serial.run_s:.1f} s",
         f"{serial.wall_s - serial.run_s:.1f} s", f"{serial.rate:.1f}", "1.00x", "-"],
        [f"noisy, Ray local ({os.cpu_count()} cores)", str(n), f"{on_ray.run_s:.1f} s",
         f"{on_ray.wall_s - on_ray.run_s:.1f} s", f"{on_ray.rate:.1f}",
         f"{on_ray.rate / serial.rate:.2f}x",
         f"starting Ray itself: {ray_start_s:.1f} s; records identical to serial: "
         f"{'yes' if identical else 'NO'}"],
    ]
    base = latency_runs[0][1].rate
    for label, run in latency_runs:
        calls = sum(r.requests for r in run.records)
        rows.append([f"{args.latency:g} s per planner call, {label}", str(len(run.records)),
                     f"{run.run_s:.1f} s", f"{run.wall_s - run.run_s:.1f} s",
                     f"{run.rate:.2f}", f"{run.rate / base:.2f}x", f"{calls} planner calls"])
    notes = (
        "Run time: from the workers being ready to the last finished episode; worker "
        "start-up (Ray actors: a process each, importing VeriGraph and loading the task "
        "table) is shown apart, task generation is not timed. Episodes/s and speed-up "
        "use the run time. The 2,000-episode slice is "
        "the noisy planner (30% mistakes) "
        "with t in {2,3,5,10} at k=3 and k in {2,3,5,10} at t=5 on the five task groups "
        "(ground-truth goal graphs). The latency rows run the noisy planner behind a "
        f"{args.latency:g} s wait per call on Ray ({os.cpu_count()} cores; 16 in flight = "
        "worker actors with several threads each). The machine is shared with other jobs, "
        "so absolute figures vary from run to run; the ratios are measured in the same run.")
    write_table("scale", "Evaluation engine: serial vs Ray, overlapping slow planner calls",
                ["run", "episodes", "run time", "worker start-up", "episodes/s", "speed-up",
                 "notes"], rows,
                notes)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
