"""A curriculum over the procedural tasks, in the Reasoning Gym style.

Reasoning Gym's datasets are indexable lists of entries `{"question", "answer",
"metadata"}` with a `score_answer(answer, entry)` in [0, 1], built from a config that a
curriculum object moves through attribute levels (`increment_attr_level`,
`generate_configuration`). `VeriGraphCurriculum` is that object for one family: its
attributes are the knobs its generator reads (`FamilyGenerator.knobs`, fields of
verigraph.tasks.procedural.LevelConfig), each with
one value per level, plus `level`, which sets every knob to one level's preset at once.
`VeriGraphDataset` is the dataset: entry i is task i of the configuration (seeded, the
same in every process), the question the direct planner prompt (the whole plan in one
answer), the answer a reference plan, and the metadata the task record.

`score_answer` never compares strings: it parses the answer with the planners' parser,
runs the actions through the verifier (the tools the MCP server wraps, `load_scene`,
`set_goal`, `execute_actions`: executed up to the first refused action) and scores the
state reached: 1.0 when the goal holds, else `partial` times the share of the goal
distance the executed actions closed (0.0 for an answer that cannot be read, or that
makes things worse).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from verigraph.errors import VeriGraphError
from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.planning.models import PlannerRequest
from verigraph.planning.oracle import reference_plan
from verigraph.planning.parsing import ParseFailure, parse_answer
from verigraph.planning.progress import goal_distance
from verigraph.planning.prompting import planner_prompt
from verigraph.planning.tool_calls import InProcessTools, ToolCallError
from verigraph.tasks.procedural import LevelConfig, generate_task, generator_for
from verigraph.tasks.task import Task

MAX_PLAN = 50


class AttributeDefinition(BaseModel):
    """One attribute of a curriculum: its value at each level (level 0 first)."""

    model_config = ConfigDict(frozen=True)

    name: str
    levels: tuple[int, ...]
    description: str


class VeriGraphDatasetConfig(BaseModel):
    """What a dataset draws: a family, the knobs, how many entries, and the seed."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    family: str = "blocks"
    level: int = Field(default=1, ge=1, description="the level the knobs come from")
    knobs: LevelConfig | None = Field(default=None, description="knobs other than the "
                                      "level's preset (the curriculum sets them)")
    size: int = Field(default=100, ge=1, le=100_000)
    seed: int = 0
    partial: float = Field(default=0.5, ge=0.0, le=1.0,
                           description="score of a plan that closes the whole goal "
                                       "distance without reaching the goal; scaled down")

    def level_config(self) -> LevelConfig:
        return self.knobs or generator_for(self.family).config(self.level)


class VeriGraphCurriculum:
    """Attribute levels for one family; `generate_configuration()` gives a dataset config."""

    def __init__(self, family: str = "blocks") -> None:
        self.family = family
        generator = generator_for(family)
        presets = generator.levels
        self.knobs = generator.knobs
        self.attributes: dict[str, AttributeDefinition] = {
            "level": AttributeDefinition(name="level", levels=tuple(range(1, len(presets) + 1)),
                                         description="every knob at one level's preset"),
            **{knob: AttributeDefinition(
                name=knob, levels=tuple(getattr(p, knob) for p in presets),
                description=str(LevelConfig.model_fields[knob].description))
               for knob in self.knobs},
        }
        self._levels = dict.fromkeys(self.attributes, 0)

    def _attribute(self, name: str) -> AttributeDefinition:
        if name not in self.attributes:
            raise VeriGraphError(f"unknown curriculum attribute '{name}'", field="attribute",
                                 value=name, fix=f"use one of {', '.join(self.attributes)}")
        return self.attributes[name]

    def get_attr_level(self, name: str) -> int:
        self._attribute(name)
        return self._levels[name]

    def get_attr_value(self, name: str) -> int:
        return self._attribute(name).levels[self._levels[name]]

    def set_attr_level(self, name: str, level: int) -> None:
        """Set one attribute's level (0-based); `level` moves every knob with it."""
        attribute = self._attribute(name)
        if not 0 <= level < len(attribute.levels):
            raise VeriGraphError(f"attribute {name} has levels 0 to "
                                 f"{len(attribute.levels) - 1}, not {level}", field=name,
                                 value=level, fix="stay within the attribute's levels")
        self._levels[name] = level
        if name == "level":
            self._levels.update(dict.fromkeys(self.knobs, level))

    def increment_attr_level(self, name: str) -> bool:
        """One level up; False (nothing changes) at the top."""
        if self.get_attr_level(name) + 1 >= len(self._attribute(name).levels):
            return False
        self.set_attr_level(name, self._levels[name] + 1)
        return True

    def decrement_attr_level(self, name: str) -> bool:
        """One level down; False (nothing changes) at the bottom."""
        if self.get_attr_level(name) == 0:
            return False
        self.set_attr_level(name, self._levels[name] - 1)
        return True

    def generate_configuration(self, size: int = 100, seed: int = 0) -> VeriGraphDatasetConfig:
        level = self.get_attr_value("level")
        preset = generator_for(self.family).config(level)
        knobs = preset.model_copy(update={k: self.get_attr_value(k) for k in self.knobs})
        return VeriGraphDatasetConfig(family=self.family, level=level, size=size, seed=seed,
                                      knobs=None if knobs == preset else knobs)


