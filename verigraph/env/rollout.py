"""Rollouts of the environment: policies, one episode, and many serially or on Ray.

A policy maps `(env, observation, info)` to the action text. `PlannerPolicy` puts any
project planner (verigraph.planning: oracle, noisy, greedy, ...) in the policy's seat by
asking it what the loop would ask (`VeriGraphEnv.planner_request`) and writing its
reply as text; `RefusedActionPolicy` answers an action the verifier always refuses.
A policy is named in a `RolloutJob` so that a Ray worker can build it itself.

`run_rollouts(jobs, env_kwargs, ray=...)` runs the jobs through the job engine's
one dispatch (`verigraph.jobs.dispatch.run_on_workers`, the same serial and Ray
paths as `bench plan`): `RolloutWorker` is the engine's worker, as `EpisodeWorker` is for
episodes. `ray="local"` starts a private Ray with this machine's cores; an initialised
Ray is used as it is. Each Ray actor builds its environments from `env_kwargs`, so the
kwargs must be picklable (pass `tasks`, not a `tools` connection). A worker process that
dies is restarted and its rollouts retried (they are seeded, so idempotent); a rollout
whose worker is lost for good comes back as a failed result (`error_kind` "worker"),
not an exception, and so does one that raises (`error_kind` "tool" or "internal", as
`bench plan` records an episode's error), serially and on Ray alike. Results come back
in job order and carry the episode's trajectory lines (verigraph.env.trajectory),
identical serially and on Ray.
"""

from __future__ import annotations

import math
import os
import threading
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, Literal, Protocol, TextIO

from pydantic import BaseModel, ConfigDict, Field

from verigraph.env.core import VeriGraphEnv
from verigraph.env.trajectory import (
    TrajectoryFile,
    TrajectoryLine,
    reset_line,
    settings_diff,
    step_line,
)
from verigraph.errors import VeriGraphError
from verigraph.jobs.dispatch import plan_resume, run_on_workers
from verigraph.jobs.progress_bar import EpisodeProgress
from verigraph.jobs.workers import WorkerFactory, error_kind, worker_name
from verigraph.planning.factory import PlannerOptions, make_planner
from verigraph.planning.planner import Planner

PolicyName = Literal["oracle", "noisy", "greedy", "refuse"]
REFUSED_ACTION = "move(no_such_object, on, table)"


class Policy(Protocol):
    def __call__(self, env: VeriGraphEnv, observation: str, info: dict[str, Any]) -> str:
        """The action text for this observation."""
        ...


class PlannerPolicy:
    """A project planner as a policy (the oracle reads the privileged goal: a ceiling)."""

    def __init__(self, planner: Planner) -> None:
        self.planner = planner

    def __call__(self, env: VeriGraphEnv, observation: str, info: dict[str, Any]) -> str:
        reply = self.planner.propose(env.planner_request())
        if reply.error is not None:
            return reply.raw or ""
        return "\n".join(a.text() for a in reply.actions)


class RefusedActionPolicy:
    """Always the same action on an object no scene has: refused as unknown_object."""

    def __call__(self, env: VeriGraphEnv, observation: str, info: dict[str, Any]) -> str:
        return REFUSED_ACTION


def make_policy(name: str, seed: int = 0, noise: float = 0.3) -> Policy:
    if name == "refuse":
        return RefusedActionPolicy()
    if name in ("oracle", "noisy", "greedy"):
        return PlannerPolicy(make_planner(name, PlannerOptions(seed=seed, noise=noise)))
    raise VeriGraphError(f"unknown policy '{name}'", field="policy", value=name,
                         fix="use oracle, noisy, greedy or refuse")


class RolloutJob(BaseModel):
    """One episode to run: which task, reset seed, and the policy by name."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    task_id: str
    seed: int = 0
    policy: PolicyName = "oracle"
    policy_seed: int = 0
    noise: float = Field(default=0.3, ge=0.0, le=1.0)

    def episode(self) -> str:
        """The rollout's id (its trajectory lines' `episode`, its key when resuming)."""
        noise = f"{self.noise:g}"
        noise = noise if float(noise) == self.noise else repr(self.noise)  # exact, always
        policy = f"{self.policy}~{noise}" if self.policy == "noisy" else self.policy
        return f"{self.task_id}#{policy}:{self.policy_seed}@{self.seed}"


class RolloutResult(BaseModel):
    """An episode's outcome and its trajectory lines (none when its worker was lost)."""

    job: RolloutJob
    episode_return: float
    steps: int
    moves: int = Field(description="actions the verifier executed")
    success: bool
    stop_reason: str | None
    lines: list[TrajectoryLine]
    worker: int | None = Field(description="process id that ran it (None: lost, or read "
                                           "back from a trajectory file)")
    error: str | None = Field(default=None, description="why the episode did not run")
    error_kind: str | None = Field(default=None, description="worker: its process died; "
                                                             "tool or internal: it raised")

    @property
    def group(self) -> str:
        """The task's suite (its id up to the first "/"): a progress bar's group."""
        return self.job.task_id.split("/", 1)[0]


