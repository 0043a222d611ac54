"""Whole-arm geometry: a link, the hand or the fingers entering a keep-out zone is refused
before motion, even when the tool centre's path stays clear of it.

Through the real MCP client, on the PyBullet Panda (sim) and on a real-mode xArm whose
SDK object is `BlockCellStandIn` (a stand-in: no controller can run here).
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest
from arm_deps import require
from arm_server_helpers import BlockCellStandIn, User, loose_blocks, xarm_toolbox
from mcp import Client
from mcp_helpers import structured

from verigraph.arm import ArmWorld, parse_arm_config
from verigraph.server import build_server
from verigraph.tools import Toolbox, ToolConfig
from verigraph.tools.executors import ArmSetup

require("pybullet")
require("xarm")

pytestmark = pytest.mark.anyio
STACK = ["move(green_block, on, red_block)"]


def target_away_from_side(world: ArmWorld) -> str:
    """red or blue, whichever lies on the +y side (the side zone is on the -y side)."""
    scene = world._controller._driver.scene  # type: ignore[attr-defined]
    return max(("red_block", "blue_block"), key=lambda b: scene.body_position(b)[1])
# Above the shoulder, where the Panda's elbow passes on its way to the blocks; the tool
# centre never comes near it.
OVERHEAD = {"name": "lamp", "min": [0.1, -0.1, 0.7], "max": [0.3, 0.1, 0.9]}
# Beside the blocks: the tool stays 6 cm away, the 20 cm wide hand does not.
SIDE = {"name": "side_post", "min": [0.45, -0.15, 0.15], "max": [0.55, -0.06, 0.4]}


@pytest.mark.parametrize(("zone", "part"), [(OVERHEAD, r"panda_link\d"),
                                            (SIDE, r"panda_(hand|leftfinger|rightfinger)")],
                         ids=["elbow-overhead", "hand-side"])
async def test_a_panda_link_entering_a_zone_is_refused_before_motion(
        tmp_path: Path, zone: dict[str, Any], part: str) -> None:
    config = parse_arm_config({"driver": "pybullet", "mode": "sim", "keep_out": [zone],
                               "audit_log": str(tmp_path / "audit.jsonl")})
    box = Toolbox(config=ToolConfig(executor="arm:pybullet", arm=ArmSetup(config)))
    async with Client(build_server(box)) as client:
        eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
            "episode_id"]
        world = box.context.store.peek(eid).world
        assert isinstance(world, ArmWorld)
        scene = world._controller._driver.scene  # type: ignore[attr-defined]
        joints = scene.arm_positions()
        action = f"move(green_block, on, {target_away_from_side(world)})"
        out = structured(await client.call_tool("execute_actions", {"episode_id": eid,
                                                                    "actions": [action]}))
        assert scene.arm_positions() == joints  # refused before anything moved
        await client.call_tool("end_episode", {"episode_id": eid})
    violation = out["violation"]
    assert violation["constraint"] == "arm_refused"
    message = violation["message"]
    assert re.search(rf"the arm's {part} would come within 0.01 m of keep-out zone "
                     rf"'{zone['name']}' at waypoint \d+/\d+ of segment '[a-z ]+'", message)
    sent = [json.loads(line) for line in (tmp_path / "audit.jsonl").read_text().splitlines()]
    assert not [r for r in sent if r["command"] in ("pick", "place")]
    assert any(r["outcome"] == "refused" and zone["name"] in r["detail"] for r in sent)


async def test_the_tool_centre_alone_would_have_passed(tmp_path: Path) -> None:
    """The zones above are clear of the tool centre's path: only the whole arm sees them."""
    from verigraph.actions.model import MoveAction
    from verigraph.arm import open_arm_world
    from verigraph.arm.planning import MotionPlan
    from verigraph.arm.safety import check_path
    from verigraph.graph.model import SceneGraph

    config = parse_arm_config({"driver": "pybullet", "mode": "sim",
                               "keep_out": [OVERHEAD, SIDE]})
    world = open_arm_world(config, SceneGraph.model_validate(loose_blocks()))
    try:
        plan = world._plan(MoveAction(object="green_block",
                                      target=target_away_from_side(world)))
        assert isinstance(plan, MotionPlan)
        check_path(config, plan.path(world.status().tcp or config.home))
    finally:
        world.close()


async def test_an_xarm_elbow_in_an_overhead_zone_is_refused_before_asking(
        tmp_path: Path) -> None:
    api, user = BlockCellStandIn(), User()
    zone = {"name": "cable_tray", "min": [0.05, -0.1, 0.75], "max": [0.25, 0.1, 0.95]}
    box = xarm_toolbox(tmp_path, api, keep_out=[zone])
    async with Client(build_server(box), elicitation_callback=user) as client:
        eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
            "episode_id"]
        out = structured(await client.call_tool("execute_actions", {"episode_id": eid,
                                                                    "actions": STACK}))
    assert out["violation"]["constraint"] == "arm_refused"
    assert re.search(r"the arm's link\d would come within 0.01 m of keep-out zone "
                     r"'cable_tray' at waypoint \d+/\d+", out["violation"]["message"])
    assert api.motions() == [] and user.asked == []  # never put to the user
