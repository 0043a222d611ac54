"""The environment as an OpenEnv server: reset / step / state over HTTP and WebSocket.

This is OpenEnv's infrastructure boundary served beside `verigraph serve`:
`create_openenv_app()` is OpenEnv's own routes (`openenv.core.env_server.
HTTPEnvServer.register_routes`, what its `create_app` serves) around
`VeriGraphServerEnv`, one environment per WebSocket session, so a trainer anywhere
drives `reset(seed, task=...)`, `step({"actions": ...})` and `state` with OpenEnv's
clients (`GenericEnvClient`). The reward and the verdict are computed on
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
- **Shares.** Each caller (its token when there are several, else its address, as
  `verigraph serve` tells callers apart) holds at most `sessions_per_caller` sessions
  (default a quarter of `max_sessions`); one more is refused with the share named and
  the others are unaffected. A full server gives the least recently active session
  idle for `reclaim_after` seconds (default 300) to a new one. A session belongs to
  its caller: `POST /mcp` naming another caller's `session_id` gets OpenEnv's answer
  for an unknown one (`SharedSessions`, `Callers`).
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
import json
import time
from collections import Counter
from collections.abc import Sequence
from contextvars import ContextVar
from typing import Any
from urllib.parse import urlsplit

from pydantic import Field

from verigraph.env.core import VeriGraphEnv
from verigraph.env.openenv_adapter import ACT_TOOL, SYSTEM_PROMPT, TOOL_NAME
from verigraph.env.procedural import ProceduralEnv, make_env
from verigraph.errors import VeriGraphError
from verigraph.extras import require
from verigraph.server.callers import TokenGate, caller_of

require("env", "openenv")

from fastapi import FastAPI, Request  # noqa: E402
from fastapi.responses import JSONResponse  # noqa: E402
from openenv.core.client_types import StepResult  # noqa: E402
from openenv.core.env_server.exceptions import SessionCapacityError  # noqa: E402
from openenv.core.env_server.http_server import HTTPEnvServer  # noqa: E402
from openenv.core.env_server.interfaces import Environment  # noqa: E402
from openenv.core.env_server.mcp_types import (  # noqa: E402
    JsonRpcErrorCode,
    JsonRpcResponse,
)
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
DEFAULT_RECLAIM_AFTER = 300.0  # a full server replaces sessions idle this long
# The caller of the request being admitted (set by Callers); its own variable, so the
# environments' in-process tool stores never see it.
_CALLER: ContextVar[str] = ContextVar("verigraph_openenv_caller", default="unknown")
MAX_MCP_BODY = 1 << 20  # POST /mcp bodies read to check their session_id (OpenEnv's own
# JSON-RPC requests are a few hundred bytes)
MAX_BODY = 16 << 20  # any other body (a reset's task record at most a few MiB), as serve
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
                "timeout, it was idle when the full server needed its slot, or it was "
                "closed", field="session",
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
        self.gate = TokenGate(tokens)

    async def __call__(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        if scope["type"] not in ("http", "websocket") or scope.get("path") in OPEN_PATHS:
            await self.app(scope, receive, send)
            return
        reason = self.gate.check(scope)
        if reason is None:
            await self.app(scope, receive, send)
            return
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


class SharedSessions(HTTPEnvServer):
    """OpenEnv's session server with a share per caller and idle sessions reclaimable.

    Admission only (OpenEnv's `_create_session`; its reaper, routes and cleanup are its
    own): a caller holding `share` sessions (counted with the ones still being made) is
    refused with OpenEnv's capacity error naming the share; a full server first closes
    the least recently active session idle for `reclaim_after` seconds. The caller is
    the one `Callers` set for the request. A session's owner is kept until OpenEnv
    forgets the session, whichever way it ends (a close, the reaper, a disconnect).
    """

    def __init__(self, *args: Any, share: int, reclaim_after: float, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.share = share
        self.reclaim_after = reclaim_after
        self.owners: dict[str, str] = {}
        self._making: Counter[str] = Counter()  # sessions being made, per caller

    def owner(self, session_id: str) -> str | None:
        """The caller of a live session (None: no such session)."""
        return self.owners.get(session_id) if session_id in self._sessions else None

    async def _create_session(self) -> tuple[str, Environment]:
        caller = _CALLER.get()
        async with self._session_lock:
            self.owners = {sid: c for sid, c in self.owners.items() if sid in self._sessions}
            held = sum(1 for c in self.owners.values() if c == caller) + self._making[caller]
            cap = self._max_concurrent_envs
            if held >= self.share < cap:
                timeout = self._session_idle_timeout_s
                idle_s = f"after {timeout:.0f} s idle" if timeout else "this server closes none"
                raise SessionCapacityError(len(self._sessions), cap, message=(
                    f"Session share reached: this caller ({caller}) holds {held} of its "
                    f"{self.share} sessions (sessions_per_caller) on a server of {cap}; "
                    "other callers are not affected. Close a session (end its WebSocket), "
                    f"wait until an idle one is closed ({idle_s}), "
                    "or start the server with a larger sessions_per_caller"))
            idle = None
            if len(self._sessions) + sum(self._making.values()) >= cap:
                idle = self._idlest(time.time())
            self._making[caller] += 1
        try:
            if idle is not None:
                await self._destroy_session(idle)  # its client is told "session has ended"
            session_id, env = await super()._create_session()
            self.owners[session_id] = caller
        finally:
            self._making[caller] -= 1
        return session_id, env

    def _idlest(self, now: float) -> str | None:
        """The least recently active session idle for reclaim_after (the lock is held)."""
        idle = [(info.last_activity_at, sid) for sid, info in self._session_info.items()
                if now - info.last_activity_at >= self.reclaim_after]
        return min(idle)[1] if idle else None


class Callers:
    """ASGI layer: every request and WebSocket runs as its caller (verigraph.server.
    callers: its token when the server has several, else its address); a request body
    is read here up to its limit (MAX_MCP_BODY for `POST /mcp`, MAX_BODY for the rest;
    413 beyond, before OpenEnv reads it whole), and a `POST /mcp` that names another
    caller's `session_id` gets OpenEnv's answer for an unknown one."""

    def __init__(self, app: Any, sessions: SharedSessions) -> None:
        self.app = app
        self.sessions = sessions

    async def __call__(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        if scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        caller = caller_of(scope)
        token = _CALLER.set(caller)
        try:
            if scope["type"] == "http" and scope.get("method") in ("POST", "PUT", "PATCH"):
                mcp = scope.get("path") == "/mcp"
                limit = MAX_MCP_BODY if mcp else MAX_BODY
                body = await _read_body(receive, limit, _content_length(scope))
                if body is None:
                    await _send_json(send, 413, {"detail": VeriGraphError(
                        f"the request body is larger than {limit} bytes", field="body",
                        fix="send a smaller request: an action is at most a few KiB"
                    ).to_dict()})
                    return
                refusal = self._foreign_session(body, caller) if mcp else None
                if refusal is not None:
                    await _send_json(send, 200, refusal)
                    return
                receive = _replay(body)
            await self.app(scope, receive, send)
        finally:
            _CALLER.reset(token)

    def _foreign_session(self, body: bytes, caller: str) -> dict[str, Any] | None:
        """The answer to a body naming another caller's session, else None."""
        try:
            message = json.loads(body)
        except (ValueError, RecursionError):
            return None  # OpenEnv answers it
        params = message.get("params") if isinstance(message, dict) else None
        session_id = params.get("session_id") if isinstance(params, dict) else None
        if not isinstance(session_id, str) or self.sessions.owner(session_id) in (None, caller):
            return None
        request_id = message.get("id")
        return JsonRpcResponse.error_response(
            JsonRpcErrorCode.INVALID_PARAMS, f"Unknown session_id: {session_id}",
            request_id=request_id if isinstance(request_id, (str, int)) else None
        ).model_dump()


