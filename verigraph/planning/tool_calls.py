"""Where tool calls go: the protocol the loop and the environment call, and the tool
layer in process.

The agent's loop (verigraph.agent.loop) and the environment (verigraph.env) only need
`call(name, arguments) -> structured result`: a `ToolEnvironment`. `InProcessTools`
calls the same tool functions the MCP server wraps (`verigraph.tools.registry.Toolbox`)
without a transport; the benchmark and the environment use it so a thousand episodes do
not pay for a thousand server processes. The agent's MCP client, `McpTools`
(verigraph.agent.environment), is the other implementation. Either raises
`ToolCallError` when a tool reports an error.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Protocol

from pydantic import BaseModel

from verigraph.errors import VeriGraphError


class ToolCallError(VeriGraphError):
    """A tool answered with an error (bad arguments, unknown episode, ...)."""

    def __init__(self, tool: str, message: str) -> None:
        super().__init__(message, field=f"tool {tool}", fix="see the tool's message above")
        self.tool = tool


class ToolEnvironment(Protocol):
    """Anything that runs VeriGraph tools by name and returns their structured output."""

    transport: str

    def call(self, name: str, arguments: Mapping[str, Any]) -> dict[str, Any]:
        """Run one tool; raises ToolCallError when the tool reports an error."""
        ...

    def close(self) -> None:
        ...


class InProcessTools:
    """The tool layer without a transport (same functions the MCP server wraps)."""

    transport = "in-process"

    def __init__(self, toolbox: Any | None = None) -> None:
        from verigraph.tools.registry import Toolbox

        self.toolbox = toolbox or Toolbox()

    def call(self, name: str, arguments: Mapping[str, Any]) -> dict[str, Any]:
        try:
            result = self.toolbox.call(name, dict(arguments))
        except VeriGraphError as exc:
            raise ToolCallError(name, f"Error executing tool {name}: {exc}") from None
        if isinstance(result, BaseModel):
            return result.model_dump(mode="json")
        raise ToolCallError(name, f"tool {name} returned no structured result")

    def close(self) -> None:
        return None
