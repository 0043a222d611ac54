"""Run one episode job and return its record: the one code path of every run mode.

The serial engine and each Ray worker both call `EpisodeWorker.run` (or `run_job`
under it), so a seed gives the same episode whichever way it is scheduled.
`EpisodeWorker` is one `Worker` of the job engine (verigraph.jobs.workers), as the
environment's `RolloutWorker` (verigraph.env.rollout) is another.
Any exception an episode raises (a planner that fails after its retries, a tool error,
a bug) becomes that episode's recorded outcome; the run goes on.

Offline planners are built per episode with the job's seed; an LLM planner is built
once per worker thread and reused, so a model client (or a local model server) starts
once. A worker keeps one tool environment and one planner pool per thread, so a
threaded Ray actor can run several episodes at once.
"""

from __future__ import annotations

import threading
import time
from pathlib import Path

from pydantic import BaseModel, ConfigDict, Field

from verigraph.agent.evaluation.guard import GuardedPlanner, RetryPolicy, SimulatedLatencyPlanner
from verigraph.agent.evaluation.results import BenchRecord, blank_record
from verigraph.agent.evaluation.spec import EpisodeJob, Setting
from verigraph.agent.loop import LoopConfig, run_episode
from verigraph.agent.transcripts import RecordingPlanner, ReplayingPlanner
from verigraph.errors import VeriGraphError
from verigraph.jobs.limiter import Gate, LimiterLike, RateLimiter
from verigraph.jobs.workers import WorkerFactory, error_kind, worker_name
from verigraph.planning.factory import PlannerOptions, make_planner
from verigraph.planning.models import IterationRecord
from verigraph.planning.planner import Planner
from verigraph.planning.tool_calls import InProcessTools, ToolEnvironment
from verigraph.tasks.task import Task

OFFLINE_PLANNERS = ("oracle", "rule-based", "greedy", "noisy")


