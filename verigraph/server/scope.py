"""What one tool call carries along its path: who calls, its large body's slot, its input.

A tools/call passes through middleware, the SDK, resolvers, the tool body and worker
threads; each needs a little of the call's context (the heavy-call queue the client's
share, the arm's audit log the MCP client, the splice the large-body slot, the
confirmation resolvers the validated input). ArgumentGate puts all of it in one
CallScope at the start of the call, held by one ContextVar, which anyio copies into
the call's worker threads. Outside a tools/call (stdio's peer, a test driving a tool
directly) the scope is that of the stdio peer.
"""

from __future__ import annotations

import re
import secrets
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

from pydantic import BaseModel

PLACEHOLDER_KEY = "verigraph_offloaded"


@dataclass
class CallSlot:
    """What LargeCalls and ArgumentGate hand each other for one HTTP request (offload)."""

    # A large body's arguments, taken out and checked (argument_process):
    params: BaseModel | None = None  # the tool's validated input, if they are valid
    error: str | None = None  # else what is wrong with them
    structured: bytes | None = None  # the result's structuredContent, serialised
    marker: str | None = None  # unguessable, so no client text can pass for the placeholder

    def placeholder(self) -> dict[str, str]:
        if self.marker is None:
            self.marker = secrets.token_hex(16)
        return {PLACEHOLDER_KEY: self.marker}

    def splice(self, body: bytes) -> bytes | None:
        """`body` with the placeholder replaced by the serialised result, or None if the
        SDK's answer does not hold the placeholder (it answered an error instead)."""
        if self.structured is None or self.marker is None:
            return None
        pattern = (rb'\{\s*"' + PLACEHOLDER_KEY.encode() + rb'"\s*:\s*"'
                   + self.marker.encode() + rb'"\s*\}')
        found = re.search(pattern, body)
        if found is None:
            return None
        return body[:found.start()] + self.structured + body[found.end():]


@dataclass
class CallScope:
    """One tool call's context (see the module docstring)."""

    connection: str = "stdio"  # "host:port" of the HTTP connection: its heavy-call share
    client: str | None = None  # the MCP client's label, for the arm's audit log
    slot: CallSlot | None = None  # the large-body slot of an HTTP request
    tool: str | None = None  # the tool being called ...
    params: BaseModel | None = None  # ... and the input ArgumentGate validated for it

    def params_for(self, tool: str) -> BaseModel | None:
        """The validated input if this call is of `tool` (resolvers ask by name)."""
        return self.params if self.tool == tool else None


_STDIO = CallScope()
_SCOPE: ContextVar[CallScope | None] = ContextVar("verigraph_call_scope", default=None)


def current_scope() -> CallScope:
    """The scope of the tool call being handled (the stdio peer's outside one)."""
    return _SCOPE.get() or _STDIO


@contextmanager
def call_scope(scope: CallScope) -> Iterator[CallScope]:
    """Make `scope` the current call's for the block."""
    token = _SCOPE.set(scope)
    try:
        yield scope
    finally:
        _SCOPE.reset(token)
