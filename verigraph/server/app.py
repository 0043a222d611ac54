"""The VeriGraph MCP server: tools, resources and prompts over one Toolbox."""

from __future__ import annotations

from typing import Any, Literal

from mcp.server.mcpserver import MCPServer

from verigraph import __version__
from verigraph.server.apps import UI_META, AppsGate, episode_apps
from verigraph.server.callers import CallerScope
from verigraph.server.heavy import HeavyCalls, HeavyLimits
from verigraph.server.prompts import PromptGate, register_prompts
from verigraph.server.resources import register_resources
from verigraph.server.tools import ToolCalls, build_tools
from verigraph.tools.context import ToolConfig
from verigraph.tools.executors import enabled_executors
from verigraph.tools.registry import Toolbox

INSTRUCTIONS = """\
VeriGraph checks robot manipulation plans against a scene graph before anything moves.
Edges read `source relation target` ("cup on book": the book carries the cup).
1. load_scene (scene_id, graph or image) returns an episode_id; pass it to every call.
   set_goal, validate_plan, check_goal and solve take goal edges as text ("cup on
   table; spoon in pot"), the nodes taken from the scene.
2. Propose at most k actions at a time (move(object, relation, target), align(...),
   done). validate_action checks one without changing anything; execute_actions runs
   them until the first violation and returns feedback with a concrete fix.
3. After t consecutive failed execute_actions calls the episode stops. Call end_episode
   (the end token) for the verdict. Images: render_scene; to describe a photo with
   your own vision model use get_scene_image, then submit_scene_graph.
4. An episode on an arm (executor arm:<driver>) moves it only for validated actions;
   on a real arm the user approves each call's motions. arm_stop halts it and latches
   a stop that only arm_reset clears; arm_status reports it.
"""



def executors_instruction(config: ToolConfig) -> str:
    """The line of the instructions that names this server's executors and arm."""
    return ("5. Executors on this server (load_scene executor=...; results name the one\n"
            f"   an episode runs on): {enabled_executors(config.executor, config.arm)}.\n")


LogLevel = Literal["DEBUG", "INFO", "WARNING", "ERROR", "CRITICAL"]


def build_server(toolbox: Toolbox | None = None, *, config: ToolConfig | None = None,
                 log_level: LogLevel = "WARNING",
                 heavy: HeavyLimits | None = None) -> MCPServer[Any]:
    """An MCPServer whose tools all run on `toolbox` (a fresh one by default), every
    tools/call through ToolCalls (verigraph.server.tools); heavy calls run on worker
    threads within `heavy`'s concurrency and budget.

    The tool, prompt and resource lists never change while the server runs and nothing
    pushes resource updates, so no protocol era advertises `listChanged` or `subscribe`:
    `subscriptions/listen` (2026-07-28) stays unserved, like `resources/subscribe`.
    """
    toolbox = toolbox or Toolbox(config=config)
    calls = ToolCalls(toolbox, HeavyCalls(heavy))
    tools, app_only = build_tools(calls, meta=UI_META)
    server: MCPServer[Any] = MCPServer(
        "verigraph", title="VeriGraph", version=__version__,
        instructions=INSTRUCTIONS + executors_instruction(toolbox.context.config),
        description="Scene-graph verifier for LLM robot planning",
        middleware=[CallerScope(), calls, AppsGate(), PromptGate()], log_level=log_level,
        extensions=[episode_apps(app_only)], tools=tools, subscriptions=False)
    register_resources(server, toolbox)
    register_prompts(server, toolbox)
    return server
