"""The evaluation engine, serial path: results dataset, resume after a kill, failures,
retries on 429, the report and its figures (the limiter alone: tests/jobs)."""

from __future__ import annotations

import json
import os
import signal
import struct
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from planning_doubles import RecordedResponse as R
from planning_doubles import (
    RecordedResponseServerForTests,
    ScriptedPlannerForTests,
    chat_completion,
)

from verigraph.agent.evaluation import Setting
from verigraph.agent.evaluation.engine import RunOptions, run_jobs
from verigraph.agent.evaluation.guard import RetryPolicy
from verigraph.agent.evaluation.results import ResultsFile
from verigraph.agent.evaluation.spec import job_for, jobs_for, task_index
from verigraph.agent.evaluation.tables import outcome_part, render_report
from verigraph.agent.evaluation.worker import EngineConfig, PlannerPool, run_job
from verigraph.graph.goal import Goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.jobs.limiter import BackendLimits, Gate
from verigraph.planning.factory import PlannerOptions
from verigraph.planning.tool_calls import InProcessTools
from verigraph.solver import solve
from verigraph.tasks import build_groups

pytest.importorskip("verigraph.sim2d.generator", reason="sim2d not installed")

ROOT = Path(__file__).resolve().parents[2]
PLAN_ARGS = ["--episodes", "3", "--groups", "stacking,language", "--planners", "noisy",
             "--no-ablations"]
PLAN_EPISODES = 3 * 2 * 3  # episodes x groups x (iterative, direct, trust done)


def cli(*args: str) -> list[str]:
    return [sys.executable, "-m", "verigraph", *args]


def child_env() -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": str(ROOT)}


def wait_for_lines(path: Path, n: int, proc: subprocess.Popen[bytes]) -> int:
    """Block until the results file has n whole lines (or the process ended)."""
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        count = path.read_bytes().count(b"\n") if path.exists() else 0
        if count >= n or proc.poll() is not None:
            return count
        time.sleep(0.05)
    raise AssertionError(f"{path} never reached {n} lines")


