"""`verigraph agent` end to end: a real MCP client against `verigraph serve`.

Over stdio the agent spawns the server itself; over HTTP it connects to a server this
test starts on a free loopback port. Both go through the official SDK's client.
"""

from __future__ import annotations

import json
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import httpx2
import pytest

from verigraph.agent import LoopConfig, McpTools, run_episode
from verigraph.cli import main
from verigraph.planning.noisy import NoisyPlanner
from verigraph.tasks import EpisodeSpec

AGENT = [sys.executable, "-m", "verigraph", "agent"]


def agent(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*AGENT, *args], capture_output=True, text=True, timeout=120)


def test_cli_oracle_over_stdio_prints_iterations_and_writes_the_trace(tmp_path: Path) -> None:
    trace_file = tmp_path / "trace.json"
    done = agent("--scene", "cup_on_book", "--planner", "oracle", "--k", "1",
                 "--trace", str(trace_file))
    assert done.returncode == 0, done.stderr
    out = done.stdout
    assert "over stdio" in out and "[1] proposed: move(cup, on, desk)" in out
    assert "[2] proposed: move(book, on, shelf), done" in out
    assert "SUCCESS (goal_reached, stopped: end_token)" in out
    trace = json.loads(trace_file.read_text())
    assert trace["transport"] == "stdio" and trace["success"] is True
    assert [it["executed"] for it in trace["iterations"]] == [
        ["move(cup, on, desk)"], ["move(book, on, shelf)"]]
    assert trace["episode_id"].startswith("ep_")


def test_cli_noisy_planner_shows_feedback_and_still_succeeds(tmp_path: Path) -> None:
    done = agent("--scene", "three_blocks", "--planner", "noisy", "--noise", "0.6",
                 "--seed", "4", "--k", "1", "--threshold", "10", "--trace",
                 str(tmp_path / "t.json"))
    assert done.returncode == 0, done.stdout + done.stderr
    trace = json.loads((tmp_path / "t.json").read_text())
    refused = [it for it in trace["iterations"] if it["verdict"] == "violation"]
    assert refused, "seed 4 injects mistakes the verifier must refuse"
    assert "feedback: " in done.stdout and "REFUSED by the verifier" in done.stdout
    assert trace["success"] is True and trace["violations_caught"] == len(refused)


def test_cli_always_failing_run_exits_1_with_the_threshold_verdict(tmp_path: Path) -> None:
    goal = tmp_path / "goal.json"
    goal.write_text(json.dumps({"predicate": "single_stack"}))
    done = agent("--scene", "three_blocks", "--goal", str(goal), "--planner", "noisy",
                 "--noise", "1.0", "--mistakes", "hallucinated", "--k", "1", "--threshold",
                 "2", "-q")
    assert done.returncode == 1
    assert "FAILURE (threshold_reached, stopped: threshold)" in done.stdout
    assert "[1]" not in done.stdout  # --quiet prints only the verdict


def test_cli_bad_input_exits_2_naming_the_flag() -> None:
    done = agent("--scene", "no_such_scene")
    assert done.returncode == 2
    assert "--scene" in done.stderr and "fix:" in done.stderr
    done = agent("--scene", "cup_on_book", "--k", "0")
    assert done.returncode == 2 and "--k" in done.stderr


def test_cli_in_process_entry_point(capfd: pytest.CaptureFixture[str]) -> None:
    # capfd, not capsys: the SDK hands the server child a real stderr file descriptor
    code = main(["agent", "--scene", "cup_on_book", "--mode", "direct", "--planner", "oracle"])
    assert code == 0
    assert "mode direct" in capfd.readouterr().out


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.fixture(scope="module")
def http_server() -> Iterator[str]:
    port = _free_port()
    proc = subprocess.Popen([sys.executable, "-m", "verigraph", "serve", "--transport", "http",
                             "--port", str(port)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}/mcp"
    try:
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            try:
                httpx2.get(f"http://127.0.0.1:{port}/", timeout=1)
                break
            except httpx2.HTTPError:
                time.sleep(0.1)
        yield url
    finally:
        proc.terminate()
        proc.wait(timeout=10)


def test_cli_over_http(http_server: str, tmp_path: Path) -> None:
    done = agent("--scene", "cup_on_book", "--transport", "http", "--url", http_server,
                 "--trace", str(tmp_path / "t.json"))
    assert done.returncode == 0, done.stderr
    assert "over http" in done.stdout
    assert json.loads((tmp_path / "t.json").read_text())["transport"] == "http"


def test_library_loop_over_http_with_two_episodes(http_server: str) -> None:
    env = McpTools.http(http_server)
    try:
        traces = [run_episode(env, NoisyPlanner(0.3, seed=s),
                              EpisodeSpec(load={"scene_id": "three_blocks"}), LoopConfig(k=2))
                  for s in range(2)]
    finally:
        env.close()
    assert all(t.success for t in traces)
    assert traces[0].episode_id != traces[1].episode_id


def test_cli_http_without_url_is_bad_input() -> None:
    done = agent("--scene", "cup_on_book", "--transport", "http")
    assert done.returncode == 2 and "--url" in done.stderr


def test_agent_prompt_is_the_servers_mcp_prompt() -> None:
    """The agent renders the same text the server's `iterative_planner` prompt serves."""
    from verigraph.graph import Goal, SceneGraph, WorldState
    from verigraph.planning.prompting import planner_prompt

    env = McpTools.stdio()
    try:
        state = env.call("load_scene", {"scene_id": "cup_on_book", "k": 2})
        served = env.prompt("iterative_planner", {"episode_id": state["episode_id"]})
        env.call("end_episode", {"episode_id": state["episode_id"]})
    finally:
        env.close()
    ours = planner_prompt("iterative", WorldState.from_graph(
        SceneGraph.model_validate(state["graph"])), Goal.model_validate(state["goal"]), k=2,
        instruction=state["instruction"], history=[], feedback=None, iteration=1)
    hint = served.find("\n(With the VeriGraph tools")
    assert hint > 0
    # same lines; object order may differ (tool results list nodes in canonical order)
    assert sorted(served[:hint].rstrip().splitlines()) == sorted(ours.rstrip().splitlines())


def test_cli_planner_failure_exits_3_and_still_writes_the_trace(tmp_path: Path) -> None:
    trace_file = tmp_path / "trace.json"
    dead = f"http://127.0.0.1:{_free_port()}/v1"  # nothing listens there
    done = agent("--scene", "cup_on_book", "--planner", "openai", "--base-url", dead,
                 "--model", "m", "--api-key", "x", "--retries", "0", "--timeout", "2",
                 "--trace", str(trace_file), "-q")
    assert done.returncode == 3, done.stdout + done.stderr
    assert "the planner failed" in done.stderr
    trace = json.loads(trace_file.read_text())
    assert trace["stop_reason"] == "planner_error" and trace["planner_error"]
    assert trace["success"] is False


def test_cli_help_documents_every_stop(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["agent", "--help"])
    assert exit_info.value.code == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "--max-iterations N stop after N planner calls" in text
    assert "--no-progress N" in text and "--no-stop-on-goal" in text
    assert "--record DIR" in text and "--replay DIR" in text
