"""MCP tools as thin wrappers over verigraph.tools: one registration per ToolSpec.

Each wrapper's signature is generated from the tool's pydantic input model, so the
wire inputSchema and the library's model cannot drift apart. The body validates into
that model, runs the tool, and returns structured content plus a one-line summary
(image tools: image content only).

A tools/call's path, all in this file: ArgumentGate opens the call's CallScope (scope),
validates the arguments (or takes them from a large body's slot, offload), then runs
the tool's executor itself, or, when the call may ask the user first (the ToolSpec's
`confirmation`), hands it to the SDK, whose resolvers ask and whose wrapper
(`tool_function`) then runs the same executor. The executor places the call by the
ToolSpec's `placement`: on the event loop, as a heavy call, or on a thread of its own.
"""

from __future__ import annotations

import inspect
import logging
from collections.abc import Awaitable, Callable
from dataclasses import replace
from typing import Annotated, Any

import anyio.to_thread
from mcp.server.context import CallNext, HandlerResult, ServerRequestContext
from mcp.server.mcpserver.exceptions import ToolError
from mcp.server.mcpserver.tools import Tool
from mcp.types import CallToolResult, ImageContent, TextContent, ToolAnnotations
from pydantic import BaseModel, Field, ValidationError

from verigraph.errors import VeriGraphError
from verigraph.server.confirmation import (
    arm_call,
    asks_nothing,
    client_label,
    resolver_parameters,
    take_answers,
)
from verigraph.server.heavy import HeavyCalls
from verigraph.server.offload import offload, slot_of
from verigraph.server.schemas import compact_input_schema, compact_output_schema
from verigraph.server.scope import CallScope, CallSlot, call_scope, current_scope
from verigraph.tools.images import png_base64
from verigraph.tools.registry import TOOL_SPECS, TOOLS, Toolbox, ToolSpec, argument_error
from verigraph.tools.registry import parse_arguments as parse_tool_arguments
from verigraph.tools.scenes import ImageResult
from verigraph.tools.store import WouldBlock, non_blocking

log = logging.getLogger("verigraph.server")


def to_result(spec: ToolSpec, result: BaseModel | ImageResult, splice: bool = False
              ) -> CallToolResult:
    """Structured content + summary text, or image content for the image-only tools.

    With `splice` (on a heavy call's worker thread, for a tool the SDK does not check) a
    large structured result of an HTTP call is serialised here and spliced into the
    answer (see offload)."""
    if isinstance(result, ImageResult):
        content: list[ImageContent | TextContent] = [ImageContent(
            type="image", data=png_base64(result.png),
            mime_type=result.mime_type)]
        if result.text:
            content.append(TextContent(type="text", text=result.text))
        return CallToolResult(content=list(content))
    summary = [TextContent(type="text", text=spec.summary(result))]
    placeholder = offload(result) if splice else None
    return CallToolResult(content=list(summary), structured_content=(
        placeholder if placeholder is not None else result.model_dump(mode="json")))


def _parameters(model: type[BaseModel]) -> list[inspect.Parameter]:
    params = []
    for name, info in model.model_fields.items():
        docs = Field(description=info.description, examples=info.examples)
        annotation: Any = Annotated[(info.annotation, *info.metadata, docs)]
        default = (inspect.Parameter.empty if info.is_required()
                   else info.get_default(call_default_factory=True))
        params.append(inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY,
                                        annotation=annotation, default=default))
    return params


# Arguments that make any tool's call slow (an image to decode, a scene to generate, the
# simulator, an executor that opens a world): such a call runs as a heavy call.
SLOW_ARGUMENTS = ("image", "generator", "simulate", "executor")


BIG_GRAPH_ITEMS = 300  # nodes or edges
BIG_PLAN_ITEMS = 100
BIG_PLAN_CHARS = 2000
BIG_IMAGE_CHARS = 100_000


def _field(obj: Any, name: str) -> Any:
    return obj.get(name) if isinstance(obj, dict) else getattr(obj, name, None)


