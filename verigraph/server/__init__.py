"""The MCP server: a thin layer over verigraph.tools, for stdio and streamable HTTP."""

from verigraph.server.app import INSTRUCTIONS, build_server
from verigraph.server.http import HttpOptions, http_app, serve_http

__all__ = ["INSTRUCTIONS", "HttpOptions", "build_server", "http_app", "serve_http"]
