"""Connection hygiene for uvicorn: header timeout, connection cap, quiet accept errors.

uvicorn bounds the idle time between requests (keep-alive) but not the time a client
may take to send its headers, so connections that never finish their headers hold a
file descriptor for ever; enough of them lock every client out. `guarded_protocol`
adds a header deadline (408 and close), and answers connections beyond the cap with
a plain 503 at once instead of letting the process run out of descriptors. If
descriptors do run out anyway, asyncio logs every failed accept with a traceback;
`quiet_accept_errors` turns that into one line per interval.
"""

from __future__ import annotations

import asyncio
import logging
import time
from typing import Any

from uvicorn.protocols.http.h11_impl import H11Protocol

log = logging.getLogger("verigraph.server")


def _plain(status: str, message: str) -> bytes:
    body = ('{"jsonrpc": "2.0", "id": null, "error": {"code": -32600, "message": "'
            + message + '"}}').encode()
    return (f"HTTP/1.1 {status}\r\ncontent-type: application/json\r\n"
            f"content-length: {len(body)}\r\nconnection: close\r\n\r\n").encode() + body


def guarded_protocol(header_timeout: float, max_connections: int) -> type[H11Protocol]:
    """An H11Protocol with a header deadline and a connection cap."""
    timeout_reply = _plain("408 Request Timeout", f"request headers not received within "
                           f"{header_timeout:g} s")
    busy_reply = _plain("503 Service Unavailable", f"the server has {max_connections} open "
                        "connections, its limit; retry shortly")

    class GuardedH11Protocol(H11Protocol):
        _header_timer: asyncio.TimerHandle | None = None

        def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
            super().connection_made(transport)
            if len(self.connections) > max_connections:
                transport.write(busy_reply)
                transport.close()
                return
            self._arm_header_timer()

        def data_received(self, data: bytes) -> None:
            waiting = self.cycle is None or self.cycle.response_complete
            if waiting and self._header_timer is None:
                self._arm_header_timer()  # the first bytes of the next request
            super().data_received(data)
            if self.cycle is not None and not self.cycle.response_complete:
                self._disarm_header_timer()  # headers complete: the app has the request

        def connection_lost(self, exc: Exception | None) -> None:
            self._disarm_header_timer()
            super().connection_lost(exc)

        def _arm_header_timer(self) -> None:
            self._header_timer = self.loop.call_later(header_timeout, self._header_timeout)

        def _disarm_header_timer(self) -> None:
            if self._header_timer is not None:
                self._header_timer.cancel()
                self._header_timer = None

        def _header_timeout(self) -> None:
            self._header_timer = None
            if not self.transport.is_closing():
                self.transport.write(timeout_reply)
                self.transport.close()

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
