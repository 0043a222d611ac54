"""Admission: what a connection and a request may take, before the app has them.

Connections (uvicorn's protocol, `guarded_protocol`): a header deadline, a bounded
share for waiting connections, a connection cap, quiet accept errors. Requests (ASGI
layers): a body's size and time (`BodyLimit`), and event streams (`EventStreams`).

uvicorn bounds the idle time between requests (keep-alive) but not the time a client
may take to send its headers, and it admits every connection it accepts. So anyone on
the machine, without the token, could hold every slot with connections that never
finish their headers. `guarded_protocol` therefore sorts connections into two kinds:

* waiting: no request in progress (headers still arriving, or idle between requests
  on a kept-alive connection). Waiting connections get at most `waiting_share` of the
  slots; when a new connection would exceed that share (or the cap), the oldest waiting
  connection whose headers have not arrived is closed to make room (one whose headers
  sit unread in the socket, accepted in the same burst, is spared), and every waiting
  connection has a header deadline (408 and close). Connections that never finished a
  request go before idle kept-alive ones. A flood of half-open connections thus only
  ever evicts itself, and a client that sends its request promptly (the token is in its
  headers) is admitted.
* busy: headers complete, the app has the request. Only when every slot is busy is a
  new connection answered with a plain 503 at once (instead of letting the process run
  out of descriptors).

If descriptors do run out anyway, asyncio logs every failed accept with a traceback;
`quiet_accept_errors` turns that into one line per interval.

`BodyLimit` reads a body within its size and time limits (413 or 408 with a JSON-RPC
error that says what to do), then runs the app until the client disconnects: a client
that goes away cancels its request, and with it the tool call's worker thread.

Event streams (`GET /mcp`): a streamable-HTTP client may open a standing
server-to-client event stream. Each one holds a connection for as long as the client
likes, so without a budget one token holder could open enough of them to take every
connection slot and lock everyone else out. `EventStreams` gives streams (busy
connections) their own budget, apart from the request slots: at most `per_client` open
streams per caller (see access.caller_of) and `total` in all; more get 429 (per
caller) or 503 (in all), with the connection closed. A stream on which
nothing but keep-alive comments was sent for `idle_s` seconds is ended cleanly; the
client may open another (the server is stateless, so nothing is lost).
"""

from __future__ import annotations

import asyncio
import logging
import socket
import time
from collections import Counter, deque
from typing import Any

import anyio
from starlette.datastructures import Headers
from starlette.responses import Response
from starlette.types import ASGIApp, Message, Receive, Scope, Send
from uvicorn.protocols.http.h11_impl import H11Protocol

from verigraph.server.http.access import caller_of, rpc_response
from verigraph.server.http.workers import InFlight
from verigraph.server.rpc_errors import error_bytes

log = logging.getLogger("verigraph.server")

WAITING_SHARE = 0.25  # of --max-connections, for connections without a request in progress
MAX_PEEK = 16384  # bytes looked at for the end of a request's headers (uvicorn's h11 limit)


def _plain(status: str, message: str) -> bytes:
    body = error_bytes(message)
    return (f"HTTP/1.1 {status}\r\ncontent-type: application/json\r\n"
            f"content-length: {len(body)}\r\nconnection: close\r\n\r\n").encode() + body


def waiting_limit(max_connections: int, share: float = WAITING_SHARE) -> int:
    """How many connections may wait for their headers at once (at least one)."""
    return max(1, int(max_connections * share))


