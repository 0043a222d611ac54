"""Plan the block-stacking task through the MCP server and run it on the PyBullet Panda.

An MCP client does what an agent would: load_scene on an `arm:pybullet` episode (mode
sim), ask the server for a plan (solve), send it one action per execute_actions call,
and save the arm's camera view (render_scene) after every step as a PNG. Each action
is validated on the episode graph, again on the scene the arm's cameras observe,
checked against the workspace, executed in the physics and confirmed by locating the
blocks again.

    python examples/arm_stack_blocks_mcp.py --out arm_mcp_frames
    python examples/arm_stack_blocks_mcp.py --out arm_mcp_frames --stdio   # verigraph serve

Needs the `arm` extra: pip install -e '.[arm]'
"""

from __future__ import annotations

import argparse
import base64
import json
import shutil
import sys
from pathlib import Path
from typing import Any

import anyio
from mcp import Client, StdioServerParameters
from mcp.types import CallToolResult, ImageContent

from verigraph.arm import parse_arm_config
from verigraph.server import build_server
from verigraph.tools import Toolbox, ToolConfig
from verigraph.tools.executors import ArmSetup

BLOCKS = ("red_block", "green_block", "blue_block")


def loose_blocks() -> dict[str, Any]:
    """Three blocks side by side on the table."""
    return {"dictionary": "blocks",
            "nodes": [{"id": "table", "label": "table"}]
            + [{"id": b, "label": "block"} for b in BLOCKS],
            "edges": [{"source": b, "relation": "on", "target": "table"} for b in BLOCKS]}


def data(result: CallToolResult) -> dict[str, Any]:
    """The structured answer of a tool, or the error text as an exception."""
    if result.is_error or result.structured_content is None:
        raise RuntimeError(" ".join(getattr(c, "text", "") for c in result.content))
    return result.structured_content


async def save_frame(client: Client, episode_id: str, path: Path) -> Path:
    result = await client.call_tool("render_scene", {"episode_id": episode_id,
                                                     "width": 640, "height": 480})
    image = next(c for c in result.content if isinstance(c, ImageContent))
    path.write_bytes(base64.b64decode(image.data))
    return path


async def stack(client: Client, out: Path) -> int:
    state = data(await client.call_tool("load_scene", {
        "graph": loose_blocks(), "goal": {"predicate": "single_stack"},
        "executor": "arm:pybullet", "instruction": "stack the three blocks"}))
    eid = state["episode_id"]
    print(f"episode on {state['executor']} ({state['arm_mode']}): "
          f"{state['scene_check']['matches'] and 'the cameras see the graph' or 'MISMATCH'}")
    frames = [await save_frame(client, eid, out / "frame_00.png")]
    plan = data(await client.call_tool("solve", {"episode_id": eid}))["plan"]
    print("plan: " + "; ".join(plan))
    for step, action in enumerate([*plan, "done"], start=1):
        result = await client.call_tool("execute_actions", {"episode_id": eid,
                                                            "actions": [action]})
        print(" ".join(getattr(c, "text", "") for c in result.content))
        if action != "done":
            frames.append(await save_frame(client, eid, out / f"frame_{step:02d}.png"))
        if not data(result)["ok"]:
            break
    status = data(await client.call_tool("arm_status", {"episode_id": eid}))
    print(f"arm: {status['commands_sent']} commands sent, last outcome "
          f"{status['last_outcome']}")
    verdict = data(await client.call_tool("end_episode", {"episode_id": eid}))
    print(f"verdict: {verdict['verdict']}; {len(frames)} frames in {out}/")
    return 0 if verdict["success"] else 1


async def run(out: Path, stdio: bool) -> int:
    config = {"driver": "pybullet", "mode": "sim", "audit_log": str(out / "audit.jsonl")}
    if stdio:  # the deployed form: the server is its own process, configured by file
        (out / "arm.json").write_text(json.dumps(config))
        command = shutil.which("verigraph") or sys.executable
        prefix = [] if command != sys.executable else ["-m", "verigraph"]
        server: Any = StdioServerParameters(command=command, args=[
            *prefix, "serve", "--arm-config", str(out / "arm.json")])
    else:
        arm = ArmSetup(parse_arm_config(config))
        server = build_server(Toolbox(config=ToolConfig(executor="arm:pybullet", arm=arm)))
    async with Client(server) as client:
        return await stack(client, out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("arm_mcp_frames"),
                        help="directory for the PNG frames and the audit log")
    parser.add_argument("--stdio", action="store_true",
                        help="start `verigraph serve --arm-config` and talk to it over stdio")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    code: int = anyio.run(run, args.out, args.stdio)
    return code


if __name__ == "__main__":
    sys.exit(main())
