"""The environment in OpenEnv (`openenv` 0.4.1): sessions, a tool, and its collect runner.

OpenEnv keeps two boundaries. The agent sees only MCP-style tools; the training
infrastructure creates a session per rollout, and the reward stays inside the
environment (its harness refuses a `verify()` reward that differs from the one the
tools reported). Here:

- the agent's one tool is `act(actions)`: its text reply (up to k actions, or `done`),
  which is one `VeriGraphEnv.step`; the tool result's text is the next observation (the
  planner prompt with the verifier's feedback). The agent cannot reset, and nothing it
  calls reaches the episode's ground-truth goal.
- `VeriGraphSessionFactory.create(task)` is the infrastructure side: a fresh
  environment reset to that task. The tool result carries `reward` = the episode return
  so far (what OpenEnv's harness reads as the rollout's reward) and `step_reward`;
  `verify()` forwards that same return with the episode's metrics.

`run_collect` runs OpenEnv's own `CollectRunner` with its `MCPHarnessAdapter` against
any OpenAI-compatible endpoint (OpenEnv's `OpenAIClient`) and writes OpenEnv's
`results.jsonl` and `metadata.json`. Models that answer in text instead of tool calls
(small local models) use `TextReplyModelStep`: their reply is the `act` argument, and
they are sent the latest observation only, as one user message (it holds the whole
state: scene, goal, executed actions and the last feedback).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

from verigraph.env.core import VeriGraphEnv
from verigraph.errors import VeriGraphError
from verigraph.extras import require
from verigraph.tasks.task import Task

require("env", "openenv")

import httpx2  # noqa: E402
from openai import AsyncOpenAI  # noqa: E402
from openenv.core.env_server.mcp_types import Tool  # noqa: E402
from openenv.core.harness import (  # noqa: E402
    HarnessRunLimits,
    MCPHarnessAdapter,
    Message,
    ModelStepResult,
    ResourceSession,
    ResourceSessionFactory,
    ToolResult,
    VerifyResult,
)
from openenv.core.harness.collect import (  # noqa: E402
    CollectResult,
    CollectRunner,
    RolloutSerializer,
    build_model_step,
)
from openenv.core.llm_client import LLMResponse, OpenAIClient, ToolCall  # noqa: E402
from openenv.core.utils import run_async_safely  # noqa: E402

TOOL_NAME = "act"
SYSTEM_PROMPT = (
    "You control a robot through a scene-graph verifier. Each turn, call the `act` tool "
    "once with your next actions (at most k, one per line, e.g. move(cup, on, table)) or "
    "with `done` when the goal holds. The tool answers with the verifier's feedback and "
    "the new scene.")
ACT_TOOL = Tool(
    name=TOOL_NAME,
    description="Propose your next actions (at most k, one per line, in the action forms "
                "of the prompt) or `done`. The verifier executes them until the first "
                "refused one and answers with its feedback and the new scene.",
    input_schema={"type": "object", "additionalProperties": False, "required": ["actions"],
                  "properties": {"actions": {
                      "type": "string",
                      "description": "e.g. \"move(cup, on, table)\\nmove(book, on, shelf)\" "
                                     "or \"done\""}}})


class VeriGraphSession(ResourceSession):
    """One rollout: an environment reset to one task, driven through the `act` tool."""

    def __init__(self, env: VeriGraphEnv, task: str | Task | None,
                 seed: int | None = None) -> None:
        self.env = env
        options = {"task": task} if task is not None else None
        self.observation, self.info = env.reset(seed=seed, options=options)
        self.episode_return = 0.0
        self.done = False

    def initial_messages(self) -> list[Message]:
        return [{"role": "system", "content": SYSTEM_PROMPT},
                {"role": "user", "content": self.observation}]

    def list_tools(self) -> list[Tool]:
        return [ACT_TOOL]

    def call_tool(self, name: str, arguments: dict[str, Any]) -> ToolResult:
        if name != TOOL_NAME:
            raise KeyError(f"Unknown tool: {name}; the only tool is {TOOL_NAME}")
        if self.done:
            return ToolResult(data="The episode is over.", done=True,
                              metadata={"reward": self.episode_return},
                              error="the episode is over")
        answer = arguments.get("actions")
        if not isinstance(answer, str):
            answer = json.dumps(answer) if answer is not None else ""
        obs, reward, terminated, truncated, info = self.env.step(answer)
        self.episode_return += reward
        self.observation, self.info = obs, info
        self.done = terminated or truncated
        return ToolResult(data=obs, done=self.done, metadata={
            "reward": self.episode_return, "step_reward": reward, "verdict": info["verdict"],
            "terminated": terminated, "truncated": truncated,
            "state_hash": info["state_hash"], "violation": info["violation"]})

    def verify(self, transcript: list[Message], final_state: Any | None = None
               ) -> VerifyResult:
        info = self.info
        return VerifyResult(
            env_reward=self.episode_return, done=self.done,
            metrics={"success": bool(info.get("success")), "steps": info["step"],
                     "moves": info["moves"], "optimal_length": info["optimal_length"],
                     "stop_reason": info["stop_reason"], "goal_distance": info["goal_distance"]},
            artifacts={"task_id": info["task_id"], "family": info["family"],
                       "final_state_hash": info["state_hash"]})

    def close(self) -> None:
        self.env.close()


class VeriGraphSessionFactory(ResourceSessionFactory):
    """Sessions on fresh environments built from `env_kwargs` (as for `VeriGraphEnv`)."""

    def __init__(self, **env_kwargs: Any) -> None:
        self.env_kwargs = env_kwargs

    def create(self, task: Any, seed: int | None = None, episode_id: str | None = None
               ) -> VeriGraphSession:
        return VeriGraphSession(VeriGraphEnv(**self.env_kwargs), task, seed)


def _latest_observation(messages: Sequence[Message]) -> list[dict[str, str]]:
    """The newest observation (the first prompt or the last tool result) as the one user
    message: it holds the whole state, and the system prompt's tool wording does not
    apply to a model that answers in text."""
    latest = next(m for m in reversed(messages) if m.get("role") in ("user", "tool"))
    return [{"role": "user", "content": str(latest.get("content") or "")}]


class TextReplyModelStep:
    """An OpenEnv `ModelStep` for models without tool calling: the reply is the action."""

    def __init__(self, client: OpenAIClient) -> None:
        self.client = client
        self.turn = 0

    def __call__(self, messages: list[Message], tools: list[Tool], sampling: dict[str, Any]
                 ) -> ModelStepResult:
        prompt = _latest_observation(messages)
        kwargs = {k: v for k, v in sampling.items() if k in ("temperature", "max_tokens")}
        text = run_async_safely(self.client.complete_with_tools(prompt, [], **kwargs)).content
        self.turn += 1
        call = ToolCall(id=f"reply-{self.turn}", name=TOOL_NAME, args={"actions": text})
        return ModelStepResult(response=LLMResponse(content=text, tool_calls=[call]))


def openenv_client(base_url: str, model: str, *, api_key: str | None = None,
                  max_tokens: int = 256) -> OpenAIClient:
    """OpenEnv's client for an endpoint given as `http://HOST:PORT/v1` (or without /v1)."""
    parts = urlsplit(base_url)
    if parts.scheme not in ("http", "https") or not parts.hostname or parts.port is None:
        raise VeriGraphError(f"not an endpoint URL with a port: {base_url!r}",
                             field="base_url", value=base_url,
                             fix="use e.g. http://127.0.0.1:8080/v1")
    if parts.path.rstrip("/") not in ("", "/v1"):
        raise VeriGraphError("OpenEnv's client always calls <host:port>/v1",
                             field="base_url", value=base_url,
                             fix="give the server's root or its /v1 URL")
    return FreshConnectionOpenAIClient(f"{parts.scheme}://{parts.hostname}", parts.port,
                                       model, api_key=api_key, max_tokens=max_tokens)


