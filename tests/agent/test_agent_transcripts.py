"""Recording planner transcripts and replaying them offline, in-process, CLI and bench."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from verigraph.agent import LoopConfig, run_episode
from verigraph.agent.transcripts import RecordingPlanner, ReplayingPlanner
from verigraph.planning import InProcessTools
from verigraph.planning.noisy import NoisyPlanner
from verigraph.tasks import EpisodeSpec

STACK = EpisodeSpec(load={"scene_id": "three_blocks"})
CUP = EpisodeSpec(load={"scene_id": "cup_on_book"})


def test_a_replayed_transcript_reproduces_the_episode(tmp_path: Path) -> None:
    env = InProcessTools()
    recorder = RecordingPlanner(NoisyPlanner(0.6, seed=4), tmp_path, "three_blocks")
    live = run_episode(env, recorder, STACK, LoopConfig(k=2))
    lines = recorder.path.read_text().splitlines()
    assert json.loads(lines[0])["planner"] == "noisy(60%)"
    assert len(lines) == 1 + live.llm_calls
    replayed = run_episode(env, ReplayingPlanner(tmp_path, "three_blocks"), STACK,
                           LoopConfig(k=2))
    assert replayed.planner == "replay(noisy(60%))"
    assert [r.proposed for r in replayed.iterations] == [r.proposed for r in live.iterations]
    assert [r.verdict for r in replayed.iterations] == [r.verdict for r in live.iterations]
    assert (replayed.success, replayed.violations_caught, replayed.malformed_outputs) == (
        live.success, live.violations_caught, live.malformed_outputs)


def test_a_transcript_for_another_episode_or_none_is_a_planner_error(tmp_path: Path) -> None:
    env = InProcessTools()
    run_episode(env, RecordingPlanner(NoisyPlanner(0.0), tmp_path, "x"), STACK)
    wrong = run_episode(env, ReplayingPlanner(tmp_path, "x"), CUP)
    assert wrong.stop_reason == "planner_error"
    assert wrong.planner_error is not None and "prompt differs" in wrong.planner_error
    missing = run_episode(env, ReplayingPlanner(tmp_path, "nothing"), CUP)
    assert missing.stop_reason == "planner_error" and "no transcript" in (
        missing.planner_error or "")


def test_cli_records_then_replays_without_the_planner(tmp_path: Path) -> None:
    agent = [sys.executable, "-m", "verigraph", "agent", "--scene", "cup_on_book", "-q"]
    rec = subprocess.run([*agent, "--planner", "noisy", "--noise", "0.5", "--seed", "3",
                          "--record", str(tmp_path)], capture_output=True, text=True,
                         timeout=120)
    assert rec.returncode in (0, 1), rec.stderr
    assert (tmp_path / "cup_on_book__iterative.jsonl").is_file()
    # an openai planner with no key and no endpoint: only the transcript answers
    rep = subprocess.run([*agent, "--planner", "openai", "--replay", str(tmp_path)],
                         capture_output=True, text=True, timeout=120)
    assert rep.returncode == rec.returncode, rep.stderr
    assert rep.stdout.splitlines()[-1].split(";")[0] == rec.stdout.splitlines()[-1].split(";")[0]


def test_bench_replays_its_own_recording(tmp_path: Path) -> None:
    pytest.importorskip("verigraph.sim2d.generator")
    from verigraph.cli.bench import plan_report as run

    args = ["--episodes", "2", "--groups", "stacking", "--planners", "noisy",
            "--no-ablations"]
    live = run([*args, "--record", str(tmp_path)])
    assert len(list(tmp_path.glob("*.jsonl"))) == 3 * 2  # 3 noisy rows x 2 tasks
    replayed = run([*args, "--replay", str(tmp_path)])

    def rows(text: str) -> list[str]:
        return [line.split(" | ")[1] for line in text.splitlines()
                if line.startswith("| noisy")]

    assert rows(replayed) == rows(live)
    assert "replayed from" in replayed
