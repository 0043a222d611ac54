"""The environment's OpenEnv app under uvicorn on a loopback port, for the env tests."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

import uvicorn
from mcp_helpers import free_port

from verigraph.env.openenv_server import create_openenv_app
from verigraph.tasks.task import Task


@contextmanager
def serving(tasks: Sequence[Task], **options: Any) -> Iterator[str]:
    """`create_openenv_app(tasks=tasks, **options)` served on a loopback port; its URL."""
    with serving_app(create_openenv_app(tasks=list(tasks), **options)) as url:
        yield url


@contextmanager
def serving_app(app: Any) -> Iterator[str]:
    """An ASGI app under uvicorn on a loopback port, in a thread; its URL."""
    port = free_port()
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port,
                                           log_level="critical"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 30
    while not server.started:  # uvicorn sets it once the socket listens
        assert thread.is_alive() and time.monotonic() < deadline, "uvicorn did not start"
        time.sleep(0.02)
    try:
        yield f"http://127.0.0.1:{port}"
    finally:
        server.should_exit = True
        thread.join(timeout=10)
