"""Large tool calls cross the event loop as bytes, never as Python objects.

The MCP SDK parses each request body and walks each result several times (pydantic
validation and dumps, then `json.dumps`) on the event loop. For a 5,000-block plan
(0.5 MB in, a 1 MB report out) that is about 40 ms of loop time per call on an idle
machine, and no other client is answered meanwhile. Each of those steps is one C call
that holds the GIL from start to end, so moving them to a thread helps only so much.
LargeCalls moves them away:

* A request body above `threshold` bytes goes to a child process (argument_process: one
  for bodies up to 4 MiB and one for larger ones, each answering within a deadline, each
  taking bodies round-robin over callers, as told apart by access.caller_of), which
  parses it, takes a `tools/call`'s arguments out and validates them. The SDK gets the
  envelope with empty arguments (it still checks the protocol version, id, method, name
  and `_meta`) and the call (verigraph.server.tools, step 1) takes the validated input,
  or the argument error, from the request's CallSlot. Any other method has no business
  carrying that much and gets a JSON-RPC error saying so.
* A heavy call's structured result is serialised on its worker thread
  (`CallSlot.keep`); the SDK answers with a small placeholder, which `send` replaces
  with those bytes.

Only HTTP has other clients to be fair to; stdio serves one peer and keeps the SDK's
own path.
"""

from __future__ import annotations

import re
import secrets
from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from verigraph.server.http.access import caller_of, rpc_response
from verigraph.server.http.argument_process import ArgumentChecker
from verigraph.server.tools import SLOT_KEY

__all__ = ["DEFAULT_THRESHOLD_BYTES", "PLACEHOLDER_KEY", "CallSlot", "LargeCalls"]
DEFAULT_THRESHOLD_BYTES = 64 * 1024
# Results smaller than this are cheaper to hand to the SDK than to splice.
SPLICE_MIN_BYTES = 16 * 1024
PLACEHOLDER_KEY = "verigraph_offloaded"


@dataclass
class CallSlot:
    """What LargeCalls and the call hand each other for one HTTP request (under SLOT_KEY
    in the ASGI scope; verigraph.server.tools.LargeBodySlot)."""

    # A large body's arguments, taken out and checked (argument_process):
    params: BaseModel | None = None  # the tool's validated input, if they are valid
    error: str | None = None  # else what is wrong with them
    structured: bytes | None = None  # the result's structuredContent, serialised
    marker: str | None = None  # unguessable, so no client text can pass for the placeholder

    def keep(self, result: BaseModel) -> dict[str, Any] | None:
        """On a heavy call's worker thread: keep a large result as JSON bytes and return
        the placeholder the SDK sends instead (None: send it as is)."""
        data: bytes = result.model_dump_json().encode()
        if len(data) < SPLICE_MIN_BYTES:
            return None
        self.structured = data
        return self.placeholder()

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


class LargeCalls:
    """ASGI middleware (inside the body limit): large bodies are parsed and checked in a
    child process, large results serialised on worker threads; see the module docstring."""

    def __init__(self, app: ASGIApp, threshold: int = DEFAULT_THRESHOLD_BYTES,
                 checker: ArgumentChecker | None = None) -> None:
        self.app = app
        self.threshold = threshold
        self.checker = checker or ArgumentChecker()

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "lifespan":
            await self.app(scope, self._closing_on_shutdown(receive), send)
            return
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
            prepared = await self.checker.prepare(body, self.threshold, caller_of(scope))
            if prepared.refusal is not None:
                retry = {"Retry-After": "1"} if prepared.status == 503 else None
                reason = {"reason": prepared.reason} if prepared.reason else None
                await rpc_response(prepared.status, prepared.refusal, code=prepared.code,
                                request_id=prepared.request_id, data=reason,
                                headers=retry)(scope, receive, send)
                return
            body, slot.params, slot.error = prepared.envelope, prepared.params, prepared.error
        scope = {**scope, SLOT_KEY: slot}
        await self.app(scope, _replaying(body, receive), _splicing(slot, send))

    def _closing_on_shutdown(self, receive: Receive) -> Receive:
        async def watched() -> Message:
            message = await receive()
            if message["type"] == "lifespan.shutdown":
                self.checker.close()
            return message

        return watched


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

