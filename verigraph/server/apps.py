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

import inspect
from typing import Annotated, Any

from mcp.server.apps import Apps, ResourceCsp, client_supports_apps
from mcp.server.context import CallNext, HandlerResult, ServerRequestContext
from mcp.server.mcpserver.exceptions import ToolError
from mcp.types import CallToolResult, ToolAnnotations
from pydantic import BaseModel, ValidationError

from verigraph.errors import VeriGraphError
from verigraph.server.heavy import HeavyCalls
from verigraph.server.scope import current_scope
from verigraph.server.tools import Executor, _parameters, to_result
from verigraph.tools.registry import TOOL_SPECS, Toolbox, argument_error
from verigraph.viewer import VIEW_SPEC, EpisodeView, ViewInput, app_html, view

EPISODE_UI = "ui://verigraph/episode"
UI_TOOLS = tuple(spec.name for spec in TOOL_SPECS if spec.viewer)  # ToolSpec.viewer
# The extension's text (2026-01-26) defines the nested `ui.resourceUri`; the flat
# `ui/resourceUri` key is its deprecated earlier form, which hosts must still read and
# some read alone. Both point to the same viewer until the flat form is removed.
FLAT_UI_KEY = "ui/resourceUri"
UI_META: dict[str, dict[str, Any]] = {
    name: {"ui": {"resourceUri": EPISODE_UI}, FLAT_UI_KEY: EPISODE_UI} for name in UI_TOOLS}


def view_executor(toolbox: Toolbox, heavy: HeavyCalls) -> Executor:
    """view_episode on validated input: drawn as a heavy call (worker thread, budget,
    per-client limit). ArgumentGate checks its arguments and runs it like every tool."""

    def run(params: ViewInput) -> CallToolResult:
        try:
            return to_result(VIEW_SPEC, view(toolbox.context, params))
        except VeriGraphError as exc:
            raise ToolError(str(exc)) from None

    async def execute(params: BaseModel, answers: dict[str, Any] | None = None, *,
                      by_gate: bool = False) -> CallToolResult:
        assert isinstance(params, ViewInput)
        return await heavy.run(lambda: run(params), VIEW_SPEC.name)

    return execute


def _view_function(execute: Executor) -> Any:
    """The SDK's registration of view_episode (its schema, and a direct call when the
    server runs without ArgumentGate): the same executor on the same checked input."""

    async def view_episode(**arguments: Any) -> CallToolResult:
        params = current_scope().params_for(VIEW_SPEC.name)  # validated by ArgumentGate
        if params is None:
            try:
                params = ViewInput.model_validate(arguments)
            except ValidationError as exc:
                raise ToolError(str(argument_error(VIEW_SPEC, exc))) from None
        return await execute(params)

    view_episode.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
        _parameters(ViewInput), return_annotation=Annotated[CallToolResult, EpisodeView])
    view_episode.__doc__ = VIEW_SPEC.description
    return view_episode


def episode_apps(execute: Executor) -> Apps:
    """The extension: the viewer resource and the app-only view tool (run by `execute`,
    see view_executor)."""
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
              )(_view_function(execute))
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
