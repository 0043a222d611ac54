"""`verigraph serve --workers N`: N server processes accepting on one listening socket,
kept at N by their parent.

The parent binds the port once, forks N children before anything else starts (no
threads, no store connection, no event loop yet) and watches them. Each child builds its
own server and accepts on the shared socket; whichever child is free takes the next
connection, and a connection stays with the child that accepted it. The children
share episodes only through a durable store (SQLite or Redis, which compare-and-set
every write), so `--workers` above 1 needs one, and an arm stays with a single
process: arm worlds live in the process that opened them, so an arm server runs with
`--workers 1`. SIGTERM or SIGINT to the parent is passed on to every child; the
parent exits once they have, and a child dies with its parent.

A child that dies while the server runs (killed, out of memory, a crash) is reaped and
logged at once and a new one forked in its place, within RESTART_S (longer, up to
MAX_BACKOFF_S, for a child that keeps dying soon after its start). Its callers are not
left with an empty reply: each child hands its parent a duplicate of the socket of every
POST request in progress (from the moment its headers are in until its answer is
complete, `InFlight`), so the parent still holds the connections of a dead child's
calls and answers each with a 500 and a JSON-RPC error saying that the call may or may
not have taken effect. Only a death within the microseconds between the first and the
last bytes of an answer can leave that answer cut; event streams (GET) are not handed
over, and simply end.

What several processes buy and what they do not (docs/server.md, measured in
benchmarks/results/server_load.md): a busy process no longer slows connections that
other processes accepted, but a light client whose connection shares a process with
a heavy or hostile one is exactly as exposed as in a single process, so the in-process
protections (heavy calls on worker threads, large bodies checked in child processes)
stay.
"""

from __future__ import annotations

import contextlib
import ctypes
import logging
import os
import selectors
import signal
import socket
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from types import FrameType

from verigraph.server.rpc_errors import INTERNAL_ERROR, error_bytes

log = logging.getLogger("verigraph.server")
PR_SET_PDEATHSIG = 1  # linux/prctl.h
RESTART_S = 0.25  # how often the parent looks for dead children
MAX_BACKOFF_S = 10.0  # the longest wait before a child that keeps dying is started again
QUICK_DEATH_S = 10.0  # a child that dies sooner after its start backs the next one off
_OPEN, _CLOSE = b"o", b"c"


def listening_socket(host: str, port: int, backlog: int = 2048) -> socket.socket:
    """The socket every worker accepts on (bound and listening; inherited by fork).

    Its protocol is IPPROTO_TCP, as for a socket asyncio binds itself: asyncio turns
    Nagle's algorithm off only on connections of such a socket, and with it on, every
    answer (headers, then body) waited about 40 ms for the client's delayed ACK."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM, socket.IPPROTO_TCP)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    sock.bind((host, port))
    sock.listen(backlog)
    sock.set_inheritable(True)
    return sock


def _die_with_parent(parent: int) -> None:
    if sys.platform == "linux":
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)
    if os.getppid() != parent:  # the parent died before the line above
        os._exit(1)


class InFlight:
    """A child's side: tells the parent which requests are in progress (see the module
    docstring), over a datagram socket; admission calls `opened` and `closed`."""

    def __init__(self, channel: socket.socket) -> None:
        self.channel = channel
        self.next_key = 0

    def opened(self, fd: int) -> int | None:
        """Hand the parent a duplicate of the connection `fd`; the request's key."""
        self.next_key += 1
        try:
            socket.send_fds(self.channel, [_OPEN + self.next_key.to_bytes(8, "big")], [fd])
        except OSError:
            return None  # the parent is gone; this process follows it
        return self.next_key

    def closed(self, key: int) -> None:
        """The request's answer is complete (or its connection lost)."""
        with contextlib.suppress(OSError):
            self.channel.send(_CLOSE + key.to_bytes(8, "big"))


@dataclass
class _Child:
    pid: int
    channel: socket.socket  # the parent's end
    started: float
    flights: dict[int, socket.socket] = field(default_factory=dict)


def _died_reply() -> bytes:
    body = error_bytes("The server process handling this request stopped before it "
                       "answered (it was killed or crashed); a new one has been started. "
                       "The call may or may not have taken effect: check the episode "
                       "(get_state) before sending it again.", code=INTERNAL_ERROR)
    return (b"HTTP/1.1 500 Internal Server Error\r\ncontent-type: application/json\r\n"
            b"content-length: " + str(len(body)).encode() + b"\r\nconnection: close\r\n\r\n"
            + body)


