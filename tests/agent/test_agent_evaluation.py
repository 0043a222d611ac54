"""`verigraph bench plan`: task groups, instruction templates, metrics and the report."""

from __future__ import annotations

import io
from collections.abc import Sequence

import pytest

from verigraph.agent.evaluation import Setting
from verigraph.agent.evaluation.engine import RunOptions, run_jobs
from verigraph.agent.evaluation.spec import jobs_for, task_index
from verigraph.agent.evaluation.tables import GroupStats, stats_by_group
from verigraph.cli.bench import plan_report as run
from verigraph.jobs.progress_bar import EpisodeProgress
from verigraph.tasks import GroupTasks, build_groups
from verigraph.tasks.groups import GroupName

generator = pytest.importorskip("verigraph.sim2d.generator", reason="sim2d not installed")


def run_setting(setting: Setting, groups: Sequence[GroupTasks]) -> dict[GroupName, GroupStats]:
    """One setting over the groups, through the engine (serial, no results file)."""
    records = run_jobs(jobs_for(setting, groups, "test"), task_index(groups),
                       RunOptions(progress=False))
    return stats_by_group(records)


def test_reference_image_groups_run_with_perception() -> None:
    groups = build_groups(("ref_image_blocks", "tangram"), 2, 0, ground_truth=False)
    ref, tangram = groups
    assert ref.not_run is None and len(ref.tasks) == 2
    assert "image" in (ref.tasks[0].spec.set_goal or {})
    assert tangram.not_run is None and len(tangram.tasks) == 2
    truth = build_groups(("ref_image_blocks",), 2, 0, ground_truth=True)[0]
    assert truth.not_run is None and len(truth.tasks) == 2
    assert "graph" in (truth.tasks[0].spec.set_goal or {})


def test_oracle_solves_every_group_and_noise_hurts_direct_more_than_iterative() -> None:
    groups = build_groups(("stacking", "language", "ref_image_kitchen", "ref_image_blocks",
                           "tangram"), 8, 0, ground_truth=True)
    oracle = run_setting(Setting(planner="oracle"), groups)
    assert all(s.success_rate == 1.0 for s in oracle.values()), oracle
    assert all(s.violations_caught == 0 for s in oracle.values())

    def overall(setting: Setting) -> float:
        stats = run_setting(setting, groups)
        return sum(s.success_rate * s.episodes for s in stats.values()) / sum(
            s.episodes for s in stats.values())

    patient = overall(Setting(planner="noisy", noise=0.3, k=1, threshold=10))
    hasty = overall(Setting(planner="noisy", noise=0.3, k=1, threshold=2))
    direct = overall(Setting(planner="noisy", noise=0.3, mode="direct"))
    assert patient >= hasty + 0.2, (patient, hasty)
    assert direct <= patient - 0.4, (direct, patient)


def test_report_groups_planner_kinds_and_keeps_the_paper_in_its_own_table() -> None:
    text = run(["--episodes", "3", "--groups", "stacking,language,ref_image_blocks"])
    assert "| oracle, iterative k=3 t=5 | 100% | 100% |" in text
    assert "**Privileged ceiling: oracle" in text and "**Greedy feedback-driven" in text
    assert "greedy, iterative k=3 t=5, feedback none" in text
    assert "noisy (30%), iterative k=3 t=5, trust done, end token only" in text
    assert "### What feedback is worth (greedy baseline)" in text
    assert "### Rule-based translator: instruction to goal" in text and "| all | " in text
    assert "| Stacking | 3 | " in text  # the difficulty table
    assert "Suite version 2" in text
    assert "Reliability" not in text  # one sample per task: no pass^k table
    paper = text[text.index("### The paper's numbers"):]
    assert "| Ours (iterative) | 0.65 | 0.65 | 0.86 | 0.55 | 0.72 |" in paper
    assert "| Ours (Direct) | 0.35 | 0.73 | 0.67 | 0.50 | 0.72 |" in paper
    assert "| SayCan | 0.07 | 0.17 | - | 0.00 | - |" in paper
    assert "58 points on language" in paper
    assert "Not comparable in value" in paper
    for t in (2, 3, 5, 10):
        assert f"\n| {t} | " in text


def test_bench_rejects_unknown_groups_and_planners() -> None:
    from verigraph.errors import VeriGraphError

    with pytest.raises(VeriGraphError, match="--groups"):
        run(["--groups", "juggling"])
    with pytest.raises(VeriGraphError, match="--planners"):
        run(["--planners", "gpt-17", "--groups", "stacking"])
    with pytest.raises(VeriGraphError, match="--samples"):
        run(["--samples", "0", "--groups", "stacking"])


def test_progress_bar_reports_on_a_pipe() -> None:
    groups = build_groups(("stacking",), 4, 0, ground_truth=True)
    records = run_jobs(jobs_for(Setting(planner="oracle"), groups, "test"), task_index(groups),
                       RunOptions(progress=False))
    stream = io.StringIO()
    bar = EpisodeProgress(len(records), stream=stream)
    for record in records:
        bar.update(record)
    bar.close()
    lines = [line for line in stream.getvalue().replace("\r", "\n").splitlines() if line]
    assert 1 <= len(lines) <= 3  # a pipe gets a few lines, not one per refresh
    assert "4/4" in lines[-1] and "stacking 4/4" in lines[-1]
    assert bar.summary().startswith("finished: 4/4 episodes done (0 from the results file")


def test_a_failing_llm_planner_is_counted_and_the_bench_goes_on(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from planning_doubles import RecordedResponse, RecordedResponseServerForTests

    groups = build_groups(("stacking",), 3, 0, ground_truth=True)
    refusal = RecordedResponse({"error": {"message": "invalid key"}}, status=401)
    with RecordedResponseServerForTests([refusal] * 3) as server:
        monkeypatch.setenv("OPENAI_BASE_URL", server.url)
        monkeypatch.setenv("OPENAI_API_KEY", "not-a-key")
        monkeypatch.setenv("OPENAI_MODEL", "m")
        stats = run_setting(Setting(planner="openai"), groups)["stacking"]
    assert stats.episodes == 3 and stats.errors == 3 and stats.success_rate == 0.0
    assert len(server.requests) == 3  # one call per episode: a 401 is not retried
