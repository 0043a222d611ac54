"""Benchmark results as a dataset: one JSON line per finished episode.

The file is the run's memory. Each record is appended and flushed the moment its
episode finishes, so killing the driver loses at most the episodes in flight; a rerun
reads the file and skips every job whose key is already there. A line cut off by the
kill (no trailing newline) is dropped and the file truncated back to the last whole
record before anything is appended. Flushing hands each line to the operating
system; it survives the process dying, not the machine losing power.
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from pydantic import BaseModel, Field, ValidationError

from verigraph.agent.evaluation.spec import EpisodeJob
from verigraph.errors import VeriGraphError
from verigraph.tasks.groups import GroupName


class BenchRecord(BaseModel):
    """Everything known about one finished benchmark episode (one line of the results
    file); not the server's stored episode (`tools.records`), hence its own name."""

    key: str = Field(description="EpisodeJob.key(): identity for resuming")
    suite: str
    task_id: str
    task_hash: str
    group: GroupName
    planner: str = Field(description="planner backend name, e.g. noisy or openai:MODEL")
    settings: dict[str, Any] = Field(description="the Setting: mode, k, threshold, ...")
    label: str = Field(description="the setting's row label in tables")
    seed: int
    sample: int = Field(default=0, description="which of k samples of the task (pass^k)")
    success: bool
    stop_reason: str | None = None
    iterations: int = 0
    planner_calls: int = 0
    requests: int = Field(default=0, description="requests sent to the backend, retries included")
    retries: int = 0
    actions: int = 0
    violations: int = 0
    malformed: int = 0
    premature_done: int = 0
    prompt_tokens: int | None = None
    completion_tokens: int | None = None
    total_tokens: int | None = None
    cost_usd: float | None = None
    wall_s: float = 0.0
    trace_path: str | None = None
    error: str | None = None
    error_kind: str | None = Field(default=None, description="planner, tool or internal")
    worker: str | None = Field(default=None, description="host:pid that ran it")

    def outcome(self) -> dict[str, Any]:
        """The fields a rerun must reproduce exactly (no timing, no place)."""
        return self.model_dump(exclude={"wall_s", "trace_path", "worker"})


def blank_record(job: EpisodeJob, planner: str) -> BenchRecord:
    return BenchRecord(key=job.key(), suite=job.suite, task_id=job.task_id,
                         task_hash=job.task_hash, group=job.group, planner=planner,
                         settings=job.setting.model_dump(mode="json"),
                         label=job.setting.label(), seed=job.seed, sample=job.sample,
                       success=False)


class ResultsFile:
    """Append-only JSONL of `BenchRecord`s."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)

    def load(self, repair: bool = False) -> list[BenchRecord]:
        """Every whole record; with `repair`, cut a partial last line off the file."""
        if not self.path.exists():
            return []
        data = self.path.read_bytes()
        end = data.rfind(b"\n") + 1
        if repair and end < len(data):
            with self.path.open("r+b") as handle:
                handle.truncate(end)
        records = []
        for number, line in enumerate(data[:end].decode("utf-8").splitlines(), 1):
            if not line.strip():
                continue
            try:
                records.append(BenchRecord.model_validate(json.loads(line)))
            except (json.JSONDecodeError, ValidationError) as exc:
                raise VeriGraphError(
                    f"line {number} of {self.path} is not an episode record: "
                    f"{str(exc).splitlines()[0]}", field="--results", value=str(self.path),
                    fix="point --results at a file written by verigraph bench plan, or at "
                        "a new file") from None
        return records

    def append(self, records: Iterable[BenchRecord]) -> None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        text = "".join(r.model_dump_json() + "\n" for r in records)
        if not text:
            return
        with self.path.open("a", encoding="utf-8") as handle:
            handle.write(text)
            handle.flush()
