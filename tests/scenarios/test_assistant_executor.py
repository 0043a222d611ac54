"""Every result that acts or reports state says where the actions run, in its text.

Many clients hand the model only a result's text: it must not read a graph check as a
robot's motion, and it must find the server's executors without trial and error.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from arm_server_helpers import BlockCellStandIn, User, loose_blocks, xarm_toolbox
from mcp import Client
from mcp_helpers import (  # noqa: F401 - in_process_client: the client fixture
    in_process_client,
    structured,
    text,
)

from verigraph.arm import parse_arm_config
from verigraph.server import build_server
from verigraph.tools import Toolbox, ToolConfig
from verigraph.tools.executors import ArmSetup

pytestmark = pytest.mark.anyio
GRAPH_ONLY = "executor: graph (verified only, nothing physical moved)"


async def test_graph_episode_results_say_nothing_physical_moved(client: Client) -> None:
    loaded = await client.call_tool("load_scene", {"scene_id": "cup_on_book"})
    assert GRAPH_ONLY in text(loaded)
    eid = structured(loaded)["episode_id"]
    calls = [("validate_action", {"action": "move(cup, on, desk)"}),
             ("execute_actions", {"actions": ["move(cup, on, desk)"]}),
             ("get_state", {}), ("end_episode", {})]
    for tool, args in calls:
        result = await client.call_tool(tool, {"episode_id": eid, **args})
        assert GRAPH_ONLY in text(result), (tool, text(result))
    checked = await client.call_tool("validate_plan", {"scene_id": "cup_on_book",
                                                       "plan": "move(cup, on, desk)"})
    assert "nothing was executed" in text(checked)


async def test_simulated_episode_says_simulated() -> None:
    async with Client(build_server(Toolbox())) as c:
        loaded = await c.call_tool("load_scene", {"scene_id": "cup_on_book", "simulate": True})
        eid = structured(loaded)["episode_id"]
        moved = await c.call_tool("execute_actions", {"episode_id": eid,
                                                      "actions": ["move(cup, on, desk)"]})
    for result in (loaded, moved):
        assert "executor: sim2d (simulated in the 2D simulator, nothing physical moved)" \
            in text(result)


async def test_real_arm_episode_says_real_arm(tmp_path: Path) -> None:
    box = xarm_toolbox(tmp_path, BlockCellStandIn())
    async with Client(build_server(box), elicitation_callback=User()) as c:
        loaded = await c.call_tool("load_scene", {"graph": loose_blocks()})
        eid = structured(loaded)["episode_id"]
        moved = await c.call_tool("execute_actions", {
            "episode_id": eid, "actions": ["move(red_block, on, green_block)"]})
        assert structured(moved)["ok"], text(moved)
        ended = await c.call_tool("end_episode", {"episode_id": eid})
    for result in (loaded, moved, ended):
        assert "executor: arm:xarm (real arm: validated actions move the robot" in text(result)
        assert "nothing physical moved" not in text(result)


async def test_the_servers_executors_are_in_its_instructions_and_refusals() -> None:
    setup = ArmSetup(parse_arm_config({"driver": "pybullet", "mode": "sim"}))
    box = Toolbox(config=ToolConfig(arm=setup))
    async with Client(build_server(box)) as c:
        assert c.instructions is not None
        assert ("graph (verified only, default), sim2d (simulated), arm:pybullet (simulated "
                "arm)") in c.instructions
        refused = await c.call_tool("load_scene", {"scene_id": "cup_on_book", "executor": "arm"})
    assert refused.is_error
    assert "this server runs graph (verified only, default), sim2d (simulated), arm:pybullet" \
        in text(refused)
    async with Client(build_server(Toolbox())) as plain:
        assert plain.instructions is not None and "arm:" not in plain.instructions.split(
            "5. Executors")[1]
        no_arm = await plain.call_tool("load_scene", {"scene_id": "cup_on_book",
                                                      "executor": "arm:xarm"})
    assert no_arm.is_error and "this server runs graph (verified only) and sim2d" in text(no_arm)


async def test_arm_status_on_a_graph_episode_names_the_executor_that_reaches_the_arm() -> None:
    setup = ArmSetup(parse_arm_config({"driver": "pybullet", "mode": "sim"}))
    async with Client(build_server(Toolbox(config=ToolConfig(arm=setup)))) as c:
        eid = structured(await c.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
            "episode_id"]
        status = await c.call_tool("arm_status", {"episode_id": eid})
    said = text(status)
    assert status.is_error and "runs on graph, not on an arm" in said
    assert "this server's arm is reached with executor arm:pybullet" in said
    assert "here executor=arm:pybullet" in said and "arm:pybullet (simulated arm)" in said


async def test_arm_status_on_a_server_without_an_arm_says_none_is_configured(
        client: Client) -> None:
    eid = structured(await client.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
        "episode_id"]
    said = text(await client.call_tool("arm_status", {"episode_id": eid}))
    assert "this server has no arm configured: no executor here reaches a robot" in said
    assert "this server runs graph (verified only, default), sim2d (simulated)" in said
    assert "arm:pybullet" not in said.split("this server runs")[1]


async def test_the_tool_descriptions_say_which_executors_move_something(
        client: Client) -> None:
    """A client that shows no server instructions still tells the model where actions run."""
    tools = {t.name: t.description or "" for t in (await client.list_tools()).tools}
    assert "graph, sim2d: nothing physical moves" in tools["execute_actions"]
    # whether a robot is there is said by load_scene (its answer names the executors)
    assert "executors, robot or none" in tools["load_scene"]
