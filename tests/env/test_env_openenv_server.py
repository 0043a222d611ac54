"""The environment's OpenEnv server on loopback: a bearer token, a session per client with
idle expiry (OpenEnv's own session limits), and 4xx answers on stateless HTTP."""

from __future__ import annotations

import time
from typing import Any

import httpx
import pytest
from websockets.exceptions import ConnectionClosed

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")
require("openenv", "pip install 'verigraph-mcp[env]'")

from mcp_helpers import free_port  # noqa: E402
from openenv.core.generic_client import GenericEnvClient  # noqa: E402
from openenv_helpers import serving  # noqa: E402

from verigraph.env import build_tasks, split_tasks  # noqa: E402
from verigraph.env.openenv_server import (  # noqa: E402
    DEFAULT_MAX_SESSIONS,
    RemoteSessionFactory,
    TokenEnvClient,
    create_openenv_app,
    serve_openenv,
)
from verigraph.env.rollout import REFUSED_ACTION  # noqa: E402
from verigraph.errors import VeriGraphError  # noqa: E402

TASKS = split_tasks(build_tasks("blocks", 6), "test")
CREATE = {"jsonrpc": "2.0", "id": 1, "method": "openenv/session/create", "params": {}}


def test_a_token_guards_http_websocket_and_mcp_sessions() -> None:
    with serving(TASKS, token="s3cret") as url:
        for headers, reason in (({}, "missing_token"),
                                ({"Authorization": "Bearer wrong"}, "wrong_token"),
                                ({"Authorization": "s3cret"}, "wrong_token")):
            for answer in (httpx.post(f"{url}/reset", json={}, headers=headers),
                           httpx.post(f"{url}/mcp", json=CREATE, headers=headers),
                           httpx.get(f"{url}/state", headers=headers)):
                assert answer.status_code == 403
                assert answer.json()["detail"]["reason"] == reason
                assert "Authorization: Bearer" in answer.json()["detail"]["fix"]
        assert httpx.get(f"{url}/health").status_code == 200  # says only "healthy"
        for refused in (GenericEnvClient(base_url=url), TokenEnvClient(url, "wrong")):
            with pytest.raises(ConnectionError, match="403"):
                refused.sync().connect()
        with TokenEnvClient(url, "s3cret").sync() as client:
            first = client.reset(task=TASKS[0].task_id)
            assert first.observation["task_id"] == TASKS[0].task_id
            assert client.step({"actions": REFUSED_ACTION}).observation["verdict"] == \
                "violation"
        session = RemoteSessionFactory(url, token="s3cret").create(TASKS[1].task_id)
        try:
            assert "## Goal" in str(session.initial_messages()[-1]["content"])
            result = session.call_tool("act", {"actions": REFUSED_ACTION})
            assert result.metadata["verdict"] == "violation"
        finally:
            session.close()
        ok = httpx.post(f"{url}/reset", json={"task": TASKS[0].task_id},
                        headers={"Authorization": "Bearer s3cret"})
        assert ok.status_code == 200 and "## Goal" in ok.json()["observation"]["prompt"]
    with serving(TASKS, token=["one", "two"]) as url:  # any of several tokens admits
        for token in ("one", "two"):
            assert httpx.post(f"{url}/reset", json={},
                              headers={"Authorization": f"Bearer {token}"}).status_code == 200


def test_every_client_has_its_own_session_and_an_anonymous_mcp_session_blocks_no_one(
        ) -> None:
    assert DEFAULT_MAX_SESSIONS >= 16
    with serving(TASKS) as url:
        held = httpx.post(f"{url}/mcp", json=CREATE).json()
        assert "session_id" in held["result"]  # an MCP session that is never used again
        with GenericEnvClient(base_url=url).sync() as one, \
                GenericEnvClient(base_url=url).sync() as two:
            a = one.reset(task=TASKS[0].task_id)
            b = two.reset(task=TASKS[1].task_id)
            assert a.observation["task_id"] != b.observation["task_id"]
            one.step({"actions": REFUSED_ACTION})
            # each session is its own environment: the second one's counters are its own
            assert one.state()["step_count"] == 1 and two.state()["step_count"] == 0
            assert two.state()["task_id"] == TASKS[1].task_id


