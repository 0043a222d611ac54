"""Transport-free tool functions: the one implementation behind the MCP server, the CLI
and the library.

A tool function takes the context and the tool's validated input model and returns its
output model; the tool table (`registry.TOOL_SPECS`) names each one. Where the library
has a function of the tool's name, the tool function carries the suffix `_tool`
(`validate_plan_tool` calls `verigraph.actions.validate_plan`), so one name never means
two things.

>>> box = Toolbox()
>>> state = box.call("load_scene", {"scene_id": "cup_on_book"})
>>> box.call("validate_action", {"episode_id": state.episode_id,
...                              "action": "move(book, on, shelf)"}).violation.constraint
'object_not_clear'
"""

from verigraph.tools.context import ToolConfig, ToolContext
from verigraph.tools.errors import (
    EpisodeLimitError,
    EpisodeShareError,
    EpisodeStateError,
    FeatureUnavailableError,
    InvalidArgumentsError,
    ToolArgumentError,
    UnknownEpisodeError,
)
from verigraph.tools.registry import TOOL_SPECS, TOOLS, Toolbox, ToolSpec
from verigraph.tools.scenes import ImageResult
from verigraph.tools.store import EpisodeStore, LiveEpisode, TraceEntry, calling_as

__all__ = [
    "TOOLS", "TOOL_SPECS", "LiveEpisode", "EpisodeLimitError", "EpisodeShareError",
    "EpisodeStateError", "EpisodeStore",
    "FeatureUnavailableError", "ImageResult", "InvalidArgumentsError", "ToolArgumentError",
    "ToolConfig", "ToolContext", "ToolSpec", "Toolbox", "TraceEntry", "UnknownEpisodeError",
    "calling_as",
]
