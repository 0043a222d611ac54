"""Episodes per caller against a real `verigraph serve --transport http --token A --token B`
on loopback: one caller filling its share is refused by name while the other is served,
and no caller reads, changes or ends another caller's episode, whatever id it sends."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import httpx2
import pytest
from mcp_helpers import JSON_HEADERS, http_server, rpc

A, B = "share-token-a-7f3e", "share-token-b-91c0"
LEGACY = "2025-11-25"  # a stateless tools/call needs no initialize on this era


@pytest.fixture(scope="module")
def url(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    store = tmp_path_factory.mktemp("shares") / "episodes.db"
    # The default shares: 256 episodes, a quarter (64) per caller.
    with http_server(token=A, extra=["--token", B, "--store", f"sqlite:///{store}"]) as running:
        yield running.url


def call(url: str, token: str, name: str, arguments: dict[str, Any],
         method: str = "tools/call") -> dict[str, Any]:
    body = rpc(method, {"name": name, "arguments": arguments} if method == "tools/call"
               else arguments)
    headers = {**JSON_HEADERS, "Authorization": f"Bearer {token}",
               "MCP-Protocol-Version": LEGACY}
    response = httpx2.post(url, content=body, headers=headers, timeout=60)
    assert response.status_code == 200, response.text[:300]
    reply: dict[str, Any] = json.loads(response.content)
    return reply


def text(reply: dict[str, Any]) -> str:
    return str(reply["result"]["content"][0]["text"])


def load(url: str, token: str) -> dict[str, Any]:
    return call(url, token, "load_scene", {"scene_id": "cup_on_book"})


def test_one_caller_filling_its_share_leaves_room_for_the_other(url: str) -> None:
    opened = []
    for _ in range(256):  # as many as the whole store holds
        reply = load(url, A)
        if reply["result"].get("isError"):
            break
        opened.append(reply["result"]["structuredContent"]["episode_id"])
    assert len(opened) == 64  # its share, a quarter of --max-episodes
    refusal = text(reply)
    assert "share" in refusal and "--episodes-per-caller 64" in refusal
    assert "end_episode" in refusal and "other callers are not affected" in refusal
    for _ in range(3):  # the other caller is served as if A were not there
        other = load(url, B)
        assert not other["result"].get("isError"), text(other)
    # A makes room in its own share by ending one of its episodes
    ended = call(url, A, "end_episode", {"episode_id": opened[0]})
    assert not ended["result"].get("isError"), text(ended)
    again = load(url, A)
    assert not again["result"].get("isError"), text(again)
    assert text(load(url, A)) == refusal  # and is at its share again


def test_no_caller_reaches_another_callers_episode(url: str) -> None:
    mine = load(url, B)["result"]["structuredContent"]["episode_id"]
    before = call(url, B, "get_state", {"episode_id": mine})["result"]["structuredContent"]
    unknown = "ep_" + "x" * 22
    for name, arguments in (("get_state", {}), ("end_episode", {}),
                            ("execute_actions", {"actions": ["move(cup, on, desk)"]}),
                            ("validate_action", {"action": "move(cup, on, desk)"}),
                            ("set_goal", {"edges": "cup on desk"})):
        theirs = call(url, A, name, {"episode_id": mine, **arguments})
        nobody = call(url, A, name, {"episode_id": unknown, **arguments})
        # exactly the answer an id that does not exist gets: nothing to tell them apart
        assert theirs["result"]["isError"] and nobody["result"]["isError"]
        assert text(theirs).replace(mine, "ID") == text(nobody).replace(unknown, "ID")
        assert "no open episode" in text(theirs)
    resource = call(url, A, "", {"uri": f"verigraph://episodes/{mine}/graph"},
                    method="resources/read")
    assert "error" in resource and "no open episode" in resource["error"]["message"]
    # the owner's episode is untouched: same graph, same goal, no call counted
    after = call(url, B, "get_state", {"episode_id": mine})["result"]["structuredContent"]
    assert after == before and after["calls"] == 0
