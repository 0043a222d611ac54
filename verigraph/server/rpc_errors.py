"""JSON-RPC error answers the HTTP layers send themselves, before the SDK sees a request."""

from __future__ import annotations

import json
from typing import Any

from starlette.responses import Response

INVALID_REQUEST = -32600


def rpc_error(status: int, message: str, *, code: int = INVALID_REQUEST,
              request_id: str | int | None = None, data: dict[str, Any] | None = None,
              headers: dict[str, str] | None = None) -> Response:
    """An HTTP `status` answer whose body is a JSON-RPC error saying what to do."""
    error: dict[str, Any] = {"code": code, "message": message}
    if data is not None:
        error["data"] = data
    body = json.dumps({"jsonrpc": "2.0", "id": request_id, "error": error})
    return Response(body, status_code=status, media_type="application/json", headers=headers)
