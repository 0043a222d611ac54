"""The solver never falls over: time and memory budgets, a distinct exit code, anytime plans."""

from __future__ import annotations

import json
import subprocess
import sys
import time

import pytest

from scenes import random_blocks
from verigraph.actions import validate_plan
from verigraph.graph import Goal
from verigraph.solver import solve


def test_a_200_block_scene_ends_cleanly_on_the_time_limit():
    """The limit is the search's CPU time, so it holds on a busy machine too."""
    start, goal = random_blocks(200, 3), Goal(graph=random_blocks(200, 4))
    cpu = time.thread_time()
    result = solve(start, goal, time_limit=1.0)
    assert result.status == "budget_exhausted" and result.reachable is None
    assert "time limit 1 s CPU" in result.reason and "expansions" in result.reason
    assert time.thread_time() - cpu < 3.0


def test_a_200_block_scene_ends_cleanly_on_the_memory_limit():
    start, goal = random_blocks(200, 3), Goal(graph=random_blocks(200, 4))
    result = solve(start, goal, memory_limit_mb=5, time_limit=60)
    assert result.status == "budget_exhausted" and "memory limit 5 MB" in result.reason
    assert result.memory_mb < 60  # stopped soon after passing the limit


@pytest.mark.parametrize("n", [20, 30, 40, 50])
def test_anytime_plans_are_valid_and_within_twice_the_lower_bound(n):
    for seed in range(3):
        start, goal = random_blocks(n, seed), Goal(graph=random_blocks(n, seed + 100))
        result = solve(start, goal, anytime=True, time_limit=1.0)
        assert result.reachable and result.lower_bound is not None
        assert validate_plan(start, result.plan, goal)["valid"]
        assert result.lower_bound <= len(result.plan) <= 2 * result.lower_bound
        if result.optimal:
            assert len(result.plan) == result.lower_bound


def test_anytime_finds_the_optimum_when_the_search_can_prove_it():
    start, goal = random_blocks(8, 1), Goal(graph=random_blocks(8, 2))
    optimal = solve(start, goal)
    anytime = solve(start, goal, anytime=True)
    assert anytime.optimal and len(anytime.plan) == len(optimal.plan) == anytime.lower_bound


def test_cli_exit_3_with_a_json_reason_on_a_1000_block_scene(tmp_path):
    (tmp_path / "s.json").write_text(random_blocks(1000, 3).model_dump_json())
    (tmp_path / "g.json").write_text(random_blocks(1000, 4).model_dump_json())
    cmd = [sys.executable, "-m", "verigraph", "solve", "--scene", str(tmp_path / "s.json"),
           "--goal", str(tmp_path / "g.json"), "--json", "--time-limit", "1"]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    assert r.returncode == 3, r.stderr
    out = json.loads(r.stdout)
    assert out["status"] == "budget_exhausted" and out["reason"].startswith("budget exhausted")
    assert "Traceback" not in r.stderr
    r = subprocess.run([*cmd, "--anytime"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert len(out["plan"]) <= 2 * out["lower_bound"]


def test_cli_help_states_the_units():
    r = subprocess.run([sys.executable, "-m", "verigraph", "solve", "--help"],
                       capture_output=True, text=True, timeout=60)
    assert "--time-limit SECONDS" in r.stdout and "--memory-limit MB" in r.stdout
    assert "MiB" in r.stdout and "seconds" in r.stdout


@pytest.mark.anyio
async def test_the_solve_tool_has_the_same_budget_and_answers_when_it_runs_out():
    from mcp import Client
    from mcp_helpers import structured

    from verigraph.server import build_server
    from verigraph.solver import DEFAULT_MEMORY_LIMIT_MB, DEFAULT_TIME_LIMIT_S
    from verigraph.tools import Toolbox
    from verigraph.tools.solving import SolveInput

    fields = SolveInput.model_fields
    assert fields["time_limit"].default == DEFAULT_TIME_LIMIT_S
    assert fields["memory_limit_mb"].default == DEFAULT_MEMORY_LIMIT_MB
    start, goal = random_blocks(60, 3), random_blocks(60, 4)
    async with Client(build_server(Toolbox())) as client:
        out = structured(await client.call_tool("solve", {
            "graph": start.model_dump(), "goal": {"graph": goal.model_dump()}, "time_limit": 0.5}))
        assert out["reachable"] is None and "budget exhausted" in out["reason"]
        out = structured(await client.call_tool("solve", {
            "graph": start.model_dump(), "goal": {"graph": goal.model_dump()}, "time_limit": 0.5,
            "anytime": True}))
        assert out["verified"] and out["length"] <= 2 * out["lower_bound"]
