"""Every tools/call, in one file: `ToolCalls.__call__` reads top to bottom.

1. The tool and its arguments, checked with the tool's own input model (never the SDK's
   looser one: it ignores unknown names and decodes JSON-looking strings), or taken
   from the slot of a large HTTP body that a child process has checked already.
2. Confirmation, where the row's `confirmation` says and the call may make an arm act:
   the call is handed to the SDK, whose resolvers ask the user (verigraph.server.
   confirmation) and whose registered function (`tool_function`) then goes on at 3.
3. Lane, from the row's fields: `lane`, and for an inline tool `heavy_when`
   (its inputs that make a call heavy), the episode's size and the store; an inline
   call runs on the event loop, a heavy one on a worker thread within its budget and
   its connection's share (verigraph.server.heavy).
4. The run: `Toolbox.run`, inside the arm's scope when an arm is involved (only then
   is anything of verigraph.arm entered).
5. The result: structured content and a one-line summary (image tools: image content).

Each registration's signature is generated from the tool's input model, so the wire
inputSchema and the library's model cannot drift apart. Nothing here is HTTP's: a large
body's slot is read from the request by its key (verigraph.server.http.offload fills it).
"""

from __future__ import annotations

import inspect
import logging
from collections.abc import Callable
from contextvars import ContextVar
from dataclasses import dataclass, replace
from typing import Annotated, Any, Protocol

import anyio.to_thread
from mcp.server.context import CallNext, HandlerResult, ServerRequestContext
from mcp.server.mcpserver import Context
from mcp.server.mcpserver.exceptions import ToolError
from mcp.server.mcpserver.tools import Tool
from mcp.types import CallToolResult, ImageContent, TextContent, ToolAnnotations
from pydantic import BaseModel, Field

from verigraph.errors import VeriGraphError
from verigraph.server.heavy import HeavyCalls
from verigraph.server.schemas import compact_input_schema, compact_output_schema
from verigraph.server.table import SERVER_TOOL_SPECS, SERVER_TOOLS
from verigraph.tools.errors import UnknownEpisodeError
from verigraph.tools.images import png_base64
from verigraph.tools.registry import BIG_GRAPH_ITEMS, Toolbox, ToolSpec, parse_arguments
from verigraph.tools.scenes import ImageResult
from verigraph.tools.store import WouldBlock, non_blocking

log = logging.getLogger("verigraph.server")
SLOT_KEY = "verigraph.call_slot"  # the ASGI scope key of a large HTTP body's slot
CONTEXT_PARAM = "mcp_context"  # the SDK's Context, for the registered functions
# A confirmed call's input as step 1 checked it (the tool's name and the input), while
# the SDK runs the confirmation branch of that request: read once, not again per resolver.
_CHECKED: ContextVar[tuple[str, BaseModel] | None] = ContextVar("verigraph_checked_input",
                                                                default=None)


class LargeBodySlot(Protocol):
    """What an HTTP request's large body left for its call (verigraph.server.http.offload):
    the arguments, checked in a child process, and room for a large result as bytes."""

    params: BaseModel | None  # the tool's validated input, if the arguments are valid
    error: str | None  # else what is wrong with them

    def keep(self, result: BaseModel) -> dict[str, Any] | None:
        """Keep a large result as JSON bytes; the placeholder to answer with (None: the
        result is small, answer it as is)."""


@dataclass(frozen=True)
class Origin:
    """Where a call comes from, as its path needs it (words as in docs/architecture.md)."""

    connection: str  # "host:port" of the HTTP connection, or "stdio": its heavy-call share
    client_name: str  # the MCP client's name and session, for the arm's audit log
    slot: LargeBodySlot | None = None  # a large HTTP body's slot (None over stdio)

    @classmethod
    def of(cls, ctx: ServerRequestContext[Any, Any], with_slot: bool = True) -> Origin:
        request = ctx.request
        peer = getattr(request, "client", None)
        scope = getattr(request, "scope", None)
        slot = scope.get(SLOT_KEY) if with_slot and isinstance(scope, dict) else None
        return cls(f"{peer.host}:{peer.port}" if peer else "stdio", client_name(ctx.session),
                   slot)


