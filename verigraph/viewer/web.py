"""`verigraph view`: the viewer as a local web page for people checking plans.

Loopback only. GET / serves the page (no data in it); POST /api/view needs
`Authorization: Bearer <token>` (the page reads the token from the URL fragment, which
browsers never send to servers), checks the plan with the validate_plan tool function
and answers with the per-step view. Host names other than loopback are refused (DNS
rebinding), bodies are limited, and every response forbids fetching anything else.
"""

from __future__ import annotations

import hmac
import json
from typing import Any

import anyio.to_thread
from starlette.applications import Starlette
from starlette.middleware import Middleware
from starlette.middleware.trustedhost import TrustedHostMiddleware
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response
from starlette.routing import Route

from verigraph.errors import VeriGraphError
from verigraph.tools.context import ToolContext
from verigraph.viewer.inputs import plan_input
from verigraph.viewer.page import PAGE_CSP, page_html
from verigraph.viewer.views import plan_view

MAX_BODY_BYTES = 8 * 1024 * 1024
LOOPBACK_NAMES = ["127.0.0.1", "localhost", "[::1]", "::1"]
SECURITY_HEADERS = {"Content-Security-Policy": PAGE_CSP, "X-Content-Type-Options": "nosniff",
                    "Referrer-Policy": "no-referrer", "X-Frame-Options": "DENY",
                    "Cache-Control": "no-store"}


def _error(status: int, message: str, field: str | None = None) -> JSONResponse:
    return JSONResponse({"error": message, "field": field}, status_code=status,
                        headers=SECURITY_HEADERS)


def viewer_app(ctx: ToolContext, token: str) -> Starlette:
    """The ASGI app behind `verigraph view`."""
    expected = f"Bearer {token}".encode()

    async def page(request: Request) -> Response:
        return HTMLResponse(page_html(), headers=SECURITY_HEADERS)

    async def api_view(request: Request) -> Response:
        given = request.headers.get("authorization", "").encode()
        if not hmac.compare_digest(given, expected):
            return _error(401, "this page needs the token printed by `verigraph view`: open "
                               "the exact URL it printed (the token is after #token=)")
        declared = request.headers.get("content-length", "")
        if declared.isdigit() and int(declared) > MAX_BODY_BYTES:
            return _error(413, f"request larger than {MAX_BODY_BYTES} bytes: paste a smaller "
                               "scene or plan")
        body = await request.body()
        if len(body) > MAX_BODY_BYTES:
            return _error(413, f"request larger than {MAX_BODY_BYTES} bytes")
        try:
            fields: Any = json.loads(body)
        except ValueError:
            return _error(400, "the request is not JSON", "body")
        if not isinstance(fields, dict):
            return _error(400, "the request must be an object with scene, plan and goal", "body")

        def run() -> dict[str, Any]:
            params = plan_input(fields.get("scene", ""), fields.get("plan", ""),
                                fields.get("goal", ""))
            return plan_view(ctx, params).model_dump(mode="json", exclude_none=True)

        try:
            view = await anyio.to_thread.run_sync(run)
        except VeriGraphError as exc:
            return _error(400, str(exc), exc.field)
        return JSONResponse(view, headers=SECURITY_HEADERS)

    return Starlette(routes=[Route("/", page), Route("/api/view", api_view, methods=["POST"])],
                     middleware=[Middleware(TrustedHostMiddleware,
                                            allowed_hosts=LOOPBACK_NAMES)])
