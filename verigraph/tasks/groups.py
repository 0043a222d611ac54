"""The benchmark's episodes: the paper's five task groups, with real difficulty.

- `stacking` (suite_blocks.py): ordered stacking from blocks spread on the table (4-8),
  tower reversal (4-7) and multi-tower rearrangement; the goal graph spells out the order.
- `language` (language.py): coloured block scenes with instructions that need colours,
  quantifiers, relations and negation; the prompt shows only the words, the verifier
  checks the ground-truth partial goal graph.
- `ref_image_blocks` (suite_blocks.py) and `ref_image_kitchen` (suite_kitchen.py): the
  goal is an image of the goal state laid out afresh; 3+ moves, something to clear
  first. Its graph comes from perceiving the image (`verigraph.perception`) unless
  `ground_truth=True` hands the planner the true goal graph.
- `tangram` (suite_tangram.py): 2 to 5 pieces out of the target figure.
- `household` (suite_household.py, not one of the paper's groups): the built-in kitchen
  and dining room with doors to open and shut and a stove to switch; partial goals of
  placements and states, worded as an instruction and shown as a graph.

Every group's mean optimal plan length (reference solver) is at least 4; `suite_stats`
reports it with its distribution. Episodes are fixed by (SUITE_VERSION, group, index,
seed), so every planner sees the same tasks and results from one suite version stay
comparable; a change to any generator must bump SUITE_VERSION.
"""

from __future__ import annotations

import base64
import random
import statistics
from collections import Counter
from collections.abc import Callable
from typing import Any, Literal

from pydantic import BaseModel, Field

from verigraph.errors import VeriGraphError
from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.tasks import language, suite_blocks, suite_household, suite_kitchen, suite_tangram
from verigraph.tasks.suite_blocks import Drawn
from verigraph.tasks.task import GROUPS, SUITE_VERSION, Family, GroupName, Task

__all__ = ["GROUPS", "SUITE_VERSION", "GroupName", "GroupTasks", "SuiteStats", "Task",
           "build_groups", "suite_stats"]

MAX_DRAWS = 20  # draws tried per episode before the group gives up on an index
KITCHEN_TARGETS = (4, 5, 6, 5)  # optimal lengths aimed at, in turn
REF_INSTRUCTION = "Rearrange the scene so that it looks like the reference image."


class GroupTasks(BaseModel):
    """A group's episodes, or the reason it cannot run in this installation."""

    group: GroupName
    tasks: list[Task] = Field(default_factory=list)
    not_run: str | None = Field(default=None, description="why the group was skipped")
    graphs: str = Field(default="ground truth",
                        description="where the graphs come from: ground truth or perceived")
    note: str | None = None


class SuiteStats(BaseModel):
    """Optimal plan lengths of one group: mean and distribution."""

    group: GroupName
    episodes: int
    mean_optimal: float
    distribution: dict[int, int]
    kinds: dict[str, int]


def suite_stats(group: GroupTasks) -> SuiteStats:
    lengths = [t.optimal_length for t in group.tasks]
    return SuiteStats(group=group.group, episodes=len(lengths),
                      mean_optimal=statistics.fmean(lengths) if lengths else 0.0,
                      distribution=dict(sorted(Counter(lengths).items())),
                      kinds=dict(sorted(Counter(t.kind for t in group.tasks).items())))


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
    from verigraph.actions.execution import execute_in_world
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


def _rng(group: str, seed: int, index: int, draw: int) -> random.Random:
    return random.Random(f"verigraph-bench:{SUITE_VERSION}:{group}:{seed}:{index}:{draw}")


def _task(group: GroupName, index: int, drawn: Drawn, load: dict[str, Any],
          set_goal: dict[str, Any], family: Family, **labels: Any) -> Task:
    return Task.create(task_id=f"{group}/{index}", load=load, set_goal=set_goal,
                       family=family, group=group, kind=drawn.kind,
                       optimal_length=drawn.optimal_length,
                       show_goal_graph=group != "language", **labels)


def stacking_tasks(n: int, seed: int, *, simulate: bool = False) -> GroupTasks:
    tasks = []
    for i in range(n):
        for draw in range(MAX_DRAWS):
            drawn = suite_blocks.stacking_task(_rng("stacking", seed, i, draw), i)
            if simulate and not feasible_in_sim(drawn.graph, drawn.goal, draw):
                continue
            assert drawn.goal.graph is not None
            tasks.append(_task("stacking", i, drawn, _load(drawn.graph, simulate, draw),
                               {"graph": _graph_json(drawn.goal.graph),
                                "instruction": drawn.goal.instruction}, "blocks"))
            break
    return GroupTasks(group="stacking", tasks=tasks)


