"""The benchmark's episodes: generated sim2d scenes in the paper's four task groups.

- `stacking`: block scenes with incomplete stacks; goal predicate `single_stack`.
- `language`: kitchen and tableware scenes with an instruction (a command or a goal
  description, see `language.py`); the planner's prompt shows only the words, the
  verifier checks the ground-truth goal graph.
- `ref_image_blocks`, `ref_image_kitchen`: the goal is an image of a structurally
  similar scene (the goal state laid out afresh by the simulator); the goal graph comes
  from perceiving it, so these groups need `verigraph.perception` unless
  `ground_truth=True` hands the planner the true goal graph instead.
- `tangram`: one piece moved away from the target figure; the planner must say which
  piece to align with which side.

Episodes are fixed by (group, index, seed), so every planner sees the same tasks.
"""

from __future__ import annotations

import base64
import random
from collections.abc import Callable
from typing import Any, Literal

from pydantic import BaseModel, Field

from verigraph.agent.evaluation.language import TEMPLATES, instruction_for
from verigraph.agent.loop import EpisodeSpec
from verigraph.errors import VeriGraphError
from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState

GroupName = Literal["stacking", "language", "ref_image_kitchen", "ref_image_blocks", "tangram"]
GROUPS: tuple[GroupName, ...] = ("stacking", "language", "ref_image_kitchen",
                                 "ref_image_blocks", "tangram")
MAX_DRAWS = 20  # scenes tried per episode before the group gives up on an index
STACK_SIZES = (4, 5, 6, 7)  # blocks per stacking scene: enough moves for mistakes to matter


class Task(BaseModel):
    """One benchmark episode: how to load it and what it is."""

    group: GroupName
    task_id: str
    spec: EpisodeSpec
    family: str
    template: str | None = Field(default=None, description="language template id")
    instruction_kind: str | None = None


class GroupTasks(BaseModel):
    """A group's episodes, or the reason it cannot run in this installation."""

    group: GroupName
    tasks: list[Task] = Field(default_factory=list)
    not_run: str | None = Field(default=None, description="why the group was skipped")
    graphs: str = Field(default="ground truth",
                        description="where the graphs come from: ground truth or perceived")


def _generate(family: str, seed: int, n_objects: int | None = None) -> Any:
    from verigraph.sim2d.generator import generate_scene

    return generate_scene(family, seed, n_objects)


def _goal_of(scene: Any) -> Goal:
    goal = scene.goal
    if isinstance(goal, Goal):
        return goal
    if isinstance(goal, SceneGraph):
        return Goal(graph=goal)
    return Goal(graph=goal.observe())


def _graph_json(graph: SceneGraph) -> dict[str, Any]:
    return graph.model_dump(mode="json", exclude_none=True)


def _load(graph: SceneGraph, simulate: bool, seed: int) -> dict[str, Any]:
    load: dict[str, Any] = {"graph": _graph_json(graph)}
    if simulate:
        load["simulate"] = True
        load["seed"] = seed
    return load


def feasible_in_sim(graph: SceneGraph, goal: Goal, seed: int, world: Any = None) -> bool:
    """With --simulate: the reference plan also works in physics (things fit where put).

    The symbolic goal can ask for placements the simulator cannot realise (a wide board
    on a narrow plate); such tasks would measure the simulator, not the planner.
    """
    from verigraph.actions.executor import execute_in_world
    from verigraph.sim2d import world_for_graph
    from verigraph.solver import solve

    state = WorldState.from_graph(graph)
    plan = solve(state, goal)
    if not plan.reachable:
        return False
    try:
        world = world.copy() if world is not None else world_for_graph(state.to_graph(),
                                                                       seed=seed)
        _, _, violation, _, final = execute_in_world(state, plan.plan, world)
    except VeriGraphError:
        return False
    return violation is None and check_goal(final, goal).satisfied


def _draws(base_seed: int, index: int) -> range:
    start = base_seed * 100_003 + index * MAX_DRAWS
    return range(start, start + MAX_DRAWS)


def stacking_tasks(n: int, seed: int, *, simulate: bool = False) -> GroupTasks:
    tasks = []
    goal = Goal(predicate="single_stack", instruction="Stack all the blocks into one tower.")
    for i in range(n):
        for draw in _draws(seed, i):
            scene = _generate("blocks", draw, STACK_SIZES[draw % len(STACK_SIZES)])
            if check_goal(WorldState.from_graph(scene.graph), goal).satisfied:
                continue  # already one tower: not a stacking task
            if simulate and not feasible_in_sim(scene.graph, goal, draw):
                continue
            spec = EpisodeSpec(task_id=f"stacking/{i}", load=_load(scene.graph, simulate, draw),
                               set_goal={"predicate": "single_stack",
                                         "instruction": goal.instruction})
            tasks.append(Task(group="stacking", task_id=spec.task_id or "", spec=spec,
                              family="blocks"))
            break
    return GroupTasks(group="stacking", tasks=tasks)