class VeriGraphDataset:
    """Reasoning Gym-style entries over procedural tasks (module docstring)."""

    def __init__(self, config: VeriGraphDatasetConfig | None = None, **fields: Any) -> None:
        self.config = config or VeriGraphDatasetConfig(**fields)
        self.tools = InProcessTools()

    def __len__(self) -> int:
        return self.config.size

    def __iter__(self) -> Iterator[dict[str, Any]]:
        return (self[i] for i in range(len(self)))

    def task(self, index: int) -> Task:
        if not 0 <= index < self.config.size:
            raise IndexError(index)
        cfg = self.config
        return generate_task(cfg.family, cfg.level, index, cfg.seed, cfg.knobs)

    def __getitem__(self, index: int) -> dict[str, Any]:
        task = self.task(index)
        graph = SceneGraph.model_validate(task.load["graph"])
        goal = task.goal
        assert goal is not None
        state = WorldState.from_graph(graph)
        question = planner_prompt("direct", state, goal, k=None, instruction=task.instruction,
                                  history=[], feedback=None, iteration=1)
        plan, _ = reference_plan(PlannerRequest(mode="direct", iteration=1, graph=graph,
                                                goal=goal, privileged_goal=goal, k=None,
                                                prompt=question), goal)
        return {"question": question, "answer": "\n".join(a.text() for a in plan),
                "metadata": {"source_dataset": f"verigraph_{cfg_name(self.config)}",
                             "source_index": index, "family": task.family,
                             "level": self.config.level, "task_id": task.task_id,
                             "optimal_length": task.optimal_length, "objects": task.objects,
                             "difficulty": task.category, "partial": self.config.partial,
                             "task": task.model_dump(mode="json")}}

    def score_answer(self, answer: str | None, entry: dict[str, Any]) -> float:
        return score_answer(answer, entry, self.tools)


def cfg_name(config: VeriGraphDatasetConfig) -> str:
    return f"{config.family}_level{config.level}"


def score_answer(answer: str | None, entry: dict[str, Any],
                 tools: InProcessTools | None = None) -> float:
    """The verifier's score of a plan for an entry, in [0, 1] (module docstring)."""
    task = Task.model_validate(entry["metadata"]["task"])
    partial = float(entry["metadata"].get("partial", 0.5))
    goal = task.goal
    if goal is None or not answer:
        return 0.0
    try:
        actions = parse_answer(answer)
    except ParseFailure:
        return 0.0
    moves = [a.model_dump(mode="json") for a in actions if a.action != "done"]
    tools = tools or InProcessTools()
    # one call takes at most MAX_PLAN actions (load_scene's k); a longer answer's tail is
    # not run
    state = tools.call("load_scene", {**task.load, "k": MAX_PLAN})
    episode = str(state["episode_id"])
    try:
        tools.call("set_goal", {"episode_id": episode, **(task.set_goal or {})})
        if moves:
            try:
                state = tools.call("execute_actions", {"episode_id": episode,
                                                       "actions": moves[:MAX_PLAN]})
            except ToolCallError:
                return 0.0  # an action the tools cannot even read
        else:
            state = tools.call("get_state", {"episode_id": episode})
    finally:
        tools.call("end_episode", {"episode_id": episode})
    graph = SceneGraph.model_validate(state["graph"])
    return reached_score(graph, task, goal, partial)


def reached_score(graph: SceneGraph, task: Task, goal: Goal, partial: float) -> float:
    if check_goal(WorldState.from_graph(graph), goal).satisfied:
        return 1.0
    start = goal_distance(SceneGraph.model_validate(task.load["graph"]), goal) or 0
    now = goal_distance(graph, goal)
    if not start or now is None:
        return 0.0
    return round(max(0.0, partial * (start - now) / start), 4)
