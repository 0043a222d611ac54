"""Trajectories as JSONL, one line per step, and their replay.

A rollout writes a `reset` line (the task record, the seed, the first observation and
the state hash) and one `step` line per step: the observation the action answered, the
action text, the actions parsed from it, the reward, the verdict and violation, the
state hash after the step, and whether the episode ended (the line that ends it also
carries the outcome: success, stop reason, actions executed). That is enough to train on
(observation, action, reward) triples and to replay: `replay` starts each episode again
from its task record and feeds the recorded actions, and reports every step whose
observation, reward, verdict or state hash differs. A replay that matches shows the
rewards were produced by the verifier, not written by hand.

`TrajectoryFile` is the same format as the results file of `run_rollouts`: episodes
are appended as they finish and a rerun skips every episode already complete there.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

from verigraph.env.core import VeriGraphEnv
from verigraph.env.jsonl import decode, parse_models, read_models, write_models
from verigraph.tasks.task import Task


class TrajectoryLine(BaseModel):
    """One line of a trajectory file: an episode's start, or one step of it."""

    model_config = ConfigDict(extra="forbid")

    kind: Literal["reset", "step"]
    episode: str = Field(description="the rollout's id, shared by its lines")
    step: int = Field(ge=0, description="0 for the reset line")
    observation: str = Field(description="reset: the first observation; step: the one "
                                         "the action answered")
    state_hash: str = Field(description="the scene graph's digest after this line")
    task: Task | None = Field(default=None, description="reset only")
    settings: dict[str, Any] | None = Field(
        default=None, description="reset only: the environment settings the episode was "
                                  "played under (VeriGraphEnv.settings)")
    seed: int | None = None
    action: str | None = None
    parsed: list[str] = Field(default_factory=list)
    reward: float = 0.0
    verdict: str | None = None
    violation: dict[str, Any] | None = None
    terminated: bool = False
    truncated: bool = False
    next_observation: str | None = Field(default=None, description="step: the observation "
                                                                   "after it")
    success: bool | None = Field(default=None, description="the line that ends the "
                                                           "episode: was the goal reached")
    stop_reason: str | None = Field(default=None, description="the line that ends the "
                                                              "episode: why it ended")
    moves: int | None = Field(default=None, description="the line that ends the episode: "
                                                        "actions the verifier executed")

    @property
    def final(self) -> bool:
        """Whether this line ends its episode."""
        return self.terminated or self.truncated


def reset_line(episode: str, task: Task, seed: int | None, observation: str,
               info: dict[str, Any], settings: dict[str, Any] | None = None
               ) -> TrajectoryLine:
    return TrajectoryLine(kind="reset", episode=episode, step=0, observation=observation,
                          state_hash=info["state_hash"], task=task, seed=seed,
                          settings=settings)


def step_line(episode: str, observation: str, action: str, reward: float, terminated: bool,
              truncated: bool, info: dict[str, Any], next_observation: str
              ) -> TrajectoryLine:
    ended = terminated or truncated
    return TrajectoryLine(kind="step", episode=episode, step=info["step"],
                          observation=observation, action=action, parsed=info["parsed"],
                          reward=reward, verdict=info["verdict"], violation=info["violation"],
                          state_hash=info["state_hash"], terminated=terminated,
                          truncated=truncated, next_observation=next_observation,
                          success=bool(info["success"]) if ended else None,
                          stop_reason=info["stop_reason"] if ended else None,
                          moves=info["moves"] if ended else None)


def write_lines(lines: Iterable[TrajectoryLine], path: str | Path) -> int:
    """Append lines to a JSONL file; returns how many."""
    return write_models(lines, path, append=True, exclude_none=True)


def read_lines(path: str | Path) -> list[TrajectoryLine]:
    """Every line of a trajectory file (a bad line is an error naming it)."""
    rows = read_models(path, TrajectoryLine, what="trajectory file",
                       fix="pass a trajectory file written by write_lines")
    return [line for _, line in rows]