class FreshConnectionOpenAIClient(OpenAIClient):
    """OpenEnv's OpenAI client without kept-alive connections.

    OpenEnv's synchronous model steps run every request on a new event loop
    (`run_async_safely` -> `asyncio.run`). A pooled connection belongs to the loop that
    opened it, so against a server that keeps connections alive (llama.cpp, vLLM) the
    second request fails with "Event loop is closed". One connection per request costs a
    loopback handshake, far less than a model's reply.
    """

    def __init__(self, endpoint: str, port: int, model: str, **kwargs: Any) -> None:
        super().__init__(endpoint, port, model, **kwargs)
        self._client = AsyncOpenAI(
            base_url=f"{self.base_url}/v1", api_key=kwargs.get("api_key") or "not-needed",
            http_client=httpx2.AsyncClient(limits=httpx2.Limits(max_keepalive_connections=0)))


def run_collect(tasks: Sequence[str | Task], out_dir: str | Path, *, base_url: str,
                model: str, api_key: str | None = None, tool_calling: bool = True,
                max_turns: int = 20, max_tokens: int = 256, resume: bool = False,
                env: dict[str, Any] | None = None,
                sessions: ResourceSessionFactory | None = None) -> CollectResult:
    """Evaluate a model on `tasks` with OpenEnv's CollectRunner; writes its files.

    `tasks` are task records (the environments then hold exactly those) or task ids of
    the environment `env` describes (`VeriGraphEnv` keyword arguments). One episode per
    task, in order; `out_dir` receives OpenEnv's `results.jsonl` (one episode per line:
    messages, reward, tool trace, metrics) and `metadata.json`. `sessions` replaces the
    in-process sessions, e.g. by `RemoteSessionFactory(url)` for a served environment
    (verigraph.env.openenv_server).
    """
    env_kwargs = dict(env or {})
    records = [t for t in tasks if isinstance(t, Task)]
    if records and "tasks" not in env_kwargs:
        env_kwargs["tasks"] = records
    ids = [t.task_id if isinstance(t, Task) else t for t in tasks]
    client = openenv_client(base_url, model, api_key=api_key, max_tokens=max_tokens)
    model_step = build_model_step(client, system_prompt=SYSTEM_PROMPT) if tool_calling \
        else TextReplyModelStep(client)
    serializer = RolloutSerializer(out_dir)
    serializer.write_metadata({"environment": "verigraph", "model": model,
                               "base_url": base_url, "tool_calling": tool_calling,
                               "tasks": len(ids), "max_turns": max_turns,
                               **{k: v for k, v in env_kwargs.items()
                                  if isinstance(v, str | int | float | bool)}})
    runner = CollectRunner(session_factory=sessions or VeriGraphSessionFactory(**env_kwargs),
                           harness_adapter=MCPHarnessAdapter(), serializer=serializer,
                           tasks=ids,
                           limits=HarnessRunLimits(max_turns=max_turns,
                                                   max_tool_calls_per_turn=1))
    return runner.run(model_step=model_step, num_episodes=len(ids),
                      episode_id_prefix="verigraph", resume=resume)
