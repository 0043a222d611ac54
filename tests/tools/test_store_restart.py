"""kill -9 the server, start it again on the same SQLite store, and continue the episodes.

Graph-only and sim2d episodes: after the restart the state, tau, the trace and a render
of the simulated world are exactly what the killed process reported.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from mcp import Client
from mcp_helpers import http_server
from store_helpers import call, connect

pytestmark = pytest.mark.anyio


async def render(client: Client, episode_id: str) -> str:
    result = await client.call_tool("render_scene", {"episode_id": episode_id, "width": 320,
                                                     "height": 240})
    assert not result.is_error and result.content[0].type == "image"
    data: str = result.content[0].data  # type: ignore[union-attr]
    return data


async def test_episodes_survive_kill_9(tmp_path: Path) -> None:
    store = ["--store", f"sqlite:///{tmp_path / 'episodes.db'}"]
    with http_server(extra=store) as first:
        async with connect(first.url) as c:
            graph_ep = (await call(c, "load_scene", scene_id="cup_on_book"))["episode_id"]
            sim_ep = (await call(c, "load_scene", generator={"family": "kitchen", "seed": 3},
                                 executor="sim2d"))["episode_id"]
            plan = (await call(c, "solve", episode_id=sim_ep))["plan"]
            calls = {graph_ep: [await call(c, "execute_actions", episode_id=graph_ep,
                                           actions=["move(desk, shelf)"]),
                                await call(c, "execute_actions", episode_id=graph_ep,
                                           actions=["move(cup, desk)"])],
                     sim_ep: [await call(c, "execute_actions", episode_id=sim_ep,
                                         actions=plan[:1])]}
            before = {ep: await call(c, "get_state", episode_id=ep) for ep in calls}
            picture = await render(c, sim_ep)
        assert calls[graph_ep][0]["tau"] == 1 and calls[graph_ep][1]["ok"]
        first.proc.kill()  # SIGKILL: no shutdown hook runs
        assert first.proc.wait(timeout=10) == -9

    with http_server(extra=store) as second:
        async with connect(second.url) as c:
            for ep in calls:
                assert await call(c, "get_state", episode_id=ep) == before[ep]
            assert await render(c, sim_ep) == picture  # the same PNG bytes
            more = await call(c, "execute_actions", episode_id=sim_ep, actions=plan[1:2])
            assert more["ok"], more
            assert (await call(c, "execute_actions", episode_id=graph_ep,
                               actions=["move(book, shelf)"]))["goal_satisfied"] is True
            verdicts = {ep: await call(c, "end_episode", episode_id=ep) for ep in calls}
    graph_trace = verdicts[graph_ep]["trace"]
    assert [t["executed"] for t in graph_trace] == [[], ["move(cup, on, desk)"],
                                                    ["move(book, on, shelf)"]]
    assert [t["tau"] for t in graph_trace] == [1, 0, 0]
    assert verdicts[graph_ep]["verdict"] == "goal_reached"
    sim_trace = verdicts[sim_ep]["trace"]
    assert [t["executed"] for t in sim_trace] == [calls[sim_ep][0]["executed"],
                                                  more["executed"]]