def lost_rollout(job: RolloutJob, error: str) -> RolloutResult:
    """The result of a rollout whose worker process was lost for good."""
    return RolloutResult(job=job, episode_return=0.0, steps=0, moves=0, success=False,
                         stop_reason="worker_error", lines=[], worker=None,
                         error=error[:500], error_kind="worker")


def failed_rollout(job: RolloutJob, exc: Exception) -> RolloutResult:
    """The result of a rollout that raised (its policy, its environment or a bug), kinded
    as `bench plan` kinds an episode's error: "tool" for a VeriGraphError, else
    "internal". No lines are kept, so a rerun from the trajectory file tries it again."""
    kind = error_kind(exc)
    return RolloutResult(job=job, episode_return=0.0, steps=0, moves=0, success=False,
                         stop_reason=f"{kind}_error", lines=[], worker=os.getpid(),
                         error=f"{type(exc).__name__}: {exc}"[:500], error_kind=kind)


def recorded_result(job: RolloutJob, lines: list[TrajectoryLine]) -> RolloutResult:
    """The result of `job` read back from its complete trajectory lines (worker unknown)."""
    end = lines[-1]
    return RolloutResult(job=job, episode_return=sum(line.reward for line in lines),
                         steps=end.step, moves=end.moves or 0, success=bool(end.success),
                         stop_reason=end.stop_reason, lines=lines, worker=None)


def run_rollout(env: VeriGraphEnv, policy: Policy, job: RolloutJob) -> RolloutResult:
    """Run one episode of `job` on `env` with `policy` until it ends."""
    episode = job.episode()
    observation, info = env.reset(seed=job.seed, options={"task": job.task_id})
    assert env.task is not None
    lines = [reset_line(episode, env.task, job.seed, observation, info, env.settings())]
    total = 0.0
    terminated = truncated = False
    while not (terminated or truncated):
        action = policy(env, observation, info)
        following, reward, terminated, truncated, info = env.step(action)
        lines.append(step_line(episode, observation, action, reward, terminated, truncated,
                               info, following))
        total += reward
        observation = following
    return RolloutResult(job=job, episode_return=total, steps=info["step"],
                         moves=info["moves"], success=bool(info["success"]),
                         stop_reason=info["stop_reason"], lines=lines, worker=os.getpid())


class RolloutWorker:
    """Environments built from `env_kwargs` (one per thread) and the policies jobs name.

    The engine's `Worker`: called directly on the serial path, wrapped as a Ray actor
    (possibly running a few rollouts at once on threads) on the Ray path.
    """

    def __init__(self, env_kwargs: dict[str, Any]) -> None:
        self.env_kwargs = dict(env_kwargs)
        self._local = threading.local()
        self._envs: list[VeriGraphEnv] = []
        self._lock = threading.Lock()
        self._env()  # built now, so a bad kwarg fails here and `ready` times start-up

    def _env(self) -> VeriGraphEnv:
        if not hasattr(self._local, "env"):
            self._local.env = VeriGraphEnv(**self.env_kwargs)
            with self._lock:
                self._envs.append(self._local.env)
        env: VeriGraphEnv = self._local.env
        return env

    def ready(self) -> str:
        """host:pid; a Ray actor answers once its first environment is built."""
        return worker_name()

    def policy(self, job: RolloutJob) -> Policy:
        """The policy `job` names (a subclass may build its own)."""
        return make_policy(job.policy, job.policy_seed, job.noise)

    def run(self, job: RolloutJob) -> RolloutResult:
        """The rollout's result; one that raises is a failed result (`failed_rollout`),
        the same serially and on Ray, and the run goes on."""
        try:
            return run_rollout(self._env(), self.policy(job), job)
        except Exception as exc:  # noqa: BLE001 (every failure is this rollout's outcome)
            return failed_rollout(job, exc)

    def close(self) -> None:
        with self._lock:
            for env in self._envs:
                env.close()
            self._envs.clear()


def rollout_factory(env_kwargs: dict[str, Any], worker: type[RolloutWorker] = RolloutWorker
                    ) -> WorkerFactory[RolloutJob, RolloutResult]:
    """`RolloutWorker`s (or a subclass) over `env_kwargs`, for the job engine."""
    return WorkerFactory(worker, (dict(env_kwargs),), lost=lost_rollout)


