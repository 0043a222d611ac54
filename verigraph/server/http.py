"""Streamable HTTP transport: stateless JSON responses behind auth and a body limit.

Layers, outermost first: bearer-token check (headers only, so unauthenticated
clients cannot make the server read large bodies), request body limit with a
JSON-RPC error that says what to do, then the SDK app with DNS-rebinding protection
(Host and Origin allow-lists; loopback always allowed).
"""

from __future__ import annotations

import hmac
import json
import logging
from collections import deque
from dataclasses import dataclass, field
from typing import Any

import anyio
from mcp.server.mcpserver import MCPServer
from mcp.server.transport_security import TransportSecuritySettings
from starlette.datastructures import Headers
from starlette.responses import Response
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from verigraph import __version__

DEFAULT_MAX_BODY_BYTES = 16 * 1024 * 1024
LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "::1")
log = logging.getLogger("verigraph.server")


@dataclass(frozen=True)
class HttpOptions:
    """How the HTTP endpoint listens and whom it lets in."""

    host: str = "127.0.0.1"
    port: int = 8000
    path: str = "/mcp"
    token: str | None = None
    max_body_bytes: int = DEFAULT_MAX_BODY_BYTES
    allowed_hosts: tuple[str, ...] = field(default_factory=tuple)

    def url(self) -> str:
        host = f"[{self.host}]" if ":" in self.host else self.host
        return f"http://{host}:{self.port}{self.path}"


def _rpc_error(status: int, code: int, message: str,
               headers: dict[str, str] | None = None) -> Response:
    body = json.dumps({"jsonrpc": "2.0", "id": None,
                       "error": {"code": code, "message": message}})
    return Response(body, status_code=status, media_type="application/json", headers=headers)


class BearerTokenAuth:
    """403 unless the request carries `Authorization: Bearer <token>` (constant-time check).

    The token is a pre-shared secret, not OAuth. MCP clients that know OAuth (the MCP
    Inspector, the TypeScript SDK with an auth provider) start OAuth discovery on every
    401, with or without a `WWW-Authenticate` challenge, and then show an OAuth failure
    instead of the reason. So a missing or wrong token gets 403 without a challenge; the
    JSON-RPC error says which (`data.reason`: missing_token or wrong_token) and what to do.
    """

    def __init__(self, app: ASGIApp, token: str) -> None:
        self.app = app
        self.expected = f"Bearer {token}".encode()

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            given = Headers(scope=scope).get("authorization", "").encode()
            if not hmac.compare_digest(given, self.expected):
                await _refusal(given)(scope, receive, send)
                return
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
    body = json.dumps({"jsonrpc": "2.0", "id": None, "error": {
        "code": -32001, "message": message, "data": {"reason": reason}}})
    return Response(body, status_code=403, media_type="application/json")


class BodyLimit:
    """413 with a JSON-RPC error for bodies above `limit` bytes, declared or streamed."""

    def __init__(self, app: ASGIApp, limit: int) -> None:
        self.app = app
        self.limit = limit

    def _too_large(self, size: int | None) -> Response:
        mib = self.limit / (1024 * 1024)
        seen = f" ({size} bytes)" if size is not None else ""
        return _rpc_error(413, -32600, f"Request body too large{seen}: this server accepts "
                          f"at most {mib:g} MiB per request. Send smaller images (downscale "
                          "or use JPEG) or split the request.")

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = Headers(scope=scope).get("content-length")
        if declared is not None and declared.isdigit() and int(declared) > self.limit:
            await self._too_large(int(declared))(scope, receive, send)
            return
        chunks: deque[Message] = deque()
        size = 0
        while True:
            message = await receive()
            chunks.append(message)
            if message["type"] != "http.request":
                break
            size += len(message.get("body", b""))
            if size > self.limit:
                await self._too_large(None)(scope, receive, send)
                return
            if not message.get("more_body", False):
                break

        async def replay() -> Message:
            return chunks.popleft() if chunks else await receive()

        await self.app(scope, replay, send)


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


def transport_security(options: HttpOptions) -> TransportSecuritySettings:
    """Host/Origin allow-lists: loopback names, the bound host, and any extra names."""
    names = list(LOOPBACK_HOSTS)
    if options.host not in ("0.0.0.0", "::", *LOOPBACK_HOSTS):
        names.append(options.host)
    names.extend(options.allowed_hosts)
    hosts = [f"[{n}]:*" if ":" in n else f"{n}:*" for n in names]
    hosts += [h.removesuffix(":*") for h in hosts]  # clients that omit the port
    origins = [f"http://{h}" for h in hosts] + [f"https://{h}" for h in hosts]
    return TransportSecuritySettings(enable_dns_rebinding_protection=True,
                                     allowed_hosts=hosts, allowed_origins=origins)


def http_app(server: MCPServer[Any], options: HttpOptions) -> ASGIApp:
    """The ASGI app for `verigraph serve --transport http` (stateless, JSON responses)."""
    app: ASGIApp = server.streamable_http_app(
        streamable_http_path=options.path, stateless_http=True, json_response=True,
        max_request_body_size=options.max_body_bytes,
        transport_security=transport_security(options), host=options.host)
    app = BodyLimit(app, options.max_body_bytes)
    if options.token:
        app = BearerTokenAuth(app, options.token)
    return HealthCheck(app)


def serve_http(server: MCPServer[Any], options: HttpOptions, log_level: str = "warning") -> None:
    """Run uvicorn in the foreground until interrupted."""
    import uvicorn

    config = uvicorn.Config(http_app(server, options), host=options.host, port=options.port,
                            log_level=log_level.lower(), access_log=False, lifespan="on")
    log.warning("VeriGraph MCP server on %s (auth %s)", options.url(),
                "on" if options.token else "off")
    anyio.run(uvicorn.Server(config).serve)
