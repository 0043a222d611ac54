"""The MCP Apps extension (`io.modelcontextprotocol/ui`): the episode viewer inside chat
clients that can show it.

`ui://verigraph/episode` is the viewer (one self-contained HTML file, no network: its
CSP allow-lists are empty). execute_actions, validate_plan, render_scene and get_state
point to it with `_meta.ui.resourceUri`; the viewer asks for the per-step view through
`view_episode`, a tool only apps may call (`visibility: ["app"]`).

Only clients that declare the extension (with the `text/html;profile=mcp-app` MIME
type) see any of it: for the others `AppsGate` removes the `_meta.ui` links, the
app-only tool and the `ui://` resource from the lists, so their tools/list and every
tool result stay exactly as without the extension.
"""

from __future__ import annotations

import inspect
from typing import Annotated, Any

from mcp.server.apps import Apps, ResourceCsp, client_supports_apps
from mcp.server.context import CallNext, HandlerResult, ServerRequestContext
from mcp.server.mcpserver.exceptions import ToolError
from mcp.types import CallToolResult, ToolAnnotations
from pydantic import BaseModel, ValidationError

from verigraph.errors import VeriGraphError
from verigraph.server.heavy import HeavyCalls
from verigraph.server.tools import _parameters, to_result
from verigraph.tools.registry import Toolbox, argument_error
from verigraph.viewer import VIEW_SPEC, EpisodeView, ViewInput, app_html, view

EPISODE_UI = "ui://verigraph/episode"
UI_TOOLS = ("execute_actions", "validate_plan", "render_scene", "get_state")
UI_META: dict[str, dict[str, Any]] = {name: {"ui": {"resourceUri": EPISODE_UI}}
                                      for name in UI_TOOLS}
def _view_function(toolbox: Toolbox, heavy: HeavyCalls) -> Any:
    """view_episode: validate like every tool, then draw as a heavy call (worker thread,
    budget, per-client limit)."""

    def run(params: ViewInput) -> CallToolResult:
        try:
            return to_result(VIEW_SPEC, view(toolbox.context, params))
        except VeriGraphError as exc:
            raise ToolError(str(exc)) from None

    async def view_episode(**arguments: Any) -> CallToolResult:
        try:
            params = ViewInput.model_validate(arguments)
        except ValidationError as exc:
            raise ToolError(str(argument_error(VIEW_SPEC, exc))) from None
        return await heavy.run(lambda: run(params), VIEW_SPEC.name)

    view_episode.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
        _parameters(ViewInput), return_annotation=Annotated[CallToolResult, EpisodeView])
    view_episode.__doc__ = VIEW_SPEC.description
    return view_episode


def episode_apps(toolbox: Toolbox, heavy: HeavyCalls) -> Apps:
    """The extension: the viewer resource and the app-only view tool."""
    apps = Apps()
    apps.add_html_resource(
        EPISODE_UI, app_html(), name="episode-viewer", title="VeriGraph episode viewer",
        description="scene drawing, scene graph and per-step verdicts with a step slider",
        csp=ResourceCsp(connect_domains=[], resource_domains=[], frame_domains=[],
                        base_uri_domains=[]),
        prefers_border=True)
    apps.tool(resource_uri=EPISODE_UI, visibility=["app"], name=VIEW_SPEC.name,
              title=VIEW_SPEC.title, description=VIEW_SPEC.description,
              annotations=ToolAnnotations(title=VIEW_SPEC.title, read_only_hint=True,
                                          idempotent_hint=True, open_world_hint=False)
              )(_view_function(toolbox, heavy))
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
    if not isinstance(meta, dict) or "ui" not in meta:
        return tool
    if meta["ui"].get("visibility") == ["app"]:
        return None
    rest = {k: v for k, v in meta.items() if k != "ui"}
    out = {k: v for k, v in tool.items() if k != "_meta"}
    return {**out, "_meta": rest} if rest else out
