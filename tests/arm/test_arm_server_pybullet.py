"""The PyBullet Panda behind the MCP server: a plan from the tools, checked in the physics.

The honest end-to-end test of the server wiring: the real SDK client asks the server
for a plan (solve), executes it with execute_actions on an `arm:pybullet` episode in
mode sim, and the simulated contacts and heights, not only the camera, confirm each
`on`.
"""

from __future__ import annotations

import json
import math
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import anyio
import anyio.to_thread
import cv2
import numpy as np
import pytest
from arm_deps import require
from arm_server_helpers import BLOCKS, loose_blocks
from mcp import Client
from mcp_helpers import decode_png, structured, text
from panda_helpers import arm_moving

from verigraph.arm import ArmWorld, CameraView, PyBulletOptions, load_arm_config, parse_arm_config
from verigraph.cli import main as cli_main
from verigraph.server import build_server
from verigraph.tools import Toolbox, ToolConfig
from verigraph.tools.executors import ArmSetup

require("pybullet")

from verigraph.arm.sim.camera import capture  # noqa: E402
from verigraph.arm.sim.panda_scene import PandaScene  # noqa: E402

pytestmark = pytest.mark.anyio
BLOCK_M = 0.06  # the blocks dictionary's 6 cm


def panda_toolbox(**config: Any) -> Toolbox:
    arm = ArmSetup(parse_arm_config({"driver": "pybullet", "mode": "sim", **config}))
    return Toolbox(config=ToolConfig(executor="arm:pybullet", arm=arm))


def scene_of(box: Toolbox, eid: str) -> PandaScene:
    world = box.context.store.peek(eid).world
    assert isinstance(world, ArmWorld)
    scene = world._controller._driver.scene  # type: ignore[attr-defined]
    assert isinstance(scene, PandaScene)
    return scene


@pytest.fixture()
async def panda() -> AsyncIterator[tuple[Toolbox, Client]]:
    box = panda_toolbox()
    async with Client(build_server(box)) as client:
        yield box, client
    for eid in box.context.store.ids():  # close the physics of anything left open
        box.call("end_episode", {"episode_id": eid})


async def test_panda_stacks_three_blocks_from_a_plan_and_the_physics_confirms_each_on(
        panda: tuple[Toolbox, Client]) -> None:
    box, client = panda
    state = structured(await client.call_tool("load_scene", {
        "graph": loose_blocks(), "goal": {"predicate": "single_stack"}}))
    eid = state["episode_id"]
    assert state["executor"] == "arm:pybullet" and state["arm_mode"] == "sim"
    assert state["scene_check"]["matches"]  # the cameras see the graph it was built from
    plan = structured(await client.call_tool("solve", {"episode_id": eid}))["plan"]
    assert len(plan) == 2
    scene = scene_of(box, eid)
    for step, action in enumerate(plan, start=1):
        out = structured(await client.call_tool("execute_actions", {"episode_id": eid,
                                                                    "actions": [action]}))
        assert out["ok"], out["violation"]
        obj, _, target = action.removeprefix("move(").removesuffix(")").split(", ")
        # the physics, not the camera: resting on the target, one block higher, centred
        assert scene.in_contact(obj, target), (step, action)
        (ox, oy, oz), (tx, ty, tz) = scene.body_position(obj), scene.body_position(target)
        assert oz - tz == pytest.approx(BLOCK_M, abs=0.004)
        assert math.dist((ox, oy), (tx, ty)) < 0.015
    done = structured(await client.call_tool("execute_actions", {"episode_id": eid,
                                                                 "actions": ["done"]}))
    assert done["goal_satisfied"] and done["done"]
    moved = {action.split(", ")[0].removeprefix("move(") for action in plan}
    (bottom,) = set(BLOCKS) - moved
    assert scene.in_contact(bottom, "table")
    assert sum(scene.in_contact(b, "table") for b in BLOCKS) == 1  # one tower
    status = structured(await client.call_tool("arm_status", {"episode_id": eid}))
    assert status["commands_sent"] == 5 and status["last_outcome"] == "done"
    picture = await client.call_tool("render_scene", {"episode_id": eid, "width": 160,
                                                      "height": 120})
    shown = decode_png(picture.content[0].data)  # type: ignore[union-attr]
    camera = capture(scene, CameraView(eye=(1.1, 0.5, 0.75), width=160, height=120))
    assert np.array_equal(shown, cv2.cvtColor(camera.rgb, cv2.COLOR_RGB2BGR))  # red is red
    verdict = await client.call_tool("end_episode", {"episode_id": eid})
    assert text(verdict).startswith("SUCCESS: goal reached")
    assert len(box.context.arms) == 0


