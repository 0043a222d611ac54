"""The environment as an OpenEnv server: reset / step / state over HTTP and WebSocket.

This is OpenEnv's infrastructure boundary served beside `verigraph serve`:
`create_openenv_app()` is OpenEnv's own FastAPI app (`openenv.core.env_server.
create_app`) around `VeriGraphServerEnv`, one environment per WebSocket session, so a
trainer anywhere drives `reset(seed, task=...)`, `step({"actions": ...})` and `state`
with OpenEnv's clients (`GenericEnvClient`). The reward and the verdict are computed on
the server; the observation carries the prompt, the step reward and the episode return.

`RemoteSessionFactory(url)` turns such a server back into OpenEnv harness sessions
(OpenEnv's `StepEnvSessionAdapter` over its client), so `run_collect` evaluates a model
against a served environment exactly as against an in-process one: the agent still
sees only the `act` tool.
"""

from __future__ import annotations

from typing import Any

from pydantic import Field

from verigraph.env.core import VeriGraphEnv
from verigraph.env.openenv_adapter import ACT_TOOL, SYSTEM_PROMPT, TOOL_NAME
from verigraph.extras import require

require("env", "openenv")

from openenv.core.client_types import StepResult  # noqa: E402
from openenv.core.env_server import create_app  # noqa: E402
from openenv.core.env_server.interfaces import Environment  # noqa: E402
from openenv.core.env_server.types import Action, Observation, State  # noqa: E402
from openenv.core.generic_client import GenericEnvClient  # noqa: E402
from openenv.core.harness import (  # noqa: E402
    Message,
    ResourceSession,
    ResourceSessionFactory,
    StepEnvSessionAdapter,
    ToolResult,
    VerifyResult,
)


class ActAction(Action):
    """One step: the model's text reply (up to k actions, or `done`)."""

    actions: str = Field(description="e.g. 'move(cup, on, table)' or 'done'")


class PromptObservation(Observation):
    """The next planner prompt, with what the verifier said of the step."""

    prompt: str
    task_id: str
    verdict: str | None = None
    violation: dict[str, Any] | None = None
    state_hash: str
    tau: int = 0
    goal_distance: int | None = None
    episode_return: float = 0.0
    terminated: bool = False
    truncated: bool = False
    success: bool | None = None


class VeriGraphServerEnv(Environment[ActAction, PromptObservation, State]):
    """`VeriGraphEnv` behind OpenEnv's Environment interface (one per session)."""

    SUPPORTS_CONCURRENT_SESSIONS = True

    def __init__(self, **env_kwargs: Any) -> None:
        super().__init__()
        self.env = VeriGraphEnv(**env_kwargs)
        self.episode_id: str | None = None

    def _observation(self, prompt: str, info: dict[str, Any], reward: float | None,
                     terminated: bool = False, truncated: bool = False) -> PromptObservation:
        return PromptObservation(
            prompt=prompt, task_id=info["task_id"], verdict=info["verdict"],
            violation=info["violation"], state_hash=info["state_hash"], tau=info["tau"],
            goal_distance=info["goal_distance"], episode_return=info["episode_return"],
            terminated=terminated, truncated=truncated, success=info["success"],
            reward=reward, done=terminated or truncated)

    def reset(self, seed: int | None = None, episode_id: str | None = None,
              task: str | None = None, **kwargs: Any) -> PromptObservation:
        self.episode_id = episode_id
        prompt, info = self.env.reset(seed=seed, options={"task": task} if task else None)
        return self._observation(prompt, info, None)

    def step(self, action: ActAction, timeout_s: float | None = None, **kwargs: Any
             ) -> PromptObservation:
        prompt, reward, terminated, truncated, info = self.env.step(action.actions)
        return self._observation(prompt, info, reward, terminated, truncated)

    @property
    def state(self) -> State:
        task = self.env.task
        return State(episode_id=self.episode_id, step_count=self.env.steps,
                     task_id=task.task_id if task else None, tau=self.env.tau,
                     episode_return=self.env.episode_return, over=self.env.over)

    def close(self) -> None:
        self.env.close()


def create_openenv_app(**env_kwargs: Any) -> Any:
    """OpenEnv's FastAPI app serving fresh `VeriGraphServerEnv(**env_kwargs)` sessions.

    Serve it with uvicorn on loopback, e.g. `uvicorn.run(app, host="127.0.0.1",
    port=8001)`, beside `verigraph serve`.
    """
    return create_app(lambda: VeriGraphServerEnv(**env_kwargs), ActAction, PromptObservation,
                      env_name="verigraph")


def _messages(result: StepResult[Any], task: Any) -> list[Message]:
    return [{"role": "system", "content": SYSTEM_PROMPT},
            {"role": "user", "content": result.observation["prompt"]}]


def _tool_result(name: str, arguments: dict[str, Any], result: StepResult[Any],
                 state: Any) -> ToolResult:
    obs = result.observation
    return ToolResult(data=obs["prompt"], done=bool(result.done), metadata={
        "reward": obs["episode_return"], "step_reward": result.reward,
        "verdict": obs["verdict"], "terminated": obs["terminated"],
        "truncated": obs["truncated"], "state_hash": obs["state_hash"],
        "violation": obs["violation"]})


def _verify(transcript: list[Message], final_state: Any, last: StepResult[Any] | None,
            state: Any) -> VerifyResult:
    obs = last.observation if last is not None else {}
    return VerifyResult(
        env_reward=float(obs.get("episode_return", 0.0)), done=bool(last and last.done),
        metrics={"success": bool(obs.get("success")), "steps": (state or {}).get(
            "step_count", 0), "goal_distance": obs.get("goal_distance")},
        artifacts={"task_id": (state or {}).get("task_id"),
                   "final_state_hash": obs.get("state_hash")})


class RemoteSessionFactory(ResourceSessionFactory):
    """Harness sessions on an OpenEnv server of this environment (`create_openenv_app`)."""

    def __init__(self, base_url: str) -> None:
        self.base_url = base_url

    def create(self, task: Any, seed: int | None = None, episode_id: str | None = None
               ) -> ResourceSession:
        reset: dict[str, Any] = {"task": task} if task is not None else {}
        return StepEnvSessionAdapter(
            GenericEnvClient(base_url=self.base_url), task=task, seed=seed,
            episode_id=episode_id, tool_specs=[ACT_TOOL],
            action_builder=lambda name, args: {"actions": str(args.get("actions", ""))},
            initial_messages_builder=_messages, tool_result_builder=_tool_result,
            verify_builder=_verify, reset_kwargs=reset)


__all__ = ["TOOL_NAME", "ActAction", "PromptObservation", "RemoteSessionFactory",
           "VeriGraphServerEnv", "create_openenv_app"]
