"""Procedural generators: levels whose knobs rise, seeded draws, optimal lengths that the
reference solver confirms, a family added by one registration, bad levels refused."""

from __future__ import annotations

import random
import statistics

import pytest

from verigraph.errors import VeriGraphError
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.solver import solve
from verigraph.tasks.procedural import (
    GENERATORS,
    FamilyGenerator,
    LevelConfig,
    draw_blocks,
    generate_task,
    generate_tasks,
    max_level,
    register_generator,
)

pytestmark = pytest.mark.fast

KNOBS = ("objects", "distractors", "constraints")


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tangram"])
def test_levels_raise_every_knob(family: str) -> None:
    levels = GENERATORS[family].levels
    assert len(levels) >= 5
    for knob in KNOBS:
        values = [getattr(c, knob) for c in levels]
        assert values == sorted(values) and values[-1] > values[0], (knob, values)


@pytest.mark.parametrize("family", ["blocks", "tangram"])
def test_generated_difficulty_rises_with_the_level(family: str) -> None:
    means = []
    for level in range(1, max_level(family) + 1):
        tasks = generate_tasks(family, level, 3, seed=0)
        assert {t.kind for t in tasks} == {f"level_{level}"}
        assert all(t.family == family for t in tasks)
        means.append((statistics.fmean(t.optimal_length for t in tasks),
                      statistics.fmean(t.objects for t in tasks)))
    lengths, objects = [m[0] for m in means], [m[1] for m in means]
    assert lengths == sorted(lengths) and lengths[-1] >= lengths[0] + 3, lengths
    assert objects == sorted(objects) and objects[-1] > objects[0], objects


def test_kitchen_levels_reach_their_lengths() -> None:
    for level in (1, 3):
        cfg = GENERATORS["kitchen"].config(level)
        task = generate_task("kitchen", level, 0, seed=0)
        assert cfg.length <= task.optimal_length <= cfg.length + 1
        assert task.set_goal is not None and task.set_goal["partial"] is True
        distractors, constraints = (int(p.split("=")[1])
                                    for p in (task.category or "").split(","))
        assert distractors >= cfg.distractors and constraints >= cfg.constraints


def test_draws_are_seeded() -> None:
    a = generate_task("blocks", 4, 7, seed=3)
    assert a.content_hash == generate_task("blocks", 4, 7, seed=3).content_hash
    assert a.content_hash != generate_task("blocks", 4, 8, seed=3).content_hash
    assert a.content_hash != generate_task("blocks", 4, 7, seed=4).content_hash
    assert a.task_id == "blocks-L4/3/7"


@pytest.mark.parametrize("level", [1, 2, 3, 4])
def test_blocks_length_by_construction_is_the_solvers(level: int) -> None:
    for index in range(3):
        task = generate_task("blocks", level, index, seed=1)
        assert task.goal is not None
        result = solve(WorldState.from_graph(SceneGraph.model_validate(task.load["graph"])),
                       task.goal)
        assert result.reachable and len(result.plan) == task.optimal_length


def test_blocks_distractors_bury_goal_blocks() -> None:
    cfg = LevelConfig(objects=5, distractors=3, constraints=2)
    made = draw_blocks(random.Random(0), cfg)
    assert made is not None and made.goal.graph is not None
    goal_blocks = {e.source for e in made.goal.graph.edges}
    state = WorldState.from_graph(made.graph)
    buried = [b for b in goal_blocks if not state.is_clear(b)]
    assert buried and made.constraints == 2 and made.distractors == 3
    assert made.optimal_length == 5 - 1 + 2


def test_tangram_wrong_contacts_are_not_in_the_figure() -> None:
    task = generate_task("tangram", 5, 0, seed=0)
    assert task.goal is not None and task.goal.graph is not None
    figure = {(e.source, e.target) for e in task.goal.graph.edges}
    start = SceneGraph.model_validate(task.load["graph"])
    assert any((e.source, e.target) not in figure for e in start.edges)


def test_a_family_is_one_registration() -> None:
    def draw(rng: random.Random, cfg: LevelConfig):  # type: ignore[no-untyped-def]
        return draw_blocks(rng, cfg.model_copy(update={"objects": cfg.objects + 1}))

    before = GENERATORS["blocks"]
    levels = tuple(LevelConfig(objects=n, distractors=0, constraints=0) for n in (3, 4))
    register_generator(FamilyGenerator("blocks", "stacking", draw, levels))
    try:
        assert max_level("blocks") == 2
        task = generate_task("blocks", 2, 0)
        assert task.task_id.startswith("blocks-L2/") and task.optimal_length == 4
    finally:
        register_generator(before)


@pytest.mark.parametrize(("family", "level"), [("blocks", 0), ("kitchen", 99),
                                               ("household_x", 1)])
def test_bad_levels_and_families_are_structured_errors(family: str, level: int) -> None:
    with pytest.raises(VeriGraphError) as err:
        generate_task(family, level, 0)
    assert err.value.field in ("level", "family") and err.value.fix
