"""Large tool calls cross the event loop as bytes, never as Python objects.

The MCP SDK parses each request body and walks each result several times (pydantic
validation and dumps, then `json.dumps`) on the event loop. For a 5,000-block plan
(0.5 MB in, a 1 MB report out) that is about 40 ms of loop time per call on an idle
machine, and no other client is answered meanwhile. Each of those steps is one C call
that holds the GIL from start to end, so moving the tool alone to a thread does not
help. LargeCalls moves them off the loop:

* A request body above `threshold` bytes is parsed on a worker thread. A `tools/call`
  keeps its `arguments` in the request's CallSlot and the SDK gets the envelope with
  empty arguments: it still checks the protocol version, id, method, name and `_meta`
  as usual, and ArgumentGate takes the arguments from the slot. Any other method has
  no business carrying that much and gets a JSON-RPC error saying so; a body that is
  not JSON reaches the SDK as a one-byte stand-in, so the SDK answers its usual parse
  error without parsing megabytes on the loop.
* A heavy call's structured result is serialised on its worker thread (`offload`);
  the SDK answers with a small placeholder, which `send` replaces with those bytes.

Only HTTP has other clients to be fair to; stdio serves one peer and keeps the SDK's
own path.
"""

from __future__ import annotations

import json
import re
import secrets
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import Any

import anyio
import anyio.to_thread
from starlette.responses import Response
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from verigraph.server.rpc_errors import rpc_error

SCOPE_KEY = "verigraph.call_slot"
PLACEHOLDER_KEY = "verigraph_offloaded"
DEFAULT_THRESHOLD_BYTES = 64 * 1024
# Results smaller than this are cheaper to hand to the SDK than to splice.
SPLICE_MIN_BYTES = 16 * 1024


@dataclass
class CallSlot:
    """What LargeCalls and ArgumentGate hand each other for one HTTP request."""

    arguments: dict[str, Any] | None = None  # parsed off the loop, taken out of the body
    structured: bytes | None = None  # the result's structuredContent, serialised
    marker: str = field(default_factory=lambda: secrets.token_hex(16))

    def placeholder(self) -> dict[str, str]:
        return {PLACEHOLDER_KEY: self.marker}

    def splice(self, body: bytes) -> bytes | None:
        """`body` with the placeholder replaced by the serialised result, or None if the
        SDK's answer does not hold the placeholder (it answered an error instead)."""
        if self.structured is None:
            return None
        pattern = (rb'\{\s*"' + PLACEHOLDER_KEY.encode() + rb'"\s*:\s*"'
                   + self.marker.encode() + rb'"\s*\}')
        found = re.search(pattern, body)
        if found is None:
            return None
        return body[:found.start()] + self.structured + body[found.end():]


# The slot of the tools/call being handled, for `offload` on the call's worker thread.
CURRENT_SLOT: ContextVar[CallSlot | None] = ContextVar("verigraph_call_slot", default=None)


def slot_of(request: Any) -> CallSlot | None:
    """The CallSlot LargeCalls gave this HTTP request (None over stdio)."""
    scope = getattr(request, "scope", None)
    slot = scope.get(SCOPE_KEY) if isinstance(scope, dict) else None
    return slot if isinstance(slot, CallSlot) else None


def offload(structured: Any) -> dict[str, Any] | None:
    """On a heavy call's worker thread: keep a large pydantic result as JSON bytes in the
    current slot and return the placeholder the SDK sends instead (None: send it as is)."""
    slot = CURRENT_SLOT.get()
    if slot is None:
        return None
    data: bytes = structured.model_dump_json().encode()
    if len(data) < SPLICE_MIN_BYTES:
        return None
    slot.structured = data
    return slot.placeholder()


def _refusal(message: Any, size: int) -> Response:
    method = message.get("method") if isinstance(message, dict) else None
    request_id = message.get("id") if isinstance(message, dict) else None
    what = repr(method) if isinstance(method, str) else "a message that is no single request"
    return rpc_error(413, f"Request too large for {what} ({size} bytes): only tools/call "
                          "arguments may be this large; send a smaller request",
                     request_id=request_id if isinstance(request_id, str | int) else None)


def _split(body: bytes, threshold: int) -> tuple[bytes, dict[str, Any] | None] | Response:
    """(body for the SDK, the tools/call arguments taken out), or the refusal.

    Runs on a worker thread: parsing is the expensive part."""
    try:
        message = json.loads(body)
    except (ValueError, RecursionError):
        return b"{", None  # the SDK answers its parse error without the cost
    params = message.get("params") if isinstance(message, dict) else None
    if isinstance(params, dict) and message.get("method") == "tools/call" \
            and isinstance(params.get("arguments"), dict):
        envelope = json.dumps({**message, "params": {**params, "arguments": {}}}).encode()
        if len(envelope) <= threshold:
            return envelope, params["arguments"]
    return _refusal(message, len(body))


class LargeCalls:
    """ASGI middleware (inside the body limit): large bodies are parsed, and large results
    serialised, on worker threads; see the module docstring."""

    def __init__(self, app: ASGIApp, threshold: int = DEFAULT_THRESHOLD_BYTES,
                 parsers: int = 2) -> None:
        self.app = app
        self.threshold = threshold
        self._parsers = anyio.CapacityLimiter(parsers)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope["method"] != "POST":
            await self.app(scope, receive, send)
            return
        chunks: list[bytes] = []
        while True:  # the body limit has read it already: this only collects the chunks
            message = await receive()
            if message["type"] != "http.request":
                return
            chunks.append(message.get("body", b""))
            if not message.get("more_body", False):
                break
        body = b"".join(chunks)
        slot = CallSlot()
        if len(body) > self.threshold:
            split = await anyio.to_thread.run_sync(_split, body, self.threshold,
                                                   limiter=self._parsers)
            if isinstance(split, Response):
                await split(scope, receive, send)
                return
            body, slot.arguments = split
        scope = {**scope, SCOPE_KEY: slot}
        await self.app(scope, _replaying(body, receive), _splicing(slot, send))


def _replaying(body: bytes, receive: Receive) -> Receive:
    sent = False

    async def replay() -> Message:
        nonlocal sent
        if not sent:
            sent = True
            return {"type": "http.request", "body": body, "more_body": False}
        return await receive()

    return replay


def _splicing(slot: CallSlot, send: Send) -> Send:
    """`send` that puts the slot's serialised result into the SDK's answer. The result is
    in the slot before the SDK starts its answer, so other answers pass straight on."""
    held: Message | None = None

    async def spliced(message: Message) -> None:
        nonlocal held
        if message["type"] == "http.response.start" and slot.structured is not None:
            held = message  # its content-length changes with the body
            return
        if held is not None and message["type"] == "http.response.body":
            start, held = held, None
            body = message.get("body", b"")
            joined = None if message.get("more_body") else slot.splice(body)
            if joined is not None:
                headers = [(k, v) for k, v in start.get("headers", [])
                           if k.lower() != b"content-length"]
                headers.append((b"content-length", str(len(joined)).encode()))
                start = {**start, "headers": headers}
                message = {**message, "body": joined}
            await send(start)
        await send(message)

    return spliced