def large_input(arguments: Any) -> bool:
    """Whether a call's input, raw JSON arguments or the validated model alike, is large
    enough that checking or running it would hold the event loop: a graph (or goal graph)
    of more than 300 nodes or edges, a plan of more than 100 items or 2,000 characters, an
    image of more than 100,000 characters."""
    goal = _field(arguments, "goal")
    for graph in (_field(arguments, "graph"), _field(goal, "graph")):
        if any(isinstance(items := _field(graph, key), list) and len(items) > BIG_GRAPH_ITEMS
               for key in ("nodes", "edges")):
            return True
    image, plan = _field(arguments, "image"), _field(arguments, "plan")
    return (isinstance(image, str) and len(image) > BIG_IMAGE_CHARS) or (
        isinstance(plan, str) and len(plan) > BIG_PLAN_CHARS) or (
        isinstance(plan, list) and len(plan) > BIG_PLAN_ITEMS)


def may_block(spec: ToolSpec, params: BaseModel) -> bool:
    """Whether a call could hold the event loop for long (decode, render, simulate, search,
    or a large graph or plan)."""
    return spec.placement == "heavy" or any(getattr(params, a, None) for a in SLOW_ARGUMENTS) \
        or large_input(params)


def big_episode(toolbox: Toolbox, spec: ToolSpec, params: BaseModel) -> bool:
    """Whether the call works on (and mostly returns) a large episode graph: then its
    result alone takes long to build, so it runs as a heavy call. A tool whose work does
    not grow with the episode (validate_action answers in O(degree)) stays on the loop."""
    episode_id = getattr(params, "episode_id", None)
    if not spec.episode_sized or not isinstance(episode_id, str):
        return False
    try:
        state = toolbox.context.store.peek(episode_id).state
    except VeriGraphError:
        return False  # the tool reports it
    return state is not None and len(state.objects) > BIG_GRAPH_ITEMS


Executor = Callable[..., Awaitable[CallToolResult]]


def tool_executor(spec: ToolSpec, toolbox: Toolbox, heavy: HeavyCalls) -> Executor:
    """Run the tool on validated input where its ToolSpec's `placement` says.

    Fast calls run directly on the event loop: a thread hop costs more than the
    verification itself. A call that could block (slow tool, busy episode, simulator,
    large input) runs on a worker thread within its budget (see heavy). The arm's
    controls answer while a motion runs: a worker thread outside the heavy queue, and
    for arm_stop a thread of its own, so the stop path waits on nothing (not even
    calls that hold the shared worker threads).
    """
    slow_default = spec.opens_world and toolbox.context.config.executor != "graph"
    # A durable store reads and writes on every call: trying the loop first would only
    # run the tool's checks twice before it hops to a worker thread anyway.
    off_loop = slow_default or toolbox.context.store.blocking_io

    def run(params: BaseModel, splice: bool = False) -> CallToolResult:
        try:
            return to_result(spec, toolbox.run(spec, params), splice)
        except VeriGraphError as exc:
            raise ToolError(str(exc)) from None

    async def placed(params: BaseModel, splice: bool) -> CallToolResult:
        if spec.placement in ("thread", "own_thread"):  # never behind what they interrupt
            own = anyio.CapacityLimiter(1) if spec.placement == "own_thread" else None
            return await anyio.to_thread.run_sync(run, params, limiter=own)
        if not (off_loop or may_block(spec, params) or big_episode(toolbox, spec, params)):
            try:
                with non_blocking():
                    return run(params)
            except WouldBlock:
                pass
        return await heavy.run(lambda: run(params, splice), spec.name)

    async def execute(params: BaseModel, answers: dict[str, Any] | None = None, *,
                      by_gate: bool = False) -> CallToolResult:
        """`by_gate`: ArgumentGate answers the client itself, so a large result may be
        spliced in as bytes; the SDK checks what it answers, which a placeholder fails."""
        # The arm's scope of the call: audit identity, confirmation, heartbeat, deadman.
        async with arm_call(spec, toolbox, params, answers):
            return await placed(params, splice=by_gate)

    return execute


