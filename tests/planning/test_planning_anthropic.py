"""The `anthropic` backend (Messages API, forced tool use) against recorded responses.

The Anthropic API cannot be reached here, so `RecordedResponseServerForTests` replays
Messages API bodies over real loopback HTTP.
"""

from __future__ import annotations

from typing import Any

import pytest
from planning_doubles import RecordedResponse as R
from planning_doubles import RecordedResponseServerForTests, anthropic_tool_use

from verigraph.agent import LoopConfig, run_episode
from verigraph.graph.builtin_scenes import three_blocks
from verigraph.graph.goal import Goal
from verigraph.llm.http import JsonHttpClient
from verigraph.planning import InProcessTools, PlannerRequest
from verigraph.planning.anthropic_backend import TOOL_NAME, AnthropicConfig, AnthropicPlanner
from verigraph.tasks import EpisodeSpec

STACK = [{"action": "move", "object": "green_block", "relation": "on", "target": "red_block"},
         {"action": "done"}]


def planner(url: str) -> AnthropicPlanner:
    cfg = AnthropicConfig(base_url=url, model="claude-recorded", api_key="sk-ant-test")
    headers = {"x-api-key": "sk-ant-test", "anthropic-version": "2023-06-01"}
    return AnthropicPlanner(cfg, client=JsonHttpClient(url, headers=headers,
                                                       sleep=lambda s: None, timeout=10))


def request() -> PlannerRequest:
    return PlannerRequest(mode="iterative", iteration=1, graph=three_blocks(),
                          goal=Goal(predicate="single_stack"), k=2, prompt="STACK THEM")


def test_tool_use_answer_and_the_request_that_was_sent() -> None:
    with RecordedResponseServerForTests([R(anthropic_tool_use(STACK))]) as server:
        reply = planner(server.url).propose(request())
    assert [a.text() for a in reply.actions] == ["move(green_block, on, red_block)", "done"]
    sent = server.requests[0]
    assert sent.path == "/v1/messages"
    assert sent.headers["x-api-key"] == "sk-ant-test"
    assert sent.headers["anthropic-version"] == "2023-06-01"
    body: dict[str, Any] = sent.body
    assert body["tool_choice"] == {"type": "tool", "name": TOOL_NAME}
    tool = body["tools"][0]
    assert tool["name"] == TOOL_NAME and "at most 2 actions" in tool["description"]
    move = tool["input_schema"]["properties"]["actions"]["items"]["anyOf"][0]
    assert "green_block" in move["properties"]["object"]["enum"]
    assert body["messages"][0]["content"].startswith("STACK THEM")


def test_text_instead_of_tool_use_is_parsed_or_reported() -> None:
    text_plan = {"type": "message", "stop_reason": "end_turn",
                 "content": [{"type": "text", "text": "move(green_block, red_block)\ndone"}]}
    chatter = {"type": "message", "stop_reason": "end_turn",
               "content": [{"type": "text", "text": "I would stack them nicely."}]}
    with RecordedResponseServerForTests([R(text_plan), R(chatter)]) as server:
        p = planner(server.url)
        readable = p.propose(request())
        unreadable = p.propose(request())
    assert [a.text() for a in readable.actions] == ["move(green_block, on, red_block)", "done"]
    assert unreadable.error is not None and f"no {TOOL_NAME} tool call" in unreadable.error


def test_bad_tool_input_and_truncation_become_errors() -> None:
    bad = anthropic_tool_use([{"action": "move", "object": "green_block"}])
    cut = anthropic_tool_use([{"action": "move"}], stop_reason="max_tokens")
    with RecordedResponseServerForTests([R(bad), R(cut)]) as server:
        p = planner(server.url)
        r1, r2 = p.propose(request()), p.propose(request())
    assert r1.error is not None and "actions[0]" in r1.error
    assert r2.error is not None and "cut off by the token limit" in r2.error


def test_overloaded_529_is_retried() -> None:
    responses = [R({"type": "error", "error": {"type": "overloaded_error",
                                                "message": "Overloaded"}}, status=529),
                 R(anthropic_tool_use(STACK))]
    with RecordedResponseServerForTests(responses) as server:
        reply = planner(server.url).propose(request())
    assert reply.error is None and len(server.requests) == 2


def test_missing_model_names_the_variable(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ANTHROPIC_MODEL", raising=False)
    with pytest.raises(Exception, match="ANTHROPIC_MODEL"):
        AnthropicConfig.from_env()


def test_loop_with_the_anthropic_backend() -> None:
    wrong = anthropic_tool_use([{"action": "move", "object": "blue_block", "relation": "on",
                                 "target": "green_block"}])
    with RecordedResponseServerForTests([R(wrong), R(anthropic_tool_use(STACK))]) as server:
        trace = run_episode(InProcessTools(), planner(server.url),
                            EpisodeSpec(load={"scene_id": "three_blocks"}),
                            LoopConfig(k=2, threshold=3))
    assert [r.verdict for r in trace.iterations] == ["violation", "end_token"]
    assert trace.success
    assert "object_not_clear" in server.requests[1].body["messages"][0]["content"]
