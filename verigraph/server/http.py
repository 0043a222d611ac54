"""Streamable HTTP transport: stateless JSON responses behind auth and a body limit.

Layers, outermost first: uvicorn with a header deadline, a bounded share of the
slots for connections still sending headers and a connection cap (connections),
bearer-token check (headers only, so unauthenticated clients cannot
make the server read large bodies), DNS-rebinding protection (Host and Origin parsed
per RFC 9110; hostcheck), event streams capped per client and closed when idle
(streams), request body limit and deadline with a JSON-RPC error that
says what to do and cancellation when the client leaves, large calls checked in a
child process and answered as bytes (offload), then the SDK app.
"""

from __future__ import annotations

import asyncio
import hmac
import json
import logging
import os
import socket
import threading
from collections import deque
from dataclasses import dataclass, field
from typing import Any

import anyio
import uvicorn
from mcp.server.mcpserver import MCPServer
from mcp.server.transport_security import TransportSecuritySettings
from starlette.datastructures import Headers
from starlette.responses import Response
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from verigraph import __version__
from verigraph.server.argument_process import (
    DEFAULT_DEADLINE_S,
    DEFAULT_QUEUED_PER_CLIENT,
    ArgumentChecker,
)
from verigraph.server.callers import CALLER_KEY
from verigraph.server.connections import guarded_protocol, quiet_accept_errors
from verigraph.server.hostcheck import HostCheck, HostPolicy
from verigraph.server.offload import DEFAULT_THRESHOLD_BYTES, LargeCalls
from verigraph.server.rpc_errors import rpc_error
from verigraph.server.streams import DEFAULT_STREAM_IDLE_S, DEFAULT_STREAMS_PER_CLIENT, EventStreams

DEFAULT_MAX_BODY_BYTES = 16 * 1024 * 1024
log = logging.getLogger("verigraph.server")


