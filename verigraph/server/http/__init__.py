"""The HTTP wing: streamable HTTP (stateless, JSON responses) and its defences.

stdio imports nothing of this package. Layers, outermost first:

* admission (uvicorn's protocol): a header deadline, a bounded share of the slots for
  connections still sending headers, a connection cap, quiet accept errors;
* access: `GET /healthz`, the bearer token (headers only, so unauthenticated clients
  cannot make the server read large bodies), DNS-rebinding protection (Host and Origin
  parsed per RFC 9110);
* admission again (ASGI layers): event streams capped per caller and closed when idle;
  the request body's size limit and deadline, and cancellation when the client leaves;
* offload: large calls checked in a child process (argument_process) and answered as
  bytes;
* then the SDK's app, whose tools/calls run in verigraph.server.tools.

workers runs several such servers on one port (`verigraph serve --workers N`).

uvicorn's own `limit_concurrency` answers 503 once that many connections and tasks are
open, but it neither evicts connections that never finish their headers nor tells
waiting connections from busy ones, so a flood of half-open sockets would lock every
client out; admission does both. The SDK's body limit (`max_request_body_size`) is set
too, as a second line; BodyLimit is the one that also bounds the time a body takes and
answers with a JSON-RPC error.
"""

from __future__ import annotations

import asyncio
import logging
import os
import socket
import threading
from dataclasses import dataclass, field
from typing import Any

import anyio
import uvicorn
from mcp.server.mcpserver import MCPServer
from mcp.server.transport_security import TransportSecuritySettings
from starlette.types import ASGIApp

from verigraph.budget import DEFAULT_MEMORY_MIB
from verigraph.server.http.access import BearerTokenAuth, HealthCheck, HostCheck, HostPolicy
from verigraph.server.http.admission import (
    DEFAULT_BODY_TIMEOUT_S,
    DEFAULT_MAX_BODY_BYTES,
    DEFAULT_STREAM_IDLE_S,
    DEFAULT_STREAMS_PER_CLIENT,
    BodyLimit,
    EventStreams,
    guarded_protocol,
    quiet_accept_errors,
)
from verigraph.server.http.argument_process import (
    DEFAULT_DEADLINE_S,
    DEFAULT_QUEUED_PER_CLIENT,
    ArgumentChecker,
)
from verigraph.server.http.offload import DEFAULT_THRESHOLD_BYTES, LargeCalls
from verigraph.server.http.workers import InFlight

__all__ = ["HttpOptions", "http_app", "serve_http", "uvicorn_config"]
log = logging.getLogger("verigraph.server")


@dataclass(frozen=True)
class HttpOptions:
    """How the HTTP endpoint listens and whom it lets in."""

    host: str = "127.0.0.1"
    port: int = 8000
    path: str = "/mcp"
    # Bearer tokens accepted; with several, each is one caller's own (see access.caller_of).
    tokens: tuple[str, ...] = ()
    max_body_bytes: int = DEFAULT_MAX_BODY_BYTES
    allowed_hosts: tuple[str, ...] = field(default_factory=tuple)
    header_timeout_s: float = 10.0
    body_timeout_s: float = DEFAULT_BODY_TIMEOUT_S
    keep_alive_s: float = 75.0  # clients keep connections across long local steps
    max_connections: int = 512
    shutdown_s: float = 0.5  # SIGTERM: in-flight calls get this long, then are cancelled
    large_call_bytes: int = DEFAULT_THRESHOLD_BYTES  # bodies checked in a child (offload)
    large_call_mib: float = DEFAULT_MEMORY_MIB  # the child's memory budget for one body
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


def http_app(server: MCPServer[Any], options: HttpOptions) -> ASGIApp:
    """The ASGI app for `verigraph serve --transport http` (stateless, JSON responses).

    The SDK's own Host/Origin check matches text prefixes; HostCheck parses the headers
    instead (see access), so the SDK's is turned off here.
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


def uvicorn_config(server: MCPServer[Any], options: HttpOptions, log_level: str = "warning",
                   in_flight: InFlight | None = None) -> uvicorn.Config:
    return uvicorn.Config(
        http_app(server, options), host=options.host, port=options.port,
        log_level=log_level.lower(), access_log=False, lifespan="on",
        http=guarded_protocol(options.header_timeout_s, options.max_connections,
                              in_flight=in_flight),
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
               sock: socket.socket | None = None, in_flight: InFlight | None = None) -> None:
    """Run uvicorn in the foreground until interrupted (SIGINT/SIGTERM), on `sock` if
    given (a socket shared by several server processes, each reporting its requests in
    progress to their parent through `in_flight`, see workers).

    On SIGTERM uvicorn stops accepting, gives running requests `shutdown_s`, then
    cancels them; their worker threads stop at their next budget checkpoint.
    """
    config = uvicorn_config(server, options, log_level, in_flight)
    log.warning("VeriGraph MCP server on %s (auth %s)", options.url(),
                f"on, {len(options.tokens)} token(s)" if options.tokens else "off")

    async def main() -> None:
        quiet_accept_errors(asyncio.get_running_loop())
        await StoppableServer(config, options.shutdown_s + 0.8).serve(
            sockets=[sock] if sock is not None else None)

    anyio.run(main)
