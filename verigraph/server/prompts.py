"""MCP prompts: the iterative planner, the direct planner and scene-graph generation.

Each is the matching template in verigraph/prompts filled from an episode (when an
episode_id is given) or from a built-in scene, so a chat assistant can use it as is.
Errors are JSON-RPC invalid params (-32602) with the real reason: an unknown prompt
names the known ones (PromptGate), a bad argument says what to send instead.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable
from typing import Annotated, Any

from mcp.server.context import CallNext, HandlerResult, ServerRequestContext
from mcp.server.mcpserver import MCPServer
from mcp.shared.exceptions import MCPError
from mcp.types import INVALID_PARAMS
from pydantic import Field

from verigraph.errors import VeriGraphError
from verigraph.graph.builtin_scenes import BUILTIN_SCENES
from verigraph.graph.state import WorldState
from verigraph.prompts.filling import fill_planner_prompt, scene_graph_prompt
from verigraph.tools.fields import builtin_scene, dictionary_for
from verigraph.tools.registry import Toolbox
from verigraph.tools.scenes import episode_dictionary

EpisodeArg = Annotated[str, Field(
    description="an episode_id from load_scene: fill in its graph, goal, history and last "
                "feedback (optional)")]
SceneArg = Annotated[str, Field(
    description=f"built-in scene used without episode_id: {', '.join(BUILTIN_SCENES)} "
                "(default cup_on_book)")]
DictionaryArg = Annotated[str, Field(
    description="dictionary D: blocks, kitchen, tableware, tangram or all (default all)")]
TaskArg = Annotated[str, Field(description="what the scene graph is for (optional)")]
ImageEpisodeArg = Annotated[str, Field(
    description="an episode_id from load_scene whose image the graph describes (optional)")]

PROMPT_ARGUMENTS = {
    "iterative_planner": ("episode_id", "scene_id"),
    "direct_planner": ("episode_id", "scene_id"),
    "scene_graph_generation": ("dictionary", "task", "episode_id"),
}


def _planner(toolbox: Toolbox, name: str, episode_id: str, scene_id: str) -> str:
    if episode_id:
        with toolbox.context.store.use(episode_id) as episode:
            state = episode.require_state().copy()
            return fill_planner_prompt(name, state, episode.goal, k=episode.k,
                                  executed=list(episode.executed),
                                  violation=episode.last_violation, calls=episode.calls,
                                  instruction=episode.instruction, episode_id=episode.id)
    graph, goal = builtin_scene(scene_id or "cup_on_book")
    text = fill_planner_prompt(name, WorldState.from_graph(graph), goal)
    return (text + f"\n(To verify with the VeriGraph tools, first call load_scene(scene_id="
            f"\"{scene_id or 'cup_on_book'}\") and use the episode_id it returns.)\n")


def _doc(text: str) -> str:
    """One line from a wrapped literal: no leftover indentation in the description."""
    return " ".join(text.split())


def register_prompts(server: MCPServer[Any], toolbox: Toolbox) -> None:
    @server.prompt(name="iterative_planner", title="Iterative planner (Algorithm 1)",
                   description=_doc("""Plan at most k actions per answer with verifier
                   feedback; end with done. With episode_id the episode's current graph,
                   goal, history and last feedback are filled in; otherwise a built-in
                   scene (scene_id, default cup_on_book)."""))
    def iterative_planner(episode_id: EpisodeArg = "", scene_id: SceneArg = "") -> str:
        return _guard(lambda: _planner(toolbox, "iterative_planner", episode_id, scene_id))

    @server.prompt(name="direct_planner", title="Direct (one-shot) planner",
                   description="Write the whole plan at once, ending with done.")
    def direct_planner(episode_id: EpisodeArg = "", scene_id: SceneArg = "") -> str:
        return _guard(lambda: _planner(toolbox, "direct_planner", episode_id, scene_id))

    @server.prompt(name="scene_graph_generation", title="Scene-graph generation",
                   description="Turn an image into a scene graph over dictionary D and "
                               "relations R.")
    def scene_graph_generation(dictionary: DictionaryArg = "all", task: TaskArg = "",
                               episode_id: ImageEpisodeArg = "") -> str:
        def build() -> str:
            d = dictionary_for(dictionary or None)
            if episode_id and dictionary in ("", "all"):  # the episode's, its own labels too
                d = episode_dictionary(toolbox.context, episode_id)
            return scene_graph_prompt(d, task or None, episode_id=episode_id or None)
        return _guard(build)


def _guard(build: Callable[[], str]) -> str:
    """The prompt text, or invalid params carrying the real reason and fix."""
    try:
        return build()
    except VeriGraphError as exc:
        raise MCPError(INVALID_PARAMS, str(exc)) from None


class PromptGate:
    """Server middleware: prompts/get with an unknown prompt or argument name is invalid
    params naming what exists (the SDK would answer with code 0)."""

    async def __call__(self, ctx: ServerRequestContext[Any, Any], call_next: CallNext
                       ) -> HandlerResult:
        if ctx.method != "prompts/get" or ctx.params is None:
            return await call_next(ctx)
        name = ctx.params.get("name")
        if name not in PROMPT_ARGUMENTS:
            shown = str(name)[:64]
            near = difflib.get_close_matches(shown, list(PROMPT_ARGUMENTS), n=1)
            hint = f"did you mean {near[0]}? " if near else ""
            raise MCPError(INVALID_PARAMS, f"no prompt named '{shown}' ({hint}prompts: "
                                           f"{', '.join(PROMPT_ARGUMENTS)})")
        known = PROMPT_ARGUMENTS[name]
        for argument in ctx.params.get("arguments") or {}:
            if argument not in known:
                raise MCPError(INVALID_PARAMS, f"{name} has no argument '{str(argument)[:64]}' "
                                               f"(it takes {', '.join(known)})")
        return await call_next(ctx)