def tool_function(spec: ToolSpec, toolbox: Toolbox, execute: Executor) -> Callable[..., Any]:
    """An async function whose signature mirrors `spec.input_model` and runs the tool.

    It gives the SDK the tool's schema; ArgumentGate runs most calls itself (see
    there). A tool that can make a real arm act also takes the user's answer, which
    the SDK elicits before the body runs (see confirmation).
    """
    confirmed = spec.confirmation is not None

    async def call(**arguments: Any) -> CallToolResult:
        answers = take_answers(arguments) if confirmed else None
        params = current_scope().params_for(spec.name)  # validated by ArgumentGate
        if params is None:
            try:
                params = spec.input_model.model_validate(arguments)
            except ValidationError as exc:
                raise ToolError(str(argument_error(spec, exc))) from None
        return await execute(params, answers)

    returns: Any = (Annotated[CallToolResult, spec.output_model] if spec.output_model
                    else CallToolResult)
    parameters = _parameters(spec.input_model)
    if confirmed:
        extra = resolver_parameters(spec, toolbox)
        parameters += extra
        # The SDK finds resolvers with typing.get_type_hints, which reads __annotations__.
        call.__annotations__ = {p.name: p.annotation for p in extra}
    call.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
        parameters, return_annotation=returns)
    call.__name__ = spec.name
    call.__qualname__ = spec.name
    call.__doc__ = spec.description
    return call


# The hints' defaults in the MCP specification; a hint equal to its default is not sent.
_HINT_DEFAULTS = {"read_only_hint": False, "destructive_hint": True, "idempotent_hint": False,
                  "open_world_hint": True}


def tool_annotations(spec: ToolSpec) -> ToolAnnotations:
    """The tool's behaviour hints, sending only those that differ from the defaults."""
    hints = {"read_only_hint": spec.read_only, "destructive_hint": spec.destructive,
             "idempotent_hint": spec.idempotent, "open_world_hint": spec.open_world}
    if spec.read_only:
        hints.pop("destructive_hint")  # meaningful only for tools that write
    # The title is the tool's own `title`; no copy inside the annotations.
    return ToolAnnotations.model_validate(
        {k: v for k, v in hints.items() if v != _HINT_DEFAULTS[k]})


def build_tools(toolbox: Toolbox, heavy: HeavyCalls,
                meta: dict[str, dict[str, Any]] | None = None
                ) -> tuple[list[Tool], dict[str, Executor]]:
    """Every tool in TOOL_SPECS order (the order tools/list reports), with the compact
    published schemas of verigraph.server.schemas; `meta` gives some tools a `_meta`
    (the MCP Apps viewer link). Also returns each tool's executor, which ArgumentGate
    runs directly unless the call may ask for a confirmation."""
    tools = []
    executors: dict[str, Executor] = {}
    documented: set[str] = set()
    for spec in TOOL_SPECS:
        execute = executors[spec.name] = tool_executor(spec, toolbox, heavy)
        tool = Tool.from_function(
            tool_function(spec, toolbox, execute), name=spec.name, title=spec.title,
            description=spec.description, annotations=tool_annotations(spec),
            meta=(meta or {}).get(spec.name))
        tool.parameters = compact_input_schema(tool.parameters, documented)
        if tool.fn_metadata.output_schema is not None:
            tool.fn_metadata.output_schema = compact_output_schema(tool.fn_metadata.output_schema)
        tools.append(tool)
    return tools, executors


def _error_result(name: str, error: object) -> CallToolResult:
    return CallToolResult(content=[TextContent(
        type="text", text=f"Error executing tool {name}: {error}")], is_error=True)


def _with_arguments(ctx: ServerRequestContext[Any, Any], slot: CallSlot | None
                    ) -> ServerRequestContext[Any, Any]:
    """`ctx` as the SDK needs it when it runs the tool itself: with the arguments a large
    body had taken out (as the validated input's JSON; offload) put back."""
    if slot is None or slot.params is None or ctx.params is None:
        return ctx
    arguments = slot.params.model_dump(mode="json", exclude_unset=True)
    return replace(ctx, params={**ctx.params, "arguments": arguments})


