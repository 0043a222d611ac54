"""The `openai` backend over real HTTP on loopback, against recorded responses.

`RecordedResponseServerForTests` replays canned chat-completions answers (well formed,
malformed, truncated, transient 503s), so every edge case is reproducible; the real
local model is exercised in test_planning_llm_local.py.
"""

from __future__ import annotations

import json
from typing import Any

import pytest
from planning_doubles import RecordedResponse as R
from planning_doubles import RecordedResponseServerForTests, chat_completion

from verigraph.agent import LoopConfig, run_episode
from verigraph.graph.builtin_scenes import cup_on_book, cup_on_book_goal
from verigraph.llm.http import JsonHttpClient, LLMEndpointError
from verigraph.planning import InProcessTools, PlannerRequest
from verigraph.planning.openai_backend import OpenAIConfig, OpenAIPlanner
from verigraph.tasks import EpisodeSpec

MOVE_CUP = {"action": "move", "object": "cup", "relation": "on", "target": "desk"}
MOVE_BOOK = {"action": "move", "object": "book", "relation": "on", "target": "shelf"}
DONE = {"action": "done"}


def answer(*actions: dict[str, Any]) -> dict[str, Any]:
    return chat_completion(json.dumps({"actions": list(actions)}))


def planner(url: str, **config: Any) -> OpenAIPlanner:
    cfg = OpenAIConfig(base_url=f"{url}/v1", model="recorded-model", api_key="sk-test",
                       **config)
    client = JsonHttpClient(cfg.base_url, headers={"Authorization": "Bearer sk-test"},
                            retries=cfg.retries, sleep=lambda s: None, timeout=10)
    return OpenAIPlanner(cfg, client=client)


def request(k: int | None = 3) -> PlannerRequest:
    return PlannerRequest(mode="iterative", iteration=1, graph=cup_on_book(),
                          goal=cup_on_book_goal(), k=k, prompt="PLAN THIS")


def test_valid_answer_and_the_request_that_was_sent() -> None:
    with RecordedResponseServerForTests([R(answer(MOVE_CUP, MOVE_BOOK, DONE))]) as server:
        reply = planner(server.url).propose(request())
    assert [a.text() for a in reply.actions] == [
        "move(cup, on, desk)", "move(book, on, shelf)", "done"]
    assert reply.error is None and reply.usage and reply.usage["total_tokens"] == 120
    sent = server.requests[0]
    assert sent.path == "/v1/chat/completions"
    assert sent.headers["authorization"] == "Bearer sk-test"
    body = sent.body
    assert body["model"] == "recorded-model"
    assert [m["role"] for m in body["messages"]] == ["user"]  # no system message
    assert body["messages"][0]["content"].startswith("PLAN THIS")
    fmt = body["response_format"]
    assert fmt["type"] == "json_schema" and fmt["json_schema"]["strict"] is True
    assert fmt["json_schema"]["schema"]["required"] == ["actions"]


@pytest.mark.parametrize(("kind", "expected"), [
    ("json_object_schema", {"type": "json_object"}),
    ("json_object", {"type": "json_object"}),
    ("none", None),
])
def test_response_format_dialects(kind: str, expected: dict[str, Any] | None) -> None:
    with RecordedResponseServerForTests([R(answer(DONE))]) as server:
        planner(server.url, response_format=kind).propose(request())
    fmt = server.requests[0].body.get("response_format")
    if expected is None:
        assert fmt is None
    else:
        assert fmt["type"] == expected["type"]
        assert ("schema" in fmt) == (kind == "json_object_schema")


@pytest.mark.parametrize(("content", "finish", "needle"), [
    ('{"actions": [{"action": "move", "object": "cup"', "stop", "not valid JSON"),
    ('{"actions": [{"action": "move", "object": "cup", "rel', "length", "cut off"),
    ("Sure! First I would lift the cup.", "stop", "could not read the answer"),
    ('{"actions": [{"action": "move", "object": "cup", "relation": "on"}]}', "stop",
     "actions[0].target"),
    ("", "stop", "empty"),
])
def test_malformed_and_truncated_outputs_become_errors_not_exceptions(
        content: str, finish: str, needle: str) -> None:
    with RecordedResponseServerForTests([R(chat_completion(content, finish))]) as server:
        reply = planner(server.url).propose(request())
    assert reply.actions == [] and reply.error is not None and needle in reply.error
    assert reply.raw == content


