"""Run planner settings over benchmark tasks and aggregate the paper's metrics.

For speed the benchmark runs the loop in-process against the tool layer
(`InProcessTools`: the same tool functions the MCP server wraps) instead of spawning a
server per episode; `verigraph agent` and its tests cover the real MCP transport.
A planner is built afresh per episode with a seed derived from the task id, so results
do not depend on the order episodes run in. Every episode goes through
`episode.run_job`, the function the serial and Ray engines call too.
"""

from __future__ import annotations

import statistics
import sys
import time
from collections.abc import Callable, Sequence
from typing import TextIO

from pydantic import BaseModel

from verigraph.agent.environment import InProcessTools, ToolEnvironment
from verigraph.agent.evaluation.episode import (
    OFFLINE_PLANNERS,
    EngineConfig,
    PlannerPool,
    run_job,
)
from verigraph.agent.evaluation.limiter import Gate
from verigraph.agent.evaluation.spec import EpisodeResult, Setting, episode_seed, job_for
from verigraph.agent.evaluation.tasks import GroupName, GroupTasks, Task
from verigraph.agent.planner import Planner

__all__ = ["OFFLINE_PLANNERS", "EpisodeResult", "GroupStats", "Progress", "Setting",
           "aggregate", "episode_seed", "run_setting", "run_task"]


class GroupStats(BaseModel):
    """Aggregates of one setting on one group."""

    group: GroupName
    episodes: int
    success_rate: float
    mean_llm_calls: float
    mean_actions: float
    violations_caught: int
    errors: int
    seconds: float


def run_task(env: ToolEnvironment, task: Task, setting: Setting,
             shared: Planner | None = None) -> EpisodeResult:
    """One episode; tool and planner errors are recorded failures, not exceptions.

    Offline planners are built per episode (seeded by the task); an LLM planner is
    `shared` across the setting's episodes, so a local model server starts only once.
    """
    pool = PlannerPool(EngineConfig(), Gate(None),
                       shared={setting.planner: shared} if shared is not None else None)
    return run_job(job_for(task, setting, ""), task, env, pool).to_result()

def aggregate(group: GroupName, results: Sequence[EpisodeResult]) -> GroupStats:
    n = len(results)
    return GroupStats(
        group=group, episodes=n,
        success_rate=sum(r.success for r in results) / n if n else 0.0,
        mean_llm_calls=statistics.fmean(r.llm_calls for r in results) if n else 0.0,
        mean_actions=statistics.fmean(r.actions for r in results) if n else 0.0,
        violations_caught=sum(r.violations for r in results),
        errors=sum(r.error is not None for r in results),
        seconds=sum(r.seconds for r in results))


class Progress:
    """A one-line progress bar on stderr (a line per 10% when not a terminal)."""

    def __init__(self, total: int, stream: TextIO | None = None, width: int = 30) -> None:
        self.total = max(total, 1)
        self.done = 0
        self.stream = stream or sys.stderr
        self.width = width
        self.started = time.perf_counter()
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self._last_decile = -1

    def advance(self, label: str = "") -> None:
        self.done += 1
        fraction = self.done / self.total
        elapsed = time.perf_counter() - self.started
        eta = elapsed / fraction - elapsed if fraction else 0.0
        filled = int(self.width * fraction)
        line = (f"[{'#' * filled}{'.' * (self.width - filled)}] {self.done}/{self.total} "
                f"episodes, {elapsed:5.1f} s elapsed, ~{eta:4.0f} s left  {label[:40]}")
        if self.tty:
            self.stream.write("\r" + line.ljust(110))
            if self.done == self.total:
                self.stream.write("\n")
        elif int(fraction * 10) != self._last_decile or self.done == self.total:
            self._last_decile = int(fraction * 10)
            self.stream.write(line + "\n")
        self.stream.flush()


def run_setting(setting: Setting, groups: Sequence[GroupTasks], *,
                env: ToolEnvironment | None = None,
                progress: Progress | None = None,
                on_result: Callable[[EpisodeResult], None] | None = None
                ) -> dict[GroupName, GroupStats]:
    """Every runnable group's stats for one setting (serially, in this process)."""
    env = env or InProcessTools()
    pool = PlannerPool(EngineConfig(), Gate(None))
    stats: dict[GroupName, GroupStats] = {}
    try:
        for group in groups:
            if group.not_run is not None:
                continue
            results = []
            for task in group.tasks:
                result = run_job(job_for(task, setting, ""), task, env, pool).to_result()
                results.append(result)
                if on_result is not None:
                    on_result(result)
                if progress is not None:
                    progress.advance(setting.label())
            stats[group.group] = aggregate(group.group, results)
    finally:
        pool.close()
    return stats
