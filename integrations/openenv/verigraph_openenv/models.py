"""The action and observation of the VeriGraph environment (OpenEnv models)."""

from __future__ import annotations

from typing import Any

from openenv.core.env_server.types import Action, Observation
from pydantic import Field


class VeriGraphAction(Action):
    """One step: the model's text reply, up to k actions (`move(cup, on, table)` lines,
    JSON or a fenced block) or `done`."""

    actions: str = Field(description="e.g. 'move(red_block, on, table)' or 'done'")


class VeriGraphObservation(Observation):
    """The next planner prompt and what the verifier said of the step.

    `reward` (OpenEnv's) is the step's reward: 1.0 on the step that reaches the goal
    with the default rubric, else 0.0.
    """

    prompt: str = ""
    task_id: str = ""
    verdict: str | None = Field(default=None, description="clean, violation, malformed, "
                                "premature_done or end_token")
    violation: dict[str, Any] | None = Field(default=None, description="the verifier's "
                                             "report of a refused action")
    state_hash: str = ""
    tau: int = Field(default=0, description="consecutive failed steps")
    goal_distance: int | None = None
    episode_return: float = 0.0
    terminated: bool = False
    truncated: bool = False
    success: bool | None = None