def test_answer_without_choices_is_feedback() -> None:
    with RecordedResponseServerForTests([R({"object": "chat.completion"})]) as server:
        reply = planner(server.url).propose(request())
    assert reply.error is not None and "choices" in reply.error


def test_transient_errors_are_retried_with_backoff() -> None:
    responses = [R({"error": {"message": "overloaded"}}, status=503),
                 R({"error": {"message": "slow down"}}, status=429,
                   headers={"retry-after": "0"}),
                 R("<html>bad gateway</html>", status=502),
                 R(answer(DONE))]
    with RecordedResponseServerForTests(responses) as server:
        p = planner(server.url, retries=4)
        reply = p.propose(request())
    assert reply.actions and reply.actions[0].text() == "done"
    assert len(server.requests) == 4 and p.client.attempts == 4


def test_retries_run_out_with_an_error_naming_the_endpoint() -> None:
    with RecordedResponseServerForTests([R({"error": "down"}, status=503)] * 3) as server, \
            pytest.raises(LLMEndpointError, match="failed after 3 attempt") as info:
        planner(server.url, retries=2).propose(request())
    assert "chat/completions" in str(info.value) and "HTTP 503" in str(info.value)


def test_client_errors_fail_fast_without_retrying() -> None:
    bad = R({"error": {"message": "Unrecognized request argument: json_schema"}}, status=400)
    with RecordedResponseServerForTests([bad, R(answer(DONE))]) as server:
        with pytest.raises(LLMEndpointError, match="HTTP 400: Unrecognized") as info:
            planner(server.url, retries=4).propose(request())
        assert len(server.requests) == 1
    assert info.value.fix and "--response-format" in info.value.fix


def test_unreachable_endpoint_is_a_clear_error() -> None:
    client = JsonHttpClient("http://127.0.0.1:9/v1", retries=1, sleep=lambda s: None)
    with pytest.raises(LLMEndpointError, match="ConnectError"):
        client.post("chat/completions", {})


def test_config_from_env_and_missing_model(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_BASE_URL", "http://127.0.0.1:1234/v1")
    monkeypatch.setenv("OPENAI_MODEL", "env-model")
    monkeypatch.setenv("OPENAI_API_KEY", "sk-env")
    cfg = OpenAIConfig.from_env(model=None, temperature=None)
    assert (cfg.base_url, cfg.model, cfg.api_key) == ("http://127.0.0.1:1234/v1",
                                                     "env-model", "sk-env")
    assert "sk-env" not in repr(cfg)
    monkeypatch.delenv("OPENAI_MODEL")
    with pytest.raises(Exception, match="OPENAI_MODEL"):
        OpenAIConfig.from_env()


def test_loop_with_the_openai_backend_turns_bad_output_into_feedback() -> None:
    """Malformed, then invalid, then a correct plan: the loop recovers through feedback."""
    responses = [R(chat_completion("not json at all, sorry")),
                 R(answer({"action": "move", "object": "book", "relation": "on",
                           "target": "shelf"})),
                 R(answer(MOVE_CUP, MOVE_BOOK, DONE))]
    with RecordedResponseServerForTests(responses) as server:
        p = planner(server.url)
        trace = run_episode(InProcessTools(), p, EpisodeSpec(load={"scene_id": "cup_on_book"}),
                            LoopConfig(k=3, threshold=3))
    assert [r.verdict for r in trace.iterations] == ["malformed", "violation", "end_token"]
    assert trace.success and trace.llm_calls == 3
    second_prompt = server.requests[1].body["messages"][0]["content"]
    assert "could not read the answer" in second_prompt
    third_prompt = server.requests[2].body["messages"][0]["content"]
    assert "object_not_clear" in third_prompt
