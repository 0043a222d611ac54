"""`VeriGraphProxyEnvironment`: an OpenEnv Environment whose episodes run in VeriGraph.

VeriGraph (the verifier, its tasks, levels and reward) needs `mcp` 2.3 or newer and
OpenEnv 0.10 needs `mcp` below 2, so they cannot share a Python environment. This
environment holds one WebSocket session with a VeriGraph environment server
(`verigraph.env.openenv_server.serve_openenv`, OpenEnv's `/ws` protocol: `reset`,
`step`, `state` messages) and forwards reset and step to it unchanged: the episode, the
verifier's verdicts and the reward are VeriGraph's. `VERIGRAPH_URL` names that server
(default http://127.0.0.1:8001) and `VERIGRAPH_TOKEN` its bearer token, if any.
"""

from __future__ import annotations

import json
import os
from typing import Any
from urllib.parse import urlsplit, urlunsplit

from openenv.core.env_server.interfaces import Environment
from openenv.core.env_server.types import State
from websockets.sync.client import ClientConnection, connect

from verigraph_openenv.models import VeriGraphAction, VeriGraphObservation

DEFAULT_URL = "http://127.0.0.1:8001"
TIMEOUT_S = 120.0


class VeriGraphError(RuntimeError):
    """What the VeriGraph server answered to a refused request (message, field, fix)."""


def ws_url(base_url: str) -> str:
    parts = urlsplit(base_url)
    scheme = {"http": "ws", "https": "wss"}.get(parts.scheme, parts.scheme)
    return urlunsplit((scheme, parts.netloc, parts.path.rstrip("/") + "/ws", "", ""))


class VeriGraphProxyEnvironment(Environment[VeriGraphAction, VeriGraphObservation, State]):
    """One OpenEnv session = one VeriGraph session (module docstring)."""

    SUPPORTS_CONCURRENT_SESSIONS = True

    def __init__(self, base_url: str | None = None, token: str | None = None) -> None:
        super().__init__()
        self.base_url = base_url or os.environ.get("VERIGRAPH_URL", DEFAULT_URL)
        self.token = token if token is not None else os.environ.get("VERIGRAPH_TOKEN")
        self._ws: ClientConnection | None = None
        self._state = State(episode_id=None, step_count=0)

    def _session(self) -> ClientConnection:
        if self._ws is None:
            headers = {"Authorization": f"Bearer {self.token}"} if self.token else None
            self._ws = connect(ws_url(self.base_url), additional_headers=headers,
                               open_timeout=30, max_size=None)
        return self._ws

    def _call(self, kind: str, data: dict[str, Any] | None = None) -> dict[str, Any]:
        ws = self._session()
        ws.send(json.dumps({"type": kind, **({"data": data} if data is not None else {})}))
        answer = json.loads(ws.recv(timeout=TIMEOUT_S))
        if answer.get("type") == "error":
            raise VeriGraphError(str(answer.get("data", {}).get("message", answer)))
        return dict(answer.get("data", {}))

    @staticmethod
    def _observation(data: dict[str, Any]) -> VeriGraphObservation:
        fields = VeriGraphObservation.model_fields
        body = {k: v for k, v in data.get("observation", {}).items() if k in fields}
        body.update(done=bool(data.get("done", False)), reward=data.get("reward"))
        return VeriGraphObservation(**body)

    def reset(self, seed: int | None = None, episode_id: str | None = None,
              **kwargs: Any) -> VeriGraphObservation:
        """A new VeriGraph episode; `task` (id, index or record) and `level` pass on."""
        data = {"seed": seed, **({"episode_id": episode_id} if episode_id else {}),
                **{k: v for k, v in kwargs.items() if v is not None}}
        observation = self._observation(self._call("reset", data))
        self._state = State(episode_id=episode_id, step_count=0,
                            task_id=observation.task_id)
        return observation

    def step(self, action: VeriGraphAction, timeout_s: float | None = None,
             **kwargs: Any) -> VeriGraphObservation:
        observation = self._observation(self._call("step", {"actions": action.actions}))
        self._state = State(episode_id=self._state.episode_id,
                            step_count=self._state.step_count + 1,
                            task_id=observation.task_id)
        return observation

    @property
    def state(self) -> State:
        return self._state

    def close(self) -> None:
        if self._ws is not None:
            try:
                self._ws.send(json.dumps({"type": "close"}))
            finally:
                self._ws.close()
                self._ws = None
