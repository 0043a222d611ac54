"""`verigraph rollouts`: a suite's rollouts from the command line, resumable, with pass^k."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path
from typing import Any, get_args

import pytest
from mcp_helpers import verigraph_command

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")

from verigraph.cli import main  # noqa: E402
from verigraph.cli.rollouts import FAMILIES, POLICIES  # noqa: E402
from verigraph.env import dataset  # noqa: E402
from verigraph.env.dataset import split_tasks, suite_tasks  # noqa: E402
from verigraph.env.rollout import PolicyName  # noqa: E402
from verigraph.env.trajectory import episodes, read_lines  # noqa: E402


def test_the_command_offers_the_environment_s_policies_and_families() -> None:
    assert get_args(PolicyName) == POLICIES and FAMILIES == dataset.FAMILIES


def summary(capsys: pytest.CaptureFixture[str], *args: str) -> dict[str, Any]:
    assert main(["rollouts", "--no-progress", "--json", *args]) == 0
    out: dict[str, Any] = json.loads(capsys.readouterr().out)
    return out


def test_the_oracle_solves_every_test_task_of_a_suite(capsys: pytest.CaptureFixture[str]
                                                       ) -> None:
    tests = split_tasks(suite_tasks("kitchen"), "test")
    got = summary(capsys, "--family", "kitchen", "--policy", "oracle", "--limit", "6")
    assert got["tasks"] == min(6, len(tests)) and got["rollouts"] == got["tasks"]
    assert got["pass@1"] == got["pass^k"] == 1.0 and got["mean_return"] >= 1.0
    assert got["errors"] == {}


def test_refused_actions_never_pass(capsys: pytest.CaptureFixture[str]) -> None:
    got = summary(capsys, "--family", "blocks", "--policy", "refuse", "--limit", "3",
                  "--threshold", "2")
    assert got["pass@1"] == got["pass^k"] == 0.0 and got["mean_steps"] == 2.0


def test_pass_hat_k_is_read_from_the_trajectories_and_a_rerun_resumes(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "run.jsonl"
    args = ["--family", "blocks", "--split", "all", "--policy", "noisy", "--noise", "0.5",
            "--samples", "3", "--limit", "8", "--trajectories", str(path)]
    first = summary(capsys, *args)
    written = path.read_bytes()
    runs: dict[str, list[bool]] = {}
    for lines in episodes(read_lines(path)):
        task = lines[0].task
        assert task is not None
        runs.setdefault(task.task_id, []).append(bool(lines[-1].success))
    assert len(runs) == 8 and all(len(v) == 3 for v in runs.values())
    assert first["pass@1"] == pytest.approx(sum(map(sum, runs.values())) / 24)
    assert first["pass^k"] == pytest.approx(sum(all(v) for v in runs.values()) / 8)
    assert first["pass^k"] < first["pass@1"]  # noise 0.5 fails some samples, not all
    again = summary(capsys, *args)
    assert again == first
    assert path.read_bytes() == written  # nothing run twice


def test_bad_input_is_one_message_and_exit_two(tmp_path: Path) -> None:
    for args, field in ((["--samples", "0"], "--samples"), (["--noise", "2"], "--noise"),
                        (["--tasks", str(tmp_path / "none.jsonl")], "task file")):
        done = subprocess.run([*verigraph_command(), "rollouts", *args], capture_output=True,
                              text=True, timeout=120, stdin=subprocess.DEVNULL)
        assert done.returncode == 2, done.stderr
        assert field in done.stderr and "Traceback" not in done.stderr


def run_cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*verigraph_command(), "rollouts", "--no-progress", *args],
                          capture_output=True, text=True, timeout=180,
                          stdin=subprocess.DEVNULL)


def test_a_resume_with_other_settings_is_refused_not_reported(tmp_path: Path) -> None:
    path = tmp_path / "run.jsonl"
    base = ["--family", "kitchen", "--policy", "oracle", "--limit", "2", "--json",
            "--trajectories", str(path)]
    first = run_cli(*base, "--max-steps", "1")
    assert first.returncode == 0, first.stderr
    assert json.loads(first.stdout)["pass@1"] == 0.0
    written = path.read_bytes()
    for extra, named in ((["--max-steps", "40"], "max_steps 1 (now 40)"),
                         (["--max-steps", "1", "--k", "1"], "k 3 (now 1)"),
                         (["--max-steps", "1", "--threshold", "2"], "threshold 5 (now 2)")):
        again = run_cli(*base, *extra)
        assert again.returncode == 2 and again.stdout == ""
        assert named in again.stderr and "--trajectories" in again.stderr
        assert "Traceback" not in again.stderr
        assert path.read_bytes() == written
    fresh = run_cli(*base[:-1], str(tmp_path / "fresh.jsonl"), "--max-steps", "40")
    assert json.loads(fresh.stdout)["pass@1"] == 1.0  # what the old run would have hidden


def test_a_byte_that_is_not_utf8_is_exit_two_naming_file_and_line(tmp_path: Path) -> None:
    run = tmp_path / "run.jsonl"
    args = ["--family", "blocks", "--policy", "refuse", "--limit", "1", "--threshold", "1",
            "--trajectories", str(run)]
    assert run_cli(*args).returncode == 0
    lines = run.read_bytes().count(b"\n")
    run.write_bytes(run.read_bytes() + b"\xff\n")
    tasks = tmp_path / "tasks.jsonl"
    dataset.write_jsonl(split_tasks(suite_tasks("tangram"), "test")[:2], tasks)
    tasks.write_bytes(tasks.read_bytes().replace(b'"tangram"', b'"tan\xffgram"', 1))
    for done, where in ((run_cli(*args), f"{run}:{lines + 1}"),
                        (run_cli("--tasks", str(tasks)), f"{tasks}:1")):
        assert done.returncode == 2, done.stderr
        assert where in done.stderr and "UTF-8" in done.stderr
        assert "Traceback" not in done.stderr