def client_name(session: Any) -> str:
    """The client name behind `session` for the audit log: its declared name and version,
    and the session (a client name is not an identity; the id tells sessions apart)."""
    params = getattr(session, "client_params", None)
    info = getattr(params, "client_info", None)
    name = f"{info.name} {info.version}" if info is not None else "unnamed client"
    return f"{name} (connection {id(session):x})"


class ToolCalls:
    """Server middleware that runs every tools/call of a tool in the table (see the
    module docstring); other requests, and calls of unknown tools, go to the SDK."""

    def __init__(self, toolbox: Toolbox, heavy: HeavyCalls,
                 specs: dict[str, ToolSpec] = SERVER_TOOLS) -> None:
        self.toolbox = toolbox
        self.heavy = heavy
        self.specs = specs
        config = toolbox.context.config
        self.has_arm = config.arm is not None or config.executor.startswith("arm")
        # A durable store reads and writes on every call: trying the loop first would only
        # run the tool's checks twice before it hops to a worker thread anyway.
        self.store_blocks = toolbox.context.store.blocking_io
        self.default_opens_world = config.executor != "graph"

    async def __call__(self, ctx: ServerRequestContext[Any, Any], call_next: CallNext
                       ) -> HandlerResult:
        if ctx.method != "tools/call" or ctx.params is None:
            return await call_next(ctx)
        origin = Origin.of(ctx)
        name = ctx.params.get("name")
        # 1. The tool and its arguments.
        if origin.slot is not None and origin.slot.error is not None:
            return error_result(str(name), origin.slot.error)  # found by the child process
        spec = self.specs.get(name) if isinstance(name, str) else None
        if spec is None:
            return await call_next(with_arguments(ctx, origin.slot))  # the SDK's "unknown"
        try:
            params = await self.arguments(spec, ctx.params.get("arguments"), origin)
        except VeriGraphError as exc:
            return error_result(spec.name, exc)
        # 2. Confirmation: the SDK's resolvers ask, then `tool_function` goes on at 3.
        answers: dict[str, Any] | None = None
        if spec.confirmation is not None:
            if self.may_ask(spec, params):
                checked = _CHECKED.set((spec.name, params))  # for the resolvers and `call`
                try:
                    return await call_next(with_arguments(ctx, origin.slot))
                finally:
                    _CHECKED.reset(checked)
            answers = {}  # the empty approval the resolvers would give: nothing to ask
        # 3.-5. Placed, run, turned into a result.
        try:
            return await self.execute(spec, params, origin, answers)
        except ToolError as exc:
            log.info("Tool %r failed: %r", spec.name, str(exc))
            return error_result(spec.name, exc)
        except Exception:  # a bug: logged in full, the client learns only that
            log.exception("Tool %r raised an unexpected exception", spec.name)
            return CallToolResult(content=[TextContent(
                type="text", text=f"Error executing tool {spec.name}")], is_error=True)

    async def arguments(self, spec: ToolSpec, arguments: Any, origin: Origin) -> BaseModel:
        """The tool's input: checked already (a large HTTP body), or parsed here, on a
        worker thread if its size would hold the event loop."""
        if origin.slot is not None and origin.slot.params is not None:
            return origin.slot.params
        if spec.heavy_when.large(arguments):
            return await self.heavy.run(lambda: parse_arguments(spec, arguments, large=True),
                                        f"{spec.name} arguments", origin.connection)
        return parse_arguments(spec, arguments, large=False)

    async def execute(self, spec: ToolSpec, params: BaseModel, origin: Origin,
                      answers: dict[str, Any] | None) -> CallToolResult:
        """Steps 3 to 5 on validated input; `answers`: the resolved confirmation (None for
        a tool that asks nothing). A tool's VeriGraphError comes out as a ToolError."""
        if self.arm_involved(params):
            from verigraph.server.confirmation import arm_call  # only where an arm is

            async with arm_call(spec, self.toolbox, params, answers, origin.client_name):
                return await self.placed(spec, params, origin)
        return await self.placed(spec, params, origin)

    async def placed(self, spec: ToolSpec, params: BaseModel, origin: Origin
                     ) -> CallToolResult:
        lane = self.lane(spec, params)
        if lane == "inline":  # a thread hop costs more than the verification itself
            try:
                with non_blocking():
                    return self.result(spec, params)
            except WouldBlock:  # the episode is busy: wait for it on a worker thread
                lane = "heavy"
        if lane == "heavy":
            try:
                return await self.heavy.run(lambda: self.result(spec, params, origin.slot),
                                            spec.name, origin.connection)
            except VeriGraphError as exc:  # its budget, stopped outside the tool's code
                raise ToolError(str(exc)) from None
        # The arm's controls answer while a motion runs: a worker thread outside the heavy
        # queue, and for arm_stop one of its own, waiting on nothing.
        own = anyio.CapacityLimiter(1) if lane == "own_thread" else None
        return await anyio.to_thread.run_sync(self.result, spec, params, limiter=own)

    def lane(self, spec: ToolSpec, params: BaseModel) -> str:
        """The row's `lane`; an inline tool's call is heavy when its input says so
        (`heavy_when`), when it works on a large episode, when the store blocks, or when
        it may open a world (the server's default executor is not the graph)."""
        if spec.lane != "inline":
            return spec.lane
        if self.store_blocks or (spec.opens_world and self.default_opens_world) \
                or spec.heavy_when(params) or self.big_episode(spec, params):
            return "heavy"
        return "inline"

    def result(self, spec: ToolSpec, params: BaseModel, slot: LargeBodySlot | None = None
               ) -> CallToolResult:
        """Run the tool and turn its result into the answer; with `slot` (a heavy call of
        a large HTTP body, on its worker thread) a large structured result is kept as
        bytes and answered by a placeholder (verigraph.server.http.offload)."""
        try:
            result = self.toolbox.run(spec, params)
        except VeriGraphError as exc:
            raise ToolError(str(exc)) from None
        return to_result(spec, result, slot)

    def big_episode(self, spec: ToolSpec, params: BaseModel) -> bool:
        """Whether the call works on (and mostly returns) a large episode graph; a tool
        whose work does not grow with the episode (validate_action answers in O(degree))
        stays on the loop."""
        episode_id = getattr(params, "episode_id", None)
        if not spec.episode_sized or not isinstance(episode_id, str):
            return False
        try:
            state = self.toolbox.context.store.peek(episode_id).state
        except VeriGraphError:
            return False  # the tool reports it
        return state is not None and len(state.objects) > BIG_GRAPH_ITEMS

    def arm_involved(self, params: BaseModel) -> bool:
        """Whether this call may touch an arm: never on a server without one; on one with
        an arm, unless the call is on an existing episode that runs on the graph or the
        simulator."""
        if not self.has_arm:
            return False
        episode_id = getattr(params, "episode_id", None)
        if not isinstance(episode_id, str):
            return True  # a new episode, or the server's arm itself
        try:
            executor = self.toolbox.context.store.peek(episode_id).executor
        except UnknownEpisodeError:
            return True  # the tool reports it, in the arm's scope as before
        return executor.startswith("arm")

    def may_ask(self, spec: ToolSpec, params: BaseModel) -> bool:
        """Whether a confirmed tool's call may have something to ask: any doubt (a tool
        that does not move the arm, such as arm_reset; no such episode; an arm) leaves it
        to the SDK's resolvers. execute_actions on an episode without an arm asks
        nothing."""
        return not spec.moves_arm or self.arm_involved(params)


