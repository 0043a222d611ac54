"""The one writer of the JSON-RPC errors the server words itself, before or beside the SDK.

stdio answers the lines the SDK would drop (verigraph.server.jsonrpc_screen), HTTP
refuses requests before the SDK reads them (verigraph.server.http); both write
`error_message`. The codes are JSON-RPC 2.0's, as the SDK defines them, plus the one
code of this server's own: a missing or wrong token.
"""

from __future__ import annotations

import json
from typing import Any

from mcp.types import INTERNAL_ERROR, INVALID_PARAMS, INVALID_REQUEST, PARSE_ERROR

__all__ = ["FORBIDDEN", "INTERNAL_ERROR", "INVALID_PARAMS", "INVALID_REQUEST", "PARSE_ERROR",
           "error_bytes", "error_message", "valid_id"]
FORBIDDEN = -32001  # no token, or a wrong one (a server-defined code)


def valid_id(value: Any) -> bool:
    """MCP request ids are strings or integers (not booleans, floats or null)."""
    return isinstance(value, str) or (isinstance(value, int) and not isinstance(value, bool))


def error_message(message: str, *, code: int = INVALID_REQUEST, request_id: Any = None,
                  data: dict[str, Any] | None = None) -> dict[str, Any]:
    """A JSON-RPC error response; an id that is not a valid one becomes null."""
    error: dict[str, Any] = {"code": code, "message": message}
    if data is not None:
        error["data"] = data
    return {"jsonrpc": "2.0", "id": request_id if valid_id(request_id) else None,
            "error": error}


def error_bytes(message: str, *, code: int = INVALID_REQUEST, request_id: Any = None,
                data: dict[str, Any] | None = None) -> bytes:
    """`error_message` as the bytes of a response body."""
    return json.dumps(error_message(message, code=code, request_id=request_id,
                                    data=data)).encode()
