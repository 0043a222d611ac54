"""Two `verigraph serve --transport http` replicas sharing one real Redis.

An episode created on one replica is continued on the other, and four clients that
alternate between the replicas and send execute_actions at the same time on one episode
lose no move and apply none twice: the final graph is the replay of the moves reported.
"""

from __future__ import annotations

import random
from collections import Counter
from typing import Any

import anyio
import pytest
from mcp_helpers import http_server
from store_helpers import call, connect, redis_url  # noqa: F401 - redis_url: the session fixture

pytestmark = pytest.mark.anyio
BLOCKS = ["red_block", "blue_block", "green_block"]


async def test_replicas_share_episodes_and_serialise_moves(redis_url: str) -> None:  # noqa: F811
    store = ["--store", redis_url, "--log-level", "INFO"]
    with http_server(extra=store) as a, http_server(extra=store) as b:
        replicas = [a.url, b.url]
        async with connect(a.url) as on_a, connect(b.url) as on_b:
            ep = (await call(on_a, "load_scene", scene_id="three_blocks", t=100))["episode_id"]
            moved = await call(on_b, "execute_actions", episode_id=ep,
                               actions=["move(green_block, red_block)"])
            assert moved["ok"]
            seen = await call(on_a, "get_state", episode_id=ep)
            assert seen["executed"] == ["move(green_block, on, red_block)"]
            initial = (await call(on_a, "load_scene", scene_id="three_blocks"))["graph"]

        results: list[dict[str, Any]] = []
        turns = 8
        # Each turn the four clients read the state, wait for each other, then send their
        # moves at the same moment: two on each replica, so the replicas race on one version.
        ready = [anyio.Event() for _ in range(turns)]
        arrived = [0] * turns

        async def agent(index: int) -> None:
            rng = random.Random(index)
            async with connect(replicas[0]) as c0, connect(replicas[1]) as c1:
                clients = [c0, c1]
                for turn in range(turns):
                    client = clients[(index + turn) % 2]  # alternate replicas
                    # A move that is valid on the state just read; a racing client may
                    # make it invalid before it runs, which is fine: it then fails whole.
                    graph = (await call(client, "get_state", episode_id=ep))["graph"]
                    covered = {e["target"] for e in graph["edges"]}
                    clear = [b for b in BLOCKS if b not in covered]
                    obj = rng.choice(clear)
                    below = next(e["target"] for e in graph["edges"] if e["source"] == obj)
                    target = rng.choice([b for b in clear if b != obj]
                                        + (["table"] if below != "table" else []))
                    arrived[turn] += 1
                    if arrived[turn] == 4:
                        ready[turn].set()
                    await ready[turn].wait()
                    results.append(await call(client, "execute_actions", episode_id=ep,
                                              actions=[f"move({obj}, {target})"]))

        async with anyio.create_task_group() as tg:
            for index in range(4):
                tg.start_soon(agent, index)

        async with connect(b.url) as client:
            final = await call(client, "get_state", episode_id=ep)
            reported = ["move(green_block, on, red_block)"] + [
                m for r in results for m in r["executed"]]
            assert Counter(final["executed"]) == Counter(reported)  # none lost or doubled
            assert final["calls"] == 1 + len(results) == 33
            order = final["executed"]
            replay = await call(client, "validate_plan", graph=initial,
                                plan=final["executed"])
            assert replay["valid"]
            assert replay["final_graph"] == final["graph"]
            # Every reply's graph is the replay of the moves committed up to it.
            prefixes = []
            for n in range(len(order) + 1):
                prefixes.append((await call(client, "validate_plan", graph=initial,
                                            plan=order[:n] or ["done"]))["final_graph"])
            for r in results:
                assert r["graph"] in prefixes
                if r["executed"]:  # a graph may recur: some prefix ending in its move
                    assert any(g == r["graph"] and order[n - 1] == r["executed"][-1]
                               for n, g in enumerate(prefixes) if n > 0)
            trace = (await call(client, "end_episode", episode_id=ep))["trace"]
            assert [t["call"] for t in trace] == list(range(1, 34))
            assert sum(bool(r["executed"]) for r in results) == len(order) - 1 > 4, [
                (r["executed"], r["violation"]) for r in results]
        retried = sum(server.stop()[1].count(b"changed in another process") for server in (a, b))
        print(f"calls run again after losing a compare-and-set: {retried}")
