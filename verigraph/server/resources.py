"""MCP resources: dictionaries D, relation sets R, the action schema, constraints, the
built-in scenes, and each episode's graph and goal (by URI template).

Everything is JSON. Episode resources need the unguessable episode id, like the tools.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import Any

from mcp.server.mcpserver import MCPServer
from mcp.server.mcpserver.exceptions import ResourceNotFoundError

from verigraph.actions.feedback import CONSTRAINT_DESCRIPTIONS
from verigraph.actions.model import ActionAdapter
from verigraph.errors import VeriGraphError
from verigraph.graph.builtin_scenes import BUILTIN_GOALS, BUILTIN_SCENES
from verigraph.graph.dictionary import BUILTIN_DICTIONARIES, load_dictionary
from verigraph.graph.formula_eval import FORMULA_MEANINGS
from verigraph.server.schemas import without_openapi_keywords
from verigraph.tools.registry import Toolbox
from verigraph.tools.summaries import describe_episode

JSON = "application/json"
RELATION_MEANINGS = {
    "on": "source rests on target; target must be a surface",
    "in": f"source is inside target; target must be a container; {FORMULA_MEANINGS['inside']}",
    "touches": "tangram: side source_side of source lies against side target_side of target",
    "under": "source stands under target, on what target stands on; target must be "
             "furniture (a fixed surface); counts against no capacity",
    "nextto": "source stands next to target, on what target stands on; target must not be "
              f"a room; counts against no capacity; {FORMULA_MEANINGS['nextto']}",
    "inroom": "furniture (a fixed object) source stands in room target",
}


def _dump(data: Any) -> str:
    return json.dumps(data, indent=2, sort_keys=False)


def dictionary_json(name: str) -> str:
    d = load_dictionary(None if name == "all" else name)
    return _dump(d.model_dump(mode="json"))


def relations_json() -> str:
    sets = {name: list(load_dictionary(name).relations) for name in BUILTIN_DICTIONARIES}
    return _dump({"meanings": RELATION_MEANINGS, "by_dictionary": sets,
                  "all": list(load_dictionary(None).relations)})


def scenes_json() -> str:
    out = {}
    for scene_id, make in BUILTIN_SCENES.items():
        goal = BUILTIN_GOALS.get(scene_id)
        out[scene_id] = {"graph": make().model_dump(mode="json", exclude_none=True),
                         "goal": goal().model_dump(mode="json", exclude_none=True)
                         if goal else None}
    return _dump(out)


def register_resources(server: MCPServer[Any], toolbox: Toolbox) -> None:
    for name in (*BUILTIN_DICTIONARIES, "all"):
        server.resource(
            f"verigraph://dictionaries/{name}", name=f"dictionary-{name}",
            title=f"Dictionary D: {name}", mime_type=JSON,
            description=f"object names, synonyms and properties of the {name} dictionary"
        )(_constant(dictionary_json(name)))
    server.resource("verigraph://relations", name="relations", title="Relation sets R",
                    mime_type=JSON, description="relations per dictionary and what they mean"
                    )(_constant(relations_json()))
    server.resource("verigraph://schema/action", name="action-schema",
                    title="Action JSON schema", mime_type=JSON,
                    description="JSON schema of move, open, close, toggle_on, toggle_off, "
                                "align and done actions"
                    )(_constant(_dump(without_openapi_keywords(ActionAdapter.json_schema()))))
    server.resource("verigraph://constraints", name="constraints", title="Constraints C",
                    mime_type=JSON, description="constraint ids used in violation feedback"
                    )(_constant(_dump(CONSTRAINT_DESCRIPTIONS)))
    server.resource("verigraph://scenes", name="scenes", title="Built-in scenes",
                    mime_type=JSON, description="built-in scene ids with graphs and goals"
                    )(_constant(scenes_json()))

    @server.resource("verigraph://episodes/{episode_id}/graph", name="episode-graph",
                     title="Episode graph", mime_type=JSON,
                     description="the current scene graph of an episode")
    def episode_graph(episode_id: str) -> str:
        return _episode_field(toolbox, episode_id, "graph")

    @server.resource("verigraph://episodes/{episode_id}/goal", name="episode-goal",
                     title="Episode goal", mime_type=JSON,
                     description="the goal of an episode (null when none is set)")
    def episode_goal(episode_id: str) -> str:
        return _episode_field(toolbox, episode_id, "goal")


def _constant(text: str) -> Callable[[], str]:
    def read() -> str:
        return text
    return read


def _episode_field(toolbox: Toolbox, episode_id: str, field: str) -> str:
    try:
        with toolbox.context.store.use(episode_id) as episode:
            state = describe_episode(episode)
    except VeriGraphError as exc:
        raise ResourceNotFoundError(str(exc)) from None
    return _dump(state.model_dump(mode="json", exclude_none=True).get(field))
