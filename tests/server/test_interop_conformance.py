"""The official conformance suite (@modelcontextprotocol/conformance) against the server.

Only the scenarios that apply to a server without test fixtures of the suite's own
(its tools-call-* and prompts-get-* scenarios expect tools and prompts named by the
suite) run here, against `verigraph serve --transport http` without a token.
"""

from __future__ import annotations

import os
import subprocess
from collections.abc import Iterator

import pytest
from interop_helpers import INTEROP, interop_package, node22
from mcp_helpers import http_server

SCENARIOS = ("server-initialize", "ping", "tools-list", "resources-list", "prompts-list",
             "dns-rebinding-protection")


@pytest.fixture(scope="module")
def server_url() -> Iterator[str]:
    with http_server() as server:
        yield server.url


@pytest.mark.parametrize("scenario", SCENARIOS)
def test_conformance_scenario(server_url: str, scenario: str) -> None:
    node = node22()
    suite = interop_package("@modelcontextprotocol/conformance") / "dist" / "index.js"
    done = subprocess.run([node, str(suite), "server", "--url", server_url,
                           "--scenario", scenario], cwd=INTEROP, capture_output=True,
                          text=True, timeout=180, env={**os.environ, "NO_COLOR": "1"})
    output = done.stdout + done.stderr
    assert done.returncode == 0, output[-3000:]
    assert " 0 failed" in output and "Passed:" in output, output[-3000:]
