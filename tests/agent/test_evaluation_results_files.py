"""Committed results stay as committed: `bench plan` writes a file only when asked and
never replaces a larger run with a smaller one; it runs from the package alone."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from verigraph.agent.evaluation.markdown import run_size, write_results
from verigraph.cli import bench, main
from verigraph.errors import VeriGraphError

pytest.importorskip("verigraph.sim2d.generator", reason="sim2d not installed")

ROOT = Path(__file__).resolve().parents[2]
QUICK = ["--episodes", "1", "--groups", "stacking", "--planners", "oracle", "--no-ablations",
         "--no-progress-bar"]
LARGE = "# Planning benchmark\n\nrows\n\nEpisodes run: 4000; total wall time 77.2 s.\n"


def test_a_quick_run_leaves_the_committed_table_alone(capsys: pytest.CaptureFixture[str]
                                                      ) -> None:
    committed = ROOT / "benchmarks" / "results" / "plan.md"
    before = committed.read_bytes()
    assert main(["bench", "plan", *QUICK]) == 0
    assert "Episodes run: 2;" in capsys.readouterr().out  # oracle iterative and direct
    assert committed.read_bytes() == before


def test_update_results_refuses_to_replace_a_larger_run(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    checkout = tmp_path / "benchmarks"
    (checkout / "results").mkdir(parents=True)
    target = checkout / "results" / "plan.md"
    target.write_text(LARGE)
    monkeypatch.setattr(bench, "benchmarks_dir", lambda: checkout)
    assert main(["bench", "plan", *QUICK, "--update-results"]) == 2
    assert target.read_text() == LARGE
    with pytest.raises(VeriGraphError, match="holds a run of 4000 episodes") as err:
        bench.plan_report([*QUICK, "--update-results"])
    assert err.value.field == "--update-results" and "--force" in (err.value.fix or "")
    assert main(["bench", "plan", *QUICK, "--update-results", "--force"]) == 0
    assert run_size(target.read_text()) == 2
    assert "# Planning benchmark (verigraph bench plan)" in target.read_text()
    truth = checkout / "results" / "plan_ground_truth.md"
    assert main(["bench", "plan", *QUICK, "--update-results", "--ground-truth-graphs"]) == 0
    assert "with true goal graphs" in truth.read_text()


def test_out_follows_the_same_rule(tmp_path: Path) -> None:
    out = tmp_path / "plan.md"
    out.write_text(LARGE)
    assert main(["bench", "plan", *QUICK, "--out", str(out)]) == 2
    assert out.read_text() == LARGE
    write_results(out, "no size stated\n")  # nothing to compare: written
    assert out.read_text() == "no size stated\n"
    assert main(["bench", "plan", *QUICK, "--out", str(out)]) == 0
    assert run_size(out.read_text()) == 2


def test_bench_plan_runs_from_the_package_without_the_benchmarks_folder(tmp_path: Path
                                                                        ) -> None:
    shutil.copytree(ROOT / "verigraph", tmp_path / "verigraph",
                    ignore=shutil.ignore_patterns("__pycache__"))
    env = {**os.environ, "PYTHONPATH": str(tmp_path)}
    done = subprocess.run([sys.executable, "-m", "verigraph", "bench", "plan", *QUICK],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "| oracle, iterative k=3 t=5 | 100% |" in done.stdout
    assert "### The paper's numbers (Table 2)" in done.stdout
    other = subprocess.run([sys.executable, "-m", "verigraph", "bench", "validate"],
                           cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert other.returncode == 2 and "no benchmarks/ directory found" in other.stderr
    refused = subprocess.run([sys.executable, "-m", "verigraph", "bench", "plan", *QUICK,
                              "--update-results"], cwd=tmp_path, env=env,
                             capture_output=True, text=True, timeout=300)
    assert refused.returncode == 2 and "needs a source checkout" in refused.stderr
