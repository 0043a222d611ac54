"""Who may talk to the HTTP endpoint: health check, bearer tokens, Host and Origin.

Outermost first: `HealthCheck` answers `GET /healthz` with no token (it says only that
the server is up); `BearerTokenAuth` checks the token from the headers alone, so an
unauthenticated client cannot make the server read a large body; `HostCheck` is the
DNS-rebinding protection. A refusal is a JSON-RPC error (`rpc_response`, the HTTP form
of verigraph.server.rpc_errors) that says what to do.

Who a caller is, for the budgets kept per caller (event streams, large bodies waiting
for the checking process, episodes): the token it presents when the server was given
several (`--token` repeated: one per caller, the standard API-key arrangement), else the
address it connects from. With a single shared token every holder presents the same
header, so the token cannot tell them apart and the address is all there is; callers on
one host then count as one, which is why a server shared by local callers gives each its
own token. BearerTokenAuth writes the matched token's caller (a fingerprint, never the
token itself, see verigraph.server.callers) into the ASGI scope; the inner layers read
it with `caller_of`.

Host and Origin are parsed per RFC 9110, not matched as text. A Host header is
`uri-host [":" port]` (RFC 9110 section 7.2, RFC 3986 section 3.2.2): the name is
case-insensitive and the port is digits only, so `LOCALHOST:8000` is loopback and
`127.0.0.1:8000@evil.example` is no Host at all. Loopback names and the bound address
must carry the server's own port (or none); a name given with `--allow-host NAME`
accepts any port (a reverse proxy chooses it), `NAME:PORT` only that one. An Origin is
compared by its parsed host name (any port: a local web page may be served from another
port), never by prefix.
"""

from __future__ import annotations

import json
import logging
import re
from collections.abc import Iterable
from typing import Any
from urllib.parse import urlsplit

from starlette.datastructures import Headers
from starlette.responses import Response
from starlette.types import ASGIApp, Receive, Scope, Send

from verigraph import __version__
from verigraph.server.callers import CALLER_KEY, Refusal, TokenGate, caller_of
from verigraph.server.rpc_errors import FORBIDDEN, INVALID_REQUEST, error_bytes

__all__ = ["CALLER_KEY", "BearerTokenAuth", "HealthCheck", "HostCheck", "HostPolicy",
           "caller_of", "rpc_response"]
log = logging.getLogger("verigraph.server")


def rpc_response(status: int, message: str, *, code: int = INVALID_REQUEST,
                 request_id: str | int | None = None, data: dict[str, Any] | None = None,
                 headers: dict[str, str] | None = None) -> Response:
    """An HTTP `status` answer whose body is a JSON-RPC error saying what to do."""
    return Response(error_bytes(message, code=code, request_id=request_id, data=data),
                    status_code=status, media_type="application/json", headers=headers)


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



class BearerTokenAuth:
    """403 unless the request carries `Authorization: Bearer <token>` with one of the
    server's tokens (constant-time checks, every token compared).

    With several tokens, the one matched tells the client apart (its caller goes into
    the scope for the per-caller budgets, see caller_of); with one, every holder is alike.

    The token is a pre-shared secret, not OAuth. MCP clients that know OAuth (the MCP
    Inspector, the TypeScript SDK with an auth provider) start OAuth discovery on every
    401, with or without a `WWW-Authenticate` challenge, and then show an OAuth failure
    instead of the reason. So a missing or wrong token gets 403 without a challenge; the
    JSON-RPC error says which (`data.reason`: missing_token or wrong_token) and what to do.
    """

    def __init__(self, app: ASGIApp, tokens: tuple[str, ...]) -> None:
        self.app = app
        self.gate = TokenGate(tokens)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            refusal = self.gate.check(scope)
            if refusal is not None:
                await _refusal(refusal)(scope, receive, send)
                return
        await self.app(scope, receive, send)


def _refusal(reason: Refusal) -> Response:
    if reason == "missing_token":
        message = (
            "Forbidden: no token was sent; this VeriGraph server needs the header "
            "'Authorization: Bearer <token>' with the token it was started with "
            "(--token or VERIGRAPH_TOKEN)")
    else:
        message = (
            "Forbidden: the token sent does not match; send 'Authorization: Bearer <token>' "
            "with the token this VeriGraph server was started with (--token or "
            "VERIGRAPH_TOKEN)")
    return rpc_response(403, message, code=FORBIDDEN, data={"reason": reason})


LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "::1")
_HOST = re.compile(r"^(?P<name>\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9._~!$&'()*+,;=%-]+)"
                   r"(?::(?P<port>[0-9]*))?$")


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
                await rpc_response(421, "Misdirected request: the Host header names another "
                                "server; connect to this server by a loopback name with its "
                                "port, or start it with --allow-host NAME")(scope, receive, send)
                return
            origin = headers.get("origin")
            if not self.policy.origin_ok(origin):
                log.warning("refused Origin header %r", (origin or "")[:100])
                await rpc_response(403, "Forbidden: requests from this web origin are not "
                                "accepted (DNS-rebinding protection); use --allow-host NAME "
                                "for a trusted origin")(scope, receive, send)
                return
        await self.app(scope, receive, send)
