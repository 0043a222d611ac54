"""Helpers for the MCP server tests: in-process and subprocess servers, result access."""

from __future__ import annotations

import base64
import json
import os
import selectors
import shutil
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import AsyncIterator, Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

import anyio.to_thread
import cv2
import numpy as np
import pytest
import uvicorn
from mcp import Client
from mcp.client.extension import advertise
from mcp.types import CallToolResult

from verigraph.server import build_server
from verigraph.server.http import HttpOptions, argument_process, http_app
from verigraph.tools import Toolbox

REPO = Path(__file__).resolve().parents[1]


def verigraph_command() -> list[str]:
    """The installed console script next to this Python, else `python -m verigraph`."""
    exe = shutil.which("verigraph", path=str(Path(sys.executable).parent))
    return [exe] if exe else [sys.executable, "-m", "verigraph"]


@pytest.fixture(name="client")
async def in_process_client() -> AsyncIterator[Client]:
    """The `client` fixture: the SDK client on a fresh server with a fresh Toolbox, in memory.
    A test module that imports this name gets the fixture."""
    async with Client(build_server(Toolbox())) as c:
        yield c


APP_MIME = "text/html;profile=mcp-app"  # the MCP Apps resource type


def apps_extension() -> Any:
    """The MCP Apps extension as a client advertises it."""
    return advertise("io.modelcontextprotocol/ui", {"mimeTypes": [APP_MIME]})


def apps_client() -> Client:
    """The SDK client, advertising MCP Apps, on a fresh server in memory."""
    return Client(build_server(), extensions=[apps_extension()])


def structured(result: CallToolResult) -> dict[str, Any]:
    assert not result.is_error, text(result)
    assert result.structured_content is not None
    return result.structured_content


def text(result: CallToolResult) -> str:
    return "\n".join(getattr(c, "text", "") for c in result.content)


def png_b64(width: int = 32, height: int = 24, color: tuple[int, int, int] = (0, 0, 255)) -> str:
    image = np.zeros((height, width, 3), dtype=np.uint8)
    image[:] = color
    ok, buf = cv2.imencode(".png", image)
    assert ok
    return base64.b64encode(buf.tobytes()).decode()


def decode_png(data_b64: str) -> np.ndarray:
    raw = base64.b64decode(data_b64)
    assert raw[:8] == b"\x89PNG\r\n\x1a\n"
    image = cv2.imdecode(np.frombuffer(raw, np.uint8), cv2.IMREAD_COLOR)
    assert image is not None
    return image


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def wait_for_port(port: int, proc: subprocess.Popen[bytes], what: str,
                  timeout: float = 30.0) -> None:
    """Return once `proc` accepts connections on loopback `port`; RuntimeError if it
    exits first or not within `timeout` seconds."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise RuntimeError(f"{what} exited with {proc.returncode}")
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=0.5):
                return
        except OSError:
            time.sleep(0.05)  # polling a port, not waiting for an effect
    raise RuntimeError(f"{what} did not open its port within {timeout:g} s")


@dataclass
class RunningServer:
    """A `verigraph serve --transport http` subprocess; its output goes to temp files."""

    url: str
    proc: subprocess.Popen[bytes]
    stdout: IO[bytes]
    stderr: IO[bytes]

    def stop(self) -> tuple[bytes, bytes]:
        """Terminate and return everything it wrote to stdout and stderr."""
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.stdout.seek(0)
        self.stderr.seek(0)
        return self.stdout.read(), self.stderr.read()


@contextmanager
def http_server(token: str | None = None, extra: list[str] | None = None
                ) -> Iterator[RunningServer]:
    """`verigraph serve --transport http` on a free loopback port."""
    port = free_port()
    env = {k: v for k, v in os.environ.items() if k != "VERIGRAPH_TOKEN"}
    args = [*verigraph_command(), "serve", "--transport", "http", "--port", str(port)]
    if token:
        args += ["--token", token]
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        proc = subprocess.Popen(args + (extra or []), env=env, stdout=out, stderr=err)
        server = RunningServer(f"http://127.0.0.1:{port}/mcp", proc, out, err)
        try:
            try:
                wait_for_port(port, proc, "verigraph serve")
            except RuntimeError as exc:
                raise RuntimeError(f"{exc}: {server.stop()[1][-2000:]!r}") from None
            yield server
        finally:
            server.stop()


@contextmanager
def http_in_thread(box: Toolbox, options: HttpOptions) -> Iterator[str]:
    """`box` served over HTTP by uvicorn on a thread of this process (on options.port)."""
    server = uvicorn.Server(uvicorn.Config(http_app(build_server(box), options),
                                           host=options.host, port=options.port,
                                           log_level="warning", access_log=False,
                                           lifespan="on"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 30
    while not server.started:
        if not thread.is_alive() or time.monotonic() > deadline:
            raise RuntimeError("the HTTP server did not start")
        time.sleep(0.05)
    with socket.create_connection(("127.0.0.1", options.port), timeout=1):
        pass
    try:
        yield options.url()
    finally:
        server.should_exit = True
        thread.join(timeout=30)


def rpc(method: str, params: dict[str, Any] | None = None, request_id: int = 1) -> bytes:
    body: dict[str, Any] = {"jsonrpc": "2.0", "id": request_id, "method": method}
    if params is not None:
        body["params"] = params
    return json.dumps(body).encode()


JSON_HEADERS = {"Content-Type": "application/json",
                "Accept": "application/json, text/event-stream"}


class RawStdio:
    """`verigraph serve` over stdio, spoken to line by line."""

    def __init__(self, *extra: str) -> None:
        self.proc = subprocess.Popen([*verigraph_command(), "serve", *extra],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL)
        assert self.proc.stdin is not None and self.proc.stdout is not None
        self.stdin, self.stdout = self.proc.stdin, self.proc.stdout
        self.pending = bytearray()
        self.selector = selectors.DefaultSelector()
        self.selector.register(self.stdout, selectors.EVENT_READ)

    def send(self, line: str | bytes) -> None:
        data = line.encode() if isinstance(line, str) else line
        self.stdin.write(data + b"\n")
        self.stdin.flush()

    def reply(self, timeout: float = 60) -> dict[str, Any]:
        """The next line on stdout as JSON (read unbuffered, so select() stays truthful)."""
        while b"\n" not in self.pending:
            assert self.selector.select(timeout), "no reply from the server"
            chunk = os.read(self.stdout.fileno(), 1 << 16)
            assert chunk, "the server closed stdout"
            self.pending += chunk
        line, _, rest = bytes(self.pending).partition(b"\n")
        self.pending = bytearray(rest)
        return json.loads(line)

    def initialize(self) -> None:
        self.send(json.dumps({"jsonrpc": "2.0", "id": 0, "method": "initialize", "params": {
            "protocolVersion": "2025-11-25", "capabilities": {},
            "clientInfo": {"name": "raw", "version": "0"}}}))
        assert self.reply()["id"] == 0
        self.send(json.dumps({"jsonrpc": "2.0", "method": "notifications/initialized"}))

    def still_serving(self, request_id: int = 999) -> None:
        self.send(json.dumps({"jsonrpc": "2.0", "id": request_id, "method": "ping"}))
        assert self.reply() == {"jsonrpc": "2.0", "id": request_id, "result": {}}

    def close(self) -> int:
        self.stdin.close()
        return self.proc.wait(timeout=30)


def tower_graph(n: int) -> dict[str, Any]:
    """A tower of n - 1 blocks on a table, as a scene graph (blocks dictionary)."""
    nodes = [{"id": "table", "label": "table"}] + [
        {"id": f"b{i}", "label": "block"} for i in range(n - 1)]
    edges = [{"source": f"b{i}", "relation": "on", "target": f"b{i - 1}" if i else "table"}
             for i in range(n - 1)]
    return {"nodes": nodes, "edges": edges, "dictionary": "blocks"}


def checking_processes(server_pid: int) -> list[int]:
    """The children of `server_pid` that check large bodies (not multiprocessing's
    resource tracker)."""
    children = Path(f"/proc/{server_pid}/task/{server_pid}/children").read_text().split()
    return [int(pid) for pid in children
            if b"spawn_main" in Path(f"/proc/{pid}/cmdline").read_bytes()]


def process_gone(pid: int) -> bool:
    """True once `pid` has exited (or is a zombie)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except FileNotFoundError:
        return True
    return state == "Z"


