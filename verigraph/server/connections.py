"""Connection admission for uvicorn: header deadline, a bounded share for waiting
connections, a connection cap, quiet accept errors.

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

Event streams (`GET /mcp`) are busy connections with their own, smaller budget
(verigraph.server.streams), so they cannot take the request slots either. If
descriptors do run out anyway, asyncio logs every failed accept with a traceback;
`quiet_accept_errors` turns that into one line per interval.
"""

from __future__ import annotations

import asyncio
import logging
import socket
import time
from typing import Any

from uvicorn.protocols.http.h11_impl import H11Protocol

log = logging.getLogger("verigraph.server")

WAITING_SHARE = 0.25  # of --max-connections, for connections without a request in progress
MAX_PEEK = 16384  # bytes looked at for the end of a request's headers (uvicorn's h11 limit)


def _plain(status: str, message: str) -> bytes:
    body = ('{"jsonrpc": "2.0", "id": null, "error": {"code": -32600, "message": "'
            + message + '"}}').encode()
    return (f"HTTP/1.1 {status}\r\ncontent-type: application/json\r\n"
            f"content-length: {len(body)}\r\nconnection: close\r\n\r\n").encode() + body


def waiting_limit(max_connections: int, share: float = WAITING_SHARE) -> int:
    """How many connections may wait for their headers at once (at least one)."""
    return max(1, int(max_connections * share))


def guarded_protocol(header_timeout: float, max_connections: int,
                     waiting_share: float = WAITING_SHARE) -> type[H11Protocol]:
    """An H11Protocol with a header deadline, a bounded waiting share and a connection cap.

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

        def on_response_complete(self) -> None:
            self._served += 1
            super().on_response_complete()
            if self._waiting_for_request() and not self.transport.is_closing():
                waiting.pop(self, None)
                waiting[self] = None  # idle between requests: waiting again, newest

        def connection_lost(self, exc: Exception | None) -> None:
            waiting.pop(self, None)
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
