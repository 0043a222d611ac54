"""The VeriGraph environment client: OpenEnv's `EnvClient` over a WebSocket session."""

from __future__ import annotations

from typing import Any

from openenv.core import EnvClient
from openenv.core.client_types import StepResult
from openenv.core.env_server.types import State

from verigraph_openenv.models import VeriGraphAction, VeriGraphObservation


class VeriGraphEnv(EnvClient[VeriGraphAction, VeriGraphObservation, State]):
    """Client of a VeriGraph OpenEnv server; each instance is one session.

    >>> with VeriGraphEnv(base_url="http://localhost:8000").sync() as env:  # doctest: +SKIP
    ...     result = env.reset(seed=0, level=3)
    ...     result = env.step(VeriGraphAction(actions="move(red_block, on, table)"))
    ...     result.reward, result.observation.verdict
    """

    def _step_payload(self, action: VeriGraphAction) -> dict[str, Any]:
        return {"actions": action.actions}

    def _parse_result(self, payload: dict[str, Any]) -> StepResult[VeriGraphObservation]:
        data = dict(payload.get("observation", {}))
        data.update(done=payload.get("done", False), reward=payload.get("reward"))
        fields = VeriGraphObservation.model_fields
        observation = VeriGraphObservation(**{k: v for k, v in data.items() if k in fields})
        return StepResult(observation=observation, reward=payload.get("reward"),
                          done=payload.get("done", False))

    def _parse_state(self, payload: dict[str, Any]) -> State:
        return State(**payload)
