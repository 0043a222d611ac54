"""Who a request comes from, for the budgets that are kept per client over HTTP.

Two budgets are per client: event streams open at once (streams) and large bodies
waiting for the checking process (argument_process's fair turns). A client is the
token it presents when the server was given several (`--token` repeated: one per
client, the standard API-key arrangement), else the address it connects from. With a
single shared token every holder presents the same header, so the token cannot tell
them apart and the address is all there is; clients on one host then count as one,
which is why a server shared by local clients gives each its own token.

BearerTokenAuth, outermost, writes the matched token's number into the ASGI scope
(never the token itself); the inner layers only read it here.
"""

from __future__ import annotations

from starlette.types import Scope

CALLER_KEY = "verigraph.caller"


def caller_of(scope: Scope) -> str:
    """`token 2` (its own token, of several), else `address 127.0.0.1`."""
    named = scope.get(CALLER_KEY)
    if isinstance(named, str):
        return named
    peer = scope.get("client")
    return f"address {peer[0] if peer else 'unknown'}"
