"""What one benchmark episode is, as data: task, suite version, planner settings, seed.

An `EpisodeJob` is small and self-describing, so it can be shipped to a Ray worker,
written next to its result, and compared on a rerun: its `key()` hashes everything
that decides the outcome (the task's content, the settings, the seed) and nothing
that does not (where or when it ran), which is what makes resuming safe. The task's
content hash guards against a changed task generator silently reusing old results.
"""

from __future__ import annotations

import hashlib
import json
import zlib
from collections.abc import Iterable

from pydantic import BaseModel, ConfigDict, Field

from verigraph import __version__
from verigraph.planning.iteration import DEFAULT_K, DEFAULT_THRESHOLD
from verigraph.planning.models import DonePolicy, FeedbackMode, Mode
from verigraph.tasks.groups import GroupTasks
from verigraph.tasks.task import SUITE_VERSION, GroupName, Task


class Setting(BaseModel):
    """One row of a table: a planner with its loop parameters."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    planner: str
    mode: Mode = "iterative"
    k: int = DEFAULT_K
    threshold: int = DEFAULT_THRESHOLD  # the error threshold t
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

    def transcript_key(self, task_id: str) -> str:
        """Where this setting's transcript of one task is recorded or replayed."""
        return f"{self.label()}__{task_id}"


def episode_seed(task_id: str, setting: Setting, sample: int = 0) -> int:
    """The planner's seed: fixed by task, setting and sample, independent of run order.

    Sample 0 keeps the seed it had before samples existed, so old results files resume.
    """
    suffix = f"|{sample}" if sample else ""
    return zlib.crc32(f"{task_id}|{setting.label()}{suffix}".encode())


def suite_version(seed: int, *, ground_truth: bool, simulate: bool) -> str:
    """The task suite an episode belongs to, in words a reader can match across files."""
    graphs = "ground-truth-goals" if ground_truth else "perceived-goals"
    execution = "simulated" if simulate else "graph-only"
    return f"plan-{__version__}/suite={SUITE_VERSION}/seed={seed}/{graphs}/{execution}"


class EpisodeJob(BaseModel):
    """One episode to run: enough to find its task and rebuild its planner anywhere."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    suite: str
    task_id: str
    task_hash: str = Field(description="the first 12 hex digits of the task's record_hash")
    group: GroupName
    setting: Setting
    seed: int
    sample: int = Field(default=0, ge=0, description="which of k samples of the task (pass^k)")

    @property
    def task_ref(self) -> str:
        return f"{self.task_id}@{self.task_hash}"

    def key(self) -> str:
        """Identity for resuming: the same key means the same outcome."""
        parts: list[object] = [self.task_id, self.task_hash,
                               self.setting.model_dump(mode="json"), self.seed]
        if self.sample:
            parts.append(self.sample)  # sample 0 keeps its key from before samples existed
        payload = json.dumps(parts, sort_keys=True)
        return hashlib.sha256(payload.encode()).hexdigest()[:20]


def job_for(task: Task, setting: Setting, suite: str, sample: int = 0) -> EpisodeJob:
    return EpisodeJob(suite=suite, task_id=task.task_id, task_hash=task.record_hash[:12],
                      group=task.group, setting=setting,
                      seed=episode_seed(task.task_id, setting, sample), sample=sample)


def jobs_for(setting: Setting, groups: Iterable[GroupTasks], suite: str,
             samples: int = 1) -> list[EpisodeJob]:
    """Every runnable episode of one setting (groups that cannot run are left out),
    `samples` times per task with a different planner seed each (for pass^k)."""
    return [job_for(task, setting, suite, sample) for group in groups
            if group.not_run is None for task in group.tasks for sample in range(samples)]


def task_index(groups: Iterable[GroupTasks]) -> dict[str, Task]:
    """Tasks by `EpisodeJob.task_ref`, what a worker looks jobs up in."""
    return {f"{task.task_id}@{task.record_hash[:12]}": task for group in groups
            for task in group.tasks}