def to_result(spec: ToolSpec, result: BaseModel | ImageResult,
              slot: LargeBodySlot | None = None) -> CallToolResult:
    """Structured content + summary text, or image content for the image-only tools. The
    result is dumped once: its JSON-ready dict is the structured content and what the
    summary may render (a plan report's text), unless a large body keeps it as bytes."""
    if isinstance(result, ImageResult):
        content: list[ImageContent | TextContent] = [ImageContent(
            type="image", data=png_base64(result.png),
            mime_type=result.mime_type)]
        if result.text:
            content.append(TextContent(type="text", text=result.text))
        return CallToolResult(content=list(content))
    placeholder = slot.keep(result) if slot is not None else None
    data = result.model_dump(mode="json") if placeholder is None else None
    summary = [TextContent(type="text", text=spec.summary(result, data))]
    return CallToolResult(content=list(summary), structured_content=(
        placeholder if placeholder is not None else data))


def error_result(name: str, error: object) -> CallToolResult:
    return CallToolResult(content=[TextContent(
        type="text", text=f"Error executing tool {name}: {error}")], is_error=True)


def with_arguments(ctx: ServerRequestContext[Any, Any], slot: LargeBodySlot | None
                   ) -> ServerRequestContext[Any, Any]:
    """`ctx` as the SDK needs it when it runs the tool itself: with the arguments a large
    body had taken out (as the validated input's JSON) put back."""
    if slot is None or slot.params is None or ctx.params is None:
        return ctx
    arguments = slot.params.model_dump(mode="json", exclude_unset=True)
    return replace(ctx, params={**ctx.params, "arguments": arguments})


