"""A confirmation answered after `confirm_timeout_s` is a no, on every path.

The user is late on purpose (the waiting in the callbacks is the stimulus, not a
synchronisation). The arm is a real-mode xArm whose SDK object is `BlockCellStandIn`
(a stand-in: no controller can run here).
"""

from __future__ import annotations

import json
import time
from pathlib import Path

import anyio
import pytest
from arm_deps import require
from arm_server_helpers import LAYOUT, BlockCellStandIn, User, loose_blocks, xarm_toolbox
from mcp import Client
from mcp.client.context import ClientRequestContext
from mcp.types import ElicitRequestParams, ElicitResult
from mcp_helpers import structured, text

from verigraph.actions.execution import execute_in_world
from verigraph.actions.model import MoveAction
from verigraph.arm import ConfirmationRequest, LayoutLocator, open_arm_world, parse_arm_config
from verigraph.arm.drivers.xarm import XArmDriver
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.server import build_server

require("xarm")

TIMEOUT_S = 0.3


class LateUser(User):
    """Approves, but only after the deadline has passed."""

    async def __call__(self, context: ClientRequestContext,
                       params: ElicitRequestParams) -> ElicitResult:
        await anyio.sleep(TIMEOUT_S * 2)
        return await super().__call__(context, params)


def audit(tmp_path: Path) -> list[dict[str, object]]:
    return [json.loads(line) for line in (tmp_path / "audit.jsonl").read_text().splitlines()]


@pytest.mark.anyio
@pytest.mark.parametrize("mode", ["auto", "legacy"])
async def test_a_late_yes_through_elicitation_moves_nothing(tmp_path: Path, mode: str) -> None:
    api, user = BlockCellStandIn(), LateUser()
    box = xarm_toolbox(tmp_path, api, confirm_timeout_s=TIMEOUT_S)
    async with Client(build_server(box), elicitation_callback=user, mode=mode) as client:
        eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
            "episode_id"]
        result = await client.call_tool("execute_actions", {
            "episode_id": eid, "actions": ["move(green_block, on, red_block)"]})
    assert result.is_error and "after the 0.3 s deadline" in text(result)
    assert "nothing moved" in text(result)
    assert len(user.asked) == 1 and "Answer within 0.3 s" in user.asked[0]
    assert api.motions() == []
    late = [r for r in audit(tmp_path) if r["command"] == "confirm"]
    assert [r["outcome"] for r in late] == ["timeout"]
    assert late[0]["question"] == user.asked[0] and late[0]["episode_id"] == eid


def test_a_late_yes_from_a_synchronous_hook_moves_nothing(tmp_path: Path) -> None:
    config = parse_arm_config({"driver": "xarm", "mode": "real", "host": "192.168.1.185",
                               "audit_log": str(tmp_path / "audit.jsonl"),
                               "confirm_timeout_s": TIMEOUT_S})
    api = BlockCellStandIn()

    def slow_yes(request: ConfirmationRequest) -> bool:
        time.sleep(TIMEOUT_S * 2)  # a person at a console, answering late
        return True

    graph = SceneGraph.model_validate(loose_blocks())
    world = open_arm_world(config, graph, confirm=slow_yes, locator=LayoutLocator(
        parse_arm_config({"driver": "xarm", "layout": LAYOUT}).layout),
        driver=XArmDriver(config, api_factory=lambda host: api))
    _, _, violation, _, _ = execute_in_world(
        WorldState.from_graph(graph),
        [MoveAction(object="green_block", target="red_block")], world)
    assert violation is not None and "past the 0.3 s deadline" in violation.message
    assert api.motions() == []
    assert [r["outcome"] for r in audit(tmp_path) if r["command"] == "confirm"] == ["timeout"]