class TrajectoryFile:
    """A trajectory JSONL that rollouts append to as they finish: their results file.

    Each finished episode's lines go out in one write, flushed, so killing the run loses
    at most the episodes in flight. `complete(repair=True)` reads the episodes already
    there and cuts off whatever follows the last line that ended an episode (a line cut
    short, an episode whose end never came) before anything more is appended, so a
    resumed run leaves every episode in the file exactly once.
    """

    FIX = "pass a trajectory file written by run_rollouts or write_lines, or a new file"

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)

    def complete(self, repair: bool = False) -> dict[str, list[TrajectoryLine]]:
        """Lines of every complete episode (a reset ... the line that ended it), by id."""
        if not self.path.exists():
            return {}
        data = self.path.read_bytes()
        whole = decode(data[:data.rfind(b"\n") + 1], source=str(self.path),
                       what="trajectory file", fix=self.FIX)
        rows = parse_models(whole, TrajectoryLine, source=str(self.path), fix=self.FIX)
        last = max((number for number, line in rows if line.final), default=0)
        keep = sum(len(text.encode("utf-8")) + 1 for text in whole.split("\n")[:last])
        if repair and keep < len(data):
            with self.path.open("r+b") as handle:
                handle.truncate(keep)
        groups: dict[str, list[TrajectoryLine]] = {}
        for number, line in rows:
            if number <= last:
                groups.setdefault(line.episode, []).append(line)
        return {episode: group for episode, group in groups.items()
                if group[0].kind == "reset" and group[-1].final}

    def append(self, lines: Iterable[TrajectoryLine]) -> None:
        """One episode's lines (or several), in one write, flushed."""
        text = "".join(line.model_dump_json(exclude_none=True) + "\n" for line in lines)
        if not text:
            return
        self.path.parent.mkdir(parents=True, exist_ok=True)
        with self.path.open("a", encoding="utf-8") as handle:
            handle.write(text)
            handle.flush()


def episodes(lines: Iterable[TrajectoryLine]) -> Iterator[list[TrajectoryLine]]:
    """Lines grouped per episode, in file order (each group starts with its reset)."""
    groups: dict[str, list[TrajectoryLine]] = {}
    for line in lines:
        groups.setdefault(line.episode, []).append(line)
    yield from groups.values()


class ReplayReport(BaseModel):
    """What a replay found: episodes and steps replayed, and every mismatch."""

    episodes: int = 0
    steps: int = 0
    mismatches: list[str] = Field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.mismatches


def replay(lines: Iterable[TrajectoryLine], env: VeriGraphEnv) -> ReplayReport:
    """Re-run every recorded episode on `env` and compare step by step."""
    report = ReplayReport()
    for group in episodes(lines):
        start = group[0]
        if start.kind != "reset" or start.task is None:
            report.mismatches.append(f"{start.episode}: does not start with a reset line")
            continue
        report.episodes += 1
        if start.settings is not None and start.settings != env.settings():
            report.mismatches.append(f"{start.episode}: recorded under the settings "
                                     f"{settings_diff(start.settings, env.settings())}")
        obs, info = env.reset(seed=start.seed, options={"task": start.task})
        where = f"{start.episode} step 0"
        if obs != start.observation or info["state_hash"] != start.state_hash:
            report.mismatches.append(f"{where}: the first observation or state differs")
        for line in group[1:]:
            report.steps += 1
            where = f"{line.episode} step {line.step}"
            if env.over:
                report.mismatches.append(f"{where}: recorded after the episode ended")
                break
            obs, reward, terminated, truncated, info = env.step(line.action or "")
            got = (reward, info["verdict"], info["state_hash"], terminated, truncated, obs)
            want = (line.reward, line.verdict, line.state_hash, line.terminated,
                    line.truncated, line.next_observation)
            for name, a, b in zip(("reward", "verdict", "state_hash", "terminated",
                                   "truncated", "observation"), got, want, strict=True):
                if a != b and not (name == "observation" and b is None):
                    report.mismatches.append(f"{where}: {name} {_short(a)} != recorded "
                                             f"{_short(b)}")
            ending = (bool(info["success"]), info["stop_reason"], info["moves"])
            if line.final and line.success is not None \
                    and ending != (line.success, line.stop_reason, line.moves):
                report.mismatches.append(f"{where}: the episode ended as {_short(ending)}, "
                                         f"recorded {_short(line.success)}, "
                                         f"{_short(line.stop_reason)}, {_short(line.moves)}")
    return report


def settings_diff(recorded: dict[str, Any], current: dict[str, Any]) -> str:
    """The settings that differ, e.g. "max_steps 40 (now 10), k 3 (now 1)"."""
    names = [n for n in dict.fromkeys([*recorded, *current])
             if recorded.get(n) != current.get(n)]
    return ", ".join(f"{n} {_short(recorded.get(n))} (now {_short(current.get(n))})"
                     for n in names)


def _short(value: Any) -> str:
    text = json.dumps(value) if not isinstance(value, str) else repr(value)
    return text if len(text) <= 60 else text[:57] + "..."
