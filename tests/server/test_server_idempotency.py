"""execute_actions with a request_id is idempotent; expected_calls guards against races."""

from __future__ import annotations

import pytest
from mcp import Client
from mcp_helpers import in_process_client, structured, text  # noqa: F401 - the client fixture

pytestmark = [pytest.mark.fast, pytest.mark.anyio]


async def test_a_retry_returns_the_original_result_and_applies_nothing(client: Client) -> None:
    eid = structured(await client.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
        "episode_id"]
    call = {"episode_id": eid, "actions": ["move(cup, on, desk)"], "request_id": "step-1"}
    first = structured(await client.call_tool("execute_actions", call))
    retry = structured(await client.call_tool("execute_actions", call))
    assert first["ok"] and retry == first
    state = structured(await client.call_tool("get_state", {"episode_id": eid}))
    assert state["calls"] == 1 and state["tau"] == 0
    assert state["executed"] == ["move(cup, on, desk)"]
    # without a request id the same call runs again (and now fails: the cup is there)
    again = structured(await client.call_tool("execute_actions", {
        "episode_id": eid, "actions": ["move(cup, on, desk)"]}))
    assert not again["ok"] and again["tau"] == 1


async def test_a_request_id_reused_for_other_actions_is_refused(client: Client) -> None:
    eid = structured(await client.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
        "episode_id"]
    structured(await client.call_tool("execute_actions", {
        "episode_id": eid, "actions": ["move(cup, on, desk)"], "request_id": "r"}))
    other = await client.call_tool("execute_actions", {
        "episode_id": eid, "actions": ["move(book, on, shelf)"], "request_id": "r"})
    assert other.is_error and "request_id 'r' was already used" in text(other)
    state = structured(await client.call_tool("get_state", {"episode_id": eid}))
    assert state["calls"] == 1


async def test_expected_calls_refuses_a_stale_plan(client: Client) -> None:
    eid = structured(await client.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
        "episode_id"]
    ok = structured(await client.call_tool("execute_actions", {
        "episode_id": eid, "actions": ["move(cup, on, desk)"], "expected_calls": 0}))
    assert ok["ok"]
    stale = await client.call_tool("execute_actions", {
        "episode_id": eid, "actions": ["move(book, on, shelf)"], "expected_calls": 0})
    assert stale.is_error and "expected_calls" in text(stale)
    state = structured(await client.call_tool("get_state", {"episode_id": eid}))
    assert state["calls"] == 1 and state["executed"] == ["move(cup, on, desk)"]
