"""For the store tests: a real Redis server on a free loopback port (stopped after), and
an MCP client over streamable HTTP to a running `verigraph serve`."""

from __future__ import annotations

import shutil
import subprocess
from collections.abc import AsyncIterator, Iterator
from contextlib import asynccontextmanager
from typing import Any

import httpx2
import pytest
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp_helpers import free_port, structured, wait_for_port

from optional import in_ci


@pytest.fixture(scope="session")
def redis_url() -> Iterator[str]:
    """redis://127.0.0.1:PORT/0 of a private redis-server (skips locally, fails in CI)."""
    binary = shutil.which("redis-server")
    if binary is None:
        message = "redis-server is not installed; install it with: apt-get install -y redis-server"
        if in_ci():
            pytest.fail(message, pytrace=False)
        pytest.skip(message)
    port = free_port()
    proc = subprocess.Popen([binary, "--port", str(port), "--bind", "127.0.0.1", "--save", "",
                             "--appendonly", "no", "--daemonize", "no"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_for_port(port, proc, "redis-server", timeout=20.0)
        yield f"redis://127.0.0.1:{port}/0"
    finally:
        proc.terminate()
        proc.wait(timeout=10)


@asynccontextmanager
async def connect(url: str) -> AsyncIterator[Client]:
    """A client of the server at url; reads wait up to 2 minutes (moves are serialised)."""
    async with httpx2.AsyncClient(timeout=httpx2.Timeout(30, read=120)) as http, \
            Client(streamable_http_client(url, http_client=http)) as client:
        yield client


async def call(client: Client, name: str, **arguments: Any) -> dict[str, Any]:
    return structured(await client.call_tool(name, arguments))
