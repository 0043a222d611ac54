"""Rollouts of the environment: policies, one episode, and many serially or on Ray.

A policy maps `(env, observation, info)` to the action text. `PlannerPolicy` puts any
project planner (verigraph.agent: oracle, noisy, greedy, ...) in the policy's seat by
asking it what the loop would ask (`VeriGraphEnv.planner_request`) and writing its
reply as text; `RefusedActionPolicy` answers an action the verifier always refuses.
A policy is named in a `RolloutJob` so that a Ray worker can build it itself.

`run_rollouts(jobs, env_kwargs, ray=...)` runs the jobs in this process or on Ray
(`ray="local"` starts a private Ray with this machine's cores through the evaluation
engine's `connect`; an initialised Ray is used as it is). Each Ray actor holds one
environment built from `env_kwargs`, so the kwargs must be picklable (pass `tasks`, not
a `tools` connection). Results come back in job order and carry the episode's
trajectory lines (verigraph.env.trajectory), identical serially and on Ray.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterator, Sequence
from typing import Any, Literal, Protocol

from pydantic import BaseModel, ConfigDict, Field

from verigraph.agent.evaluation.ray_runner import connect
from verigraph.agent.factory import PlannerOptions, make_planner
from verigraph.agent.planner import Planner
from verigraph.env.core import VeriGraphEnv
from verigraph.env.trajectory import TrajectoryLine, reset_line, step_line
from verigraph.errors import VeriGraphError
from verigraph.extras import require

PolicyName = Literal["oracle", "noisy", "greedy", "refuse"]
REFUSED_ACTION = "move(no_such_object, on, table)"
QUEUE_PER_WORKER = 2


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
        return f"{self.task_id}#{self.policy}:{self.policy_seed}@{self.seed}"


class RolloutResult(BaseModel):
    """An episode's outcome and its trajectory lines."""

    job: RolloutJob
    episode_return: float
    steps: int
    moves: int = Field(description="actions the verifier executed")
    success: bool
    stop_reason: str | None
    lines: list[TrajectoryLine]
    worker: int = Field(description="process id that ran it")


def run_rollout(env: VeriGraphEnv, policy: Policy, job: RolloutJob) -> RolloutResult:
    """Run one episode of `job` on `env` with `policy` until it ends."""
    episode = job.episode()
    observation, info = env.reset(seed=job.seed, options={"task": job.task_id})
    assert env.task is not None
    lines = [reset_line(episode, env.task, job.seed, observation, info)]
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
    """One environment and the policies jobs name; the serial path and a Ray actor alike."""

    def __init__(self, env_kwargs: dict[str, Any]) -> None:
        self.env = VeriGraphEnv(**env_kwargs)

    def ready(self) -> bool:
        return True

    def run(self, job: RolloutJob) -> RolloutResult:
        policy = make_policy(job.policy, job.policy_seed, job.noise)
        return run_rollout(self.env, policy, job)

    def close(self) -> None:
        self.env.close()


def _ray_results(ray: Any, workers: list[Any], jobs: Sequence[RolloutJob]
                 ) -> Iterator[tuple[int, RolloutResult]]:
    queue = iter(enumerate(jobs))
    in_flight: dict[Any, int] = {}
    turn = 0
    while True:
        while len(in_flight) < len(workers) * QUEUE_PER_WORKER \
                and (item := next(queue, None)) is not None:
            in_flight[workers[turn % len(workers)].run.remote(item[1])] = item[0]
            turn += 1
        if not in_flight:
            return
        ready, _ = ray.wait(list(in_flight), num_returns=1)
        for ref in ready:
            yield in_flight.pop(ref), ray.get(ref)


def run_rollouts(jobs: Sequence[RolloutJob], env_kwargs: dict[str, Any], *,
                 ray: str | None = None, workers: int | None = None,
                 on_ready: Callable[[], None] | None = None) -> list[RolloutResult]:
    """Every job's result, in job order; serial without `ray`, else on Ray actors.

    `on_ready` is called once the workers are up (environments built), before the first
    episode, so a benchmark can time throughput apart from start-up.
    """
    if ray is None:
        worker = RolloutWorker(env_kwargs)
        try:
            if on_ready is not None:
                on_ready()
            return [worker.run(job) for job in jobs]
        finally:
            worker.close()
    require("scale", "ray")
    import ray as ray_module

    started = connect(ray)
    actors: list[Any] = []
    try:
        cpus = max(1, int(ray_module.cluster_resources().get("CPU", 1)))
        count = max(1, min(workers or cpus, len(jobs) or 1))
        remote = ray_module.remote(RolloutWorker).options(num_cpus=min(1.0, cpus / count))
        actors = [remote.remote(env_kwargs) for _ in range(count)]
        ray_module.get([a.ready.remote() for a in actors])
        if on_ready is not None:
            on_ready()
        results: list[RolloutResult | None] = [None] * len(jobs)
        for index, result in _ray_results(ray_module, actors, jobs):
            results[index] = result
        return [r for r in results if r is not None]
    finally:
        for actor in actors:
            ray_module.kill(actor)
        if started:
            ray_module.shutdown()


def pass_rates(results: Sequence[RolloutResult]) -> dict[str, float]:
    """pass@1 (mean success) and pass^k (every sample of a task succeeded) over tasks."""
    by_task: dict[str, list[bool]] = {}
    for r in results:
        by_task.setdefault(r.job.task_id, []).append(r.success)
    if not by_task:
        return {"pass@1": math.nan, "pass^k": math.nan}
    return {"pass@1": sum(map(sum, by_task.values())) / sum(map(len, by_task.values())),
            "pass^k": sum(all(v) for v in by_task.values()) / len(by_task)}