def request_arguments(spec: ToolSpec, ctx: Context) -> BaseModel:
    """The call's input as step 1 checked it (for the confirmation branch: resolvers and
    the registered function, which run inside step 1's request); parsed from the request
    the SDK handles only when step 1 did not run in this context."""
    checked = _CHECKED.get()
    if checked is not None and checked[0] == spec.name:
        return checked[1]
    params = ctx.request_context.params or {}
    return parse_arguments(spec, params.get("arguments"))


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


def tool_function(spec: ToolSpec, calls: ToolCalls) -> Callable[..., Any]:
    """An async function whose signature mirrors `spec.input_model`: it gives the SDK the
    tool's schema, and it is the SDK's end of step 2. For a tool that can make a real
    arm act, the SDK fills two more parameters by running the confirmation resolvers
    (the user's answer) before it calls this; the function then takes the input step 1
    checked and goes on at step 3 (ToolCalls.execute)."""
    confirmed = spec.confirmation is not None

    async def call(**arguments: Any) -> CallToolResult:
        ctx: Context = arguments.pop(CONTEXT_PARAM)
        answers = None
        if confirmed:
            from verigraph.server.confirmation import take_answers

            answers = take_answers(arguments)
        try:
            params = request_arguments(spec, ctx)
        except VeriGraphError as exc:
            raise ToolError(str(exc)) from None
        # No large-body slot: the SDK checks the result it answers, a placeholder fails.
        origin = Origin.of(ctx.request_context, with_slot=False)
        return await calls.execute(spec, params, origin, answers)

    returns: Any = (Annotated[CallToolResult, spec.output_model] if spec.output_model
                    else CallToolResult)
    extra = [inspect.Parameter(CONTEXT_PARAM, inspect.Parameter.KEYWORD_ONLY,
                               annotation=Context)]
    if confirmed:
        from verigraph.server.confirmation import resolver_parameters

        extra += resolver_parameters(spec, calls.toolbox, request_arguments)
    # The SDK finds the context and the resolvers with typing.get_type_hints, which reads
    # __annotations__.
    call.__annotations__ = {p.name: p.annotation for p in extra}
    call.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
        _parameters(spec.input_model) + extra, return_annotation=returns)
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


def build_tools(calls: ToolCalls, meta: dict[str, dict[str, Any]] | None = None
                ) -> tuple[list[Tool], list[tuple[ToolSpec, Callable[..., Any]]]]:
    """Every row of the table in order (the order tools/list reports): the tools every
    client sees, with the compact published schemas of verigraph.server.schemas and
    `meta` (the MCP Apps viewer link), and the app-only rows with their functions, which
    the Apps extension registers (verigraph.server.apps)."""
    tools = []
    app_only = []
    documented: set[str] = set()
    for spec in SERVER_TOOL_SPECS:
        function = tool_function(spec, calls)
        if "model" not in spec.visibility:
            app_only.append((spec, function))
            continue
        tool = Tool.from_function(
            function, name=spec.name, title=spec.title, description=spec.description,
            annotations=tool_annotations(spec), meta=(meta or {}).get(spec.name))
        tool.parameters = compact_input_schema(tool.parameters, documented)
        if tool.fn_metadata.output_schema is not None:
            tool.fn_metadata.output_schema = compact_output_schema(tool.fn_metadata.output_schema)
        tools.append(tool)
    return tools, app_only