async def test_dry_run_panda_predicts_but_the_physics_does_not_move() -> None:
    box = panda_toolbox(mode="dry-run")
    async with Client(build_server(box)) as client:
        eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
            "episode_id"]
        scene = scene_of(box, eid)
        before, joints = [scene.body_position(b) for b in BLOCKS], scene.arm_positions()
        out = structured(await client.call_tool("execute_actions", {
            "episode_id": eid, "actions": ["move(green_block, on, red_block)",
                                           "move(blue_block, on, green_block)"]}))
        assert out["ok"]
        assert [scene.body_position(b) for b in BLOCKS] == before
        assert scene.arm_positions() == joints
        await client.call_tool("end_episode", {"episode_id": eid})


async def test_the_stop_latches_the_arm_across_episodes_and_restarts(tmp_path: Path) -> None:
    """arm_stop mid-motion latches the arm itself: a new episode on it, or a new server,
    is latched too; the agent cannot reset it; the operator's reset moves nothing."""
    config_file = tmp_path / "arm.json"
    config_file.write_text(json.dumps({
        "driver": "pybullet", "mode": "sim", "audit_log": str(tmp_path / "audit.jsonl"),
        "pybullet": PyBulletOptions(real_time_factor=1.0).model_dump()}))
    box = Toolbox(config=ToolConfig(executor="arm:pybullet",
                                    arm=ArmSetup(load_arm_config(config_file))))
    async with Client(build_server(box)) as client:
        eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
            "episode_id"]
        scene = scene_of(box, eid)
        moving = arm_moving(scene)
        results: list[dict[str, Any]] = []

        async def execute() -> None:
            results.append(structured(await client.call_tool("execute_actions", {
                "episode_id": eid, "actions": ["move(green_block, on, red_block)"]})))

        async with anyio.create_task_group() as tg:
            tg.start_soon(execute)
            assert await anyio.to_thread.run_sync(moving.wait, 10)  # the arm is moving
            stopped = structured(await client.call_tool("arm_stop", {"episode_id": eid}))
        assert stopped["stop_latched"]
        out = results[0]
        assert out["violation"]["constraint"] == "execution_failed"
        assert not scene.in_contact("green_block", "red_block")
        refused = await client.call_tool("arm_reset", {"episode_id": eid})
        assert refused.is_error and "verigraph arm reset --config FILE" in text(refused)
        await client.call_tool("end_episode", {"episode_id": eid})
        # a new episode on the same arm: still latched, nothing runs
        again = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))
        status = structured(await client.call_tool("arm_status", {
            "episode_id": again["episode_id"]}))
        assert status["stop_latched"] and status["stop_reason"] == "stop requested through arm_stop"
        out = structured(await client.call_tool("execute_actions", {
            "episode_id": again["episode_id"], "actions": ["move(green_block, on, red_block)"]}))
        assert out["violation"]["constraint"] == "arm_refused"
        assert "stop is latched" in out["violation"]["message"]
        await client.call_tool("end_episode", {"episode_id": again["episode_id"]})
    # a restarted server on the same arm: still latched
    box = Toolbox(config=ToolConfig(executor="arm:pybullet",
                                    arm=ArmSetup(load_arm_config(config_file))))
    async with Client(build_server(box)) as client:
        eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
            "episode_id"]
        assert structured(await client.call_tool("arm_status", {"episode_id": eid}))[
            "stop_latched"]
        joints = scene_of(box, eid).arm_positions()
        assert cli_main(["arm", "reset", "--config", str(config_file)]) == 0  # the operator
        status = structured(await client.call_tool("arm_status", {"episode_id": eid}))
        assert not status["stop_latched"]
        assert scene_of(box, eid).arm_positions() == joints  # a reset moves nothing
        await client.call_tool("end_episode", {"episode_id": eid})
    audit = [json.loads(line) for line in (tmp_path / "audit.jsonl").read_text().splitlines()]
    assert [r["outcome"] for r in audit if r["command"] == "reset"] == ["refused", "done"]
    assert cli_main(["arm", "audit-verify", str(tmp_path / "audit.jsonl")]) == 0
