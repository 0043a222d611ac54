"""The server's tool table: the registry's tools, then the viewer's app-only tool.

Every tools/call is looked up here (verigraph.server.tools, and the process that
checks large HTTP bodies), so each tool is one row: `view_episode` (drawn for the MCP
Apps episode viewer, a heavy call) differs from the others only by its row's fields,
`visibility=("app",)` and `lane="heavy"`.
"""

from __future__ import annotations

from dataclasses import replace

from verigraph.tools.registry import TOOL_SPECS, HeavyWhen, ToolSpec
from verigraph.viewer import VIEW_SPEC

SERVER_TOOL_SPECS: tuple[ToolSpec, ...] = (*TOOL_SPECS, replace(
    VIEW_SPEC, visibility=("app",), lane="heavy",
    heavy_when=HeavyWhen(graphs=("graph", "goal"), plans=("plan",))))
SERVER_TOOLS: dict[str, ToolSpec] = {spec.name: spec for spec in SERVER_TOOL_SPECS}
