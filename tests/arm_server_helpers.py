"""Helpers for the arm-through-the-server tests: an xArm cell built on the SDK stand-in.

No xArm controller can run here, so the vendor SDK's API object is replaced by
`XArmAPIStandIn` (named as such). `BlockCellStandIn` adds blocks that follow its
gripper, and `StandInCamera` reports where they are, so the closed-loop check after a
real-mode motion sees the block move. Everything between the MCP client and the
stand-in is the real code: the server, the tools, the arm adapter, the xArm driver.
"""

from __future__ import annotations

import time
from collections.abc import Collection
from pathlib import Path
from typing import Any

from mcp.client.context import ClientRequestContext
from mcp.types import ElicitRequestParams, ElicitResult
from xarm_standin import XArmAPIStandIn

from verigraph.arm import ArmWorld, ObjectLocation, open_arm_world, parse_arm_config, scoped_confirm
from verigraph.arm.drivers.xarm import XArmDriver
from verigraph.graph.model import SceneGraph
from verigraph.tools import Toolbox, ToolConfig
from verigraph.tools.executors import ArmSetup

BLOCKS = ("red_block", "green_block", "blue_block")
BLOCK = [0.05, 0.05, 0.05]
LAYOUT: dict[str, dict[str, list[float]]] = {
    "table": {"centre": [0.45, 0.0, -0.01], "size": [1.0, 1.2, 0.02]},
    "red_block": {"centre": [0.4, -0.12, 0.025], "size": BLOCK},
    "green_block": {"centre": [0.4, 0.0, 0.025], "size": BLOCK},
    "blue_block": {"centre": [0.4, 0.12, 0.025], "size": BLOCK},
}
MOTION_CALLS = ("set_position", "set_gripper_position", "open_lite6_gripper",
                "close_lite6_gripper")


class User:
    """The person behind an MCP client: answers every confirmation question the same
    way (an elicitation callback) and keeps the questions."""

    def __init__(self, action: str = "accept", approve: bool = True) -> None:
        self.action = action
        self.approve = approve
        self.asked: list[str] = []

    async def __call__(self, context: ClientRequestContext,
                       params: ElicitRequestParams) -> ElicitResult:
        self.asked.append(params.message)
        assert params.requested_schema["properties"]["approve"]["type"] == "boolean"
        if self.action != "accept":
            return ElicitResult(action=self.action)  # type: ignore[arg-type]
        return ElicitResult(action="accept", content={"approve": self.approve})


def loose_blocks() -> dict[str, Any]:
    """The three blocks side by side on the table, as load_scene's JSON graph."""
    return {"dictionary": "blocks",
            "nodes": [{"id": "table", "label": "table"}]
            + [{"id": b, "label": "block"} for b in BLOCKS],
            "edges": [{"source": b, "relation": "on", "target": "table"} for b in BLOCKS]}


class BlockCellStandIn(XArmAPIStandIn):
    """The SDK stand-in plus blocks that follow its gripper (a test double of the cell).

    A block under the tool centre is held when the gripper closes and released when
    it opens, falling onto whatever is below it. Commands the stand-in refuses (fence,
    emergency stop) move nothing, as on the controller.
    """

    def __init__(self, layout: dict[str, dict[str, list[float]]] = LAYOUT) -> None:
        super().__init__()
        self.boxes = {k: (list(v["centre"]), list(v["size"])) for k, v in layout.items()}
        self.held: str | None = None

    def tcp(self) -> tuple[float, float, float]:
        return (self.position[0] / 1000, self.position[1] / 1000, self.position[2] / 1000)

    def set_position(self, *args: Any, **kwargs: Any) -> int:
        code = super().set_position(*args, **kwargs)
        if code == 0 and self.held is not None:
            self.boxes[self.held][0][:] = self.tcp()
        return code

    def set_gripper_position(self, pos: float, *args: Any, **kwargs: Any) -> int:
        code = super().set_gripper_position(pos, *args, **kwargs)
        if code != 0:
            return code
        x, y, z = self.tcp()
        if pos == 0 and self.held is None:
            self.held = next((k for k, (c, s) in self.boxes.items() if k != "table"
                              and abs(c[0] - x) < s[0] / 2 and abs(c[1] - y) < s[1] / 2
                              and abs(c[2] - z) < s[2] / 2), None)
        elif pos > 0 and self.held is not None:
            centre, size = self.boxes[self.held]
            below = [c[2] + s[2] / 2 for k, (c, s) in self.boxes.items()
                     if k != self.held and abs(c[0] - x) < s[0] / 2 and abs(c[1] - y) < s[1] / 2
                     and c[2] + s[2] / 2 <= z]
            centre[:] = [x, y, max(below, default=0.0) + size[2] / 2]
            self.held = None
        return code

    def motions(self) -> list[str]:
        return [name for name, _, _ in self.calls if name in MOTION_CALLS]


class StandInCamera:
    """An ObjectLocator reading the stand-in cell's blocks (the test's camera)."""

    def __init__(self, cell: BlockCellStandIn) -> None:
        self.cell = cell

    def locate(self, object_ids: Collection[str]) -> dict[str, ObjectLocation]:
        now = time.time()
        return {i: ObjectLocation(object_id=i, centre=tuple(c), size=tuple(s),  # type: ignore[arg-type]
                                  timestamp=now, source="stand-in camera")
                for i in object_ids if i in self.cell.boxes
                for c, s in [self.cell.boxes[i]]}


def xarm_toolbox(tmp_path: Path, api: XArmAPIStandIn, *, mode: str = "real",
                 camera: bool = True, **overrides: Any) -> Toolbox:
    """A Toolbox whose default executor is an xArm on `api`, configured like a real one."""
    config = parse_arm_config({"driver": "xarm", "mode": mode, "host": "192.168.1.185",
                               "audit_log": str(tmp_path / "audit.jsonl"), "layout": LAYOUT,
                               **overrides})

    def opener(config: Any, graph: SceneGraph) -> ArmWorld:
        locator = StandInCamera(api) if camera and isinstance(api, BlockCellStandIn) else None
        return open_arm_world(config, graph, confirm=scoped_confirm, locator=locator,
                              driver=XArmDriver(config, api_factory=lambda host: api))

    return Toolbox(config=ToolConfig(executor="arm:xarm", arm=ArmSetup(config, opener)))
