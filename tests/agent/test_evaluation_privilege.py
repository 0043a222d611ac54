"""Privilege by construction: only a planner that declares itself privileged (the
oracle) is handed the ground-truth goal; the others cannot read it on language tasks."""

from __future__ import annotations

import json
from typing import Any

import pytest
from planning_doubles import RecordedResponse as R
from planning_doubles import (
    RecordedResponseServerForTests,
    anthropic_tool_use,
    chat_completion,
)

from verigraph.agent import LoopConfig, run_episode
from verigraph.agent.evaluation.guard import GuardedPlanner, RetryPolicy
from verigraph.agent.transcripts import RecordingPlanner
from verigraph.jobs.limiter import Gate
from verigraph.planning import InProcessTools
from verigraph.planning.factory import PlannerOptions, make_planner
from verigraph.planning.models import PlannerReply, PlannerRequest
from verigraph.planning.planner import Planner, is_privileged
from verigraph.tasks import build_groups

pytest.importorskip("verigraph.sim2d.generator", reason="sim2d not installed")

DONE = [{"action": "done"}]


class RequestSpy:
    """Keeps every request the episode sends to `inner` (declares what `inner` declares)."""

    def __init__(self, inner: Planner) -> None:
        self.inner = inner
        self.name = inner.name
        self.privileged = is_privileged(inner)
        self.requests: list[PlannerRequest] = []

    def propose(self, request: PlannerRequest) -> PlannerReply:
        self.requests.append(request)
        return self.inner.propose(request)

    def close(self) -> None:
        self.inner.close()


@pytest.fixture(scope="module")
def language_tasks() -> list[Any]:
    return build_groups(("language",), 3, 0, ground_truth=True)[0].tasks


def _run(planner: Planner, task: Any) -> tuple[RequestSpy, bool]:
    spy = RequestSpy(planner)
    trace = run_episode(InProcessTools(), spy, task.spec, LoopConfig(max_iterations=4))
    assert spy.requests, "the planner was never asked"
    return spy, trace.success


@pytest.mark.parametrize("name", ["greedy", "noisy", "rule-based"])
def test_offline_planners_receive_no_goal_graph_on_language_tasks(
        name: str, language_tasks: list[Any]) -> None:
    for task in language_tasks:
        spy, _ = _run(make_planner(name, PlannerOptions(seed=1)), task)
        assert not is_privileged(spy.inner)
        for request in spy.requests:
            assert request.privileged_goal is None
            assert request.goal is None  # a language task shows only its words
            assert request.instruction == task.instruction


def test_llm_planners_receive_no_goal_graph_on_language_tasks(
        language_tasks: list[Any]) -> None:
    task = language_tasks[0]
    with RecordedResponseServerForTests([R(chat_completion(json.dumps({"actions": DONE})))]
                                        ) as server:
        openai = make_planner("openai", PlannerOptions(base_url=f"{server.url}/v1",
                                                       model="recorded", api_key="sk-test"))
        spy, _ = _run(openai, task)
    with RecordedResponseServerForTests([R(anthropic_tool_use(DONE))]) as server:
        anthropic = make_planner("anthropic", PlannerOptions(base_url=server.url,
                                                             model="recorded", api_key="k"))
        spy_a, _ = _run(anthropic, task)
    truth = task.goal
    assert truth is not None and truth.graph is not None
    for request in [*spy.requests, *spy_a.requests]:
        assert request.privileged_goal is None and request.goal is None
        assert "Goal graph" not in request.prompt


def test_only_the_declared_oracle_gets_the_true_goal_through_every_wrapper(
        language_tasks: list[Any], tmp_path: Any) -> None:
    oracle = make_planner("oracle")
    assert is_privileged(oracle)
    wrapped = GuardedPlanner(RecordingPlanner(oracle, tmp_path, "t"), Gate(None), RetryPolicy())
    assert is_privileged(wrapped)
    for task in language_tasks:
        spy, success = _run(wrapped, task)
        assert success  # the ceiling solves every task with the goal it was handed
        assert all(r.privileged_goal is not None and r.goal is None for r in spy.requests)
