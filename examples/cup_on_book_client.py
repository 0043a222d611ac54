"""The paper's cup-on-book example, played through the VeriGraph MCP server over stdio.

A scripted client (no LLM) starts `verigraph serve`, makes the classic mistake first
(moving the book while the cup stands on it), reads the verifier's feedback, fixes the
plan, and ends the episode. Every call and its result is printed.

Run: python examples/cup_on_book_client.py [--image out/cup_on_book.png]
"""

from __future__ import annotations

import argparse
import asyncio
import base64
import json
import os
import sys
from pathlib import Path
from typing import Any

from mcp import Client, StdioServerParameters
from mcp.types import CallToolResult

REPO = Path(__file__).resolve().parents[1]


def show(name: str, args: dict[str, Any], result: CallToolResult) -> None:
    print(f"\n-> {name}({json.dumps(args)})")
    for block in result.content:
        if block.type == "text":
            print("<- " + block.text.replace("\n", "\n   "))
        elif block.type == "image":
            print(f"<- [{block.mime_type} image, {len(block.data) * 3 // 4} bytes]")
    if result.is_error:
        print("   (tool error)")


async def play(image_path: Path | None) -> int:
    env = {"PYTHONPATH": str(REPO), "PYTHONUNBUFFERED": "1"}
    server = StdioServerParameters(command=sys.executable, args=["-m", "verigraph", "serve"],
                                   env={**env, **{k: v for k, v in os.environ.items()
                                                  if k.startswith("VERIGRAPH_")}})
    async with Client(server) as client:
        async def call(name: str, **args: Any) -> dict[str, Any]:
            result = await client.call_tool(name, args)
            show(name, args, result)
            return result.structured_content or {}

        state = await call("load_scene", scene_id="cup_on_book")
        episode = state["episode_id"]
        print(f"   current graph: {'; '.join(_sentences(state['graph']))}")
        print(f"   goal: {state['instruction']}")

        # The naive plan: put the book on the shelf. The cup is standing on it.
        check = await call("validate_action", episode_id=episode,
                           action="move(book, on, shelf)")
        print(f"   blocking: {check['violation']['blocking']}")
        failed = await call("execute_actions", episode_id=episode,
                            actions=["move(book, on, shelf)"])
        print(f"   tau after a failed call: {failed['tau']} of t={failed['t']}")

        # The fix the feedback suggests: clear the book first, then move it.
        done = await call("execute_actions", episode_id=episode,
                          actions=["move(cup, on, desk)", "move(book, on, shelf)", "done"])
        print(f"   new graph: {'; '.join(_sentences(done['graph']))}")
        await call("check_goal", episode_id=episode)

        picture = await client.call_tool("render_scene", {"episode_id": episode})
        show("render_scene", {"episode_id": episode}, picture)
        if image_path is not None and picture.content and picture.content[0].type == "image":
            image_path.parent.mkdir(parents=True, exist_ok=True)
            image_path.write_bytes(base64.b64decode(picture.content[0].data))
            print(f"   saved {image_path}")

        verdict = await call("end_episode", episode_id=episode)
        return 0 if verdict.get("success") else 1


def _sentences(graph: dict[str, Any]) -> list[str]:
    return [f"{e['source']} {e['relation']} {e['target']}" for e in graph["edges"]]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--image", type=Path, default=None,
                        help="save the rendered final scene here (PNG)")
    args = parser.parse_args()
    return asyncio.run(play(args.image))


if __name__ == "__main__":
    sys.exit(main())