def wait_until(condition: Callable[[], bool], what: str, timeout: float = 30.0) -> None:
    """Poll `condition` until it holds; fail with `what` after `timeout` seconds (only so
    that a broken server fails the test)."""
    deadline = time.monotonic() + timeout
    while not condition():
        assert time.monotonic() < deadline, what
        time.sleep(0.02)


@dataclass
class CheckerSpy:
    """The large-body checker of a server in this process, watched (`checker_spy`).

    `order` holds the JSON-RPC id of each body in the order its check starts; a body
    whose id is in `hold` waits in its check, its turn held, until `release` is set
    (`entered` is set once one has started waiting). `abandoned` is set once a caller
    left while the child was checking its body."""

    order: list[Any] = field(default_factory=list)
    hold: set[Any] = field(default_factory=set)
    entered: threading.Event = field(default_factory=threading.Event)
    release: threading.Event = field(default_factory=threading.Event)
    abandoned: threading.Event = field(default_factory=threading.Event)
    lanes: list[Any] = field(default_factory=list)

    def waiting(self) -> int:
        """Bodies waiting for their turn in the lanes seen so far."""
        return sum(lane.turns.waiting() for lane in list(self.lanes))


@pytest.fixture()
def checker_spy(monkeypatch: pytest.MonkeyPatch) -> Iterator[CheckerSpy]:
    """Watch (and hold, on request) the checks of servers run in this process."""
    spy = CheckerSpy()
    lane_type = argument_process._Lane
    check, finish = lane_type.check, lane_type._finish_abandoned

    async def watched_check(lane: Any, body: bytes, threshold: int) -> Any:
        request_id = json.loads(body).get("id")
        spy.order.append(request_id)
        if request_id in spy.hold:
            spy.entered.set()
            await anyio.to_thread.run_sync(spy.release.wait)
        return await check(lane, body, threshold)

    async def watched_finish(lane: Any, *args: Any) -> None:
        spy.abandoned.set()
        await finish(lane, *args)

    def watched_init(lane: Any, *args: Any, **kwargs: Any) -> None:
        init(lane, *args, **kwargs)
        spy.lanes.append(lane)

    init = lane_type.__init__
    monkeypatch.setattr(lane_type, "check", watched_check)
    monkeypatch.setattr(lane_type, "_finish_abandoned", watched_finish)
    monkeypatch.setattr(lane_type, "__init__", watched_init)
    try:
        yield spy
    finally:
        spy.release.set()
