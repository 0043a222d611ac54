"""The benchmark suites as task datasets: pools, splits, difficulty knobs, JSONL.

A dataset is a list of `Task`s (verigraph.tasks.task): how to load the scene and set the
goal, family and group, difficulty (optimal plan length from the reference solver, object
count) and two hashes. The `content_hash` covers only the scene and goal, never the id or
seed, so the same task drawn from two seeds has the same hash; the `record_hash` covers
every other field that reaches a prompt, a score or a selection (whether the prompt shows
the goal graph, the instruction, the optimal length the efficiency reward divides by, the
family, group, kind, object count and suite version), again never the id: a task read
back must match both, so no such field can be edited unnoticed.

Splits are decided by that hash alone (`split_of`): a task lands in the same split in
every pool, whatever seed or size built the pool, so a train and a test split can never
share a task; `check_disjoint` verifies it on any two lists, and `read_jsonl` recomputes
every hash so an edited line cannot pass as the task it claims to be.

Language tasks keep their ground-truth goal graph in `set_goal` (the verifier needs it)
with `show_goal_graph=False`: the environment's prompt shows only the instruction.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any, Literal, get_args

from pydantic import ValidationError

from verigraph.env.jsonl import read_models, write_models
from verigraph.errors import VeriGraphError
from verigraph.tasks.groups import build_groups
from verigraph.tasks.task import FAMILIES, SUITE_VERSION, Family, GroupName, Task, content_hash

Split = Literal["train", "test"]
FAMILY_GROUPS: dict[Family, tuple[GroupName, ...]] = {
    "blocks": ("stacking", "language", "ref_image_blocks"),
    "kitchen": ("ref_image_kitchen",),
    "tangram": ("tangram",),
    "household": ("household",),
    "behavior": ("behavior",),
}
DEFAULT_TEST_FRACTION = 0.2
HASH_SPACE = 16 ** 12
SUITE_PER_GROUP = 40  # the bundled suites: this many tasks per group, seed 0


def split_of(digest: str, test_fraction: float = DEFAULT_TEST_FRACTION) -> Split:
    """The split a content hash belongs to: a fixed cut of the hash space."""
    if not 0.0 <= test_fraction <= 1.0:
        raise VeriGraphError("test_fraction must lie between 0 and 1", field="test_fraction",
                             value=test_fraction, fix="use e.g. 0.2")
    return "test" if int(digest[:12], 16) < test_fraction * HASH_SPACE else "train"


@cache
def _suite(family: Family, per_group: int, seed: int) -> tuple[Task, ...]:
    groups = build_groups(FAMILY_GROUPS[family], per_group, seed, ground_truth=True)
    records: dict[str, Task] = {}
    for group in groups:
        for task in group.tasks:
            index = task.task_id.rsplit("/", 1)[-1]
            record = task.model_copy(update={"task_id": f"{task.group}/{seed}/{index}"})
            records.setdefault(record.content_hash, record)  # a repeated draw is one task
    return tuple(records.values())


def build_tasks(family: Family | str, per_group: int = 20, seed: int = 0
                ) -> list[Task]:
    """A family's tasks from the benchmark suites: `per_group` of each of its groups.

    Built once per process and argument set (the kitchen group runs the solver on each
    draw, about 0.1 s a task); identical draws are kept once.
    """
    if family not in FAMILY_GROUPS:
        raise VeriGraphError(f"unknown task family '{family}'", field="family", value=family,
                             fix=f"use one of {', '.join(FAMILIES)}")
    if not 1 <= per_group <= 10_000:
        raise VeriGraphError("per_group must be between 1 and 10000", field="per_group",
                             value=per_group, fix="use e.g. 20")
    return list(_suite(family, per_group, seed))


def suite_path(family: Family) -> Path:
    """The bundled JSONL suite of a family (verigraph/env/data/FAMILY.jsonl)."""
    return Path(str(resources.files("verigraph.env").joinpath("data", f"{family}.jsonl")))


@cache
def _bundled(family: Family) -> tuple[Task, ...]:
    return tuple(read_jsonl(suite_path(family)))


def suite_tasks(family: Family | str) -> list[Task]:
    """The bundled suite of a family: a frozen draw of `build_tasks(family,
    SUITE_PER_GROUP, 0)`, read from the package's JSONL (hash-checked) instead of drawn
    again (for the kitchen group that runs the solver on every draw). A frozen draw stays
    the same dataset when a scene generator changes; `write_suites` draws it afresh. A
    file from another suite version is ignored and the suite built instead."""
    if family not in FAMILY_GROUPS:
        raise VeriGraphError(f"unknown task family '{family}'", field="family", value=family,
                             fix=f"use one of {', '.join(FAMILIES)}")
    records = list(_bundled(family))
    if any(r.suite_version != SUITE_VERSION for r in records):
        return build_tasks(family, SUITE_PER_GROUP, 0)
    return records


def write_suites(directory: str | Path | None = None) -> list[Path]:
    """Write every family's bundled suite (into the package unless `directory`)."""
    paths = []
    for family in FAMILIES:
        path = suite_path(family) if directory is None else Path(directory) / f"{family}.jsonl"
        path.parent.mkdir(parents=True, exist_ok=True)
        write_jsonl(build_tasks(family, SUITE_PER_GROUP, 0), path)
        paths.append(path)
    return paths


