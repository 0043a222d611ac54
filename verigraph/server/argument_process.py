"""A large request is parsed and checked in a child process, never in the server's.

Parsing JSON and validating a tool's input are each one long C call that holds the GIL
from start to end: a 12 MB body of 300,000 small nodes held it for over a second, during
which no other client was answered, only to be refused. ArgumentChecker sends the raw
body to a child process (spawned on first use) that parses it, takes a `tools/call`'s
arguments out and validates them with the tool's input model (an oversized graph is
refused before its items are validated). What comes back is small or cheap: the request
without its arguments (for the SDK, which still checks the envelope), the argument error
as text, or the validated input, pickled; unpickling runs Python code for each model, so
the server's event loop gets the GIL between them. Only input within the limits ever
enters the server process.

The child's address space is capped (RLIMIT_AS) at its size after start-up plus the
heavy-call memory budget: a body that would parse into gigabytes fails there, with an
error that says so. A child that dies is replaced. Parsing and checking are bounded by
the body limit, so a call is not cancelled once the child has it.
"""

from __future__ import annotations

import ctypes
import json
import logging
import multiprocessing
import multiprocessing.process
import os
import resource
import signal
import sys
from concurrent.futures import Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import anyio
import anyio.to_thread
from pydantic import BaseModel

from verigraph.errors import VeriGraphError
from verigraph.tools.registry import TOOLS, ToolSpec, parse_arguments
from verigraph.viewer import VIEW_SPEC

log = logging.getLogger("verigraph.server")
INPUT_SPECS: dict[str, ToolSpec] = {**TOOLS, VIEW_SPEC.name: VIEW_SPEC}


@dataclass(frozen=True)
class Prepared:
    """A large body, checked: what the SDK gets and what the argument gate uses."""

    envelope: bytes = b"{"  # the request without its arguments; "{" makes the SDK answer
    # its own parse error without parsing megabytes on the event loop
    params: BaseModel | None = None  # the tool's validated input
    error: str | None = None  # or why the arguments are invalid, field by field
    refusal: str | None = None  # the body is not servable (413, JSON-RPC -32600)
    request_id: str | int | None = None


def _refusal(message: Any, size: int) -> Prepared:
    method = message.get("method") if isinstance(message, dict) else None
    request_id = message.get("id") if isinstance(message, dict) else None
    what = repr(method) if isinstance(method, str) else "a message that is no single request"
    return Prepared(refusal=f"Request too large for {what} ({size} bytes): only tools/call "
                            "arguments may be this large; send a smaller request",
                    request_id=request_id if isinstance(request_id, str | int) else None)


def prepare(body: bytes, threshold: int) -> Prepared:
    """In the child: parse `body`, take a tools/call's arguments out and validate them."""
    try:
        return _prepare(body, threshold)
    except MemoryError:
        return Prepared(refusal=f"Request of {len(body)} bytes needs more memory to parse "
                                "than one call may use: send a smaller request")


def _prepare(body: bytes, threshold: int) -> Prepared:
    try:
        message = json.loads(body)
    except (ValueError, RecursionError):
        return Prepared()
    params = message.get("params") if isinstance(message, dict) else None
    if not (isinstance(params, dict) and message.get("method") == "tools/call"
            and isinstance(params.get("arguments"), dict)):
        return _refusal(message, len(body))
    envelope = json.dumps({**message, "params": {**params, "arguments": {}}}).encode()
    if len(envelope) > threshold:
        return _refusal(message, len(body))
    spec = INPUT_SPECS.get(params.get("name"))  # type: ignore[arg-type]
    if spec is None:
        return Prepared(envelope)  # the SDK answers that there is no such tool
    try:
        return Prepared(envelope, params=parse_arguments(spec, params["arguments"]))
    except VeriGraphError as exc:
        return Prepared(envelope, error=str(exc))


def _vm_bytes() -> int:
    """This process's address-space size (0 where /proc does not say)."""
    try:
        status = Path("/proc/self/status").read_text()
    except OSError:
        return 0
    for line in status.splitlines():
        if line.startswith("VmSize:"):
            return int(line.split()[1]) * 1024
    return 0


PR_SET_PDEATHSIG = 1  # linux/prctl.h


def _start_child(memory_mib: float, parent: int) -> None:
    """The child dies with the server (even a killed one) and its address space is what
    start-up mapped plus the memory budget (both Linux only)."""
    if sys.platform == "linux":
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    if os.getppid() != parent:  # the server died before the line above
        os._exit(0)
    size = _vm_bytes()
    if size:
        limit = size + int(memory_mib * 1024 * 1024)
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))


class ArgumentChecker:
    """The server's child process for large bodies (one per HTTP server)."""

    def __init__(self, memory_mib: float = 512.0, processes: int = 1) -> None:
        self.memory_mib = memory_mib
        self.processes = processes
        self._pool: ProcessPoolExecutor | None = None
        self._limiter = anyio.CapacityLimiter(processes)

    def _current_pool(self) -> ProcessPoolExecutor:
        if self._pool is None:
            self._pool = ProcessPoolExecutor(
                self.processes, mp_context=multiprocessing.get_context("spawn"),
                initializer=_start_child, initargs=(self.memory_mib, os.getpid()))
        return self._pool

    async def prepare(self, body: bytes, threshold: int) -> Prepared:
        """`prepare(body)` in the child; the caller waits without holding the loop.

        A child that died (killed, or out of memory on an earlier body) is replaced and
        the body tried once more; a body that takes the new child down too is refused."""
        async with self._limiter:
            for _ in range(2):
                pool = self._current_pool()
                try:
                    future: Future[Prepared] = pool.submit(prepare, body, threshold)
                    return await anyio.to_thread.run_sync(future.result,
                                                          abandon_on_cancel=True)
                except BrokenProcessPool:
                    log.warning("the argument-checking process died; starting a new one")
                    if self._pool is pool:
                        self._pool = None
                    pool.shutdown(wait=False, cancel_futures=True)
        return Prepared(refusal=f"Request of {len(body)} bytes could not be parsed within "
                                "one call's memory: send a smaller request")

    def _children(self) -> list[multiprocessing.process.BaseProcess]:
        # The pool's own table (Python 3.14 adds kill_workers() for this).
        processes = getattr(self._pool, "_processes", None) or {}
        return list(processes.values())

    def close(self) -> None:
        """Stop the children now (at server shutdown); a later call starts new ones."""
        children = self._children()
        pool, self._pool = self._pool, None
        if pool is not None:
            pool.shutdown(wait=False, cancel_futures=True)
        for child in children:
            child.kill()
