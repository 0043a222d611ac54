"""Who a request comes from: its caller (docs/architecture.md, glossary).

Over HTTP the caller is the bearer token it matched when the server has several (one per
caller), else the address it connects from (an IPv6 address by its /64); over stdio the
one peer. `TokenGate` is the one bearer-token check of every HTTP endpoint (the MCP
server's BearerTokenAuth, the OpenEnv server's BearerToken): it writes a token caller
into the ASGI scope under CALLER_KEY; the per-caller budgets there and the episode
store's owners and shares read it with `caller_of`.

A token caller is named `token` and a fingerprint of the token (a slow hash of it, cut
to 12 hex digits; never the token): the same token is the same caller after a restart
whatever the order of `--token`, so a durable store's episodes stay with their caller,
and a log line never carries anything a token could be recovered from cheaply.
"""

from __future__ import annotations

import hashlib
import hmac
import ipaddress
from collections.abc import MutableMapping, Sequence
from typing import Any, Literal

from mcp.server.context import CallNext, HandlerResult, ServerRequestContext
from mcp.shared.exceptions import MCPError

from verigraph.server.rpc_errors import INVALID_REQUEST, MAX_ID_CHARS, id_problem
from verigraph.tools.store import LOCAL_CALLER, calling_as

CALLER_KEY = "verigraph.caller"
# stdio's one peer is the user who started the server: the same caller as in-process
# tool calls (the CLI, the library, a test driving both), so their episodes are shared
STDIO_CALLER = LOCAL_CALLER
_SALT = b"verigraph caller"
_ROUNDS = 50_000  # once per token at start-up (~25 ms); a guess costs as much offline


def token_caller(token: str) -> str:
    """`token 1a2b3c4d5e6f`: the caller a bearer token stands for."""
    digest = hashlib.pbkdf2_hmac("sha256", token.encode(), _SALT, _ROUNDS, dklen=6)
    return f"token {digest.hex()}"


Refusal = Literal["missing_token", "wrong_token"]


class TokenGate:
    """The bearer-token check of an ASGI request (HTTP or WebSocket handshake): the
    request's first `Authorization` header, as sent, against `Bearer <token>` for each
    accepted token, in constant time and every token compared.

    `check(scope)` gives None when a token matches, and then, with several tokens (one
    per caller), writes the matched token's caller into the scope under CALLER_KEY; else
    why not (`missing_token`, `wrong_token`), which each endpoint answers in its own
    words. Checked from the headers alone, so a refused client makes the server read no
    body.
    """

    def __init__(self, tokens: Sequence[str]) -> None:
        self.expected = [f"Bearer {token}".encode() for token in tokens]
        # with several tokens each is one caller's own; with one, every holder is alike
        self.callers = [token_caller(t) for t in tokens] if len(tokens) > 1 else []

    def check(self, scope: MutableMapping[str, Any]) -> Refusal | None:
        given = authorization(scope)
        matches = [hmac.compare_digest(given, expected) for expected in self.expected]
        if not any(matches):
            return "wrong_token" if given.strip() else "missing_token"
        if self.callers:
            scope[CALLER_KEY] = self.callers[matches.index(True)]
        return None


def authorization(scope: MutableMapping[str, Any]) -> bytes:
    """The first `Authorization` header of an ASGI scope, as sent (b"" if none)."""
    for name, value in scope.get("headers", ()):
        if name.lower() == b"authorization":
            return bytes(value)
    return b""


def caller_of(scope: Any) -> str:
    """A token caller (several tokens), else `address 127.0.0.1`."""
    named = scope.get(CALLER_KEY)
    if isinstance(named, str):
        return named
    peer = scope.get("client")
    return address_caller(str(peer[0])) if peer else "address unknown"


def address_caller(host: str) -> str:
    """The caller an address stands for. An IPv6 host is its /64: one end site is
    given a /64 (RFC 6177) and may use any of its 2**64 addresses, so counting them
    one by one would give a single client unbounded shares; an IPv4-mapped address is
    its IPv4 address."""
    try:
        ip = ipaddress.ip_address(host.split("%", 1)[0])
    except ValueError:
        return f"address {host[:64]}"
    if isinstance(ip, ipaddress.IPv6Address):
        if ip.ipv4_mapped is not None:
            return f"address {ip.ipv4_mapped}"
        if not ip.is_loopback:
            return f"address {ipaddress.IPv6Network((ip, 64), strict=False)}"
    return f"address {ip}"


class CallerScope:
    """Server middleware (outermost): every request runs as its caller, so tools,
    resources and prompts find only that caller's episodes and open them in its share;
    a request whose id is longer than MAX_ID_CHARS is refused for its id, whatever its
    method (the HTTP wing refuses such a large body before it is parsed, in the same
    words). A tools/call enters no other module of the server than this one and
    verigraph.server.tools."""

    async def __call__(self, ctx: ServerRequestContext[Any, Any], call_next: CallNext
                       ) -> HandlerResult:
        request_id = ctx.request_id
        if isinstance(request_id, str) and len(request_id) > MAX_ID_CHARS:
            raise MCPError(INVALID_REQUEST, id_problem(request_id) or "id too long")
        scope = getattr(ctx.request, "scope", None)
        with calling_as(caller_of(scope) if isinstance(scope, dict) else STDIO_CALLER):
            return await call_next(ctx)
