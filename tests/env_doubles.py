"""A loopback OpenAI-compatible endpoint that answers as a project planner would.

A test stand-in, named as such, for a model server that cannot run in the normal suite:
it speaks the real chat-completions protocol over a real socket, and its answers come
from running a policy (verigraph.env.rollout, e.g. the oracle planner) on the same
tasks beforehand. The answer to a request is looked up by the newest observation in
it (the first prompt or the last tool result), so it works for tool-calling clients
(it answers with a call of the first tool offered) and for text-only ones alike, in any
order. A request with `"stream": true` gets the same answer as server-sent chunks
(`chat.completion.chunk` events, a usage chunk, `[DONE]`), as clients that stream
(verifiers' model proxy) read it. An observation it was not scripted for gets HTTP 500
saying so, so a test that drifts fails loudly instead of hanging.
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from typing import Any

from planning_doubles import (
    ReceivedRequest,
    RecordedResponse,
    RecordedResponseServerForTests,
)

from verigraph.env.core import VeriGraphEnv
from verigraph.env.rollout import Policy, RolloutJob, run_rollout


def script_from_policy(env: VeriGraphEnv, policy: Policy, task_ids: Iterable[str],
                       seed: int = 0) -> dict[str, str]:
    """observation -> the policy's answer, over whole episodes of the given tasks."""
    script: dict[str, str] = {}
    for task_id in task_ids:
        result = run_rollout(env, policy, RolloutJob(task_id=task_id, seed=seed))
        for line in result.lines[1:]:
            script[line.observation] = line.action or ""
    return script


def _completion(answer: str, tool: str | None, turn: int) -> dict[str, Any]:
    message: dict[str, Any] = {"role": "assistant", "content": answer if tool is None else None}
    finish = "stop"
    if tool is not None:
        finish = "tool_calls"
        message["tool_calls"] = [{"id": f"call_{turn}", "type": "function", "function": {
            "name": tool, "arguments": json.dumps({"actions": answer})}}]
    return {"id": f"chatcmpl-scripted-{turn}", "object": "chat.completion",
            "model": "scripted-planner", "created": 0,
            "choices": [{"index": 0, "finish_reason": finish, "message": message}],
            "usage": {"prompt_tokens": 0, "completion_tokens": 0, "total_tokens": 0}}


def _stream(completion: dict[str, Any]) -> str:
    """A chat completion as the server-sent events of a streamed one."""
    choice = completion["choices"][0]
    message = choice["message"]
    delta: dict[str, Any] = {"role": "assistant", "content": message.get("content")}
    if message.get("tool_calls"):
        delta["tool_calls"] = [{**call, "index": i}
                               for i, call in enumerate(message["tool_calls"])]
    head = {k: completion[k] for k in ("id", "model", "created")}
    chunks = [{**head, "object": "chat.completion.chunk",
               "choices": [{"index": 0, "delta": delta, "finish_reason": None}]},
              {**head, "object": "chat.completion.chunk",
               "choices": [{"index": 0, "delta": {}, "finish_reason": choice["finish_reason"]}]},
              {**head, "object": "chat.completion.chunk", "choices": [],
               "usage": completion["usage"]}]
    return "".join(f"data: {json.dumps(c)}\n\n" for c in chunks) + "data: [DONE]\n\n"


def _text(content: Any) -> str:
    """A message's text: a string, or the text parts of a list of content parts."""
    if isinstance(content, str):
        return content
    if isinstance(content, list):
        return "".join(p.get("text", "") for p in content
                       if isinstance(p, dict) and p.get("type") == "text")
    return ""


class ScriptedPlannerEndpointForTests(RecordedResponseServerForTests):
    """Serves `script` (observation -> answer) as /v1/chat/completions on 127.0.0.1.

    The HTTP side is `RecordedResponseServerForTests` (tests/planning_doubles.py); only
    the choice of answer differs: looked up in the script, not taken from a queue.
    `requests` keeps every request received (its `body` is the chat request).
    """

    def __init__(self, script: dict[str, str]) -> None:
        super().__init__()
        self.script = dict(script)

    def reply(self, request: ReceivedRequest) -> RecordedResponse:
        with self._lock:
            self.requests.append(request)
            turn = len(self.requests)
        body: dict[str, Any] = request.body if isinstance(request.body, dict) else {}
        messages = body.get("messages") or []
        latest: dict[str, Any] = next(
            (m for m in reversed(messages) if m.get("role") in ("user", "tool")), {})
        text = _text(latest.get("content"))
        if text not in self.script:
            return RecordedResponse({"error": {"message": "no scripted answer for this "
                                               f"observation (starts {text[:80]!r})"}},
                                    status=500)
        tools = body.get("tools") or []
        tool = tools[0]["function"]["name"] if tools else None
        completion = _completion(self.script[text], tool, turn)
        if body.get("stream"):
            return RecordedResponse(_stream(completion),
                                    headers={"content-type": "text/event-stream"})
        return RecordedResponse(completion)

    @property
    def base_url(self) -> str:
        return f"{self.url}/v1"