@dataclass(frozen=True)
class HttpOptions:
    """How the HTTP endpoint listens and whom it lets in."""

    host: str = "127.0.0.1"
    port: int = 8000
    path: str = "/mcp"
    # Bearer tokens accepted; with several, each is one client's own (see callers).
    tokens: tuple[str, ...] = ()
    max_body_bytes: int = DEFAULT_MAX_BODY_BYTES
    allowed_hosts: tuple[str, ...] = field(default_factory=tuple)
    header_timeout_s: float = 10.0
    body_timeout_s: float = 30.0
    keep_alive_s: float = 75.0  # clients keep connections across long local steps
    max_connections: int = 512
    shutdown_s: float = 0.5  # SIGTERM: in-flight calls get this long, then are cancelled
    large_call_bytes: int = DEFAULT_THRESHOLD_BYTES  # bodies checked in a child (offload)
    large_call_mib: float = 512.0  # the child's memory budget for one body
    large_call_deadline_s: float = DEFAULT_DEADLINE_S  # the child's time for one body
    large_calls_queued: int = DEFAULT_QUEUED_PER_CLIENT  # bodies one client may have waiting
    streams_per_client: int = DEFAULT_STREAMS_PER_CLIENT  # open GET event streams per client
    stream_idle_s: float = DEFAULT_STREAM_IDLE_S  # a stream with no event this long is ended

    def max_streams(self) -> int:
        """Event streams open at once in all: a quarter of the connection slots."""
        return max(1, self.max_connections // 4)

    def url(self) -> str:
        host = f"[{self.host}]" if ":" in self.host else self.host
        return f"http://{host}:{self.port}{self.path}"


class BearerTokenAuth:
    """403 unless the request carries `Authorization: Bearer <token>` with one of the
    server's tokens (constant-time checks, every token compared).

    With several tokens, the one matched tells the client apart (its number goes into
    the scope for the per-client budgets, see callers); with one, every holder is alike.

    The token is a pre-shared secret, not OAuth. MCP clients that know OAuth (the MCP
    Inspector, the TypeScript SDK with an auth provider) start OAuth discovery on every
    401, with or without a `WWW-Authenticate` challenge, and then show an OAuth failure
    instead of the reason. So a missing or wrong token gets 403 without a challenge; the
    JSON-RPC error says which (`data.reason`: missing_token or wrong_token) and what to do.
    """

    def __init__(self, app: ASGIApp, tokens: tuple[str, ...]) -> None:
        self.app = app
        self.expected = [f"Bearer {token}".encode() for token in tokens]

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            given = Headers(scope=scope).get("authorization", "").encode()
            matches = [hmac.compare_digest(given, expected) for expected in self.expected]
            if not any(matches):
                await _refusal(given)(scope, receive, send)
                return
            if len(self.expected) > 1:
                scope[CALLER_KEY] = f"token {matches.index(True) + 1}"
        await self.app(scope, receive, send)


def _refusal(given: bytes) -> Response:
    if not given.strip():
        reason, message = "missing_token", (
            "Forbidden: no token was sent; this VeriGraph server needs the header "
            "'Authorization: Bearer <token>' with the token it was started with "
            "(--token or VERIGRAPH_TOKEN)")
    else:
        reason, message = "wrong_token", (
            "Forbidden: the token sent does not match; send 'Authorization: Bearer <token>' "
            "with the token this VeriGraph server was started with (--token or "
            "VERIGRAPH_TOKEN)")
    return rpc_error(403, message, code=-32001, data={"reason": reason})


class BodyLimit:
    """Read the body within its time and size limits, then run the app until the client
    disconnects.

    413 with a JSON-RPC error for bodies above `limit` bytes (declared or streamed), 408
    when the body does not arrive within `timeout` seconds. Once the body is in, a
    watcher waits for `http.disconnect`: a client that goes away cancels its request,
    and with it the tool call's worker (see heavy.HeavyCalls).
    """

    def __init__(self, app: ASGIApp, limit: int, timeout: float = 30.0) -> None:
        self.app = app
        self.limit = limit
        self.timeout = timeout

    def _too_large(self, size: int | None) -> Response:
        mib = self.limit / (1024 * 1024)
        seen = f" ({size} bytes)" if size is not None else ""
        return rpc_error(413, f"Request body too large{seen}: this server accepts "
                          f"at most {mib:g} MiB per request. Send smaller images (downscale "
                          "or use JPEG) or split the request.")

    async def _read_body(self, receive: Receive) -> deque[Message] | Response | None:
        chunks: deque[Message] = deque()
        size = 0
        while True:
            message = await receive()
            chunks.append(message)
            if message["type"] != "http.request":
                return None  # the client left while sending
            size += len(message.get("body", b""))
            if size > self.limit:
                return self._too_large(None)
            if not message.get("more_body", False):
                return chunks

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = Headers(scope=scope).get("content-length")
        if declared is not None and declared.isdigit() and int(declared) > self.limit:
            await self._too_large(int(declared))(scope, receive, send)
            return
        body: deque[Message] | Response | None = None
        with anyio.move_on_after(self.timeout):
            body = await self._read_body(receive)
            if body is None:
                return
        if body is None:
            await rpc_error(408, f"Request body not received within {self.timeout:g} "
                             "s: send the whole body promptly")(scope, receive, send)
            return
        if isinstance(body, Response):
            await body(scope, receive, send)
            return
        chunks = body
        gone = anyio.Event()

        async def replay() -> Message:
            if chunks:
                return chunks.popleft()
            await gone.wait()
            return {"type": "http.disconnect"}

        async with anyio.create_task_group() as tg:
            async def watch() -> None:
                while (await receive())["type"] != "http.disconnect":
                    pass
                gone.set()
                log.info("client went away: cancelling its request")
                tg.cancel_scope.cancel()

            tg.start_soon(watch)
            await self.app(scope, replay, send)
            tg.cancel_scope.cancel()

HEALTH_PATH = "/healthz"


class HealthCheck:
    """`GET /healthz` -> 200 {"status": "ok", ...} for load balancers and humans.

    Outermost, so it needs no token and no allowed Host: it says only that the server
    is up and which version it runs. Everything else passes through.
    """

    def __init__(self, app: ASGIApp) -> None:
        self.app = app
        self.body = json.dumps({"status": "ok", "name": "verigraph", "version": __version__})

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope["path"] != HEALTH_PATH:
            await self.app(scope, receive, send)
            return
        if scope["method"] not in ("GET", "HEAD"):
            response = Response(status_code=405, headers={"Allow": "GET, HEAD"})
        else:
            response = Response(self.body, media_type="application/json",
                                headers={"Cache-Control": "no-store"})
        await response(scope, receive, send)



def http_app(server: MCPServer[Any], options: HttpOptions) -> ASGIApp:
    """The ASGI app for `verigraph serve --transport http` (stateless, JSON responses).

    The SDK's own Host/Origin check matches text prefixes; HostCheck parses the headers
    instead (see hostcheck), so the SDK's is turned off here.
    """
    app: ASGIApp = server.streamable_http_app(
        streamable_http_path=options.path, stateless_http=True, json_response=True,
        max_request_body_size=options.max_body_bytes,
        transport_security=TransportSecuritySettings(enable_dns_rebinding_protection=False),
        host=options.host)
    if options.large_call_bytes > 0:  # 0: every body is parsed by this process (measured)
        app = LargeCalls(app, options.large_call_bytes, ArgumentChecker(
            options.large_call_mib, options.large_call_deadline_s,
            queued_per_client=options.large_calls_queued))
    app = BodyLimit(app, options.max_body_bytes, options.body_timeout_s)
    app = EventStreams(app, options.path, options.streams_per_client, options.max_streams(),
                       options.stream_idle_s)
    app = HostCheck(app, HostPolicy(options.host, options.port, options.allowed_hosts))
    if options.tokens:
        app = BearerTokenAuth(app, options.tokens)
    return HealthCheck(app)


def uvicorn_config(server: MCPServer[Any], options: HttpOptions, log_level: str = "warning"
                   ) -> uvicorn.Config:
    return uvicorn.Config(
        http_app(server, options), host=options.host, port=options.port,
        log_level=log_level.lower(), access_log=False, lifespan="on",
        http=guarded_protocol(options.header_timeout_s, options.max_connections),
        timeout_keep_alive=int(options.keep_alive_s),
        timeout_graceful_shutdown=options.shutdown_s)  # type: ignore[arg-type]


class StoppableServer(uvicorn.Server):
    """uvicorn that exits within `hard_exit_s` of the start of its shutdown.

    Cancelled calls stop at their next budget checkpoint; a call stuck in code that
    never checks (a C extension, a blocking driver) would hold the process, so a
    timer ends it once the grace time is over.
    """

    def __init__(self, config: uvicorn.Config, hard_exit_s: float) -> None:
        super().__init__(config)
        self.hard_exit_s = hard_exit_s

    async def shutdown(self, sockets: list[socket.socket] | None = None) -> None:
        timer = threading.Timer(self.hard_exit_s, _hard_exit)
        timer.daemon = True
        timer.start()
        await super().shutdown(sockets)


def _hard_exit() -> None:
    log.error("shutdown: tool calls still running after the grace time; exiting now")
    logging.shutdown()
    os._exit(0)


def serve_http(server: MCPServer[Any], options: HttpOptions, log_level: str = "warning",
               sock: socket.socket | None = None) -> None:
    """Run uvicorn in the foreground until interrupted (SIGINT/SIGTERM), on `sock` if
    given (a socket shared by several server processes, see workers).

    On SIGTERM uvicorn stops accepting, gives running requests `shutdown_s`, then
    cancels them; their worker threads stop at their next budget checkpoint.
    """
    config = uvicorn_config(server, options, log_level)
    log.warning("VeriGraph MCP server on %s (auth %s)", options.url(),
                f"on, {len(options.tokens)} token(s)" if options.tokens else "off")

    async def main() -> None:
        quiet_accept_errors(asyncio.get_running_loop())
        await StoppableServer(config, options.shutdown_s + 0.8).serve(
            sockets=[sock] if sock is not None else None)

    anyio.run(main)
