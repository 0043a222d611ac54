"""Checking an MCP HTTP endpoint before a session: up, and does it take our token?

The SDK's client folds every connection failure into one "unhandled errors in a
TaskGroup". One plain request first tells the three failures a user must fix
differently apart: nothing listening (ServerUnreachableError), a token needed but
not given (MissingTokenError), a token refused (TokenRejectedError). Each has its own
exit code in the CLI.
"""

from __future__ import annotations

import json

import httpx2

from verigraph.errors import MissingTokenError, ServerUnreachableError, TokenRejectedError

PING = json.dumps({"jsonrpc": "2.0", "id": 0, "method": "ping"})
HEADERS = {"Content-Type": "application/json", "Accept": "application/json, text/event-stream"}


def _reason(response: httpx2.Response) -> str:
    try:
        error = response.json().get("error", {})
        return str(error.get("message") or response.reason_phrase)
    except (ValueError, AttributeError):
        return response.text[:200] or response.reason_phrase


def check_endpoint(url: str, token: str | None, timeout_s: float = 10.0) -> None:
    """Raise the error that names the fix, or return when the endpoint lets us in."""
    headers = dict(HEADERS)
    if token:
        headers["Authorization"] = f"Bearer {token}"
    try:
        response = httpx2.post(url, content=PING, headers=headers, timeout=timeout_s)
    except httpx2.ConnectError as exc:
        raise ServerUnreachableError(
            f"no MCP server answers at {url} ({exc or 'connection refused'})", field="--url",
            value=url, fix="start it with `verigraph serve --transport http` (add --port if "
                           "needed) or correct --url") from None
    except httpx2.HTTPError as exc:
        raise ServerUnreachableError(
            f"the MCP server at {url} did not answer: {type(exc).__name__} {exc}",
            field="--url", value=url, fix="check that the server runs and --url is its "
                                          "/mcp endpoint") from None
    if response.status_code == 404:
        raise ServerUnreachableError(
            f"a web server answers at {url} but has no MCP endpoint there (HTTP 404)",
            field="--url", value=url, fix="use the server's MCP path, e.g. "
                                          "http://127.0.0.1:8000/mcp")
    if response.status_code not in (401, 403):
        return
    reason = f"HTTP {response.status_code}: {_reason(response)}"
    if not token:
        raise MissingTokenError(f"the server at {url} needs a bearer token ({reason})",
                                field="--token", value=None,
                                fix="pass --token TOKEN or set VERIGRAPH_TOKEN to the token "
                                    "the server was started with")
    raise TokenRejectedError(f"the server at {url} refused the token ({reason})",
                             field="--token", value="***",
                             fix="use the token the server was started with (its --token or "
                                 "VERIGRAPH_TOKEN)")
