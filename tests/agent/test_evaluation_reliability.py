"""pass^k (every one of k samples of a task succeeds) next to pass@1 in `bench plan` and
`bench report`, from samples that differ only in the planner's seed."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from verigraph.agent.evaluation import Setting
from verigraph.agent.evaluation.engine import RunOptions, run_jobs
from verigraph.agent.evaluation.results import ResultsFile
from verigraph.agent.evaluation.spec import job_for, jobs_for, task_index
from verigraph.agent.evaluation.tables import pass_hat_k, render_report, stats_by_group
from verigraph.cli.bench import plan_report
from verigraph.tasks import build_groups

pytest.importorskip("verigraph.sim2d.generator", reason="sim2d not installed")


def test_pass_hat_k_is_taus_estimator() -> None:
    assert pass_hat_k(4, 4, 4) == 1.0 and pass_hat_k(3, 4, 4) == 0.0
    assert pass_hat_k(3, 4, 2) == pytest.approx(3 / 6)  # C(3,2)/C(4,2)
    assert pass_hat_k(4, 4, 1) == 1.0 and pass_hat_k(1, 4, 1) == 0.25  # pass^1 = pass@1


def test_samples_get_their_own_seeds_and_sample_zero_keeps_its_key() -> None:
    groups = build_groups(("stacking",), 2, 0, ground_truth=True)
    setting = Setting(planner="noisy")
    jobs = jobs_for(setting, groups, "s", samples=3)
    assert [(j.task_id, j.sample) for j in jobs][:3] == [("stacking/0", 0), ("stacking/0", 1),
                                                         ("stacking/0", 2)]
    assert len({j.seed for j in jobs}) == len(jobs) == 6
    assert len({j.key() for j in jobs}) == 6
    single = jobs_for(setting, groups, "s")
    assert [j.key() for j in single] == [jobs[0].key(), jobs[3].key()]
    assert job_for(groups[0].tasks[0], setting, "s").seed == single[0].seed


def test_pass_k_counts_a_task_only_when_every_sample_succeeds() -> None:
    groups = build_groups(("stacking", "language"), 6, 0, ground_truth=True)
    noisy = Setting(planner="noisy", noise=0.5, mode="direct")
    records = run_jobs(jobs_for(noisy, groups, "s", samples=4), task_index(groups),
                       RunOptions(progress=False))
    assert {r.sample for r in records} == {0, 1, 2, 3}
    for group, stats in stats_by_group(records).items():
        by_task: dict[str, list[bool]] = {}
        for r in records:
            if r.group == group:
                by_task.setdefault(r.task_id, []).append(r.success)
        assert stats.samples == 4 and stats.tasks == 6 and stats.episodes == 24
        assert stats.pass_k == sum(all(v) for v in by_task.values()) / 6
        assert stats.success_rate == sum(sum(v) for v in by_task.values()) / 24
        assert stats.pass_k <= stats.success_rate
    overall = sum(r.success for r in records) / len(records)
    assert 0 < overall < 1  # a noisy direct planner: the samples really differ
    oracle = run_jobs(jobs_for(Setting(planner="oracle"), groups, "s", samples=2),
                      task_index(groups), RunOptions(progress=False))
    assert all(s.pass_k == 1.0 for s in stats_by_group(oracle).values())


def test_bench_plan_and_report_print_pass_k_beside_pass_at_1(tmp_path: Path) -> None:
    results = tmp_path / "r.jsonl"
    text = plan_report(["--episodes", "3", "--groups", "stacking", "--planners", "oracle,noisy",
                        "--no-ablations", "--samples", "3", "--results", str(results),
                        "--no-progress-bar"])
    assert "3 samples per task" in text
    section = text[text.index("### Reliability: pass^k (all k = 3 samples"):]
    assert "| oracle, iterative k=3 t=5 | 3 | 100% / 100% | 100% / 100% |" in section
    row = next(line for line in section.splitlines() if line.startswith("| noisy (30%), direct"))
    pass1, passk = map(int, re.findall(r"(\d+)% / (\d+)%", row)[0])
    assert passk <= pass1
    assert "Episodes run: 45;" in text  # (2 oracle + 3 noisy rows) x 3 tasks x 3 samples
    report = render_report(ResultsFile(results).load())
    assert "### Reliability: pass^k" in report
    assert "| oracle, direct | 3 | 100% / 100% | 100% / 100% |" in report
