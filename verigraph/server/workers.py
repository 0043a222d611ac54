"""`verigraph serve --workers N`: N server processes accepting on one listening socket.

The parent binds the port once, forks N children before anything else starts (no
threads, no store connection, no event loop yet) and waits. Each child builds its own
server and accepts on the shared socket; whichever child is free takes the next
connection, and a connection stays with the child that accepted it. The children
share episodes only through a durable store (SQLite or Redis, which compare-and-set
every write), so `--workers` above 1 needs one, and an arm stays with a single
process: arm worlds live in the process that opened them, so an arm server runs with
`--workers 1`. SIGTERM or SIGINT to the parent is passed on to every child; the
parent exits once they have, and a child dies with its parent.

What this buys and what it does not (docs/server.md, measured in
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
import signal
import socket
import sys
from collections.abc import Callable
from types import FrameType

log = logging.getLogger("verigraph.server")
PR_SET_PDEATHSIG = 1  # linux/prctl.h


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


def run_workers(count: int, sock: socket.socket, serve: Callable[[socket.socket], None]
                ) -> int:
    """Fork `count` children that each run `serve(sock)`; wait for all of them.

    Returns 0 when every child exited cleanly, else 1."""
    parent = os.getpid()
    children: list[int] = []
    for _ in range(count):
        pid = os.fork()
        if pid == 0:  # the child: serve until told to stop, never return into the CLI
            code = 1
            try:
                _die_with_parent(parent)
                serve(sock)
                code = 0
            except BaseException:
                log.exception("a server process failed")
            finally:
                logging.shutdown()
                os._exit(code)
        children.append(pid)
    sock.close()
    log.warning("%d server processes share the port (pids %s)", count,
                ", ".join(map(str, children)))

    def forward(signum: int, frame: FrameType | None) -> None:
        for child in children:
            with contextlib.suppress(ProcessLookupError):
                os.kill(child, signum)

    signal.signal(signal.SIGTERM, forward)
    signal.signal(signal.SIGINT, forward)
    worst = 0
    for child in children:
        while True:
            try:
                _, status = os.waitpid(child, 0)
                break
            except InterruptedError:  # a forwarded signal; keep waiting
                continue
        code = os.waitstatus_to_exitcode(status)
        # uvicorn re-raises the signal it shut down on, so that is a clean exit too
        if code not in (0, -signal.SIGTERM, -signal.SIGINT):
            log.warning("server process %d exited with %d", child, code)
            worst = 1
    return worst