def split_tasks(records: Iterable[Task], split: Split,
                test_fraction: float = DEFAULT_TEST_FRACTION) -> list[Task]:
    """The records of one split (by content hash; see `split_of`)."""
    if split not in get_args(Split):
        raise VeriGraphError(f"unknown split '{split}'", field="split", value=split,
                             fix="use train or test")
    return [r for r in records if split_of(r.content_hash, test_fraction) == split]


def check_disjoint(train: Sequence[Task], test: Sequence[Task]) -> None:
    """Raise when a task (by content hash, recomputed) is in both lists."""
    def hashes(records: Sequence[Task]) -> dict[str, str]:
        return {content_hash(r.load, r.set_goal): r.task_id for r in records}

    shared = set(hashes(train)) & set(hashes(test))
    if shared:
        ids = sorted(hashes(train)[h] for h in shared)
        raise VeriGraphError(f"{len(shared)} task(s) are in both splits: {', '.join(ids[:5])}",
                             field="split", value=ids[:5],
                             fix="split by content hash (split_tasks) instead of by id")


def select(records: Iterable[Task], *, family: str | None = None,
           groups: Sequence[str] | None = None, min_optimal: int | None = None,
           max_optimal: int | None = None, min_objects: int | None = None,
           max_objects: int | None = None) -> list[Task]:
    """The difficulty knobs: family, groups, optimal plan length and object count ranges."""
    def keep(r: Task) -> bool:
        return ((family is None or r.family == family)
                and (groups is None or r.group in groups)
                and (min_optimal is None or r.optimal_length >= min_optimal)
                and (max_optimal is None or r.optimal_length <= max_optimal)
                and (min_objects is None or r.objects >= min_objects)
                and (max_objects is None or r.objects <= max_objects))

    return [r for r in records if keep(r)]


def write_jsonl(records: Iterable[Task], path: str | Path) -> int:
    """One JSON task per line; returns the number written."""
    return write_models(records, path, append=False, exclude_none=False)


def read_jsonl(path: str | Path) -> list[Task]:
    """Tasks from a JSONL file; a bad line or a hash that does not match is an error."""
    rows = read_models(path, Task, what="task file",
                       fix="pass a JSONL file of tasks written by write_jsonl")
    return [_checked(record, f"{path}:{number}", f"line {number}") for number, record in rows]


def _checked(record: Task, where: str, field: str) -> Task:
    """The record, if its scene and goal still match its content hash and every other
    field its record hash."""
    try:
        digest = content_hash(record.load, record.set_goal)
    except (ValidationError, ValueError, RecursionError, TypeError) as exc:
        # a graph that is not one, a number json cannot write, nesting past the limit
        detail = exc.errors()[0]["msg"] if isinstance(exc, ValidationError) else str(exc)
        raise VeriGraphError(f"{where}: task {record.task_id}: its scene or goal cannot be "
                             f"read: {detail[:200]}", field=field, value=record.task_id,
                             fix="rebuild the task with build_tasks and write_jsonl") from None
    if digest != record.content_hash:
        raise VeriGraphError(
            f"{where}: task {record.task_id} does not match its content_hash",
            field=field, value=record.task_id,
            fix="a task's scene or goal was edited; rebuild it with build_tasks or "
                "write_jsonl")
    if record.expected_record_hash() != record.record_hash:
        raise VeriGraphError(
            f"{where}: task {record.task_id} does not match its record_hash",
            field=field, value=record.task_id,
            fix="a field that reaches the prompt or the reward (show_goal_graph, "
                "instruction, optimal_length, ...) was edited; rebuild the task with "
                "build_tasks and write_jsonl")
    return record


def load_tasks(tasks: str | Path | Sequence[Task | dict[str, Any]]) -> list[Task]:
    """Tasks from a JSONL path, or records (or their dicts) given directly."""
    if isinstance(tasks, str | Path):
        return read_jsonl(tasks)
    out = []
    for index, item in enumerate(tasks):
        try:
            record = item if isinstance(item, Task) else Task.model_validate(item)
        except ValidationError as exc:
            err = exc.errors()[0]
            where = ".".join(str(p) for p in err["loc"]) or "task"
            raise VeriGraphError(f"tasks[{index}]: {where}: {err['msg']}",
                                 field=f"tasks[{index}]", value=where,
                                 fix="pass task records from build_tasks or read_jsonl"
                                 ) from None
        out.append(_checked(record, f"tasks[{index}]", f"tasks[{index}]"))
    return out
