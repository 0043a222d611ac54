"""Task records as prompt rows, and as a Hugging Face `datasets.Dataset` when installed.

A row is what LLM-RL frameworks load: the task's first prompt as chat messages (the
environment's first observation, so the words are exactly those a rollout starts
from), the difficulty columns, the split, and the whole task record as a JSON string
in `info` for the environment to start the episode from. The prompt of a language task
shows only its instruction; its ground-truth goal graph is in `info`, which is the
verifier's, not the model's.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from verigraph.env.core import VeriGraphEnv
from verigraph.env.dataset import DEFAULT_TEST_FRACTION, split_of
from verigraph.errors import VeriGraphError
from verigraph.tasks.task import Task


def prompt_rows(records: Iterable[Task], *, test_fraction: float = DEFAULT_TEST_FRACTION,
                **env_kwargs: Any) -> list[dict[str, Any]]:
    """One row per task: prompt messages, difficulty, split and the record as JSON."""
    records = list(records)
    if not records:
        return []
    env = VeriGraphEnv(tasks=records, **env_kwargs)
    try:
        rows = []
        for record in records:
            observation, _ = env.reset(options={"task": record})
            rows.append({
                "task_id": record.task_id, "family": record.family, "group": record.group,
                "kind": record.kind, "optimal_length": record.optimal_length,
                "objects": record.objects, "split": split_of(record.content_hash, test_fraction),
                "content_hash": record.content_hash,
                "prompt": [{"role": "user", "content": observation}],
                "info": record.model_dump_json()})
        return rows
    finally:
        env.close()


def to_hf_dataset(records: Iterable[Task], **kwargs: Any) -> Any:
    """`datasets.Dataset.from_list(prompt_rows(...))`; needs the `datasets` package."""
    try:
        import datasets
    except ImportError:
        raise VeriGraphError("the datasets package is not installed", field="datasets",
                             fix="pip install datasets (or use prompt_rows / write_jsonl)"
                             ) from None
    return datasets.Dataset.from_list(prompt_rows(records, **kwargs))
