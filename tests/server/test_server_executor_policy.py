"""Executors are the operator's choice: clients pick only what the server enables, arm
episodes are capped per server, and end_episode releases the arm world."""

from __future__ import annotations

from collections.abc import AsyncIterator

import pytest
from mcp import Client
from mcp_helpers import structured, text

from verigraph.arm import ArmWorld, parse_arm_config
from verigraph.server import build_server
from verigraph.tools import Toolbox
from verigraph.tools.context import ToolConfig
from verigraph.tools.executors import ArmSetup

pytestmark = pytest.mark.anyio


@pytest.mark.parametrize("executor", ["arm:pybullet", "arm:xarm", "arm:rosbridge"])
async def test_a_server_without_an_arm_refuses_every_arm_executor(executor: str) -> None:
    box = Toolbox()
    async with Client(build_server(box)) as client:
        result = await client.call_tool("load_scene", {"scene_id": "three_blocks",
                                                       "executor": executor})
        assert result.is_error
        assert f"this server has no arm, so executor {executor} is not available" in text(result)
        assert "--arm-config" in text(result)
        assert len(box.context.arms) == 0 and len(box.context.store) == 0
        # what the operator did not restrict still works
        ok = await client.call_tool("load_scene", {"scene_id": "three_blocks",
                                                   "executor": "sim2d"})
        assert structured(ok)["executor"] == "sim2d"


@pytest.fixture()
async def two_arm_server() -> AsyncIterator[tuple[Client, Toolbox]]:
    arm = ArmSetup(parse_arm_config({"driver": "pybullet"}))  # dry-run: moves nothing
    box = Toolbox(config=ToolConfig(executor="graph", arm=arm, max_arm_worlds=2))
    async with Client(build_server(box)) as client:
        yield client, box


async def test_arm_episodes_are_capped_and_end_episode_releases_the_cell(
        two_arm_server: tuple[Client, Toolbox]) -> None:
    client, box = two_arm_server
    args = {"scene_id": "three_blocks", "executor": "arm:pybullet"}
    first = structured(await client.call_tool("load_scene", args))["episode_id"]
    structured(await client.call_tool("load_scene", args))
    assert len(box.context.arms) == 2
    refused = await client.call_tool("load_scene", args)
    assert refused.is_error and "already runs 2 arm cells" in text(refused)
    assert len(box.context.store) == 2  # the refused call left nothing behind
    world = box.context.store.peek(first).world
    assert isinstance(world, ArmWorld)
    structured(await client.call_tool("end_episode", {"episode_id": first}))
    assert len(box.context.arms) == 1
    assert world.status().connected is False
    third = await client.call_tool("load_scene", args)
    assert structured(third)["executor"] == "arm:pybullet"
