"""The procedural household family: five levels whose knobs rise, formula goals over a
home's states (closed containers to open, a stove to switch on, food to cook,
quantified parts), the oracle solving every level over several seeds, the environment
id and the curriculum, and `score_answer` from the verifier."""

from __future__ import annotations

import statistics

import pytest

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")

import gymnasium as gym  # noqa: E402
from gymnasium.utils.env_checker import check_env  # noqa: E402

import verigraph.env  # noqa: E402,F401
from verigraph.env.curriculum import VeriGraphCurriculum, VeriGraphDataset  # noqa: E402
from verigraph.env.procedural import procedural_id  # noqa: E402
from verigraph.env.rollout import RolloutJob, run_rollouts  # noqa: E402
from verigraph.graph.formula import parse_formula  # noqa: E402
from verigraph.graph.model import SceneGraph  # noqa: E402
from verigraph.graph.state import WorldState  # noqa: E402
from verigraph.solver import solve  # noqa: E402
from verigraph.tasks.procedural import GENERATORS, generate_task, max_level  # noqa: E402


def _counts(category: str | None) -> dict[str, int]:
    return {k: int(v) for k, v in (p.split("=") for p in (category or "").split(","))}


@pytest.mark.fast
def test_levels_raise_every_household_knob() -> None:
    levels = GENERATORS["household"].levels
    assert len(levels) >= 5 and max_level("household") == len(levels)
    for knob in GENERATORS["household"].knobs:
        values = [getattr(c, knob) for c in levels]
        assert values == sorted(values) and values[-1] > values[0], (knob, values)


@pytest.mark.fast
def test_tasks_are_household_scenes_with_formula_goals_that_rise_with_the_level() -> None:
    lengths, objects = [], []
    for level in range(1, max_level("household") + 1):
        cfg = GENERATORS["household"].config(level)
        tasks = [generate_task("household", level, i, seed=0) for i in range(2)]
        for task in tasks:
            assert task.set_goal is not None and task.goal is not None
            assert task.goal.formula is not None and task.goal.graph is None
            formula = task.goal.formula
            assert task.load["graph"]["dictionary"] == "household"
            assert task.objects == cfg.objects
            counts = _counts(task.category)
            assert counts["distractors"] == cfg.distractors
            assert counts["constraints"] >= cfg.constraints
            assert cfg.length <= task.optimal_length <= cfg.length + 2
            assert (formula.count("(forall") + formula.count("(exists")) == cfg.quantified
            parse_formula(formula)
            assert task.kind == f"level_{level}" and task.group == "household"
        lengths.append(statistics.fmean(t.optimal_length for t in tasks))
        objects.append(statistics.fmean(t.objects for t in tasks))
    assert lengths == sorted(lengths) and lengths[-1] >= lengths[0] + 3, lengths
    assert objects == sorted(objects) and objects[-1] > objects[0]


@pytest.mark.fast
def test_the_optimal_plan_opens_and_switches_on_before_it_moves_and_cooks() -> None:
    task = generate_task("household", 3, 0, seed=1)
    assert task.goal is not None
    start = WorldState.from_graph(SceneGraph.model_validate(task.load["graph"]))
    closed = {o for o in start.openable if not start.state_value(o, "open")}
    result = solve(start, task.goal)
    assert result.reachable and len(result.plan) == task.optimal_length
    texts = [a.text() for a in result.plan]
    switched = [t for t in texts if t.startswith(("open(", "toggle_on("))]
    assert len(switched) == _counts(task.category)["constraints"] >= 2
    assert any(t[len("open("):-1] in closed for t in switched if t.startswith("open("))


# level 5 draws take about a second each (the bounded solver rejects the hard ones), so
# it stays out of the fast tier
@pytest.mark.parametrize("level", [pytest.param(1, marks=pytest.mark.fast),
                                   pytest.param(2, marks=pytest.mark.fast),
                                   pytest.param(3, marks=pytest.mark.fast),
                                   pytest.param(4, marks=pytest.mark.fast), 5])
def test_the_oracle_solves_every_level_over_several_seeds(level: int) -> None:
    tasks = [generate_task("household", level, 0, seed=s) for s in (0, 1, 2)]
    results = run_rollouts([RolloutJob(task_id=t.task_id) for t in tasks],
                           {"tasks": tasks})
    for task, result in zip(tasks, results, strict=True):
        assert result.success, (task.task_id, result.stop_reason)
        assert result.moves == task.optimal_length


@pytest.mark.fast
def test_the_environment_id_and_the_curriculum_cover_household() -> None:
    env = gym.make(procedural_id("household"), level=2)
    check_env(env.unwrapped, skip_render_check=True)
    _, info = env.reset(seed=4)
    assert info["family"] == "household" and info["level"] == 2
    assert info["kind"] == "level_2" and info["goal_distance"] > 0
    obs, _, _, _, info = env.step("toggle_on(no_such_stove)")
    assert info["verdict"] == "violation" and "## Goal" in obs
    curriculum = VeriGraphCurriculum("household")
    assert "quantified" in curriculum.attributes and "towers" not in curriculum.attributes
    curriculum.set_attr_level("level", 3)
    assert curriculum.get_attr_value("quantified") == 1
    assert curriculum.decrement_attr_level("quantified")
    config = curriculum.generate_configuration(size=1, seed=0)
    assert config.knobs is not None and config.knobs.quantified == 0
    assert config.knobs.objects == GENERATORS["household"].config(4).objects


@pytest.mark.fast
def test_dataset_entries_are_scored_by_the_verifier() -> None:
    data = VeriGraphDataset(family="household", level=2, size=1, seed=3)
    entry = data[0]
    lines = entry["answer"].splitlines()
    assert len(lines) == entry["metadata"]["optimal_length"] >= 4
    assert data.score_answer(entry["answer"], entry) == 1.0
    assert data.score_answer("\n".join(lines[:-1]), entry) < 1.0
    assert data.score_answer("cook(no_such_food)", entry) == 0.0
    assert data.score_answer("nothing to do", entry) == 0.0