def test_an_idle_session_expires_and_frees_its_slot() -> None:
    # one slot, so the expiry is what lets the next client in; OpenEnv's reaper looks
    # every max(timeout / 4, 5 s)
    with serving(TASKS, max_sessions=1, session_timeout=1.0) as url:
        holder = TokenEnvClient(url).sync()
        holder.connect()
        holder.reset(task=TASKS[0].task_id)
        squatter = httpx.post(f"{url}/mcp", json=CREATE).json()
        assert "error" in squatter and "capacity" in squatter["error"]["message"].lower()
        deadline = time.monotonic() + 30
        while True:  # the idle WebSocket session is closed by the server
            answer = httpx.post(f"{url}/mcp", json=CREATE).json()
            if "result" in answer:
                break
            assert time.monotonic() < deadline, "the idle session never expired"
            time.sleep(0.25)
        squatted = answer["result"]["session_id"]
        with pytest.raises(RuntimeError, match="session has ended"):
            holder.step({"actions": REFUSED_ACTION})  # told why, not a bare failure
        holder.close()
        deadline = time.monotonic() + 30
        while True:  # and the MCP session nobody uses expires too
            try:
                with GenericEnvClient(base_url=url).sync() as client:
                    assert client.reset(task=TASKS[1].task_id).observation["task_id"] == \
                        TASKS[1].task_id
                break
            except (RuntimeError, ConnectionClosed) as exc:
                # refused at capacity: the error message, or the close right after it
                assert isinstance(exc, ConnectionClosed) or "capacity" in str(exc).lower()
                assert time.monotonic() < deadline, "the idle MCP session never expired"
                time.sleep(0.25)
        closed = httpx.post(f"{url}/mcp", json={
            "jsonrpc": "2.0", "id": 2, "method": "openenv/session/close",
            "params": {"session_id": squatted}}).json()
        assert "Unknown session_id" in closed["error"]["message"]


def test_stateless_http_answers_4xx_with_the_reason_never_500() -> None:
    with serving(TASKS) as url:
        unknown = httpx.post(f"{url}/reset", json={"task": "no/such/task"})
        assert unknown.status_code == 400
        detail = unknown.json()["detail"]
        assert detail["field"] == "options.task" and "no task" in detail["message"]
        assert TASKS[0].task_id in detail["fix"] or "task id" in detail["fix"]
        typo = httpx.post(f"{url}/reset", json={"taks": TASKS[0].task_id})
        assert typo.status_code == 400 and "taks" in typo.json()["detail"]["message"]
        index = httpx.post(f"{url}/reset", json={"task": 0})  # an index, 0 included
        assert index.status_code == 200
        assert index.json()["observation"]["task_id"] == TASKS[0].task_id
        for _ in range(2):  # reset, then step: the step has no episode to land on
            assert httpx.post(f"{url}/reset", json={"task": 1}).status_code == 200
            step = httpx.post(f"{url}/step", json={"action": {"actions": "done"}})
            assert step.status_code == 409
            detail = step.json()["detail"]
            assert detail["error"] == "NoEpisodeError" and "never reset" in detail["message"]
            assert "/ws" in detail["fix"]
        bad = httpx.post(f"{url}/step", json={"action": {"wrong": 1}})
        assert bad.status_code == 422  # OpenEnv's own validation of the action
        with GenericEnvClient(base_url=url).sync() as client:
            with pytest.raises(RuntimeError, match="never reset"):
                client.step({"actions": "done"})
            with pytest.raises(RuntimeError, match="no task"):
                client.reset(task="no/such/task")
            assert client.reset(task=TASKS[0].task_id).observation["task_id"] == \
                TASKS[0].task_id  # the session is still good after both


def test_bad_server_settings_are_clear_errors() -> None:
    for options, field in (({"token": " padded "}, "token"), ({"token": ""}, "token"),
                           ({"max_sessions": 0}, "max_sessions"),
                           ({"session_timeout": 0}, "session_timeout"),
                           ({"k": 0}, "k")):
        with pytest.raises(VeriGraphError) as err:
            create_openenv_app(tasks=TASKS, **options)
        assert err.value.field == field
    with pytest.raises(VeriGraphError) as err:  # refused before anything listens
        serve_openenv("0.0.0.0", free_port(), tasks=TASKS)
    assert err.value.field == "host" and "token" in (err.value.fix or "")


def create_session(url: str, token: str) -> dict[str, Any]:
    answer: dict[str, Any] = httpx.post(f"{url}/mcp", json=CREATE, headers={
        "Authorization": f"Bearer {token}"}).json()
    return answer


