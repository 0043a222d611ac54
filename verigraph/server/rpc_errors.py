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

__all__ = ["FORBIDDEN", "INTERNAL_ERROR", "INVALID_PARAMS", "INVALID_REQUEST", "MAX_ID_CHARS",
           "PARSE_ERROR", "error_bytes", "error_message", "id_problem", "valid_id"]
FORBIDDEN = -32001  # no token, or a wrong one (a server-defined code)
# The longest request id served: clients send counters or UUIDs; a longer one is refused
# for its id (it would be echoed in every answer and log line).
MAX_ID_CHARS = 1024


def valid_id(value: Any) -> bool:
    """MCP request ids are strings or integers (not booleans, floats or null)."""
    return isinstance(value, str) or (isinstance(value, int) and not isinstance(value, bool))


def id_problem(request_id: Any) -> str | None:
    """Why a request's id is refused (None: it is served): one too long to echo."""
    if isinstance(request_id, str) and len(request_id) > MAX_ID_CHARS:
        return (f"Invalid Request: the request's id is {len(request_id)} characters long; "
                f"this server accepts an id of at most {MAX_ID_CHARS} characters (field: "
                "id); send a counter or a UUID")
    if isinstance(request_id, int) and not isinstance(request_id, bool) \
            and len(str(abs(request_id))) > MAX_ID_CHARS:  # pragma: no cover - json caps it
        return f"Invalid Request: the request's id has more than {MAX_ID_CHARS} digits"
    return None


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
