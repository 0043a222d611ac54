"""The MCP Apps extension (`io.modelcontextprotocol/ui`): the episode viewer inside chat
clients that can show it.

`ui://verigraph/episode` is the viewer (one self-contained HTML file, no network: its
CSP allow-lists are empty). The tools whose ToolSpec has `viewer`
(execute_actions, validate_plan, render_scene, get_state) point to it with
`_meta.ui.resourceUri` and the flat `_meta["ui/resourceUri"]` that some hosts read; the
viewer asks for the per-step view through `view_episode`, a tool only apps may call
(`visibility: ["app"]`).

Only clients that declare the extension (with the `text/html;profile=mcp-app` MIME
type) see any of it: for the others `AppsGate` removes the `_meta.ui` links, the
app-only tool and the `ui://` resource from the lists, so their tools/list and every
tool result stay exactly as without the extension.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from mcp.server.apps import Apps, ResourceCsp, client_supports_apps
from mcp.server.context import CallNext, HandlerResult, ServerRequestContext
from pydantic import BaseModel

from verigraph.server.tools import tool_annotations
from verigraph.tools.registry import TOOL_SPECS, ToolSpec
from verigraph.viewer import app_html

EPISODE_UI = "ui://verigraph/episode"
UI_TOOLS = tuple(spec.name for spec in TOOL_SPECS if spec.viewer)  # ToolSpec.viewer
# The extension's text (2026-01-26) defines the nested `ui.resourceUri`; the flat
# `ui/resourceUri` key is its deprecated earlier form, which hosts must still read and
# some read alone. Both point to the same viewer until the flat form is removed.
FLAT_UI_KEY = "ui/resourceUri"
UI_META: dict[str, dict[str, Any]] = {
    name: {"ui": {"resourceUri": EPISODE_UI}, FLAT_UI_KEY: EPISODE_UI} for name in UI_TOOLS}


def episode_apps(app_only: list[tuple[ToolSpec, Callable[..., Any]]]) -> Apps:
    """The extension: the viewer resource, and the table's app-only rows (view_episode)
    with their registered functions (verigraph.server.tools.build_tools)."""
    apps = Apps()
    apps.add_html_resource(
        EPISODE_UI, app_html(), name="episode-viewer", title="VeriGraph episode viewer",
        description="scene drawing, scene graph and per-step verdicts with a step slider",
        csp=ResourceCsp(connect_domains=[], resource_domains=[], frame_domains=[],
                        base_uri_domains=[]),
        prefers_border=True)
    for spec, function in app_only:
        # The extension's registration carries the title in the annotations too.
        annotations = tool_annotations(spec).model_copy(update={"title": spec.title})
        apps.tool(resource_uri=EPISODE_UI, visibility=list(spec.visibility), name=spec.name,
                  title=spec.title, description=spec.description,
                  annotations=annotations)(function)
    return apps


class AppsGate:
    """Server middleware: hide the extension from clients that did not declare it."""

    async def __call__(self, ctx: ServerRequestContext[Any, Any], call_next: CallNext
                       ) -> HandlerResult:
        result = await call_next(ctx)
        if ctx.method not in ("tools/list", "resources/list") or client_supports_apps(ctx):
            return result
        if isinstance(result, BaseModel):
            result = result.model_dump(mode="json", by_alias=True, exclude_none=True)
        if not isinstance(result, dict):
            return result
        if ctx.method == "tools/list" and isinstance(result.get("tools"), list):
            return {**result, "tools": [t for t in map(_without_ui, result["tools"])
                                        if t is not None]}
        if ctx.method == "resources/list" and isinstance(result.get("resources"), list):
            return {**result, "resources": [r for r in result["resources"]
                                            if not str(r.get("uri", "")).startswith("ui://")]}
        return result


def _without_ui(tool: dict[str, Any]) -> dict[str, Any] | None:
    """The tool as a client without the extension sees it (None: an app-only tool)."""
    meta = tool.get("_meta")
    if not isinstance(meta, dict) or not ({"ui", FLAT_UI_KEY} & set(meta)):
        return tool
    if isinstance(meta.get("ui"), dict) and meta["ui"].get("visibility") == ["app"]:
        return None
    rest = {k: v for k, v in meta.items() if k not in ("ui", FLAT_UI_KEY)}
    out = {k: v for k, v in tool.items() if k != "_meta"}
    return {**out, "_meta": rest} if rest else out
