"""VeriGraph planning episodes as a verifiers taskset, the verifier playing the user.

Each task is one episode of a VeriGraph environment server
(`verigraph.env.openenv_server.serve_openenv`, reached over OpenEnv's WebSocket
protocol): `reset(seed=i, level=L)` gives the first prompt (the scene, the goal, the
actions and constraints). The env's `run()` sends each assistant reply to the server as
one step (up to k actions, or `done`); the server's next observation, the planner prompt
with the verifier's verdict on that reply (which constraint an action broke, what
blocks it, a suggested fix), comes back as the next user turn, until the episode ends
(goal reached, `done` accepted, too many failed steps in a row, or the step limit).
The reward is the episode's return under VeriGraph's documented rubric (docs/env.md,
"Reward"): 1.0 when the goal is reached, else 0.0 by default.
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Iterator
from typing import Any
from urllib.parse import urlsplit, urlunsplit

import verifiers.v1 as vf
from websockets.asyncio.client import connect as connect_async
from websockets.sync.client import connect

SYSTEM_PROMPT = ("You plan robot manipulation tasks. Reply with the next actions only, in "
                 "the forms the prompt lists, one per line; reply `done` once the goal "
                 "holds.")


def ws_url(base_url: str) -> str:
    parts = urlsplit(base_url)
    scheme = {"http": "ws", "https": "wss"}.get(parts.scheme, parts.scheme)
    return urlunsplit((scheme, parts.netloc, parts.path.rstrip("/") + "/ws", "", ""))


def _data(answer: str | bytes) -> dict[str, Any]:
    message = json.loads(answer)
    if message.get("type") == "error":
        raise vf.TaskError(str(message.get("data", {}).get("message", message)))
    return dict(message.get("data", {}))


class VeriGraphConfig(vf.TasksetConfig):
    base_url: str = "http://127.0.0.1:8001"
    """The VeriGraph environment server (serve_openenv); it fixes the family."""
    level: int | None = None
    """Difficulty level 1-6 (the server must serve a family with levels); None: the
    server's own tasks."""
    size: int | None = 100
    """Tasks (reset seeds 0..size-1); None: an endless stream."""
    token: str | None = None
    """The server's bearer token, if it has one."""


class VeriGraphData(vf.TaskData):
    reset: dict[str, Any]
    """What the env sends to reset (seed, level)."""
    base_url: str
    token: str | None = None


class VeriGraphTask(vf.Task[VeriGraphData]):
    pass


class VeriGraphEnvConfig(vf.EnvConfig):
    player: vf.AgentConfig = vf.AgentConfig()


def _headers(token: str | None) -> dict[str, str] | None:
    return {"Authorization": f"Bearer {token}"} if token else None


class VeriGraphEnv(vf.Env[VeriGraphEnvConfig]):
    async def run(self, task, agents):  # type: ignore[no-untyped-def]
        data = task.data
        episode_return = 0.0
        async with connect_async(ws_url(data.base_url), max_size=None,
                                 additional_headers=_headers(data.token)) as ws:
            await ws.send(json.dumps({"type": "reset", "data": data.reset}))
            result = _data(await ws.recv())
            async with agents.player.interaction(task) as interaction:
                segment = await interaction.turn()  # the first prompt is the task's
                while not segment.terminated:
                    reply = segment.last_reply.strip() or "(no answer)"
                    await ws.send(json.dumps({"type": "step", "data": {"actions": reply}}))
                    result = _data(await ws.recv())
                    observation = result.get("observation", {})
                    episode_return = float(observation.get("episode_return", 0.0))
                    if result.get("done"):
                        interaction.trace.info["verigraph_success"] = \
                            observation.get("success")
                        break
                    segment = await interaction.turn(observation.get("prompt", ""))
            await ws.send(json.dumps({"type": "close"}))
        interaction.trace.record_reward("verigraph_reward", episode_return, 1.0)


class VeriGraphTaskset(vf.Taskset[VeriGraphTask, VeriGraphConfig]):
    INFINITE = False

    @property
    def bounded(self) -> bool:
        return self.config.size is not None

    def load(self) -> Iterator[VeriGraphTask]:
        config = self.config
        seeds = range(config.size) if config.size is not None else itertools.count()
        with connect(ws_url(config.base_url), max_size=None,
                     additional_headers=_headers(config.token)) as ws:
            for seed in seeds:
                reset: dict[str, Any] = {"seed": seed}
                if config.level is not None:
                    reset["level"] = config.level
                ws.send(json.dumps({"type": "reset", "data": reset}))
                observation = _data(ws.recv()).get("observation", {})
                yield VeriGraphTask(
                    VeriGraphData(name=str(observation.get("task_id")),
                                  prompt=str(observation.get("prompt", "")),
                                  system_prompt=SYSTEM_PROMPT, reset=reset,
                                  base_url=config.base_url, token=config.token),
                    config.task)


def load_environment(base_url: str = "http://127.0.0.1:8001", level: int | None = None,
                     size: int | None = 100, token: str | None = None,
                     **env: Any) -> vf.Env:
    """The verifiers Env for a VeriGraph server: what `vf.load_environment` builds for
    `--env.taskset.id verigraph-verifiers` with these taskset settings."""
    config = vf.resolve_env_config({**env, "taskset": {
        "id": "verigraph-verifiers", "base_url": base_url, "level": level, "size": size,
        "token": token}})
    return vf.load_environment(config)