def test_one_caller_holding_its_share_leaves_the_others_served() -> None:
    with serving(TASKS, token=["holder-a", "client-b"]) as url:  # 64 sessions, 16 each
        answers = [create_session(url, "holder-a") for _ in range(DEFAULT_MAX_SESSIONS)]
        held = [a["result"]["session_id"] for a in answers if "result" in a]
        assert len(held) == DEFAULT_MAX_SESSIONS // 4
        refusal = answers[-1]["error"]["message"]
        assert "share" in refusal and "sessions_per_caller" in refusal
        assert "other callers are not affected" in refusal
        with TokenEnvClient(url, "client-b").sync() as client:  # served as if A were not
            assert client.reset(task=TASKS[0].task_id).observation["task_id"] == \
                TASKS[0].task_id
        mine = create_session(url, "client-b")["result"]["session_id"]
        # a session belongs to its caller: A can neither close nor use B's
        for method, params in (("openenv/session/close", {"session_id": mine}),
                               ("tools/list", {"session_id": mine})):
            foreign = httpx.post(f"{url}/mcp", headers={"Authorization": "Bearer holder-a"},
                                 json={**CREATE, "method": method, "params": params}).json()
            assert foreign["error"]["message"] == f"Unknown session_id: {mine}"
        closed = httpx.post(f"{url}/mcp", headers={"Authorization": "Bearer client-b"},
                            json={**CREATE, "method": "openenv/session/close",
                                  "params": {"session_id": mine}}).json()
        assert closed["result"] == {"session_id": mine, "closed": True}
        # A closes one of its own and may open one again
        own = httpx.post(f"{url}/mcp", headers={"Authorization": "Bearer holder-a"},
                         json={**CREATE, "method": "openenv/session/close",
                               "params": {"session_id": held[0]}}).json()
        assert own["result"]["closed"] is True
        assert "result" in create_session(url, "holder-a")
        assert "error" in create_session(url, "holder-a")


def test_a_full_server_gives_the_idlest_session_to_a_newcomer() -> None:
    with serving(TASKS, token=["holder-a", "client-b"], max_sessions=2,
                 sessions_per_caller=2, reclaim_after=0.2) as url:
        first, second = TokenEnvClient(url, "holder-a").sync(), \
            TokenEnvClient(url, "holder-a").sync()
        try:
            first.connect()
            first.reset(task=TASKS[0].task_id)
            second.connect()
            second.reset(task=TASKS[1].task_id)  # the server is full, `first` the idlest
            deadline = time.monotonic() + 30
            while True:  # once `first` has been idle for reclaim_after, B gets its slot
                answer = create_session(url, "client-b")
                if "result" in answer:
                    break
                assert "capacity" in answer["error"]["message"]
                assert time.monotonic() < deadline, "no idle session was reclaimed"
                second.state()  # keeps `second` the most recently active
                time.sleep(0.05)
            with pytest.raises(RuntimeError, match="session has ended"):
                first.step({"actions": REFUSED_ACTION})
            assert second.step({"actions": REFUSED_ACTION}).observation["verdict"] == \
                "violation"
        finally:
            first.close()
            second.close()


def test_share_settings_are_checked() -> None:
    for options, field in (({"sessions_per_caller": 0}, "sessions_per_caller"),
                           ({"sessions_per_caller": 65}, "sessions_per_caller"),
                           ({"reclaim_after": 0}, "reclaim_after")):
        with pytest.raises(VeriGraphError) as err:
            create_openenv_app(tasks=TASKS, **options)
        assert err.value.field == field


def test_bodies_are_bounded_before_openenv_reads_them() -> None:
    with serving(TASKS) as url:
        big = httpx.post(f"{url}/reset", content=b"{" + b" " * (17 << 20) + b"}",
                         headers={"Content-Type": "application/json"}, timeout=60)
        assert big.status_code == 413 and big.json()["detail"]["field"] == "body"
        chunked = httpx.post(f"{url}/mcp", timeout=60,  # no Content-Length: counted
                             content=iter([b"{" + b" " * (1 << 20), b"}"]))
        assert chunked.status_code == 413
        deep = httpx.post(f"{url}/mcp", content=b"[" * 500_000, timeout=60)
        assert deep.status_code == 200 and deep.json()["error"]["code"] == -32700
        assert httpx.post(f"{url}/reset", json={"task": 0}).status_code == 200
