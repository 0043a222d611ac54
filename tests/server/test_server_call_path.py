"""One small tool call's path: the modules it runs in, and what a stdio server imports.

A call on a graph-only episode never enters verigraph/arm/, the call itself runs in
one server module (verigraph.server.tools), and a stdio server loads nothing of the HTTP
wing (verigraph.server.http)."""

from __future__ import annotations

import subprocess
import sys
import threading
from types import FrameType
from typing import Any

import pytest
from mcp import Client
from mcp_helpers import structured

from verigraph.server import build_server
from verigraph.tools import Toolbox

pytestmark = pytest.mark.fast


async def modules_entered(client: Client, name: str, arguments: dict[str, Any]) -> set[str]:
    """The verigraph modules whose functions run during one call (all threads)."""
    seen, _ = await modules_switched(client, name, arguments)
    return seen


async def modules_switched(client: Client, name: str, arguments: dict[str, Any]
                           ) -> tuple[set[str], int]:
    """The verigraph modules one call runs in, and how often it switches between them
    (a function entered in another module than the one entered last)."""
    entered: list[str] = []

    def profile(frame: FrameType, event: str, arg: Any) -> None:
        if event == "call":
            module = frame.f_globals.get("__name__") or ""
            if module.startswith("verigraph") and (not entered or entered[-1] != module):
                entered.append(module)

    sys.setprofile(profile)
    threading.setprofile(profile)  # type: ignore[arg-type]
    try:
        structured(await client.call_tool(name, arguments))
    finally:
        sys.setprofile(None)
        threading.setprofile(None)  # type: ignore[arg-type]
    return set(entered), max(len(entered) - 1, 0)


@pytest.mark.anyio
async def test_a_small_plan_check_reads_its_scene_goal_and_plan_once() -> None:
    """validate_plan on a built-in scene with a goal as edge text: the scene is not
    rebuilt nor checked again (a built-in's state is indexed once), no built-in goal is
    built beside the one given, and the path stays short (21 modules and 48 switches
    here, in process, the report's one text renderer, `verigraph.reporting`, among them;
    the aim is 14 and 40)."""
    arguments = {"scene_id": "cup_on_book", "goal": "book on shelf",
                 "plan": "move(cup, on, desk)\nmove(book, on, shelf)"}
    async with Client(build_server(Toolbox())) as client:
        await client.call_tool("validate_plan", arguments)  # warm-up
        seen, switches = await modules_switched(client, "validate_plan", arguments)
    again = {"verigraph.graph.builtin_scenes", "verigraph.graph.cycles",
             "verigraph.graph.support", "verigraph.graph.io"}
    assert not seen & again, sorted(seen & again)
    assert len(seen) <= 21, sorted(seen)
    assert switches <= 49, switches


def test_a_stdio_server_imports_nothing_of_the_http_wing() -> None:
    code = ("import sys\n"
            "from verigraph.server import build_server\n"
            "from verigraph.server.stdio import run_stdio\n"
            "build_server()\n"
            "print(sorted(m for m in sys.modules if m.startswith('verigraph.server.http')))\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "[]", done.stdout


def test_the_confirmation_module_imports_nothing_of_the_call_path_that_enters_it() -> None:
    """verigraph.server.tools enters verigraph.server.confirmation (only where an arm is);
    the way back would be an import circle."""
    import ast
    import importlib.util
    from pathlib import Path

    spec = importlib.util.find_spec("verigraph.server.confirmation")  # not imported: no arm
    assert spec is not None and spec.origin is not None
    tree = ast.parse(Path(spec.origin).read_text())
    imported = {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
    imported |= {a.name for node in ast.walk(tree) if isinstance(node, ast.Import)
                 for a in node.names}
    assert "verigraph.server.tools" not in imported, sorted(m for m in imported if m)
