"""Classify a raw JSON-RPC line the SDK would reject, and word the error reply.

The SDK's stdio transport drops a line that fails JSON-RPC validation (upstream:
modelcontextprotocol/python-sdk issue 2751), so a client that sent a request with
an id waits forever. `screen` decides for each such line what JSON-RPC 2.0 asks for:
a parse error (-32700), an invalid request (-32600) or invalid params (-32602), with
the request's id when it can be recovered and null otherwise; notifications get no
reply. Recovering the id never recurses, so arbitrarily deep nesting is safe.
"""

from __future__ import annotations

import json
from typing import Any

from mcp_types import JSONRPCError
from pydantic import ValidationError

from verigraph.server.rpc_errors import (
    INVALID_PARAMS,
    INVALID_REQUEST,
    PARSE_ERROR,
    error_message,
    id_problem,
    valid_id,
)

_SCALAR = json.JSONDecoder()


def top_level_id(text: str) -> Any:
    """The value of the top-level `"id"` key of a JSON object, found by scanning.

    Works on text too deep or too broken for a parser: tracks string state and depth
    only, and decodes just the id's scalar value. Returns None when there is none.
    """
    depth = 0
    i, n = 0, len(text)
    expect_key = False
    while i < n:
        ch = text[i]
        if ch == '"':
            end = i + 1
            while end < n and text[end] != '"':
                end += 2 if text[end] == "\\" else 1
            if depth == 1 and expect_key and text[i + 1:end] == "id":
                rest = text[end + 1:].lstrip()
                if rest.startswith(":"):
                    value_text = rest[1:].lstrip()
                    try:
                        value, _ = _SCALAR.raw_decode(value_text[:200])
                    except ValueError:
                        return None
                    return value if valid_id(value) else None
            expect_key = False
            i = end + 1
            continue
        if ch in "{[":
            depth += 1
            expect_key = ch == "{" and depth == 1
        elif ch in "}]":
            depth -= 1
        elif ch == "," and depth == 1:
            expect_key = True
        i += 1
    return None


def error_reply(request_id: Any, code: int, message: str) -> JSONRPCError:
    return JSONRPCError.model_validate(error_message(message, code=code,
                                                     request_id=request_id))


def _first_problem(exc: Exception) -> str:
    if isinstance(exc, ValidationError) and exc.errors():
        err = exc.errors()[0]
        where = ".".join(str(p) for p in err["loc"] if not str(p).startswith(
            ("JSONRPC", "function", "tagged", "json-or-python")))
        return f"{where}: {err['msg']}" if where else str(err["msg"])
    return str(exc)[:200]


def screen(text: str, exc: Exception) -> list[JSONRPCError]:
    """The replies owed for a line the SDK could not accept (empty: a notification)."""
    try:
        message = json.loads(text)
    except RecursionError:
        return [error_reply(top_level_id(text), INVALID_REQUEST,
                            "Invalid Request: the JSON is nested too deeply; send at most a "
                            "few hundred levels")]
    except ValueError as err:
        return [error_reply(top_level_id(text), PARSE_ERROR,
                            f"Parse error: {err}; send one JSON-RPC message per line")]
    if isinstance(message, list):
        ids = [m.get("id") for m in message if isinstance(m, dict) and valid_id(m.get("id"))]
        reason = ("Invalid Request: JSON-RPC batches are not supported by MCP; send each "
                  "request as its own message")
        return [error_reply(i, INVALID_REQUEST, reason) for i in ids] or \
            [error_reply(None, INVALID_REQUEST, reason)]
    if not isinstance(message, dict):
        return [error_reply(None, INVALID_REQUEST, "Invalid Request: a JSON-RPC message is "
                            f"an object, got {type(message).__name__}")]
    if "id" not in message:
        return []  # a notification: JSON-RPC never answers one, even when it is wrong
    request_id = message["id"]
    if not valid_id(request_id):
        return [error_reply(None, INVALID_REQUEST, "Invalid Request: the id must be a string "
                            f"or an integer, got {json.dumps(request_id)[:40]}")]
    too_long = id_problem(request_id)
    if too_long is not None:  # refused for its id, which is not echoed
        return [error_reply(None, INVALID_REQUEST, too_long)]
    if message.get("jsonrpc") != "2.0" or not isinstance(message.get("method"), str):
        if "result" in message or "error" in message:
            return []  # a malformed response to one of our requests: nothing to answer
        return [error_reply(request_id, INVALID_REQUEST, "Invalid Request: a request needs "
                            '"jsonrpc": "2.0" and a string "method" '
                            f"({_first_problem(exc)})")]
    return [error_reply(request_id, INVALID_PARAMS, "Invalid params: "
                        f"{_first_problem(exc)}; params must be an object of valid JSON "
                        "text (no lone UTF-16 surrogates)")]


def oversized(prefix: str, size: int, limit: int) -> list[JSONRPCError]:
    """The reply to a message larger than the server accepts (it is not parsed)."""
    mib = limit / (1024 * 1024)
    return [error_reply(top_level_id(prefix), INVALID_REQUEST,
                        f"Request too large ({size} bytes): this server accepts at most "
                        f"{mib:g} MiB per message. Send smaller images (downscale or use "
                        "JPEG) or split the request.")]
