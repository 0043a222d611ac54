"""The benchmark suites as task datasets: records, content hashes, splits, JSONL.

A `TaskRecord` is one benchmark task (verigraph.tasks.groups) in a form a
training pipeline can store: how to load the scene and set the goal, its family and
group, and its difficulty (optimal plan length from the reference solver, object count).
Its `content_hash` covers only what defines the task (scene and goal), never its id or
seed, so the same task drawn from two seeds has the same hash. Its `record_hash` covers
every other field too (whether the prompt shows the goal graph, the instruction, the
optimal length the efficiency reward divides by, the family, group, kind, object count
and suite version), again never the id: a record read back must match both, so no field
that reaches a prompt, a score or a selection can be edited unnoticed.

Splits are decided by that hash alone (`split_of`): a task lands in the same split in
every pool, whatever seed or size built the pool, so a train and a test split can never
share a task; `check_disjoint` verifies it on any two lists, and `read_jsonl` recomputes
every hash so an edited line cannot pass as the task it claims to be.

Language tasks keep their ground-truth goal graph in `set_goal` (the verifier needs it)
with `show_goal_graph=False`: the environment's prompt shows only the instruction.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Iterable, Sequence
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any, Literal, get_args

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from verigraph.env.jsonl import read_models, write_models
from verigraph.errors import VeriGraphError
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.tasks.groups import SUITE_VERSION, GroupName, Task, build_groups

Family = Literal["blocks", "kitchen", "tangram"]
FAMILIES: tuple[Family, ...] = get_args(Family)
Split = Literal["train", "test"]
FAMILY_GROUPS: dict[Family, tuple[GroupName, ...]] = {
    "blocks": ("stacking", "language", "ref_image_blocks"),
    "kitchen": ("ref_image_kitchen",),
    "tangram": ("tangram",),
}
DEFAULT_TEST_FRACTION = 0.2
HASH_SPACE = 16 ** 12
SUITE_PER_GROUP = 40  # the bundled suites: this many tasks per group, seed 0


def content_hash(load: dict[str, Any], set_goal: dict[str, Any] | None) -> str:
    """sha256 of the scene and goal alone (canonical JSON, graphs in canonical order)."""
    def canon(value: Any) -> Any:
        if isinstance(value, dict):
            if "nodes" in value and "edges" in value:
                graph = SceneGraph.model_validate(value).canonical()
                return graph.model_dump(mode="json", exclude_none=True)
            return {k: canon(v) for k, v in value.items()}
        if isinstance(value, list):
            return [canon(v) for v in value]
        return value

    blob = json.dumps({"load": canon(load), "set_goal": canon(set_goal)}, sort_keys=True,
                      separators=(",", ":"))
    return hashlib.sha256(blob.encode("utf-8")).hexdigest()


RECORD_FIELDS = ("family", "group", "kind", "optimal_length", "objects", "show_goal_graph",
                 "instruction", "suite_version")


def hash_record(content: str, fields: dict[str, Any]) -> str:
    """sha256 of a record's content hash and its `RECORD_FIELDS` (canonical JSON)."""
    blob = json.dumps({"content_hash": content,
                       **{name: fields.get(name) for name in RECORD_FIELDS}},
                      sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(blob.encode("utf-8")).hexdigest()


class TaskRecord(BaseModel):
    """One task of a suite, with its difficulty and the hash that identifies it."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    task_id: str = Field(description="group/seed/index; unique within a pool")
    family: Family
    group: GroupName
    kind: str = Field(description="the task's kind within its group (ordered, reversal, ...)")
    optimal_length: int = Field(ge=0, description="moves in the reference solver's plan")
    objects: int = Field(ge=0, description="movable objects in the scene")
    load: dict[str, Any] = Field(description="load_scene arguments (without k and t)")
    set_goal: dict[str, Any] | None = Field(description="set_goal arguments")
    show_goal_graph: bool = Field(description="False: the prompt shows only the instruction")
    instruction: str | None = None
    suite_version: str = SUITE_VERSION
    content_hash: str = Field(description="sha256 of the scene and goal: the task itself")
    record_hash: str = Field(description="sha256 of content_hash and every other field "
                                         "but the id (see RECORD_FIELDS)")

    @classmethod
    def from_task(cls, task: Task, family: Family, seed: int) -> TaskRecord:
        load = dict(task.spec.load)
        graph = SceneGraph.model_validate(load["graph"])
        objects = sum(o.props.movable for o in WorldState.from_graph(graph).objects.values())
        index = task.task_id.rsplit("/", 1)[-1]
        fields: dict[str, Any] = {
            "family": family, "group": task.group, "kind": task.kind,
            "optimal_length": task.optimal_length, "objects": objects,
            "show_goal_graph": task.spec.show_goal_graph, "instruction": task.instruction,
            "suite_version": SUITE_VERSION}
        digest = content_hash(load, task.spec.set_goal)
        return cls(task_id=f"{task.group}/{seed}/{index}", load=load,
                   set_goal=task.spec.set_goal, content_hash=digest,
                   record_hash=hash_record(digest, fields), **fields)

    def expected_record_hash(self) -> str:
        """The record hash this record's fields give (equal to `record_hash` unless one
        was edited)."""
        return hash_record(self.content_hash, self.model_dump(include=set(RECORD_FIELDS)))

    def split(self, test_fraction: float = DEFAULT_TEST_FRACTION) -> Split:
        return split_of(self.content_hash, test_fraction)


def split_of(digest: str, test_fraction: float = DEFAULT_TEST_FRACTION) -> Split:
    """The split a content hash belongs to: a fixed cut of the hash space."""
    if not 0.0 <= test_fraction <= 1.0:
        raise VeriGraphError("test_fraction must lie between 0 and 1", field="test_fraction",
                             value=test_fraction, fix="use e.g. 0.2")
    return "test" if int(digest[:12], 16) < test_fraction * HASH_SPACE else "train"


@cache
def _suite(family: Family, per_group: int, seed: int) -> tuple[TaskRecord, ...]:
    groups = build_groups(FAMILY_GROUPS[family], per_group, seed, ground_truth=True)
    records: dict[str, TaskRecord] = {}
    for group in groups:
        for task in group.tasks:
            record = TaskRecord.from_task(task, family, seed)
            records.setdefault(record.content_hash, record)  # a repeated draw is one task
    return tuple(records.values())


def build_tasks(family: Family | str, per_group: int = 20, seed: int = 0
                ) -> list[TaskRecord]:
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
def _bundled(family: Family) -> tuple[TaskRecord, ...]:
    return tuple(read_jsonl(suite_path(family)))


def suite_tasks(family: Family | str) -> list[TaskRecord]:
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


def split_tasks(records: Iterable[TaskRecord], split: Split,
                test_fraction: float = DEFAULT_TEST_FRACTION) -> list[TaskRecord]:
    """The records of one split (by content hash; see `split_of`)."""
    if split not in get_args(Split):
        raise VeriGraphError(f"unknown split '{split}'", field="split", value=split,
                             fix="use train or test")
    return [r for r in records if r.split(test_fraction) == split]


def check_disjoint(train: Sequence[TaskRecord], test: Sequence[TaskRecord]) -> None:
    """Raise when a task (by content hash, recomputed) is in both lists."""
    def hashes(records: Sequence[TaskRecord]) -> dict[str, str]:
        return {content_hash(r.load, r.set_goal): r.task_id for r in records}

    shared = set(hashes(train)) & set(hashes(test))
    if shared:
        ids = sorted(hashes(train)[h] for h in shared)
        raise VeriGraphError(f"{len(shared)} task(s) are in both splits: {', '.join(ids[:5])}",
                             field="split", value=ids[:5],
                             fix="split by content hash (split_tasks) instead of by id")


def select(records: Iterable[TaskRecord], *, family: str | None = None,
           groups: Sequence[str] | None = None, min_optimal: int | None = None,
           max_optimal: int | None = None, min_objects: int | None = None,
           max_objects: int | None = None) -> list[TaskRecord]:
    """The difficulty knobs: family, groups, optimal plan length and object count ranges."""
    def keep(r: TaskRecord) -> bool:
        return ((family is None or r.family == family)
                and (groups is None or r.group in groups)
                and (min_optimal is None or r.optimal_length >= min_optimal)
                and (max_optimal is None or r.optimal_length <= max_optimal)
                and (min_objects is None or r.objects >= min_objects)
                and (max_objects is None or r.objects <= max_objects))

    return [r for r in records if keep(r)]


def write_jsonl(records: Iterable[TaskRecord], path: str | Path) -> int:
    """One JSON task per line; returns the number written."""
    return write_models(records, path, append=False, exclude_none=False)


def read_jsonl(path: str | Path) -> list[TaskRecord]:
    """Tasks from a JSONL file; a bad line or a hash that does not match is an error."""
    rows = read_models(path, TaskRecord, what="task file",
                       fix="pass a JSONL file of tasks written by write_jsonl")
    return [_checked(record, f"{path}:{number}", f"line {number}") for number, record in rows]


def _checked(record: TaskRecord, where: str, field: str) -> TaskRecord:
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


def load_tasks(tasks: str | Path | Sequence[TaskRecord | dict[str, Any]]) -> list[TaskRecord]:
    """Tasks from a JSONL path, or records (or their dicts) given directly."""
    if isinstance(tasks, str | Path):
        return read_jsonl(tasks)
    out = []
    for index, item in enumerate(tasks):
        try:
            record = item if isinstance(item, TaskRecord) else TaskRecord.model_validate(item)
        except ValidationError as exc:
            err = exc.errors()[0]
            where = ".".join(str(p) for p in err["loc"]) or "task"
            raise VeriGraphError(f"tasks[{index}]: {where}: {err['msg']}",
                                 field=f"tasks[{index}]", value=where,
                                 fix="pass task records from build_tasks or read_jsonl"
                                 ) from None
        out.append(_checked(record, f"tasks[{index}]", f"tasks[{index}]"))
    return out
