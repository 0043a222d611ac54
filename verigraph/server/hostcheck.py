"""DNS-rebinding protection: Host and Origin parsed per RFC 9110, not matched as text.

A Host header is `uri-host [":" port]` (RFC 9110 section 7.2, RFC 3986 section 3.2.2):
the name is case-insensitive and the port is digits only, so `LOCALHOST:8000` is
loopback and `127.0.0.1:8000@evil.example` is no Host at all. Loopback names and the
bound address must carry the server's own port (or none); a name given with
`--allow-host NAME` accepts any port (a reverse proxy chooses it), `NAME:PORT` only
that one. An Origin is compared by its parsed host name (any port: a local web page
may be served from another port), never by prefix.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Iterable
from urllib.parse import urlsplit

from starlette.datastructures import Headers
from starlette.types import ASGIApp, Receive, Scope, Send

from verigraph.server.rpc_errors import rpc_error

LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "::1")
_HOST = re.compile(r"^(?P<name>\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9._~!$&'()*+,;=%-]+)"
                   r"(?::(?P<port>[0-9]*))?$")
log = logging.getLogger("verigraph.server")


def parse_host(value: str) -> tuple[str, int | None] | None:
    """(lower-case name without brackets, port or None), or None if it is not a Host."""
    match = _HOST.match(value.strip())
    if match is None:
        return None
    port = match.group("port")
    if port and (len(port) > 5 or int(port) > 65535):
        return None
    return match.group("name").strip("[]").lower(), int(port) if port else None


class HostPolicy:
    """Which Host and Origin values this server answers."""

    def __init__(self, bound_host: str, port: int, extra: Iterable[str] = ()) -> None:
        self.port = port
        self.exact: set[str] = {h.lower() for h in LOOPBACK_HOSTS}
        if bound_host not in ("0.0.0.0", "::"):
            self.exact.add(bound_host.strip("[]").lower())
        self.any_port: set[str] = set()
        self.fixed: set[tuple[str, int]] = set()
        for name in extra:
            parsed = parse_host(name)
            if parsed is None:
                raise ValueError(f"--allow-host {name!r} is not a host name")
            if parsed[1] is None:
                self.any_port.add(parsed[0])
            else:
                self.fixed.add((parsed[0], parsed[1]))

    def host_ok(self, value: str | None) -> bool:
        parsed = parse_host(value) if value else None
        if parsed is None:
            return False
        name, port = parsed
        if name in self.any_port or (port is not None and (name, port) in self.fixed):
            return True
        return name in self.exact and port in (None, self.port)

    def origin_ok(self, value: str | None) -> bool:
        if not value:
            return True  # same-origin and non-browser clients send none
        try:
            parts = urlsplit(value)
            name = parts.hostname
            _ = parts.port  # raises ValueError on a malformed port
        except ValueError:
            return False
        if parts.scheme not in ("http", "https") or not name or parts.username is not None:
            return False
        return name.lower() in self.exact | self.any_port | {n for n, _ in self.fixed}


class HostCheck:
    """421 for a Host this server is not, 403 for a foreign Origin (before any body)."""

    def __init__(self, app: ASGIApp, policy: HostPolicy) -> None:
        self.app = app
        self.policy = policy

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            headers = Headers(scope=scope)
            host = headers.get("host")
            if not self.policy.host_ok(host):
                log.warning("refused Host header %r", (host or "")[:100])
                await rpc_error(421, "Misdirected request: the Host header names another "
                                "server; connect to this server by a loopback name with its "
                                "port, or start it with --allow-host NAME")(scope, receive, send)
                return
            origin = headers.get("origin")
            if not self.policy.origin_ok(origin):
                log.warning("refused Origin header %r", (origin or "")[:100])
                await rpc_error(403, "Forbidden: requests from this web origin are not "
                                "accepted (DNS-rebinding protection); use --allow-host NAME "
                                "for a trusted origin")(scope, receive, send)
                return
        await self.app(scope, receive, send)