class EngineConfig(BaseModel):
    """How episodes are run (not what they are): backend options, retries, latency."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    planner_options: PlannerOptions = Field(
        default_factory=PlannerOptions,
        description="LLM backend settings (base_url, model, ...); noise and seed come "
                    "from each job")
    retry: RetryPolicy = Field(default_factory=RetryPolicy)
    latency_s: float = Field(default=0.0, ge=0.0,
                             description="simulated wait before every planner answer")
    traces_dir: str | None = Field(default=None, description="write each trace here")


class PlannerPool:
    """Builds guarded planners for jobs; LLM planners are kept and reused."""

    def __init__(self, config: EngineConfig, gate: Gate,
                 shared: dict[str, Planner] | None = None) -> None:
        self.config = config
        self.gate = gate
        self.shared: dict[str, Planner] = dict(shared or {})
        self._owned: set[str] = set()

    def _wrap(self, planner: Planner, seed: int) -> GuardedPlanner:
        inner: Planner = planner
        if self.config.latency_s > 0:
            inner = SimulatedLatencyPlanner(planner, self.config.latency_s)
        return GuardedPlanner(inner, self.gate, self.config.retry, seed=seed)

    def get(self, setting: Setting, seed: int, task_id: str,
            sample: int = 0) -> tuple[GuardedPlanner, bool]:
        """(planner, close it after the episode); transcripts recorded or replayed per
        task (and sample) when the setting asks for it."""
        key = setting.transcript_key(task_id) + (f"__sample{sample}" if sample else "")
        if setting.replay_dir:
            return self._wrap(ReplayingPlanner(setting.replay_dir, key), seed), True
        if setting.planner in OFFLINE_PLANNERS:
            options = self.config.planner_options.model_copy(
                update={"noise": setting.noise, "seed": seed})
            planner = make_planner(setting.planner, options)
            if setting.record_dir:
                planner = RecordingPlanner(planner, setting.record_dir, key)
            return self._wrap(planner, seed), True
        if setting.planner not in self.shared:
            options = self.config.planner_options.model_copy(update={"retries": 0})
            self.shared[setting.planner] = make_planner(setting.planner, options)
            self._owned.add(setting.planner)
        shared = self.shared[setting.planner]
        if setting.record_dir:
            recording = RecordingPlanner(shared, setting.record_dir, key, close_inner=False)
            return self._wrap(recording, seed), True
        return self._wrap(shared, seed), False

    def close(self) -> None:
        for name in self._owned:
            self.shared.pop(name).close()
        self._owned.clear()


def lost_record(job: EpisodeJob, error: str) -> BenchRecord:
    """The record of an episode whose worker process was lost for good."""
    record = blank_record(job, job.setting.planner)
    record.error_kind = "worker"
    record.stop_reason = "worker_error"
    record.error = error[:500]
    return record


def run_job(job: EpisodeJob, task: Task, env: ToolEnvironment, pool: PlannerPool,
            traces_dir: str | None = None) -> BenchRecord:
    """One episode, start to verdict, as a record; never raises for a failed episode."""
    setting = job.setting
    config = LoopConfig(mode=setting.mode, k=setting.k, threshold=setting.threshold,
                        done_policy=setting.done_policy, max_iterations=setting.max_iterations,
                        feedback=setting.feedback, stop_on_goal=setting.stop_on_goal,
                        no_progress=setting.no_progress)
    started = time.perf_counter()
    iterations: list[IterationRecord] = []
    planner: GuardedPlanner | None = None
    close = False
    try:
        planner, close = pool.get(setting, job.seed, job.task_id, job.sample)
        record = blank_record(job, planner.name)
        trace = run_episode(env, planner, task.spec, config, on_iteration=iterations.append)
    except Exception as exc:  # noqa: BLE001 (every failure is this episode's outcome)
        record = blank_record(job, planner.name if planner else setting.planner)
        # A planner's own failure never lands here: the loop ends the episode with
        # stop_reason planner_error (handled below); what is left is a tool or a bug.
        kind = error_kind(exc)
        record.error_kind = kind
        record.error = f"{type(exc).__name__}: {exc}"[:500]
        record.stop_reason = f"{kind}_error"
        record.iterations = len(iterations)
        record.planner_calls = sum(i.llm_calls for i in iterations)
    else:
        record.success = trace.success
        record.stop_reason = trace.stop_reason
        record.iterations = len(trace.iterations)
        record.planner_calls = trace.llm_calls
        record.actions = trace.actions_executed
        record.violations = trace.violations_caught
        record.malformed = trace.malformed_outputs
        record.premature_done = trace.premature_done
        if trace.planner_error:
            record.error_kind = "planner"
            record.error = trace.planner_error[:500]
        if traces_dir is not None:
            path = Path(traces_dir) / f"{job.key()}.json"
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(trace.model_dump_json(indent=1))
            record.trace_path = str(path)
    finally:
        if planner is not None and close:
            planner.close()
    if planner is not None:
        record.requests = planner.requests
        record.retries = planner.retries
        record.prompt_tokens = planner.usage.prompt_tokens
        record.completion_tokens = planner.usage.completion_tokens
        record.total_tokens = planner.usage.total_tokens
        record.cost_usd = planner.usage.cost_usd
    record.wall_s = time.perf_counter() - started
    record.worker = worker_name()
    return record


class EpisodeWorker:
    """Runs jobs against a task table; one environment and planner pool per thread.

    The same class serves the serial path (called directly) and Ray (wrapped as an
    actor, possibly with several threads): that is the shared code.
    """

    def __init__(self, tasks: dict[str, Task], config: EngineConfig | None = None,
                 limiter: LimiterLike | None = None) -> None:
        self.tasks = tasks
        self.config = config or EngineConfig()
        self.gate = Gate(limiter)
        self._local = threading.local()
        self._pools: list[PlannerPool] = []
        self._lock = threading.Lock()

    def _state(self) -> tuple[ToolEnvironment, PlannerPool]:
        if not hasattr(self._local, "env"):
            self._local.env = InProcessTools()
            self._local.pool = PlannerPool(self.config, self.gate)
            with self._lock:
                self._pools.append(self._local.pool)
        return self._local.env, self._local.pool

    def ready(self) -> str:
        """Where this worker runs (a Ray actor answers once it is constructed)."""
        return worker_name()

    def run(self, job: EpisodeJob) -> BenchRecord:
        task = self.tasks.get(job.task_ref)
        if task is None:
            raise VeriGraphError(f"no task {job.task_ref} in this worker's suite",
                                 field="task_id", value=job.task_ref,
                                 fix="build the worker with the suite the job came from")
        env, pool = self._state()
        return run_job(job, task, env, pool, self.config.traces_dir)

    def close(self) -> None:
        with self._lock:
            for pool in self._pools:
                pool.close()
            self._pools.clear()


def episode_factory(tasks: dict[str, Task], config: EngineConfig,
                    limiter: RateLimiter | None = None
                    ) -> WorkerFactory[EpisodeJob, BenchRecord]:
    """`EpisodeWorker`s over this task table: the factory behind `bench plan`."""
    return WorkerFactory(EpisodeWorker, (tasks, config), lost=lost_record, limiter=limiter)