def language_tasks(n: int, seed: int, *, simulate: bool = False) -> GroupTasks:
    names = list(language.TEMPLATES)
    tasks = []
    for i in range(n):
        template = names[i % len(names)]
        for draw in range(MAX_DRAWS):
            rng = _rng("language", seed, i, draw)
            towers = language.draw_scene(rng)
            made = language.instruction_for(towers, template, rng)
            graph = suite_blocks.block_graph(towers)
            if made is None or (simulate and not feasible_in_sim(graph, made.goal, draw)):
                continue
            assert made.goal.graph is not None
            drawn = Drawn(graph, made.goal, made.category, made.optimal_length)
            tasks.append(_task(
                "language", i, drawn, _load(graph, simulate, draw),
                {"graph": _graph_json(made.goal.graph), "partial": True,
                 "instruction": made.text}, "blocks", template=template,
                category=made.category, instruction=made.text))
            break
    return GroupTasks(group="language", tasks=tasks)


def goal_image_png(goal_graph: SceneGraph, seed: int) -> bytes:
    """The goal state laid out afresh (a structurally similar scene), rendered to PNG."""
    from verigraph.sim2d import encode_png, world_for_graph

    world = world_for_graph(goal_graph, seed=seed)
    return bytes(encode_png(world.render()))


def _reference_drawn(family: str, rng: random.Random, i: int, draw: int) -> Drawn | None:
    if family == "blocks":
        return suite_blocks.reference_blocks_task(rng)
    from verigraph.sim2d.generator import generate_scene

    try:
        scene = generate_scene("kitchen", 1_000 * i + draw, 5 + draw % 3)
    except VeriGraphError:
        return None
    target = KITCHEN_TARGETS[i % len(KITCHEN_TARGETS)]
    drawn = suite_kitchen.kitchen_goal(scene.graph, rng, target)
    return drawn if drawn is not None and drawn.optimal_length >= target - 1 else None


def reference_image_tasks(family: Literal["blocks", "kitchen"], n: int, seed: int, *,
                          ground_truth: bool, simulate: bool = False) -> GroupTasks:
    group: GroupName = "ref_image_blocks" if family == "blocks" else "ref_image_kitchen"
    tasks = []
    for i in range(n):
        for draw in range(MAX_DRAWS):
            drawn = _reference_drawn(family, _rng(group, seed, i, draw), i, draw)
            if drawn is None or drawn.goal.graph is None:
                continue
            if simulate and not feasible_in_sim(drawn.graph, drawn.goal, draw):
                continue
            set_goal: dict[str, Any] = {"instruction": REF_INSTRUCTION}
            if ground_truth:
                set_goal["graph"] = _graph_json(drawn.goal.graph)
            else:
                try:
                    png = goal_image_png(drawn.goal.graph, draw + 1)
                except VeriGraphError:
                    continue  # the goal cannot be laid out afresh (no room): draw another
                set_goal["image"] = base64.b64encode(png).decode("ascii")
            tasks.append(_task(group, i, drawn, _load(drawn.graph, simulate, draw), set_goal,
                               family))
            break
    return GroupTasks(group=group, tasks=tasks,
                      graphs="ground truth" if ground_truth else "perceived goal image")


def tangram_tasks(n: int, seed: int, *, simulate: bool = False) -> GroupTasks:
    from verigraph.sim2d.generator import generate_scene

    tasks = []
    for i in range(n):
        out = suite_tangram.PIECES_OUT[i % len(suite_tangram.PIECES_OUT)]
        for draw in range(MAX_DRAWS):
            rng = _rng("tangram", seed, i, draw)
            figure = generate_scene("tangram", rng.randrange(2**31)).goal.graph
            drawn = suite_tangram.tangram_task(figure, rng, out) if figure else None
            if drawn is None or drawn.goal.graph is None:
                continue
            set_goal = {"graph": _graph_json(drawn.goal.graph),
                        "instruction": drawn.goal.instruction}
            tasks.append(_task("tangram", i, drawn, _load(drawn.graph, False, draw), set_goal,
                               "tangram"))
            break
    note = "symbolic only: --simulate does not lay out several pieces out" if simulate \
        else None
    return GroupTasks(group="tangram", tasks=tasks, note=note)


def household_tasks(n: int, seed: int) -> GroupTasks:
    tasks = []
    for i in range(n):
        target = suite_household.TARGETS[i % len(suite_household.TARGETS)]
        for draw in range(MAX_DRAWS):
            drawn = suite_household.household_task(_rng("household", seed, i, draw), target)
            if drawn is None or drawn.goal.graph is None or \
                    drawn.optimal_length < max(3, target - 1):
                continue
            set_goal = {"graph": _graph_json(drawn.goal.graph), "partial": True,
                        "instruction": drawn.goal.instruction}
            tasks.append(_task("household", i, drawn, _load(drawn.graph, False, draw),
                               set_goal, "household"))
            break
    return GroupTasks(group="household", tasks=tasks,
                      note="symbolic only: the 2D simulator does not draw household "
                           "scenes")


def _behavior_group(n: int) -> GroupTasks:
    """BEHAVIOR-1K's activities the reference solver solves (verigraph.tasks.behavior):
    a fixed set, one task per activity, so `n` does not cut it."""
    from verigraph.tasks.behavior import behavior_tasks

    del n
    return GroupTasks(group="behavior", tasks=behavior_tasks())


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
        "behavior": lambda: _behavior_group(n),
        "household": lambda: household_tasks(n, seed),
    }
    return [builders[g]() for g in groups]