class _Supervisor:
    """The parent: forks the children, keeps them at `count`, answers dead ones' calls."""

    def __init__(self, count: int, sock: socket.socket,
                 serve: Callable[[socket.socket, InFlight], None]) -> None:
        self.count = count
        self.sock = sock
        self.serve = serve
        self.parent = os.getpid()
        self.children: dict[int, _Child] = {}
        self.selector = selectors.DefaultSelector()
        self.stopping = False
        self.backoff = 0.0
        self.worst = 0

    def start_child(self) -> int:
        mine, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_DGRAM)
        pid = os.fork()
        if pid == 0:  # the child: serve until told to stop, never return into the CLI
            code = 1
            try:
                signal.signal(signal.SIGTERM, signal.SIG_DFL)  # not the parent's forward
                signal.signal(signal.SIGINT, signal.default_int_handler)
                mine.close()
                for child in self.children.values():
                    child.channel.close()
                    for conn in child.flights.values():
                        conn.close()
                self.selector.close()
                _die_with_parent(self.parent)
                self.serve(self.sock, InFlight(theirs))
                code = 0
            except BaseException:
                log.exception("a server process failed")
            finally:
                logging.shutdown()
                os._exit(code)
        theirs.close()
        mine.setblocking(False)
        self.children[pid] = _Child(pid, mine, time.monotonic())
        self.selector.register(mine, selectors.EVENT_READ, pid)
        return pid

    def forward(self, signum: int, frame: FrameType | None) -> None:
        self.stopping = True
        for pid in list(self.children):
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signum)

    def run(self) -> int:
        for _ in range(self.count):
            self.start_child()
        log.warning("%d server processes share the port (pids %s)", self.count,
                    ", ".join(map(str, self.children)))
        signal.signal(signal.SIGTERM, self.forward)
        signal.signal(signal.SIGINT, self.forward)
        next_start = 0.0
        while self.children:
            for key, _ in self.selector.select(RESTART_S):
                self.read(self.children[key.data])
            self.reap()
            missing = self.count - len(self.children)
            if missing > 0 and not self.stopping and time.monotonic() >= next_start:
                pid = self.start_child()
                log.warning("started server process %d in place of the one that died "
                            "(%d of %d running)", pid, len(self.children), self.count)
                next_start = time.monotonic() + self.backoff
        self.sock.close()
        return self.worst

    def read(self, child: _Child) -> None:
        """Take in what `child` reported: requests opened and closed."""
        while True:
            try:
                data, fds, _, _ = socket.recv_fds(child.channel, 16, 1)
            except (BlockingIOError, InterruptedError):
                return
            except OSError:
                return
            if not data:
                return
            key = int.from_bytes(data[1:9], "big")
            if data[:1] == _OPEN and fds:
                child.flights[key] = socket.socket(fileno=fds[0])
            elif data[:1] == _CLOSE:
                conn = child.flights.pop(key, None)
                if conn is not None:
                    conn.close()
            for extra in fds[1:]:
                os.close(extra)

    def reap(self) -> None:
        while True:
            try:
                pid, status = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                return
            except InterruptedError:
                continue
            if pid == 0:
                return
            child = self.children.pop(pid, None)
            if child is None:
                continue
            self.read(child)  # what it reported before it died
            self.selector.unregister(child.channel)
            child.channel.close()
            code = os.waitstatus_to_exitcode(status)
            # uvicorn re-raises the signal it shut down on, so that is a clean exit too
            clean = code in (0, -signal.SIGTERM, -signal.SIGINT)
            if self.stopping:
                if not clean:
                    log.warning("server process %d exited with %d", pid, code)
                    self.worst = 1
            else:
                how = f"signal {-code}" if code < 0 else f"exit status {code}"
                log.error("server process %d died (%s) with %d call(s) in progress; "
                          "starting a new one", pid, how, len(child.flights))
                quick = time.monotonic() - child.started < QUICK_DEATH_S
                self.backoff = min(MAX_BACKOFF_S, max(0.5, self.backoff * 2)) if quick else 0.0
            self.answer_dead(child)

    def answer_dead(self, child: _Child) -> None:
        """Answer each call the dead child had in progress, then close its connection."""
        reply = _died_reply()
        for conn in child.flights.values():
            with contextlib.suppress(OSError):
                conn.settimeout(1.0)
                conn.sendall(reply)
                conn.shutdown(socket.SHUT_RDWR)
            conn.close()
        child.flights.clear()


def run_workers(count: int, sock: socket.socket,
                serve: Callable[[socket.socket, InFlight], None]) -> int:
    """Fork `count` children that each run `serve(sock, in_flight)` and keep them at
    `count` until SIGTERM or SIGINT; then wait for all of them.

    Returns 0 when every child exited cleanly at the end, else 1."""
    return _Supervisor(count, sock, serve).run()