def _content_length(scope: dict[str, Any]) -> int | None:
    for name, value in scope.get("headers", []):
        if name.lower() == b"content-length":
            return int(value) if value.isdigit() else None
    return None


async def _read_body(receive: Any, limit: int, declared: int | None) -> bytes | None:
    """The request body, or None once it passes `limit` (the rest is not read)."""
    if declared is not None and declared > limit:
        return None
    chunks, size, more = [], 0, True
    while more:
        message = await receive()
        if message["type"] != "http.request":
            break
        chunk = message.get("body", b"")
        size += len(chunk)
        if size > limit:
            return None
        chunks.append(chunk)
        more = message.get("more_body", False)
    return b"".join(chunks)


def _replay(body: bytes) -> Any:
    sent = False

    async def receive() -> dict[str, Any]:
        nonlocal sent
        if sent:
            return {"type": "http.disconnect"}
        sent = True
        return {"type": "http.request", "body": body, "more_body": False}
    return receive


async def _send_json(send: Any, status: int, payload: dict[str, Any]) -> None:
    body = json.dumps(payload).encode()
    await send({"type": "http.response.start", "status": status, "headers": [
        (b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]})
    await send({"type": "http.response.body", "body": body})


def create_openenv_app(*, token: str | Sequence[str] | None = None,
                       max_sessions: int = DEFAULT_MAX_SESSIONS,
                       session_timeout: float | None = DEFAULT_SESSION_TIMEOUT,
                       sessions_per_caller: int | None = None,
                       reclaim_after: float = DEFAULT_RECLAIM_AFTER,
                       **env_kwargs: Any) -> Any:
    """OpenEnv's FastAPI app serving fresh `VeriGraphServerEnv(**env_kwargs)` sessions.

    `token`: one bearer token or several (any of them admits; several tell callers
    apart); None serves without one, for loopback only. `max_sessions` sessions at once
    (OpenEnv's max_concurrent_envs), each closed after `session_timeout` idle seconds
    (None: never); one caller holds at most `sessions_per_caller` (None: a quarter of
    `max_sessions`), and a full server replaces a session idle `reclaim_after` seconds.
    See the module docstring for the HTTP semantics. Serve it with uvicorn, e.g. `uvicorn.run(app,
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
    share = max(1, max_sessions // 4) if sessions_per_caller is None else sessions_per_caller
    if isinstance(share, bool) or not isinstance(share, int) or not 1 <= share <= max_sessions:
        raise VeriGraphError("sessions_per_caller must be between 1 and max_sessions",
                             field="sessions_per_caller", value=sessions_per_caller,
                             fix=f"use e.g. {max(1, max_sessions // 4)}, or None")
    if isinstance(reclaim_after, bool) or not isinstance(reclaim_after, (int, float)) \
            or not 0 < reclaim_after <= 7 * 86_400:
        raise VeriGraphError("reclaim_after must be a positive number of seconds (at most a "
                             "week)", field="reclaim_after", value=reclaim_after,
                             fix="use e.g. 300")
    make_env(**env_kwargs).close()  # bad environment arguments fail here, not per session
    concurrency = ConcurrencyConfig(max_concurrent_envs=max_sessions,
                                    session_timeout=session_timeout)
    # OpenEnv's app (create_app's routes and reaper) around its session server with the
    # shares; a partial of the class: OpenEnv reads SUPPORTS_CONCURRENT_SESSIONS from it
    # without building a throwaway environment
    app = FastAPI(title="VeriGraph environment (OpenEnv)", docs_url="/docs",
                  redoc_url="/redoc", openapi_url="/openapi.json")
    sessions = SharedSessions(functools.partial(VeriGraphServerEnv, **env_kwargs), ActAction,
                              PromptObservation, concurrency_config=concurrency,
                              share=share, reclaim_after=float(reclaim_after))
    sessions.register_routes(app)
    app.add_exception_handler(VeriGraphError, _error_response)
    app.add_middleware(Callers, sessions=sessions)
    if tokens:
        app.add_middleware(BearerToken, tokens=tokens)  # outermost: before any body is read
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


__all__ = ["DEFAULT_MAX_SESSIONS", "DEFAULT_RECLAIM_AFTER", "DEFAULT_SESSION_TIMEOUT",
           "TOOL_NAME", "ActAction", "BearerToken", "Callers", "NoEpisodeError",
           "PromptObservation", "RemoteSessionFactory", "SharedSessions", "TokenEnvClient",
           "VeriGraphServerEnv", "create_openenv_app", "serve_openenv"]
