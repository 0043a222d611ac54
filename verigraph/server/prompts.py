"""MCP prompts: the iterative planner, the direct planner and scene-graph generation.

Each is the matching template in verigraph/prompts filled from an episode (when an
episode_id is given) or from a built-in scene, so a chat assistant can use it as is.
"""

from __future__ import annotations

from typing import Any

from mcp.server.mcpserver import MCPServer

from verigraph.errors import VeriGraphError
from verigraph.graph.state import WorldState
from verigraph.prompts.filling import planner_prompt, scene_graph_prompt
from verigraph.tools.fields import builtin_scene, dictionary_for
from verigraph.tools.registry import Toolbox


def _planner(toolbox: Toolbox, name: str, episode_id: str, scene_id: str) -> str:
    if episode_id:
        with toolbox.context.store.use(episode_id) as episode:
            state = episode.require_state().copy()
            return planner_prompt(name, state, episode.goal, k=episode.k,
                                  executed=list(episode.executed),
                                  violation=episode.last_violation, calls=episode.calls,
                                  instruction=episode.instruction, episode_id=episode.id)
    graph, goal = builtin_scene(scene_id or "cup_on_book")
    text = planner_prompt(name, WorldState.from_graph(graph), goal)
    return (text + f"\n(To verify with the VeriGraph tools, first call load_scene(scene_id="
            f"\"{scene_id or 'cup_on_book'}\") and use the episode_id it returns.)\n")


def register_prompts(server: MCPServer[Any], toolbox: Toolbox) -> None:
    @server.prompt(name="iterative_planner", title="Iterative planner (Algorithm 1)")
    def iterative_planner(episode_id: str = "", scene_id: str = "") -> str:
        """Plan at most k actions per answer with verifier feedback; end with done.

        Pass episode_id to fill in that episode's current graph, goal, history and last
        feedback; otherwise a built-in scene (scene_id, default cup_on_book) is used.
        """
        return _guard(lambda: _planner(toolbox, "iterative_planner", episode_id, scene_id))

    @server.prompt(name="direct_planner", title="Direct (one-shot) planner")
    def direct_planner(episode_id: str = "", scene_id: str = "") -> str:
        """Write the whole plan at once, ending with done."""
        return _guard(lambda: _planner(toolbox, "direct_planner", episode_id, scene_id))

    @server.prompt(name="scene_graph_generation", title="Scene-graph generation")
    def scene_graph_generation(dictionary: str = "all", task: str = "",
                               episode_id: str = "") -> str:
        """Turn an image into a scene graph over dictionary D and relations R."""
        def build() -> str:
            return scene_graph_prompt(dictionary_for(dictionary or None), task or None,
                                      episode_id=episode_id or None)
        return _guard(build)


def _guard(build: Any) -> str:
    try:
        text: str = build()
    except VeriGraphError as exc:
        raise ValueError(str(exc)) from None
    return text
