"""The VeriGraph MCP server: tools, resources and prompts over one Toolbox."""

from __future__ import annotations

from typing import Any, Literal

from mcp.server.mcpserver import MCPServer

from verigraph import __version__
from verigraph.server.apps import UI_META, AppsGate, episode_apps, view_executor
from verigraph.server.heavy import HeavyCalls, HeavyLimits
from verigraph.server.prompts import PromptGate, register_prompts
from verigraph.server.resources import register_resources
from verigraph.server.tools import ArgumentGate, build_tools
from verigraph.tools.context import ToolConfig
from verigraph.tools.executors import enabled_executors
from verigraph.tools.registry import Toolbox
from verigraph.viewer import VIEW_SPEC

INSTRUCTIONS = """\
VeriGraph checks robot manipulation plans against a scene graph before anything moves.
Edges read `source relation target` ("cup on book": the book carries the cup).
1. load_scene (scene_id, graph or image) returns an episode_id; pass it to every call.
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
    """An MCPServer whose tools all run on `toolbox` (a fresh one by default); heavy
    calls run on worker threads within `heavy`'s concurrency and budget.

    The tool, prompt and resource lists never change while the server runs and nothing
    pushes resource updates, so no protocol era advertises `listChanged` or `subscribe`:
    `subscriptions/listen` (2026-07-28) stays unserved, like `resources/subscribe`.
    """
    toolbox = toolbox or Toolbox(config=config)
    runner = HeavyCalls(heavy)
    gate = ArgumentGate(runner, toolbox)
    tools, executors = build_tools(toolbox, runner, meta=UI_META)
    view = executors[VIEW_SPEC.name] = view_executor(toolbox, runner)
    gate.specs[VIEW_SPEC.name] = VIEW_SPEC
    server: MCPServer[Any] = MCPServer(
        "verigraph", title="VeriGraph", version=__version__,
        instructions=INSTRUCTIONS + executors_instruction(toolbox.context.config),
        description="Scene-graph verifier for LLM robot planning",
        middleware=[gate, AppsGate(), PromptGate()], log_level=log_level,
        extensions=[episode_apps(view)], tools=tools, subscriptions=False)
    gate.executors = executors
    register_resources(server, toolbox)
    register_prompts(server, toolbox)
    return server
