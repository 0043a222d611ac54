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

Access and capacity (docs/env.md, "Served"):

- **Token.** `create_openenv_app(token=...)` (one token or several) answers every
  request, HTTP or WebSocket, that lacks `Authorization: Bearer <token>` with 403 and a
  JSON reason (`missing_token` / `wrong_token`), as `verigraph serve --token` does; only
  `GET /health` stays open. `TokenEnvClient` (and `RemoteSessionFactory(url, token=)`)
  send the header. Without a token the app is for loopback only; `serve_openenv(host,
  port, token=...)` refuses another address without one.
- **Sessions.** Every WebSocket connection (and every `openenv/session/create` over
  `POST /mcp`) is its own session with its own environment, up to `max_sessions`
  (default 64) at once: OpenEnv's own `ConcurrencyConfig.max_concurrent_envs`. A
  session idle (no reset, step or MCP call) for `session_timeout` seconds (default
  600) is closed by OpenEnv's idle reaper (`ConcurrencyConfig.session_timeout`; it
  looks every quarter of the timeout, at least every 5 s), so an abandoned session
  frees its slot; a client that comes back to an expired session is told so.
- **Stateless HTTP.** Plain `POST /reset`, `POST /step` and `GET /state` run on a fresh
  environment per request (OpenEnv's simulation routes) and keep nothing: `/reset`
  answers a task's first observation (a preview), `/step` answers 409 (there is no
  episode to step: episodes live in WebSocket sessions), `/state` the empty state. A
  bad request (an unknown task, an unknown reset field) is 400 with the error's
  message, field and fix; no error of the environment is a 500.
"""

from __future__ import annotations

import asyncio
import functools
import hmac
import json
from collections.abc import Sequence
from typing import Any
from urllib.parse import urlsplit

from pydantic import Field

from verigraph.env.core import VeriGraphEnv
from verigraph.env.openenv_adapter import ACT_TOOL, SYSTEM_PROMPT, TOOL_NAME
from verigraph.env.procedural import ProceduralEnv, make_env
from verigraph.errors import VeriGraphError
from verigraph.extras import require

require("env", "openenv")

from fastapi import Request  # noqa: E402
from fastapi.responses import JSONResponse  # noqa: E402
from openenv.core.client_types import StepResult  # noqa: E402
from openenv.core.env_server import create_app  # noqa: E402
from openenv.core.env_server.interfaces import Environment  # noqa: E402
from openenv.core.env_server.types import (  # noqa: E402
    Action,
    ConcurrencyConfig,
    Observation,
    State,
)
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


DEFAULT_MAX_SESSIONS = 64
DEFAULT_SESSION_TIMEOUT = 600.0
OPEN_PATHS = frozenset({"/health"})  # answered without a token: says only "healthy"
SESSION_FIX = ("run the episode in one WebSocket session (/ws, e.g. OpenEnv's "
               "GenericEnvClient or TokenEnvClient): reset, then step")


class NoEpisodeError(VeriGraphError):
    """A step with no episode running in this environment (HTTP: 409 Conflict)."""


class VeriGraphServerEnv(Environment[ActAction, PromptObservation, State]):
    """`VeriGraphEnv` behind OpenEnv's Environment interface (one per session)."""

    SUPPORTS_CONCURRENT_SESSIONS = True

    def __init__(self, **env_kwargs: Any) -> None:
        super().__init__()
        self.env = make_env(**env_kwargs)
        self.episode_id: str | None = None
        self.closed = False

    def _open(self) -> VeriGraphEnv:
        if self.closed:
            raise NoEpisodeError(
                "this session has ended: it was idle longer than the server's session "
                "timeout, or it was closed", field="session",
                fix="open a new session (reconnect the WebSocket) and reset")
        return self.env

    def _observation(self, prompt: str, info: dict[str, Any], reward: float | None,
                     terminated: bool = False, truncated: bool = False) -> PromptObservation:
        return PromptObservation(
            prompt=prompt, task_id=info["task_id"], verdict=info["verdict"],
            violation=info["violation"], state_hash=info["state_hash"], tau=info["tau"],
            goal_distance=info["goal_distance"], episode_return=info["episode_return"],
            terminated=terminated, truncated=truncated, success=info["success"],
            reward=reward, done=terminated or truncated)

    def reset(self, seed: int | None = None, episode_id: str | None = None,
              task: str | int | dict[str, Any] | None = None, level: int | None = None,
              **kwargs: Any) -> PromptObservation:
        """A new episode: `task` is a task id, an index into the tasks or a task record;
        without one the seeded generator picks. `level` moves a procedural server's
        difficulty knob first. Any other field is refused by name."""
        env = self._open()
        if kwargs:
            names = ", ".join(sorted(kwargs))[:120]
            raise VeriGraphError(f"unknown reset field(s): {names}", field="reset",
                                 value=names,
                                 fix="reset takes seed, episode_id, task and level")
        if level is not None:
            if not isinstance(env, ProceduralEnv):
                raise VeriGraphError("this server serves fixed tasks: it has no levels",
                                     field="level", value=level,
                                     fix="serve with family and level (serve_openenv("
                                         "family='blocks', level=1)) to move the level")
            env.set_level(level)
        prompt, info = env.reset(seed=seed, options=None if task is None else {"task": task})
        self.episode_id = episode_id
        return self._observation(prompt, info, None)

    def step(self, action: ActAction, timeout_s: float | None = None, **kwargs: Any
             ) -> PromptObservation:
        env = self._open()
        if env.task is None:
            raise NoEpisodeError("no episode to step: this environment was never reset "
                                 "(plain HTTP /step always lands here: every HTTP request "
                                 "gets a fresh environment that keeps nothing)",
                                 field="step", fix=SESSION_FIX)
        prompt, reward, terminated, truncated, info = env.step(action.actions)
        return self._observation(prompt, info, reward, terminated, truncated)

    @property
    def state(self) -> State:
        task = self.env.task
        return State(episode_id=self.episode_id, step_count=self.env.steps,
                     task_id=task.task_id if task else None, tau=self.env.tau,
                     episode_return=self.env.episode_return, over=self.env.over)

    def close(self) -> None:
        self.closed = True
        self.env.close()


