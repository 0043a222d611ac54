"""A task: a scene with a goal, what a prompt or a score reads of it, and its identity.

One type serves the benchmark (verigraph.agent.evaluation runs a task as episodes), the
environment (verigraph.env serves it through `reset`) and the stored datasets (JSONL, one
task per line). A task is built once, by `Task.create`, which computes its two hashes:

- `content_hash` covers only what defines the task, the scene and the goal (canonical
  JSON, graphs in canonical order), never its id or seed: the same task drawn from two
  seeds has the same content hash, and splits are cut by it alone;
- `record_hash` covers the content hash and every other field that reaches a prompt, a
  score or a selection (`RECORD_FIELDS`), again never the id: a task read back must
  match both, so no such field can be edited unnoticed. `template` and `category` (the
  language tasks' labels) join the hash only when set, so tasks without them keep the
  hash they always had.

The id is `group/index` as the benchmark draws it; the environment's pools add the seed
(`group/seed/index`), which changes neither hash.
"""

from __future__ import annotations

import hashlib
import json
from typing import Any, Literal, get_args

from pydantic import BaseModel, ConfigDict, Field

from verigraph.graph.goal import Goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState

SUITE_VERSION = "2"
Family = Literal["blocks", "kitchen", "tangram", "household", "behavior"]
FAMILIES: tuple[Family, ...] = get_args(Family)
# The paper's five groups (the benchmark's default), and the household and BEHAVIOR-1K
# groups beside them.
PaperGroup = Literal["stacking", "language", "ref_image_kitchen", "ref_image_blocks",
                     "tangram"]
GroupName = PaperGroup | Literal["household", "behavior"]
GROUPS: tuple[GroupName, ...] = get_args(PaperGroup)
ALL_GROUPS: tuple[GroupName, ...] = (*GROUPS, "household", "behavior")

RECORD_FIELDS = ("family", "group", "kind", "optimal_length", "objects", "show_goal_graph",
                 "instruction", "suite_version")
LABEL_FIELDS = ("template", "category")  # in the record hash when set


class EpisodeSpec(BaseModel):
    """How to start one episode: raw `load_scene` and optional `set_goal` arguments.

    `show_goal_graph=False` hides the goal graph from LLM prompts (instruction tasks:
    the planner reads the words, the verifier checks the ground-truth graph).
    """

    model_config = ConfigDict(extra="forbid")

    task_id: str | None = None
    load: dict[str, Any] = Field(description="load_scene arguments (without k and t)")
    set_goal: dict[str, Any] | None = Field(default=None,
                                            description="set_goal arguments (no episode_id)")
    show_goal_graph: bool = True


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


def hash_record(content: str, fields: dict[str, Any]) -> str:
    """sha256 of a task's content hash, its `RECORD_FIELDS` and its set `LABEL_FIELDS`
    (canonical JSON)."""
    labels = {name: fields[name] for name in LABEL_FIELDS if fields.get(name) is not None}
    blob = json.dumps({"content_hash": content,
                       **{name: fields.get(name) for name in RECORD_FIELDS}, **labels},
                      sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(blob.encode("utf-8")).hexdigest()


class Task(BaseModel):
    """One task: how to load it, what it is, how hard it is, and the hashes that identify
    it (see the module docstring)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    task_id: str = Field(description="group/index (group/seed/index in a pool)")
    family: Family
    group: GroupName
    kind: str = Field(description="the task's kind within its group (ordered, reversal, ...)")
    optimal_length: int = Field(ge=0, description="moves in the reference solver's plan")
    objects: int = Field(ge=0, description="movable objects in the scene")
    load: dict[str, Any] = Field(description="load_scene arguments (without k and t)")
    set_goal: dict[str, Any] | None = Field(description="set_goal arguments")
    show_goal_graph: bool = Field(description="False: the prompt shows only the instruction")
    instruction: str | None = None
    template: str | None = Field(default=None, description="language: the template id")
    category: str | None = Field(default=None, description="language: what it exercises")
    suite_version: str = SUITE_VERSION
    content_hash: str = Field(description="sha256 of the scene and goal: the task itself")
    record_hash: str = Field(description="sha256 of content_hash and every other field "
                                         "but the id (see RECORD_FIELDS)")

    @classmethod
    def create(cls, *, task_id: str, load: dict[str, Any], set_goal: dict[str, Any] | None,
               **fields: Any) -> Task:
        """A task with its object count and both hashes computed from its fields."""
        graph = SceneGraph.model_validate(load["graph"])
        fields.setdefault("objects", sum(
            o.props.movable for o in WorldState.from_graph(graph).objects.values()))
        fields.setdefault("suite_version", SUITE_VERSION)
        digest = content_hash(load, set_goal)
        return cls(task_id=task_id, load=load, set_goal=set_goal, content_hash=digest,
                   record_hash=hash_record(digest, fields), **fields)

    def expected_record_hash(self) -> str:
        """The record hash this task's fields give (equal to `record_hash` unless one was
        edited)."""
        return hash_record(self.content_hash,
                           self.model_dump(include={*RECORD_FIELDS, *LABEL_FIELDS}))

    @property
    def spec(self) -> EpisodeSpec:
        """How an episode of this task starts."""
        return EpisodeSpec(task_id=self.task_id, load=self.load, set_goal=self.set_goal,
                           show_goal_graph=self.show_goal_graph)

    @property
    def goal(self) -> Goal | None:
        """The goal `set_goal` sets when it gives a graph or a formula (the language
        tasks' ground truth); None for a goal given as an image."""
        if not self.set_goal or not {"graph", "formula"} & set(self.set_goal):
            return None
        return Goal.model_validate({k: v for k, v in self.set_goal.items()
                                    if k in Goal.model_fields})