class ArgumentGate:
    """Server middleware: validate tools/call arguments with our models, from the raw JSON.

    The SDK ignores unknown argument names, words type errors for Python readers, and
    decodes JSON-looking strings (so an episode_id "null" would become None). The gate
    rejects misspelt arguments, answers in terms of fields and fixes, and hands the tool
    exactly the input it validated. It opens the call's CallScope, which the rest of
    the path reads. `specs` holds the registry's tools and the extensions' tools that
    build_server adds (view_episode), so no tool is left to the SDK's looser checks.
    """

    def __init__(self, heavy: HeavyCalls, toolbox: Toolbox) -> None:
        self.heavy = heavy
        self.toolbox = toolbox
        self.executors: dict[str, Executor] = {}  # filled by build_server
        # The tools whose calls it checks: the registry's, and the extensions' tools
        # added by build_server (view_episode), so every tool has one argument path.
        self.specs: dict[str, ToolSpec] = dict(TOOLS)

    async def __call__(self, ctx: ServerRequestContext[Any, Any], call_next: CallNext
                       ) -> HandlerResult:
        if ctx.method != "tools/call" or ctx.params is None:
            return await call_next(ctx)
        peer = getattr(ctx.request, "client", None)
        scope = CallScope(connection=f"{peer.host}:{peer.port}" if peer else "stdio",
                          client=client_label(ctx.session), slot=slot_of(ctx.request))
        with call_scope(scope):
            return await self._gate(ctx, call_next, scope)

    async def _gate(self, ctx: ServerRequestContext[Any, Any], call_next: CallNext,
                    scope: CallScope) -> HandlerResult:
        request = ctx.params or {}
        name = request.get("name")
        slot = scope.slot
        if slot is not None and slot.error is not None:  # found by the checking process
            return _error_result(str(name), slot.error)
        spec = self.specs.get(name) if isinstance(name, str) else None
        if spec is None:
            return await call_next(_with_arguments(ctx, slot))
        try:
            params = await self._params(spec, request.get("arguments"), slot)
        except VeriGraphError as exc:
            return _error_result(spec.name, exc)
        scope.tool, scope.params = spec.name, params
        return await self._run(spec, params, ctx, call_next, slot)

    async def _params(self, spec: ToolSpec, arguments: Any, slot: CallSlot | None
                      ) -> BaseModel:
        """The tool's input: checked already (a large HTTP body, see offload), or parsed
        here (on a worker thread if large)."""
        if slot is not None and slot.params is not None:
            return slot.params
        if large_input(arguments):
            return await self.heavy.run(lambda: parse_tool_arguments(spec, arguments),
                                        f"{spec.name} arguments")
        return parse_tool_arguments(spec, arguments)

    async def _run(self, spec: ToolSpec, params: BaseModel,
                   ctx: ServerRequestContext[Any, Any], call_next: CallNext,
                   slot: CallSlot | None) -> HandlerResult:
        confirmed = spec.confirmation is not None
        if not confirmed or asks_nothing(spec, self.toolbox, params):
            # Run it here: the SDK would validate the arguments and the structured
            # result once more on the event loop (both already hold by construction),
            # which for a large graph stalls every other client. A confirmed tool with
            # nothing to ask gets the empty approval the SDK's resolvers would give.
            answers: dict[str, Any] | None = {} if confirmed else None
            try:
                return await self.executors[spec.name](params, answers, by_gate=True)
            except ToolError as exc:
                log.info("Tool %r failed: %r", spec.name, str(exc))
                return _error_result(spec.name, exc)
            except Exception:  # a bug: logged in full, the client learns only that
                log.exception("Tool %r raised an unexpected exception", spec.name)
                return CallToolResult(content=[TextContent(
                    type="text", text=f"Error executing tool {spec.name}")], is_error=True)
        return await call_next(_with_arguments(ctx, slot))
