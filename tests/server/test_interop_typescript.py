"""The official TypeScript SDK as a client, with ajv (strict, JSON Schema 2020-12).

tests/interop/check_server.mjs lists the tools, compiles every input and output schema
with ajv in strict mode, plays a short episode and checks every structured result
against its tool's output schema; it prints {"tools", "results_checked", "problems"}.
Here it runs over stdio and over HTTP with a bearer token.
"""

from __future__ import annotations

import json
import subprocess
from typing import Any

from interop_helpers import INTEROP, interop_package, node22
from mcp_helpers import http_server, verigraph_command

from verigraph.tools import TOOL_SPECS

TOKEN = "interop-token"


def check(*target: str) -> dict[str, Any]:
    node = node22()
    interop_package("@modelcontextprotocol/sdk")
    interop_package("ajv")
    done = subprocess.run([node, str(INTEROP / "check_server.mjs"), *target], cwd=INTEROP,
                          capture_output=True, text=True, timeout=180)
    assert done.stdout.strip(), f"no report (exit {done.returncode}): {done.stderr[-2000:]}"
    report: dict[str, Any] = json.loads(done.stdout.strip().splitlines()[-1])
    assert done.returncode == (1 if report["problems"] else 0), done.stderr[-2000:]
    return report


def assert_clean(report: dict[str, Any]) -> None:
    assert report["problems"] == []
    assert report["tools"] == len(TOOL_SPECS)
    assert report["results_checked"] >= 9  # every structured tool of the scripted episode


def test_typescript_client_over_stdio() -> None:
    assert_clean(check("--stdio", *verigraph_command(), "serve"))


def test_typescript_client_over_http_with_a_token() -> None:
    with http_server(token=TOKEN) as server:
        assert_clean(check("--http", server.url, "--token", TOKEN))


def test_typescript_client_without_the_token_gets_no_tools() -> None:
    with http_server(token=TOKEN) as server:
        node = node22()
        interop_package("@modelcontextprotocol/sdk")
        done = subprocess.run([node, str(INTEROP / "check_server.mjs"), "--http", server.url],
                              cwd=INTEROP, capture_output=True, text=True, timeout=120)
    output = done.stdout + done.stderr
    assert done.returncode != 0
    assert "Forbidden: no token was sent" in output, output[-2000:]
