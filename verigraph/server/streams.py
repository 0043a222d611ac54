"""Event streams (`GET /mcp`): capped per client, counted apart, closed when idle.

A streamable-HTTP client may open a standing server-to-client event stream with
`GET /mcp`. Each one holds a connection for as long as the client likes, so without a
budget one token holder could open enough of them to take every connection slot and lock
everyone else out. `EventStreams` gives streams their own budget, apart from the request
slots (verigraph.server.connections): at most `per_client` open streams per client (who
a client is: verigraph.server.callers) and `total` in all; more get 429 (per client) or
503 (in all), with the connection closed. A stream on which nothing but keep-alive
comments was sent for `idle_s` seconds is ended cleanly; the client may open another
(the server is stateless, so nothing is lost).
"""

from __future__ import annotations

import logging
from collections import Counter

import anyio
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from verigraph.server.callers import caller_of
from verigraph.server.rpc_errors import rpc_error

DEFAULT_STREAMS_PER_CLIENT = 8
DEFAULT_STREAM_IDLE_S = 30.0
log = logging.getLogger("verigraph.server")


def _carries_events(body: bytes) -> bool:
    """True unless `body` is only SSE comments (keep-alive pings) and blank lines."""
    return any(line and not line.startswith(b":") for line in body.splitlines())


class EventStreams:
    """The stream budget in front of the SDK's `GET` handler (see the module docstring)."""

    def __init__(self, app: ASGIApp, path: str, per_client: int, total: int,
                 idle_s: float) -> None:
        self.app = app
        self.path = path
        self.per_client = per_client
        self.total = total
        self.idle_s = idle_s
        self.open: Counter[str] = Counter()

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if (scope["type"] != "http" or scope["method"] != "GET"
                or scope["path"].rstrip("/") != self.path.rstrip("/")):
            await self.app(scope, receive, send)
            return
        key = caller_of(scope)
        close = {"Connection": "close"}
        if self.open[key] >= self.per_client:
            await rpc_error(429, f"Too many event streams: this client already has "
                            f"{self.per_client} open (GET {self.path}), the limit per "
                            "client; close one before opening another", headers=close,
                            data={"reason": "streams_per_client"})(scope, receive, send)
            return
        if sum(self.open.values()) >= self.total:
            await rpc_error(503, f"Too many event streams: {self.total} are open, this "
                            "server's limit; retry later", headers=close,
                            data={"reason": "streams_total"})(scope, receive, send)
            return
        self.open[key] += 1
        try:
            await self._serve(scope, receive, send)
        finally:
            self.open[key] -= 1
            if not self.open[key]:
                del self.open[key]

    async def _serve(self, scope: Scope, receive: Receive, send: Send) -> None:
        last = anyio.current_time()
        started = ended = idle = False

        async def tracked(message: Message) -> None:
            nonlocal last, started, ended
            if message["type"] == "http.response.start":
                started = True
            elif message["type"] == "http.response.body":
                if _carries_events(message.get("body", b"")):
                    last = anyio.current_time()
                ended = not message.get("more_body", False)
            await send(message)

        async with anyio.create_task_group() as tg:
            async def watch() -> None:
                nonlocal idle
                while (left := last + self.idle_s - anyio.current_time()) > 0:
                    await anyio.sleep(left)
                idle = True
                tg.cancel_scope.cancel()

            tg.start_soon(watch)
            await self.app(scope, receive, tracked)
            tg.cancel_scope.cancel()
        if idle:
            log.info("event stream idle for %g s: closed", self.idle_s)
            if started and not ended:
                await send({"type": "http.response.body", "body": b"", "more_body": False})
