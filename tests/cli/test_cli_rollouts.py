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
