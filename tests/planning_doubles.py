"""A loopback HTTP server that replays recorded responses, for testing LLM backends.

This is a test fake, named as such: it stands in for endpoints that cannot run here
(paid APIs) or for answers a real model gives only rarely (malformed, truncated,
HTTP 503). The backends under test still do real HTTP over a real socket; only the
far end is a recording. Every request is kept so tests can check what was sent.
"""

from __future__ import annotations

import json
import threading
from collections import deque
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any


@dataclass
class RecordedResponse:
    """One canned answer: status, a JSON body (or raw text), extra headers."""

    body: Any
    status: int = 200
    headers: dict[str, str] = field(default_factory=dict)
    delay_s: float = 0.0


@dataclass
class ReceivedRequest:
    path: str
    headers: dict[str, str]
    body: Any


class RecordedResponseServerForTests:
    """Serves queued RecordedResponses in order on 127.0.0.1; use as a context manager.

    When the queue is empty it answers HTTP 500 with a body saying so, so a test that
    expected fewer calls fails loudly instead of hanging.
    """

    def __init__(self, responses: list[RecordedResponse] | None = None) -> None:
        self.responses: deque[RecordedResponse] = deque(responses or [])
        self.requests: list[ReceivedRequest] = []
        self._lock = threading.Lock()
        server = self

        class Handler(BaseHTTPRequestHandler):
            def do_POST(self) -> None:  # noqa: N802 (http.server's naming)
                length = int(self.headers.get("content-length") or 0)
                raw = self.rfile.read(length).decode("utf-8") if length else ""
                try:
                    body: Any = json.loads(raw) if raw else None
                except json.JSONDecodeError:
                    body = raw
                reply = server.reply(ReceivedRequest(
                    self.path, {k.lower(): v for k, v in self.headers.items()}, body))
                if reply.delay_s:
                    threading.Event().wait(reply.delay_s)
                payload = reply.body if isinstance(reply.body, str) else json.dumps(reply.body)
                data = payload.encode("utf-8")
                self.send_response(reply.status)
                headers = {"content-type": "application/json", **reply.headers}
                self.send_header("content-length", str(len(data)))
                for key, value in headers.items():
                    self.send_header(key, value)
                self.end_headers()
                self.wfile.write(data)

            def log_message(self, format: str, *args: Any) -> None:
                return None

        self._server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self._thread = threading.Thread(target=self._server.serve_forever,
                                        kwargs={"poll_interval": 0.05}, daemon=True)

    def reply(self, request: ReceivedRequest) -> RecordedResponse:
        """Keep `request` and answer it: the next queued response (a subclass may pick
        its answer from the request instead, keeping this server's HTTP side)."""
        with self._lock:
            self.requests.append(request)
            if self.responses:
                return self.responses.popleft()
        return RecordedResponse({"error": {"message": "no recorded response left"}},
                                status=500)

    @property
    def url(self) -> str:
        host, port = self._server.server_address[:2]
        return f"http://{host!s}:{port}"

    def add(self, *responses: RecordedResponse) -> None:
        with self._lock:
            self.responses.extend(responses)

    def __enter__(self) -> RecordedResponseServerForTests:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._server.shutdown()
        self._server.server_close()
        self._thread.join(timeout=5)


def chat_completion(content: str, finish_reason: str = "stop") -> dict[str, Any]:
    """A recorded OpenAI chat-completions body with one choice."""
    return {"id": "chatcmpl-recorded", "object": "chat.completion", "model": "recorded",
            "choices": [{"index": 0, "finish_reason": finish_reason,
                         "message": {"role": "assistant", "content": content}}],
            "usage": {"prompt_tokens": 100, "completion_tokens": 20, "total_tokens": 120}}


def anthropic_tool_use(actions: list[dict[str, Any]] | Any, stop_reason: str = "tool_use",
                       tool_name: str = "propose_actions") -> dict[str, Any]:
    """A recorded Messages API body whose content is one tool_use block."""
    return {"id": "msg_recorded", "type": "message", "role": "assistant", "model": "recorded",
            "stop_reason": stop_reason,
            "content": [{"type": "tool_use", "id": "toolu_recorded", "name": tool_name,
                         "input": {"actions": actions} if isinstance(actions, list)
                         else actions}],
            "usage": {"input_tokens": 100, "output_tokens": 20}}


class ScriptedPlannerForTests:
    """A planner that replays fixed replies (a test double for an LLM, named as such).

    Each item is a list of actions, a `PlannerReply`, or an exception to raise; when the
    script runs out the last item repeats, so "always invalid" is a one-item script.
    Every request is kept for assertions (what k, feedback and prompt the loop sent).
    """

    name = "scripted"

    def __init__(self, script: list[Any]) -> None:
        if not script:
            raise ValueError("the script needs at least one reply")
        self.script = list(script)
        self.requests: list[Any] = []
        self.closed = False

    def propose(self, request: Any) -> Any:
        from verigraph.actions.model import ActionAdapter
        from verigraph.planning.models import PlannerReply

        self.requests.append(request)
        item = self.script[min(len(self.requests), len(self.script)) - 1]
        if isinstance(item, BaseException):
            raise item
        if isinstance(item, PlannerReply):
            return item
        return PlannerReply(actions=[ActionAdapter.validate_python(a) if isinstance(a, dict)
                                     else _parse_one(a) for a in item])

    def close(self) -> None:
        self.closed = True


def _parse_one(text: str) -> Any:
    from verigraph.actions.parser import parse_action_text

    return parse_action_text(text)
