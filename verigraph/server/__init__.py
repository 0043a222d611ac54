"""The MCP server: a thin layer over verigraph.tools, for stdio and streamable HTTP.

The HTTP wing (verigraph.server.http) is imported only when asked for, so a stdio
server loads none of it.
"""

from __future__ import annotations

from typing import Any

from verigraph.server.app import INSTRUCTIONS, build_server

__all__ = ["INSTRUCTIONS", "HttpOptions", "build_server", "http_app", "serve_http"]


def __getattr__(name: str) -> Any:
    if name in ("HttpOptions", "http_app", "serve_http"):
        from verigraph.server import http

        return getattr(http, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