def _error_response(request: Request, exc: Exception) -> JSONResponse:
    """A VeriGraphError out of a plain HTTP route: 409 for a step with no episode, else
    400, with the message, field, value and fix (never a 500)."""
    assert isinstance(exc, VeriGraphError)
    status = 409 if isinstance(exc, NoEpisodeError) else 400
    return JSONResponse({"detail": exc.to_dict()}, status_code=status)


class BearerToken:
    """ASGI gate: HTTP requests and WebSocket handshakes need `Bearer <token>`.

    Compared in constant time against each accepted token. A refused WebSocket
    handshake gets the same 403 JSON body as HTTP where the server can send one (the
    ASGI denial-response extension; uvicorn's websockets implementation has it), else
    it is closed with 1008 (policy violation) before it is accepted.
    """

    def __init__(self, app: Any, tokens: Sequence[str]) -> None:
        self.app = app
        self.expected = [f"Bearer {t}".encode() for t in tokens]

    async def __call__(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        if scope["type"] not in ("http", "websocket") or scope.get("path") in OPEN_PATHS:
            await self.app(scope, receive, send)
            return
        given = b""
        for name, value in scope.get("headers", []):
            if name.lower() == b"authorization":
                given = value
        if any([hmac.compare_digest(given, e) for e in self.expected]):
            await self.app(scope, receive, send)
            return
        reason = "missing_token" if not given.strip() else "wrong_token"
        body = json.dumps({"detail": {
            "error": "Forbidden", "reason": reason,
            "message": ("no token was sent" if reason == "missing_token"
                        else "the token sent does not match"),
            "fix": "send the header 'Authorization: Bearer <token>' with the token this "
                   "environment server was started with"}}).encode()
        headers = [(b"content-type", b"application/json"),
                   (b"content-length", str(len(body)).encode())]
        if scope["type"] == "http":
            await send({"type": "http.response.start", "status": 403, "headers": headers})
            await send({"type": "http.response.body", "body": body})
        elif "websocket.http.response" in scope.get("extensions", {}):
            await send({"type": "websocket.http.response.start", "status": 403,
                        "headers": headers})
            await send({"type": "websocket.http.response.body", "body": body})
        else:
            await send({"type": "websocket.close", "code": 1008})


def create_openenv_app(*, token: str | Sequence[str] | None = None,
                       max_sessions: int = DEFAULT_MAX_SESSIONS,
                       session_timeout: float | None = DEFAULT_SESSION_TIMEOUT,
                       **env_kwargs: Any) -> Any:
    """OpenEnv's FastAPI app serving fresh `VeriGraphServerEnv(**env_kwargs)` sessions.

    `token`: one bearer token or several (any of them admits); None serves without one,
    for loopback only. `max_sessions` sessions at once (OpenEnv's max_concurrent_envs),
    each closed after `session_timeout` idle seconds (None: never). See the module
    docstring for the HTTP semantics. Serve it with uvicorn, e.g. `uvicorn.run(app,
    host="127.0.0.1", port=8001)`, beside `verigraph serve`.
    """
    tokens = [token] if isinstance(token, str) else list(token or ())
    if any(not isinstance(t, str) or not t.strip() or t != t.strip() for t in tokens):
        raise VeriGraphError("a token is empty or has spaces around it", field="token",
                             fix="give each token as one word, e.g. from `python -c "
                                 "'import secrets; print(secrets.token_urlsafe())'`")
    if isinstance(max_sessions, bool) or not isinstance(max_sessions, int) \
            or not 1 <= max_sessions <= 10_000:
        raise VeriGraphError("max_sessions must be between 1 and 10000",
                             field="max_sessions", value=max_sessions, fix="use e.g. 64")
    if session_timeout is not None and not 0 < session_timeout <= 7 * 86_400:
        raise VeriGraphError("session_timeout must be a positive number of seconds (at "
                             "most a week), or None", field="session_timeout",
                             value=session_timeout, fix="use e.g. 600")
    make_env(**env_kwargs).close()  # bad environment arguments fail here, not per session
    concurrency = ConcurrencyConfig(max_concurrent_envs=max_sessions,
                                    session_timeout=session_timeout)
    # a partial of the class: OpenEnv reads SUPPORTS_CONCURRENT_SESSIONS from it without
    # building a throwaway environment
    app = create_app(functools.partial(VeriGraphServerEnv, **env_kwargs), ActAction,
                     PromptObservation, env_name="verigraph", concurrency_config=concurrency)
    app.add_exception_handler(VeriGraphError, _error_response)
    if tokens:
        app.add_middleware(BearerToken, tokens=tokens)
    return app


LOOPBACK = frozenset({"127.0.0.1", "localhost", "::1"})


def serve_openenv(host: str = "127.0.0.1", port: int = 8001, *,
                  token: str | Sequence[str] | None = None,
                  max_sessions: int = DEFAULT_MAX_SESSIONS,
                  session_timeout: float | None = DEFAULT_SESSION_TIMEOUT,
                  **env_kwargs: Any) -> None:
    """Serve `create_openenv_app(...)` with uvicorn until interrupted.

    As `verigraph serve` does, an address other than loopback is refused without a
    token: an open environment server lets anyone hold its sessions.
    """
    if host not in LOOPBACK and not token:
        raise VeriGraphError(f"refusing to serve the environment on {host} without a token",
                             field="host", value=host,
                             fix="pass token=... (clients send 'Authorization: Bearer "
                                 "<token>'), or bind to 127.0.0.1")
    import uvicorn

    app = create_openenv_app(token=token, max_sessions=max_sessions,
                             session_timeout=session_timeout, **env_kwargs)
    uvicorn.run(app, host=host, port=port, log_level="warning")


class TokenEnvClient(GenericEnvClient):
    """OpenEnv's generic client that sends `Authorization: Bearer <token>` on connect."""

    def __init__(self, base_url: str, token: str | None = None, **kwargs: Any) -> None:
        super().__init__(base_url=base_url, **kwargs)
        self._token = token

    async def _connect_async(self) -> TokenEnvClient:
        # OpenEnv's connect (async and sync alike) comes here: the one place to add the
        # header
        if getattr(self, "_ws", None) is not None:  # already connected
            return self
        if self._token is None:
            await super()._connect_async()
            return self
        from websockets.asyncio.client import connect as ws_connect

        host = (urlsplit(self._ws_url).hostname or "").lower()
        loopback = host in LOOPBACK
        try:
            self._ws = await ws_connect(
                self._ws_url, open_timeout=self._connect_timeout,
                max_size=self._max_message_size, proxy=None if loopback else True,
                additional_headers={"Authorization": f"Bearer {self._token}"})
            self._ws_loop = asyncio.get_running_loop()
        except Exception as exc:  # noqa: BLE001 (OpenEnv's client raises ConnectionError)
            raise ConnectionError(f"Failed to connect to {self._ws_url}: {exc}") from exc
        return self


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
    """Harness sessions on an OpenEnv server of this environment (`create_openenv_app`);
    `token` for a server started with one."""

    def __init__(self, base_url: str, token: str | None = None) -> None:
        self.base_url = base_url
        self.token = token

    def create(self, task: Any, seed: int | None = None, episode_id: str | None = None
               ) -> ResourceSession:
        reset: dict[str, Any] = {"task": task} if task is not None else {}
        return StepEnvSessionAdapter(
            TokenEnvClient(self.base_url, self.token), task=task, seed=seed,
            episode_id=episode_id, tool_specs=[ACT_TOOL],
            action_builder=lambda name, args: {"actions": str(args.get("actions", ""))},
            initial_messages_builder=_messages, tool_result_builder=_tool_result,
            verify_builder=_verify, reset_kwargs=reset)


__all__ = ["DEFAULT_MAX_SESSIONS", "DEFAULT_SESSION_TIMEOUT", "TOOL_NAME", "ActAction",
           "BearerToken", "NoEpisodeError", "PromptObservation", "RemoteSessionFactory",
           "TokenEnvClient", "VeriGraphServerEnv", "create_openenv_app", "serve_openenv"]