def test_interrupted_and_killed_runs_resume_to_the_uninterrupted_table(tmp_path: Path) -> None:
    results = tmp_path / "partial.jsonl"
    slow = [*PLAN_ARGS, "--results", str(results), "--simulated-latency", "0.15",
            "--out", str(tmp_path / "ignored.md")]
    # Ctrl-C part way: the summary says what is done and how to resume.
    proc = subprocess.Popen(cli("bench", "plan", *slow), env=child_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert wait_for_lines(results, 3, proc) >= 3 and proc.poll() is None
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err.decode()
    assert "interrupted:" in err.decode() and "rerun the same command to resume" in err.decode()
    after_int = results.read_bytes()
    # Killed outright part way through the resumed run.
    proc = subprocess.Popen(cli("bench", "plan", *slow), env=child_env(),
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    first = after_int.count(b"\n")
    assert wait_for_lines(results, first + 3, proc) >= first + 3 and proc.poll() is None
    proc.kill()
    proc.wait(timeout=30)
    after_kill = results.read_bytes()
    assert after_kill.startswith(after_int)  # finished episodes were not run again
    finished = after_kill[:after_kill.rfind(b"\n") + 1].count(b"\n")
    assert first < finished < PLAN_EPISODES
    # The rerun completes only what is missing.
    done = subprocess.run(cli("bench", "plan", *PLAN_ARGS, "--results", str(results), "--out",
                              str(tmp_path / "ignored.md")),
                          env=child_env(), capture_output=True, timeout=300)
    assert done.returncode == 0, done.stderr.decode()
    assert f"resuming: {finished} of {PLAN_EPISODES} episodes" in done.stderr.decode()
    assert f"running {PLAN_EPISODES - finished}" in done.stderr.decode()
    records = ResultsFile(results).load()
    assert len(records) == PLAN_EPISODES == len({r.key for r in records})
    assert results.read_bytes().startswith(after_kill[:after_kill.rfind(b"\n") + 1])
    # An uninterrupted run renders the same tables.
    whole = tmp_path / "whole.jsonl"
    subprocess.run(cli("bench", "plan", *PLAN_ARGS, "--results", str(whole), "--out",
                       str(tmp_path / "ignored.md")),
                   env=child_env(), capture_output=True, timeout=300, check=True)
    resumed_report = subprocess.run(cli("bench", "report", str(results)), env=child_env(),
                                    capture_output=True, text=True, check=True).stdout
    whole_report = subprocess.run(cli("bench", "report", str(whole)), env=child_env(),
                                  capture_output=True, text=True, check=True).stdout
    assert "| noisy (30%), direct |" in whole_report
    assert outcome_part(resumed_report) == outcome_part(whole_report)


def test_a_cut_off_last_line_is_dropped_before_appending(tmp_path: Path) -> None:
    groups = build_groups(("stacking",), 2, 0, ground_truth=True)
    jobs = jobs_for(Setting(planner="oracle"), groups, "suite")
    path = tmp_path / "r.jsonl"
    options = RunOptions(results=str(path), progress=False)
    run_jobs(jobs[:1], task_index(groups), options)
    path.write_bytes(path.read_bytes() + b'{"key": "half a rec')
    records = run_jobs(jobs, task_index(groups), options)
    assert [r.task_id for r in records] == ["stacking/0", "stacking/1"]
    assert [r.task_id for r in ResultsFile(path).load()] == ["stacking/0", "stacking/1"]


def _oracle_answer(task: Any) -> dict[str, Any]:
    state = WorldState.from_graph(SceneGraph.model_validate(task.spec.load["graph"]))
    goal = Goal(graph=SceneGraph.model_validate((task.spec.set_goal or {})["graph"]))
    plan = solve(state, goal).plan
    actions = [a.model_dump(mode="json") for a in plan] + [{"action": "done"}]
    return chat_completion(json.dumps({"actions": actions}))


def _openai(url: str, retries: int = 3) -> EngineConfig:
    return EngineConfig(planner_options=PlannerOptions(base_url=f"{url}/v1", model="recorded",
                                                       api_key="sk-test"),
                        retry=RetryPolicy(retries=retries, backoff_s=0.01))


def test_429_twice_then_success_is_retried_and_recorded() -> None:
    groups = build_groups(("stacking",), 1, 0, ground_truth=True)
    task = groups[0].tasks[0]
    busy = R({"error": {"message": "rate limited"}}, status=429)
    with RecordedResponseServerForTests([busy, busy, R(_oracle_answer(task))]) as server:
        jobs = jobs_for(Setting(planner="openai", mode="direct"), groups, "suite")
        [record] = run_jobs(jobs, task_index(groups),
                            RunOptions(engine=_openai(server.url), progress=False))
    assert len(server.requests) == 3
    assert record.success and record.error is None and record.stop_reason == "single_shot"
    assert (record.requests, record.retries, record.planner_calls) == (3, 2, 1)
    assert record.total_tokens == 120 and record.planner == "openai:recorded"


def test_planner_failures_are_outcomes_and_the_run_goes_on() -> None:
    groups = build_groups(("stacking",), 3, 0, ground_truth=True)
    tasks = groups[0].tasks
    refused = R({"error": {"message": "invalid api key"}}, status=401)
    with RecordedResponseServerForTests([refused, R(_oracle_answer(tasks[1])),
                                         *[R({"error": {"message": "down"}}, status=503)] * 3]
                                        ) as server:
        jobs = jobs_for(Setting(planner="openai", mode="direct"), groups, "suite")
        records = run_jobs(jobs, task_index(groups),
                           RunOptions(engine=_openai(server.url, retries=2), progress=False))
    assert [r.success for r in records] == [False, True, False]
    assert records[0].error_kind == "planner" and "HTTP 401" in (records[0].error or "")
    assert records[0].retries == 0  # a 401 is not retried
    assert records[2].stop_reason == "planner_error" and records[2].retries == 2
    assert "HTTP 503" in (records[2].error or "")
    # A planner that raises something other than an endpoint error.
    pool = PlannerPool(EngineConfig(), Gate(None), shared={
        "openai": ScriptedPlannerForTests([RuntimeError("model client crashed")])})
    result = run_job(job_for(tasks[0], Setting(planner="openai"), "suite"), tasks[0],
                     InProcessTools(), pool)
    assert not result.success and "model client crashed" in (result.error or "")


def _png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR"
    width, height = struct.unpack(">II", data[16:24])
    return width, height


def test_report_and_plots_from_a_results_file(tmp_path: Path) -> None:
    from verigraph.cli import main
    from verigraph.cli.bench import plan_report as run

    results = tmp_path / "r.jsonl"
    run(["--episodes", "2", "--groups", "stacking,language", "--results", str(results),
         "--no-progress-bar"])
    records = ResultsFile(results).load()
    report = render_report(records)
    assert "| oracle, iterative k=3 t=5 | 100% | 100% | 4 |" in report
    assert "Ablation: error threshold t (noisy (30%), iterative, k=3)" in report
    assert "Ablation: actions per iteration k (noisy (30%), iterative, t=5)" in report
    plots = tmp_path / "plots"
    assert main(["bench", "report", str(results), "--plot", str(plots)]) == 0
    names = sorted(p.name for p in plots.iterdir())
    assert names == ["ablation_k.png", "ablation_t.png", "iterations_hist.png",
                     "success_by_group.png"]
    for path in plots.iterdir():
        width, height = _png_size(path)
        assert 500 <= width <= 4000 and 350 <= height <= 3000, (path.name, width, height)
        assert path.stat().st_size > 10_000, path.name


def test_report_rejects_a_missing_or_foreign_file(tmp_path: Path) -> None:
    from verigraph.cli import main

    assert main(["bench", "report", str(tmp_path / "none.jsonl")]) == 2
    bad = tmp_path / "bad.jsonl"
    bad.write_text('{"hello": 1}\n')
    assert main(["bench", "report", str(bad)]) == 2


def test_an_address_nobody_answers_is_a_clear_error_not_a_hang() -> None:
    pytest.importorskip("ray", reason="the scale extra (ray) is not installed")
    from verigraph.errors import VeriGraphError

    groups = build_groups(("stacking",), 1, 0, ground_truth=True)
    jobs = jobs_for(Setting(planner="oracle"), groups, "suite")
    with pytest.raises(VeriGraphError, match="--ray: nothing answers at 127.0.0.1:1"):
        run_jobs(jobs, task_index(groups), RunOptions(ray="127.0.0.1:1", progress=False))
    with pytest.raises(VeriGraphError, match="not a Ray address"):
        run_jobs(jobs, task_index(groups), RunOptions(ray="head-without-port", progress=False))


@pytest.mark.parametrize("flags", [["--concurrency", "0"], ["--rpm", "0"],
                                   ["--retries", "-1"], ["--simulated-latency", "-1"]])
def test_bad_engine_flags_are_rejected_by_name(flags: list[str]) -> None:
    from verigraph.cli import main

    assert main(["bench", "plan", "--groups", "stacking", *flags]) == 2


def test_progress_counts_success_per_group_and_traces_are_written(tmp_path: Path) -> None:
    import io

    from verigraph.jobs.progress_bar import EpisodeProgress

    groups = build_groups(("stacking", "language"), 2, 0, ground_truth=True)
    jobs = jobs_for(Setting(planner="noisy", noise=1.0, mode="direct"), groups, "suite")
    options = RunOptions(progress=False, engine=EngineConfig(traces_dir=str(tmp_path)))
    records = run_jobs(jobs, task_index(groups), options)
    stream = io.StringIO()
    bar = EpisodeProgress(5, records[:1], stream=stream)
    for record in records[1:]:
        bar.update(record)
    bar.close()
    ok = {g: sum(r.success for r in records if r.group == g) for g in ("stacking", "language")}
    assert f"stacking {ok['stacking']}/2 language {ok['language']}/2" in stream.getvalue()
    assert "4/5" in stream.getvalue()
    summary = bar.summary(interrupted=True, results="r.jsonl")
    assert summary.startswith("interrupted: 4/5 episodes done (1 from the results file, 3 run")
    assert "resume" in summary and "r.jsonl" in summary
    for record in records:
        trace = json.loads(Path(record.trace_path or "").read_text())
        assert trace["task"] == record.task_id and trace["success"] == record.success


def test_named_backend_limits_override_the_default_budget() -> None:
    from verigraph.cli import main
    from verigraph.cli.bench import parse_limit

    name, limits = parse_limit("openai:gpt-4o-mini=500/16")
    assert name == "openai:gpt-4o-mini" and (limits.requests, limits.concurrency) == (500, 16)
    assert parse_limit("anthropic:claude=/2")[1].requests is None
    options = RunOptions(limits=BackendLimits(concurrency=1),
                         backend_limits={"fast": BackendLimits(concurrency=3)})
    limiter = options.limiter()
    assert limiter is not None
    assert [limiter.try_acquire("fast") for _ in range(4)][:3] == [0, 0, 0]
    assert limiter.try_acquire("fast") > 0 and limiter.try_acquire("slow") == 0
    assert limiter.try_acquire("slow") > 0
    assert RunOptions().limiter() is None
    for bad in ("openai=fast", "=5", "openai=0/1"):
        assert main(["bench", "plan", "--groups", "stacking", "--limit", bad]) == 2