def guarded_protocol(header_timeout: float, max_connections: int,
                     waiting_share: float = WAITING_SHARE, in_flight: InFlight | None = None
                     ) -> type[H11Protocol]:
    """An H11Protocol with a header deadline, a bounded waiting share and a connection cap;
    with `in_flight` (a worker process of several, see workers) it reports each POST
    request from its complete headers to its complete answer.

    The waiting connections of one server live in one insertion-ordered dict (oldest
    first), shared by every connection this class makes; uvicorn runs one event loop,
    so no lock is needed.
    """
    max_waiting = waiting_limit(max_connections, waiting_share)
    timeout_reply = _plain("408 Request Timeout", f"request headers not received within "
                           f"{header_timeout:g} s")
    busy_reply = _plain("503 Service Unavailable", f"the server has {max_connections} open "
                        "connections with requests in progress, its limit; retry shortly")
    evicted_reply = _plain("503 Service Unavailable", "closed to admit a newer connection: "
                           f"more than {max_waiting} connections were waiting for their "
                           "request headers; send the whole request promptly")
    waiting: dict[GuardedH11Protocol, None] = {}

    def evict_oldest(keep: GuardedH11Protocol) -> bool:
        """Close the oldest waiting connection that never finished a request, else the
        oldest idle one (a client that was served once is likely to send again)."""
        for fresh_only in (True, False):
            for victim in waiting:
                if victim is keep or (fresh_only and victim._served):
                    continue
                if not victim._headers_arrived():
                    victim._evict()
                    return True
        return False

    class GuardedH11Protocol(H11Protocol):
        _header_timer: asyncio.TimerHandle | None = None
        _served = 0  # requests answered on this connection
        _partial = False  # bytes of an unfinished request arrived
        _flight: int | None = None  # the request's key with in_flight, while in progress

        def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
            super().connection_made(transport)
            waiting[self] = None
            while len(waiting) > max_waiting and evict_oldest(self):
                pass
            if len(self.connections) > max_connections and not evict_oldest(self):
                waiting.pop(self, None)
                transport.write(busy_reply)
                transport.close()
                return
            self._arm_header_timer()

        def data_received(self, data: bytes) -> None:
            if self._waiting_for_request():
                self._partial = True
                if self._header_timer is None:
                    self._arm_header_timer()  # the first bytes of the next request
            super().data_received(data)
            if not self._waiting_for_request():
                self._disarm_header_timer()  # headers complete: the app has the request
                self._partial = False
                waiting.pop(self, None)
                if in_flight is not None and self._flight is None:
                    self._report_opened()

        def on_response_complete(self) -> None:
            self._served += 1
            self._report_closed()
            super().on_response_complete()
            if self._waiting_for_request() and not self.transport.is_closing():
                waiting.pop(self, None)
                waiting[self] = None  # idle between requests: waiting again, newest

        def connection_lost(self, exc: Exception | None) -> None:
            waiting.pop(self, None)
            self._report_closed()
            self._disarm_header_timer()
            super().connection_lost(exc)

        def _headers_arrived(self) -> bool:
            """Whether this connection's request headers are complete, though not yet read
            from the socket: a connection accepted in the same burst as a flood has had no
            turn to be read yet, and must not be taken for a slow one."""
            sock = self.transport.get_extra_info("socket")
            if sock is None:
                return False
            raw = socket.socket(fileno=sock.fileno())  # borrowed: detached below, not closed
            try:
                pending = raw.recv(MAX_PEEK, socket.MSG_PEEK | socket.MSG_DONTWAIT)
            except OSError:
                pending = b""
            finally:
                raw.detach()
            return b"\r\n\r\n" in bytes(self.conn.trailing_data[0]) + pending

        def _report_opened(self) -> None:
            assert in_flight is not None
            sock = self.transport.get_extra_info("socket")
            if sock is not None and self.cycle is not None \
                    and self.cycle.scope.get("method") == "POST":
                self._flight = in_flight.opened(sock.fileno())

        def _report_closed(self) -> None:
            if self._flight is not None and in_flight is not None:
                in_flight.closed(self._flight)
                self._flight = None

        def _waiting_for_request(self) -> bool:
            return self.cycle is None or self.cycle.response_complete

        def _arm_header_timer(self) -> None:
            self._header_timer = self.loop.call_later(header_timeout, self._header_timeout)

        def _disarm_header_timer(self) -> None:
            if self._header_timer is not None:
                self._header_timer.cancel()
                self._header_timer = None

        def _close_with(self, reply: bytes | None) -> None:
            waiting.pop(self, None)
            self._disarm_header_timer()
            if not self.transport.is_closing():
                if reply is not None:
                    self.transport.write(reply)
                self.transport.close()

        def _evict(self) -> None:
            # An idle kept-alive connection asked nothing: close it without a reply.
            self._close_with(evicted_reply if self._partial or not self._served else None)

        def _header_timeout(self) -> None:
            self._header_timer = None
            self._close_with(timeout_reply)

    return GuardedH11Protocol


def quiet_accept_errors(loop: asyncio.AbstractEventLoop, interval: float = 10.0) -> None:
    """Log accept() resource errors (EMFILE and friends) once per `interval`, no traceback."""
    last = [0.0]
    suppressed = [0]
    default = loop.get_exception_handler()

    def handler(loop: asyncio.AbstractEventLoop, context: dict[str, Any]) -> None:
        message = str(context.get("message", ""))
        if "accept" in message:
            now = time.monotonic()
            if now - last[0] >= interval:
                log.warning("%s: %s (%d more like it since the last report); lower "
                            "--max-connections or raise the file-descriptor limit",
                            message, context.get("exception"), suppressed[0])
                last[0] = now
                suppressed[0] = 0
            else:
                suppressed[0] += 1
            return
        if default is not None:
            default(loop, context)
        else:
            loop.default_exception_handler(context)

    loop.set_exception_handler(handler)


DEFAULT_MAX_BODY_BYTES = 16 * 1024 * 1024
DEFAULT_BODY_TIMEOUT_S = 30.0
DEFAULT_STREAMS_PER_CLIENT = 8
DEFAULT_STREAM_IDLE_S = 30.0


class BodyLimit:
    """Read the body within its time and size limits, then run the app until the client
    disconnects.

    413 with a JSON-RPC error for bodies above `limit` bytes (declared or streamed), 408
    when the body does not arrive within `timeout` seconds. Once the body is in, a
    watcher waits for `http.disconnect`: a client that goes away cancels its request,
    and with it the tool call's worker (see heavy.HeavyCalls).
    """

    def __init__(self, app: ASGIApp, limit: int, timeout: float = DEFAULT_BODY_TIMEOUT_S
                 ) -> None:
        self.app = app
        self.limit = limit
        self.timeout = timeout

    def _too_large(self, size: int | None) -> Response:
        mib = self.limit / (1024 * 1024)
        seen = f" ({size} bytes)" if size is not None else ""
        return rpc_response(413, f"Request body too large{seen}: this server accepts "
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
            await rpc_response(408, f"Request body not received within {self.timeout:g} "
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
            await rpc_response(429, f"Too many event streams: this client already has "
                            f"{self.per_client} open (GET {self.path}), the limit per "
                            "client; close one before opening another", headers=close,
                            data={"reason": "streams_per_client"})(scope, receive, send)
            return
        if sum(self.open.values()) >= self.total:
            await rpc_response(503, f"Too many event streams: {self.total} are open, this "
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