def language_tasks(n: int, seed: int, *, simulate: bool = False) -> GroupTasks:
    names = list(TEMPLATES)
    tasks = []
    for i in range(n):
        family = "kitchen" if i % 2 == 0 else "tableware"
        for attempt, draw in enumerate(_draws(seed, i)):
            scene = _generate(family, draw)
            template = names[(i + attempt) % len(names)]
            made = instruction_for(scene.graph, template, random.Random(draw))
            if made is None or (simulate and not feasible_in_sim(scene.graph, made.goal, draw)):
                continue
            assert made.goal.graph is not None
            spec = EpisodeSpec(
                task_id=f"language/{i}", load=_load(scene.graph, simulate, draw),
                set_goal={"graph": _graph_json(made.goal.graph), "instruction": made.text},
                show_goal_graph=False)
            tasks.append(Task(group="language", task_id=spec.task_id or "", spec=spec,
                              family=family, template=template, instruction_kind=made.kind))
            break
    return GroupTasks(group="language", tasks=tasks)


def goal_image_png(goal_graph: SceneGraph, seed: int) -> bytes:
    """The goal state laid out afresh (a structurally similar scene), rendered to PNG."""
    from verigraph.sim2d import encode_png, world_for_graph

    world = world_for_graph(goal_graph, seed=seed)
    return bytes(encode_png(world.render()))


def reference_image_tasks(family: Literal["blocks", "kitchen"], n: int, seed: int, *,
                          ground_truth: bool, simulate: bool = False) -> GroupTasks:
    group: GroupName = "ref_image_blocks" if family == "blocks" else "ref_image_kitchen"
    tasks = []
    instruction = "Rearrange the scene so that it looks like the reference image."
    for i in range(n):
        for draw in _draws(seed, i):
            scene = _generate(family, draw)
            goal = _goal_of(scene)
            if goal.graph is None or goal.graph.edge_keys() == scene.graph.edge_keys():
                continue
            if simulate and not feasible_in_sim(scene.graph, goal, draw):
                continue
            set_goal: dict[str, Any] = {"instruction": instruction}
            if ground_truth:
                set_goal["graph"] = _graph_json(goal.graph)
            else:
                try:
                    png = goal_image_png(goal.graph, draw + 1)
                except VeriGraphError:
                    continue  # the goal cannot be laid out afresh (no room): draw another
                set_goal["image"] = base64.b64encode(png).decode("ascii")
            spec = EpisodeSpec(task_id=f"{group}/{i}", load=_load(scene.graph, simulate, draw),
                               set_goal=set_goal)
            tasks.append(Task(group=group, task_id=spec.task_id or "", spec=spec,
                              family=family))
            break
    return GroupTasks(group=group, tasks=tasks,
                      graphs="ground truth" if ground_truth else "perceived goal image")


def tangram_tasks(n: int, seed: int, *, simulate: bool = False) -> GroupTasks:
    tasks = []
    for i in range(n):
        for draw in _draws(seed, i):
            scene = _generate("tangram", draw)
            goal = _goal_of(scene)
            if goal.graph is None or (simulate and not feasible_in_sim(
                    scene.graph, goal, draw, world=scene.world)):
                continue
            set_goal: dict[str, Any] = {"graph": _graph_json(goal.graph)}
            if goal.instruction:
                set_goal["instruction"] = goal.instruction
            # A tangram world cannot be rebuilt from contacts alone: simulate it from the
            # generator, which lays the pieces out exactly.
            load = ({"generator": {"family": "tangram", "seed": draw}, "simulate": True}
                    if simulate else _load(scene.graph, False, draw))
            spec = EpisodeSpec(task_id=f"tangram/{i}", load=load, set_goal=set_goal)
            tasks.append(Task(group="tangram", task_id=spec.task_id or "", spec=spec,
                              family="tangram"))
            break
    return GroupTasks(group="tangram", tasks=tasks)


def build_groups(groups: tuple[GroupName, ...], n: int, seed: int, *, ground_truth: bool,
                 simulate: bool = False) -> list[GroupTasks]:
    """Every requested group's tasks (or why it is not run)."""
    builders: dict[GroupName, Callable[[], GroupTasks]] = {
        "stacking": lambda: stacking_tasks(n, seed, simulate=simulate),
        "language": lambda: language_tasks(n, seed, simulate=simulate),
        "ref_image_kitchen": lambda: reference_image_tasks(
            "kitchen", n, seed, ground_truth=ground_truth, simulate=simulate),
        "ref_image_blocks": lambda: reference_image_tasks(
            "blocks", n, seed, ground_truth=ground_truth, simulate=simulate),
        "tangram": lambda: tangram_tasks(n, seed, simulate=simulate),
    }
    return [builders[g]() for g in groups]
