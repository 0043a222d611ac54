"""Run planner settings over benchmark tasks and aggregate the paper's metrics.

For speed the benchmark runs the loop in-process against the tool layer
(`InProcessTools`: the same tool functions the MCP server wraps) instead of spawning a
server per episode; `verigraph agent` and its tests cover the real MCP transport.
A planner is built afresh per episode with a seed derived from the task id, so results
do not depend on the order episodes run in.
"""

from __future__ import annotations

import statistics
import sys
import time
import zlib
from collections.abc import Callable, Sequence
from typing import TextIO

from pydantic import BaseModel, ConfigDict, Field

from verigraph.agent.environment import InProcessTools, ToolEnvironment
from verigraph.agent.evaluation.tasks import SUITE_VERSION, GroupName, GroupTasks, Task
from verigraph.agent.factory import PlannerOptions, make_planner
from verigraph.agent.loop import LoopConfig, run_episode
from verigraph.agent.models import DonePolicy, FeedbackMode, Mode
from verigraph.agent.planner import Planner
from verigraph.agent.transcripts import RecordingPlanner, ReplayingPlanner
from verigraph.errors import VeriGraphError


class Setting(BaseModel):
    """One row of a table: a planner with its loop parameters."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    planner: str
    mode: Mode = "iterative"
    k: int = 3
    threshold: int = 5
    done_policy: DonePolicy = "verify"
    noise: float = 0.3
    max_iterations: int = 30
    feedback: FeedbackMode = "full"
    stop_on_goal: bool = True
    no_progress: int = 15
    record_dir: str | None = Field(default=None, description="write planner transcripts here")
    replay_dir: str | None = Field(default=None,
                                   description="answer from transcripts recorded here")

    def label(self) -> str:
        name = self.planner if self.planner != "noisy" else f"noisy ({self.noise:.0%})"
        if self.mode == "direct":
            return f"{name}, direct"
        policy = "" if self.done_policy == "verify" else ", trust done"
        if not self.stop_on_goal:
            policy += ", end token only"
        feedback = "" if self.feedback == "full" else f", feedback {self.feedback}"
        return f"{name}, iterative k={self.k} t={self.threshold}{policy}{feedback}"


class EpisodeResult(BaseModel):
    """The numbers one episode contributes to a table."""

    group: GroupName
    task_id: str
    success: bool
    llm_calls: int = 0
    actions: int = 0
    violations: int = 0
    malformed: int = 0
    premature_done: int = 0
    stop_reason: str | None = None
    seconds: float = 0.0
    error: str | None = Field(default=None, description="tool or planner error, if any")
    suite_version: str = SUITE_VERSION


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


def episode_seed(task_id: str, setting: Setting) -> int:
    return zlib.crc32(f"{task_id}|{setting.label()}".encode())


OFFLINE_PLANNERS = ("oracle", "rule-based", "greedy", "noisy")


def run_task(env: ToolEnvironment, task: Task, setting: Setting,
             shared: Planner | None = None) -> EpisodeResult:
    """One episode; tool errors (e.g. a perceived goal naming unknown objects) are failures.

    Offline planners are built per episode (seeded by the task); an LLM planner is
    `shared` across the setting's episodes, so a local model server starts only once.
    """
    key = f"{setting.label()}__{task.task_id}"
    planner: Planner
    if setting.replay_dir:
        planner = ReplayingPlanner(setting.replay_dir, key)
    else:
        planner = shared or make_planner(setting.planner, PlannerOptions(
            noise=setting.noise, seed=episode_seed(task.task_id, setting)))
        if setting.record_dir:
            planner = RecordingPlanner(planner, setting.record_dir, key,
                                       close_inner=shared is None)
    config = LoopConfig(mode=setting.mode, k=setting.k, threshold=setting.threshold,
                        done_policy=setting.done_policy, max_iterations=setting.max_iterations,
                        feedback=setting.feedback, stop_on_goal=setting.stop_on_goal,
                        no_progress=setting.no_progress)
    started = time.perf_counter()
    try:
        trace = run_episode(env, planner, task.spec, config)
    except VeriGraphError as exc:
        return EpisodeResult(group=task.group, task_id=task.task_id, success=False,
                             seconds=time.perf_counter() - started, error=str(exc)[:300])
    finally:
        if shared is None:
            planner.close()
    return EpisodeResult(
        group=task.group, task_id=task.task_id, success=trace.success,
        llm_calls=trace.llm_calls, actions=trace.actions_executed,
        violations=trace.violations_caught, malformed=trace.malformed_outputs,
        premature_done=trace.premature_done, stop_reason=trace.stop_reason,
        seconds=trace.wall_time_s, error=trace.planner_error)


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
    """Every runnable group's stats for one setting."""
    env = env or InProcessTools()
    shared = None if setting.planner in OFFLINE_PLANNERS or setting.replay_dir \
        else make_planner(setting.planner)
    stats: dict[GroupName, GroupStats] = {}
    try:
        for group in groups:
            if group.not_run is not None:
                continue
            results = []
            for task in group.tasks:
                result = run_task(env, task, setting, shared)
                results.append(result)
                if on_result is not None:
                    on_result(result)
                if progress is not None:
                    progress.advance(setting.label())
            stats[group.group] = aggregate(group.group, results)
    finally:
        if shared is not None:
            shared.close()
    return stats