def run_rollouts(jobs: Sequence[RolloutJob], env_kwargs: dict[str, Any], *,
                 ray: str | None = None, workers: int | None = None,
                 on_ready: Callable[[], None] | None = None,
                 worker: type[RolloutWorker] = RolloutWorker,
                 trajectories: str | Path | None = None,
                 progress: bool = False, stream: TextIO | None = None
                 ) -> list[RolloutResult]:
    """Every job's result, in job order, through the job engine's dispatch.

    Serial without `ray`, else on Ray actors (`workers`: rollouts at once, default one
    per core). A job listed twice is run once. `on_ready` is called once the workers
    are up (environments built), before the first episode, so a benchmark can time
    throughput apart from start-up. `worker` may be a subclass of `RolloutWorker`
    (one that builds its own policies, say); on Ray it must be picklable.

    `trajectories` is the run's results file (`TrajectoryFile`): each finished
    episode's lines are appended the moment it ends, and a rerun reads the episodes
    already complete there (their `worker` is None) and runs only the others, as
    `bench plan` does with its results file. A rollout whose worker was lost writes
    nothing, so a rerun tries it again. A file written under other environment settings
    or for other task records of the same ids is refused (`check_resumable`) before
    anything runs or is cut.

    `progress=True` shows `bench plan`'s bar on `stream` (stderr by default): rollouts
    done of all (those read back from the trajectory file included), success per
    suite, rate and ETA.
    """
    sink = TrajectoryFile(trajectories) if trajectories is not None else None
    known = sink.complete() if sink is not None else {}
    if sink is not None and known:
        check_resumable(sink.path, known, env_kwargs, worker)
        known = sink.complete(repair=True)
    unique, found, pending = plan_resume(jobs, RolloutJob.episode, known)
    by_episode = {job.episode(): job for job in unique}
    done = {episode: recorded_result(by_episode[episode], lines)
            for episode, lines in found.items()}
    factory = rollout_factory(env_kwargs, worker)
    bar = EpisodeProgress(len(unique), done.values(), stream=stream, enabled=progress)
    try:
        for result in run_on_workers(factory, pending, ray=ray, concurrency=workers,
                                     on_ready=on_ready):
            if sink is not None:
                sink.append(result.lines)
            done[result.job.episode()] = result
            bar.update(result)
    finally:
        bar.close()
    return [done[job.episode()] if done[job.episode()].job == job
            else done[job.episode()].model_copy(update={"job": job}) for job in jobs]


def check_resumable(path: Path, known: dict[str, list[TrajectoryLine]],
                    env_kwargs: dict[str, Any], worker: type[RolloutWorker] = RolloutWorker
                    ) -> None:
    """Refuse to resume from a trajectory file written under other settings.

    An episode's id names its task, policy and seeds; what else decides its outcome is
    the environment's settings (`VeriGraphEnv.settings`: k, threshold, max_steps,
    feedback, rubric) and the task's record. Every reset line records both, so a rerun
    whose settings differ from any episode's in the file, or whose task of the same id
    is another record (an edited task file), is an error naming the first difference,
    not a report of the old run. The file is left as it is. The environment
    compared with is the one the worker builds from `env_kwargs`.
    """
    probe = worker(env_kwargs)
    try:
        env = probe._env()
        current, pool = env.settings(), {t.task_id: t for t in env.tasks}
    finally:
        probe.close()
    fix = ("rerun with the settings the file was written with, or give a new trajectory "
           "file (--trajectories) to start afresh")
    for episode, lines in known.items():
        start = lines[0]
        if start.settings is None:
            raise VeriGraphError(f"{path}: episode {episode} was written without its "
                                 "settings, so a resume cannot tell whether they match",
                                 field="trajectories", value=str(path), fix=fix)
        if start.settings != current:
            raise VeriGraphError(f"{path}: episode {episode} was played under other "
                                 f"settings: {settings_diff(start.settings, current)}",
                                 field="trajectories", value=str(path), fix=fix)
        task = start.task
        now = pool.get(task.task_id) if task is not None else None
        if task is not None and now is not None and now != task:
            what = "content hash" if now.content_hash != task.content_hash else \
                "record hash" if now.record_hash != task.record_hash else "record"
            raise VeriGraphError(f"{path}: task {task.task_id} of episode {episode} is "
                                 f"not the task of that id in this run (its {what} "
                                 "differs)", field="trajectories", value=str(path), fix=fix)


def pass_rates(results: Sequence[RolloutResult]) -> dict[str, float]:
    """pass@1 (mean success) and pass^k (every sample of a task succeeded) over tasks."""
    by_task: dict[str, list[bool]] = {}
    for r in results:
        by_task.setdefault(r.job.task_id, []).append(r.success)
    if not by_task:
        return {"pass@1": math.nan, "pass^k": math.nan}
    return {"pass@1": sum(map(sum, by_task.values())) / sum(map(len, by_task.values())),
            "pass^k": sum(all(v) for v in by_task.values()) / len(by_task)}
