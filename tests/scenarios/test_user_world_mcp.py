"""A user's own world end to end over MCP: the SDK client over HTTP and stdio.

The home office of tests/user_worlds.py is loaded with an inline dictionary and with
labels declared in attrs; moves are refused with the right constraint ids and accepted
otherwise, `solve` reaches a goal, simulate=true executes and renders, and a server
restarted on the same SQLite store keeps the episode with its dictionary.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

import pytest
from mcp import Client, StdioServerParameters, stdio_client
from mcp_helpers import decode_png, http_server, structured, text, verigraph_command
from store_helpers import call, connect
from user_worlds import GOAL, inline_scene, open_label_scene

pytestmark = pytest.mark.anyio


async def refused(c: Client, episode_id: str, action: str) -> str:
    out = await call(c, "validate_action", episode_id=episode_id, action=action)
    assert out["violation"] is not None, out
    constraint: str = out["violation"]["constraint"]
    return constraint


async def home_office_session(c: Client, scene: dict[str, Any], dictionary: str) -> None:
    """Load, refuse and accept moves, solve to the goal: the same for either form."""
    loaded = await c.call_tool("load_scene", {"graph": scene})
    shown = text(loaded)
    ep = structured(loaded)["episode_id"]
    assert "laptop (laptop: your label, movable surface, capacity 1" in shown  # + sizes in attrs
    assert "drawers (drawer_unit: your label, fixed container, capacity 2" in shown
    assert "Mug read as mug (case and spacing" in shown
    assert "notebook read as book (synonym, tableware dictionary)" in shown
    state = structured(loaded)
    assert "laptop: movable surface, capacity 1" in state["user_labels"]
    assert any(r.startswith("Pen Holder read as pen_holder") for r in state["label_readings"])

    assert await refused(c, ep, "move(laptop, on, shelf)") == "object_not_clear"
    assert await refused(c, ep, "move(mug, in, desk)") == "target_not_container"
    filled = await call(c, "execute_actions", episode_id=ep,
                        actions=["move(book_2, in, drawers)", "move(pens, in, drawers)"])
    assert filled["ok"] and filled["tau"] == 0
    assert await refused(c, ep, "move(mug, in, drawers)") == "target_full"

    goal = await call(c, "set_goal", episode_id=ep, **GOAL)
    assert goal["goal_satisfied"] is False
    plan = (await call(c, "solve", episode_id=ep))["plan"]
    assert plan, "solve found no plan"
    done = await call(c, "execute_actions", episode_id=ep, actions=[*plan, "done"])
    assert done["ok"] and done["goal_satisfied"] is True
    later = await c.call_tool("get_state", {"episode_id": ep})
    assert f"dictionary: {dictionary}; your labels: " in text(later)
    assert "laptop: movable surface, capacity 1" in text(later)
    assert structured(later)["dictionary"] == dictionary
    assert "laptop on shelf" in text(later)


async def test_inline_dictionary_over_http() -> None:
    with http_server() as server:
        async with connect(server.url) as c:
            await home_office_session(c, inline_scene(), "home_office")


def stdio_params(*extra: str) -> StdioServerParameters:
    cmd = verigraph_command()
    return StdioServerParameters(command=cmd[0], args=[*cmd[1:], "serve", *extra])


async def test_open_labels_over_stdio() -> None:
    with tempfile.TemporaryFile("w+") as errlog:
        async with Client(stdio_client(stdio_params(), errlog=errlog)) as c:
            await home_office_session(c, open_label_scene(), "tableware")


async def test_simulated_user_world_executes_and_renders() -> None:
    with tempfile.TemporaryFile("w+") as errlog:
        async with Client(stdio_client(stdio_params(), errlog=errlog)) as c:
            loaded = await call(c, "load_scene", graph=inline_scene(), simulate=True)
            assert loaded["executor"] == "sim2d"
            ep = loaded["episode_id"]
            out = await call(c, "execute_actions", episode_id=ep,
                             actions=["move(mug, on, desk)", "move(laptop, on, shelf)",
                                      "move(pens, in, drawers)"])
            assert out["ok"], out
            state = await call(c, "get_state", episode_id=ep)
            assert {"laptop on shelf", "mug on desk", "pens in drawers"} <= {
                f"{e['source']} {e['relation']} {e['target']}" for e in state["graph"]["edges"]}
            image = await c.call_tool("render_scene", {"episode_id": ep, "width": 480,
                                                       "height": 320})
            assert not image.is_error
            picture = decode_png(image.content[0].data)  # type: ignore[union-attr]
            assert picture.shape == (320, 480, 3)
            # The user's objects are drawn: the picture is not one flat colour.
            assert picture.reshape(-1, 3).std(axis=0).max() > 10


async def test_restart_on_sqlite_keeps_the_episode_and_its_dictionary(tmp_path: Path) -> None:
    store = ["--store", f"sqlite:///{tmp_path / 'episodes.db'}"]
    with http_server(extra=store) as first:
        async with connect(first.url) as c:
            ep = (await call(c, "load_scene", graph=inline_scene()))["episode_id"]
            moved = await call(c, "execute_actions", episode_id=ep,
                               actions=["move(mug, on, desk)"])
            assert moved["ok"]
            before = await call(c, "get_state", episode_id=ep)
            sim = (await call(c, "load_scene", graph=inline_scene(),
                              simulate=True))["episode_id"]
            assert (await call(c, "execute_actions", episode_id=sim,
                               actions=["move(pens, in, drawers)"]))["ok"]
            sim_before = await call(c, "get_state", episode_id=sim)
        first.proc.kill()
        first.proc.wait(timeout=10)
    with http_server(extra=store) as second:
        async with connect(second.url) as c:
            after = await c.call_tool("get_state", {"episode_id": ep})
            assert structured(after) == before
            assert await call(c, "get_state", episode_id=sim) == sim_before
            # The simulated world came back too: it carries out the next move.
            assert (await call(c, "execute_actions", episode_id=sim,
                               actions=["move(mug, on, desk)", "move(laptop, on, shelf)"]))["ok"]
            assert before["dictionary"] == "home_office"
            assert "laptop (laptop: your label, movable surface, capacity 1)" in text(after)
            # The restored dictionary still drives the constraints.
            assert await refused(c, ep, "move(mug, in, shelf)") == "target_not_container"
            full = await call(c, "execute_actions", episode_id=ep,
                              actions=["move(book_2, in, drawers)", "move(pens, in, drawers)",
                                       "move(mug, in, drawers)"])
            assert not full["ok"] and full["violation"]["constraint"] == "target_full"
