"""`verigraph bench plan`: task groups, instruction templates, metrics and the report."""

from __future__ import annotations

import io
import random

import pytest

from verigraph.agent.evaluation import Setting, build_groups, run_setting
from verigraph.agent.evaluation.bench import run
from verigraph.agent.evaluation.language import TEMPLATES, instruction_for, template_counts
from verigraph.agent.evaluation.runner import Progress
from verigraph.graph import WorldState, check_goal, check_well_formed
from verigraph.solver import solve

generator = pytest.importorskip("verigraph.sim2d.generator", reason="sim2d not installed")


def test_at_least_30_templates_of_both_kinds() -> None:
    counts = template_counts()
    assert sum(counts.values()) >= 30
    assert counts["command"] >= 10 and counts["goal_description"] >= 10


@pytest.mark.parametrize("family", ["kitchen", "tableware"])
def test_instruction_goals_are_well_formed_new_and_reachable(family: str) -> None:
    made = 0
    for seed in range(6):
        scene = generator.generate_scene(family, seed)
        state = WorldState.from_graph(scene.graph)
        for name in TEMPLATES:
            ins = instruction_for(scene.graph, name, random.Random(seed))
            if ins is None:
                continue
            made += 1
            goal_graph = ins.goal.graph
            assert goal_graph is not None
            assert not check_well_formed(goal_graph, state.dictionary), ins.text
            assert goal_graph.edge_keys() != scene.graph.edge_keys()
            assert not check_goal(state, ins.goal).satisfied
            result = solve(state, ins.goal)
            assert result.reachable and len(result.plan) == ins.optimal_length
            assert ins.text.endswith("Leave everything else as it is.")
    assert made >= 6 * 20


def test_reference_image_groups_run_with_perception() -> None:
    groups = build_groups(("ref_image_blocks", "tangram"), 2, 0, ground_truth=False)
    ref, tangram = groups
    assert ref.not_run is None and len(ref.tasks) == 2
    assert "image" in (ref.tasks[0].spec.set_goal or {})
    assert tangram.not_run is None and len(tangram.tasks) == 2
    truth = build_groups(("ref_image_blocks",), 2, 0, ground_truth=True)[0]
    assert truth.not_run is None and len(truth.tasks) == 2
    assert "graph" in (truth.tasks[0].spec.set_goal or {})


def test_tasks_are_reproducible_and_language_hides_the_goal_graph() -> None:
    a = build_groups(("language",), 4, 3, ground_truth=True)[0]
    b = build_groups(("language",), 4, 3, ground_truth=True)[0]
    assert [t.spec for t in a.tasks] == [t.spec for t in b.tasks]
    assert all(not t.spec.show_goal_graph for t in a.tasks)
    assert {t.family for t in a.tasks} == {"kitchen", "tableware"}


def test_oracle_solves_every_group_and_noise_hurts_direct_more_than_iterative() -> None:
    groups = build_groups(("stacking", "language", "ref_image_kitchen", "ref_image_blocks",
                           "tangram"), 12, 0, ground_truth=True)
    oracle = run_setting(Setting(planner="oracle"), groups)
    assert all(s.success_rate == 1.0 for s in oracle.values()), oracle
    assert all(s.violations_caught == 0 for s in oracle.values())
    noisy = run_setting(Setting(planner="noisy", noise=0.3), groups)
    direct = run_setting(Setting(planner="noisy", noise=0.3, mode="direct"), groups)
    total = sum(s.episodes for s in noisy.values())
    iterative_rate = sum(s.success_rate * s.episodes for s in noisy.values()) / total
    direct_rate = sum(s.success_rate * s.episodes for s in direct.values()) / total
    assert iterative_rate >= 0.95
    assert direct_rate <= iterative_rate - 0.15
    assert sum(s.violations_caught for s in noisy.values()) > 0
    assert all(s.mean_llm_calls >= 1 for s in noisy.values())


def test_report_has_the_paper_row_ablations_and_not_run_groups(tmp_path: object) -> None:
    text = run(["--episodes", "3", "--groups", "stacking,ref_image_blocks"])
    assert "| oracle, iterative k=3 t=5 | 100% |" in text
    assert "paper: VeriGraph (GPT-4V, iterative), Table 2" in text
    assert "Ablation: error threshold t" in text and "Ablation: actions per iteration k" in text
    for t in (2, 3, 5, 10):
        assert f"\n| {t} | " in text


def test_bench_rejects_unknown_groups_and_planners() -> None:
    from verigraph.errors import VeriGraphError

    with pytest.raises(VeriGraphError, match="--groups"):
        run(["--groups", "juggling"])
    with pytest.raises(VeriGraphError, match="--planners"):
        run(["--planners", "gpt-17", "--groups", "stacking"])


def test_progress_bar_reports_on_a_pipe() -> None:
    stream = io.StringIO()
    bar = Progress(20, stream=stream)
    for _ in range(20):
        bar.advance("x")
    lines = stream.getvalue().splitlines()
    assert 2 <= len(lines) <= 11
    assert lines[-1].startswith("[" + "#" * 30 + "] 20/20 episodes")
