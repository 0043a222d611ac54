"""The agent's tool calls over a real MCP transport.

The loop only needs a `ToolEnvironment` (verigraph.planning.tool_calls: `call(name,
arguments) -> structured result`). `McpTools` is what `verigraph agent` uses: a real MCP
client (the official SDK) that spawns `verigraph serve` over stdio or connects to a
streamable-HTTP URL, exactly as a chat assistant would. The in-process alternative,
`InProcessTools`, sits in verigraph.planning.tool_calls beside the protocol, because the
environment (verigraph.env) uses it too.
"""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Mapping, Sequence
from typing import Any, TextIO

from verigraph.errors import VeriGraphError
from verigraph.planning.tool_calls import ToolCallError


def serve_command(extra_args: Sequence[str] = ()) -> tuple[str, list[str]]:
    """The command that starts `verigraph serve` over stdio with this interpreter."""
    return sys.executable, ["-m", "verigraph", "serve", "--transport", "stdio", *extra_args]


def _child_env() -> dict[str, str]:
    """Variables the stdio child needs; the SDK passes only a few by default."""
    keep = ("PYTHONPATH", "VIRTUAL_ENV", "HF_HUB_OFFLINE", "LANG", "LC_ALL", "TMPDIR")
    env = {k: v for k, v in os.environ.items() if k in keep or k.startswith("VERIGRAPH_")}
    env["PYTHONUNBUFFERED"] = "1"
    return env


def _errlog() -> TextIO:
    """Where the server child's stderr goes: ours if it is a real file, else the original."""
    for stream in (sys.stderr, sys.__stderr__):
        try:
            if stream is not None and not stream.closed:
                stream.fileno()
                return stream
        except (OSError, ValueError, AttributeError):
            continue
    return open(os.devnull, "w")  # noqa: SIM115 (lives as long as the child)


class McpTools:
    """A real MCP client session, driven synchronously through an anyio portal.

    `McpTools.stdio()` spawns the server; `McpTools.http(url)` connects to one. The
    loop stays synchronous (planners block on HTTP anyway); the portal runs the SDK's
    async client on its own event-loop thread for the lifetime of this object.
    """

    def __init__(self, target: Any, transport: str, *, timeout_s: float = 60.0,
                 http_client: Any | None = None) -> None:
        from anyio.from_thread import start_blocking_portal
        from mcp import Client

        self.transport = transport
        self._stack = contextlib.ExitStack()
        try:
            self._portal = self._stack.enter_context(start_blocking_portal())
            if http_client is not None:  # ours to close, on the portal's event loop
                self._stack.enter_context(self._portal.wrap_async_context_manager(http_client))
            client = Client(target, read_timeout_seconds=timeout_s)
            self._client = self._stack.enter_context(
                self._portal.wrap_async_context_manager(client))
        except BaseException:
            self._stack.close()
            raise
        self.server_name = getattr(getattr(self._client, "server_info", None), "name", None)

    @classmethod
    def stdio(cls, command: str | None = None, args: Sequence[str] | None = None, *,
              cwd: str | None = None, timeout_s: float = 60.0) -> McpTools:
        """Spawn `verigraph serve` (or `command args`) and talk to it over stdio."""
        from mcp import StdioServerParameters, stdio_client

        default_cmd, default_args = serve_command()
        params = StdioServerParameters(command=command or default_cmd,
                                       args=list(args if args is not None else default_args),
                                       env=_child_env(), cwd=cwd)
        try:
            # The SDK's default errlog is sys.stderr as it was at import time; pass the
            # current one (test runners and notebooks swap it) so the child's logs land.
            return cls(stdio_client(params, errlog=_errlog()), "stdio", timeout_s=timeout_s)
        except Exception as exc:
            raise VeriGraphError(f"could not start the MCP server over stdio: {exc}",
                                 field="--transport stdio", value=params.command,
                                 fix="check that `verigraph serve` runs in this environment"
                                 ) from exc

    @classmethod
    def http(cls, url: str, *, token: str | None = None, timeout_s: float = 60.0) -> McpTools:
        """Connect to a streamable-HTTP server such as `verigraph serve --transport http`.

        An unreachable server, a missing token and a refused token each raise their own
        error (verigraph.agent.endpoint) before the session starts."""
        from verigraph.agent.endpoint import check_endpoint

        check_endpoint(url, token, timeout_s=min(timeout_s, 10.0))
        target: Any = url
        http_client = None
        if token:
            import httpx2
            from mcp.client.streamable_http import streamable_http_client

            http_client = httpx2.AsyncClient(headers={"Authorization": f"Bearer {token}"},
                                             timeout=httpx2.Timeout(timeout_s, read=300))
            target = streamable_http_client(url, http_client=http_client)
        try:
            return cls(target, "http", timeout_s=timeout_s, http_client=http_client)
        except Exception as exc:
            raise VeriGraphError(f"could not connect to the MCP server at {url}: {exc}",
                                 field="--url", value=url,
                                 fix="start it with `verigraph serve --transport http` and "
                                     "pass its /mcp URL, e.g. http://127.0.0.1:8000/mcp"
                                 ) from exc

    def call(self, name: str, arguments: Mapping[str, Any]) -> dict[str, Any]:
        client = self._client

        async def run() -> Any:
            return await client.call_tool(name, dict(arguments))

        result = self._portal.call(run)
        if result.is_error:
            text = " ".join(getattr(c, "text", "") for c in result.content).strip()
            raise ToolCallError(name, text or f"tool {name} failed")
        if result.structured_content is None:
            raise ToolCallError(name, f"tool {name} returned no structured content")
        data: dict[str, Any] = dict(result.structured_content)
        return data

    def prompt(self, name: str, arguments: Mapping[str, str]) -> str:
        """An MCP prompt's text (e.g. the server's `iterative_planner` for an episode)."""
        client = self._client

        async def run() -> Any:
            return await client.get_prompt(name, dict(arguments))

        result = self._portal.call(run)
        return "\n".join(getattr(m.content, "text", "") for m in result.messages)

    def list_tools(self) -> list[str]:
        client = self._client

        async def run() -> Any:
            return await client.list_tools()

        return [t.name for t in self._portal.call(run).tools]

    def close(self) -> None:
        self._stack.close()
