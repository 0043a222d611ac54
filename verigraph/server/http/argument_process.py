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
the body limit, so a call is not cancelled once the child has it: if its client leaves,
the child finishes the body and the lane's turn is held until it has.

Fair between clients, twice over. Bodies up to 4 MiB and larger ones go to different
children, so one client posting 15 MB bodies delays only others that post bodies that
large. And within each child's lane, bodies wait per client and the lane takes them
round-robin over clients (FairTurns): a client with eight bodies waiting gets one turn,
then another client's single body gets the next, so however many bodies (from however
many connections) one client posts, another's waits for at most one of them. Who a
client is: access.caller_of (its own token, else its address). A client may have at
most `queued_per_client` bodies waiting in a lane; one more gets a 503 naming that
limit, so no client can make the queue (bodies of up to 16 MiB each) grow without
bound. Measured in benchmarks/results/server_load.md.

Every answer has a deadline: a child that has not answered a body within it (stopped
with SIGSTOP, stuck) is killed and replaced, and the caller gets a 503 saying to send
it again.
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
from collections import deque
from concurrent.futures import Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import anyio
import anyio.lowlevel
import anyio.to_thread
import pydantic_core
from pydantic import BaseModel

from verigraph.budget import DEFAULT_MEMORY_MIB
from verigraph.errors import VeriGraphError
from verigraph.server.http.workers import PR_SET_PDEATHSIG
from verigraph.server.jsonrpc_screen import top_level_id
from verigraph.server.rpc_errors import INVALID_REQUEST, PARSE_ERROR, id_problem
from verigraph.server.table import SERVER_TOOLS
from verigraph.tools.registry import parse_arguments

log = logging.getLogger("verigraph.server")
ID_SCAN_BYTES = 4096


@dataclass(frozen=True)
class Prepared:
    """A large body, checked: what the SDK gets and what the call uses."""

    envelope: bytes = b"{"  # the request without its arguments; "{" makes the SDK answer
    # its own parse error without parsing megabytes on the event loop
    params: BaseModel | None = None  # the tool's validated input
    error: str | None = None  # or why the arguments are invalid, field by field
    refusal: str | None = None  # the body is not servable (JSON-RPC -32600) ...
    request_id: str | int | None = None
    status: int = 413  # ... with this HTTP status
    code: int = INVALID_REQUEST  # ... and this JSON-RPC error code
    reason: str | None = None  # ... and, for a refusal a client may react to, its reason


def _refusal(message: Any, size: int, threshold: int) -> Prepared:
    method = message.get("method") if isinstance(message, dict) else None
    request_id = message.get("id") if isinstance(message, dict) else None
    too_long = id_problem(request_id)
    if too_long is not None:  # answered with a null id: it cannot be echoed
        return Prepared(refusal=too_long, status=400)
    request_id = request_id if isinstance(request_id, str | int) else None
    params = message.get("params") if isinstance(message, dict) else None
    if method == "tools/call" and isinstance(params, dict) \
            and not isinstance(params.get("arguments"), dict | None):
        return Prepared(refusal=f"Request too large for 'tools/call' ({size} bytes): its "
                                "params.arguments must be an object of name: value",
                        request_id=request_id)
    if method == "tools/call" and isinstance(params, dict):
        # the arguments may be large; what else made it so is named, with its size
        parts = {f"params.{key}": value for key, value in params.items()
                 if key != "arguments"}
        parts |= {key: value for key, value in message.items() if key != "params"}
        largest = max(parts, key=lambda key: len(json.dumps(parts[key])))
        return Prepared(refusal=(
            f"Request too large for 'tools/call' ({size} bytes): its field {largest} is "
            f"{len(json.dumps(parts[largest]))} bytes as JSON; only a tools/call's "
            "arguments (an object) may be this large, everything else at most "
            f"{threshold} bytes in all; send a shorter {largest}"), request_id=request_id)
    what = repr(method) if isinstance(method, str) else "a message that is no single request"
    return Prepared(refusal=f"Request too large for {what} ({size} bytes): only tools/call "
                            "arguments may be this large; send a smaller request",
                    request_id=request_id)


def _parse_error(body: bytes) -> Prepared:
    """Why a large body is not JSON, with where: the SDK's own parser words a small
    body's error, so the same parser (pydantic_core, which stops at its nesting limit
    instead of recursing) words this one, and the answer is the JSON-RPC parse error.
    The request's id is looked for in the first few KiB only (a scan of megabytes
    would hold the checker)."""
    try:
        pydantic_core.from_json(body)
        reason = "not one JSON value"  # json refused what pydantic_core reads
    except ValueError as exc:
        reason = str(exc).replace("recursion limit exceeded", "nesting too deep")
    request_id = top_level_id(body[:ID_SCAN_BYTES].decode("utf-8", errors="replace"))
    return Prepared(refusal=f"Parse error: {reason[:200]}; send one JSON-RPC message of "
                            "valid JSON, nested a few hundred levels at most",
                    request_id=request_id, status=400, code=PARSE_ERROR)


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
        return _parse_error(body)
    if isinstance(message, dict) and id_problem(message.get("id")) is not None:
        return _refusal(message, len(body), threshold)
    params = message.get("params") if isinstance(message, dict) else None
    if not (isinstance(params, dict) and message.get("method") == "tools/call"
            and isinstance(params.get("arguments"), dict)):
        return _refusal(message, len(body), threshold)
    envelope = json.dumps({**message, "params": {**params, "arguments": {}}}).encode()
    if len(envelope) > threshold:
        return _refusal(message, len(body), threshold)
    spec = SERVER_TOOLS.get(params.get("name"))  # type: ignore[arg-type]
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


DEFAULT_DEADLINE_S = 10.0
STARTUP_S = 60.0  # a new child's imports, on a busy machine


def _started() -> bool:
    """In a new child: proof that it has started (imports done)."""
    return True


# Bodies up to this size and larger ones are checked by different children, so a client
# posting bodies near the body limit delays only others that do the same.
LANE_SPLIT_BYTES = 4 * 1024 * 1024
# Bodies of one client that may wait for one lane's child (the one being checked aside).
DEFAULT_QUEUED_PER_CLIENT = 8
QUEUE_FULL_REASON = "large_calls_queued"


class QueueFull(Exception):
    """A client already has as many bodies waiting in a lane as it may."""

    def __init__(self, waiting: int) -> None:
        super().__init__(waiting)
        self.waiting = waiting


@dataclass
class _Client:
    """One client's place in a lane: its waiting bodies (one event each, set when its
    turn comes), how many of its bodies hold or are being granted the turn, and the
    number of the lane's last turn it had (-1: none since it arrived)."""

    waiting: deque[anyio.Event] = field(default_factory=deque)
    holding: int = 0
    last_turn: int = -1


class FairTurns:
    """Whose body a lane's child checks next: round-robin over clients.

    One body holds the turn at a time. When it ends, the turn goes to the waiting client
    whose last turn is oldest (a client new to the lane first, in order of arrival), to
    its oldest body. So a client with many bodies waiting gets one turn per round, and a
    body waits for the one being checked and at most one body of each other client with
    bodies waiting, however many those have and whatever order they arrived in (beside
    one client posting many, another's body is next). Everything runs on the server's
    event loop and nothing here awaits except the wait for a turn, so no lock is
    needed; a client is forgotten once it has nothing waiting or held (the table stays
    as small as the set of clients with calls in flight)."""

    def __init__(self, queued_per_client: int = DEFAULT_QUEUED_PER_CLIENT) -> None:
        self.queued_per_client = queued_per_client
        self._clients: dict[str, _Client] = {}  # insertion order: order of arrival
        self._held = False
        self._turns = 0

    def waiting(self) -> int:
        """Bodies waiting for a turn, all clients together."""
        return sum(len(c.waiting) for c in self._clients.values())

    async def acquire(self, client: str) -> None:
        """Wait for `client`'s turn (QueueFull at once if it has too many waiting); a
        caller cancelled while waiting leaves the queue, and passes on a turn it was
        being given. Every return is to be matched by one `release()`."""
        place = self._clients.setdefault(client, _Client())
        if not self._held:  # idle: nothing waits either (release() hands the turn on)
            self._grant(place)
            return
        if len(place.waiting) >= self.queued_per_client:
            self._forget_if_idle(client)
            raise QueueFull(len(place.waiting))
        turn = anyio.Event()
        place.waiting.append(turn)
        try:
            await turn.wait()
        except BaseException:
            if turn.is_set():  # given the turn as the wait was cancelled: pass it on
                self.release(client)
            else:
                place.waiting.remove(turn)
                self._forget_if_idle(client)
            raise

    def release(self, client: str) -> None:
        """End `client`'s turn and give the next one (or leave the lane idle)."""
        self._clients[client].holding -= 1
        self._forget_if_idle(client)
        ready = [(c.last_turn, name) for name, c in self._clients.items() if c.waiting]
        if not ready:
            self._held = False
            return
        _, name = min(ready, key=lambda entry: entry[0])  # ties: the first to arrive
        place = self._clients[name]
        self._grant(place)
        place.waiting.popleft().set()

    def _grant(self, place: _Client) -> None:
        self._held = True
        place.holding += 1
        place.last_turn = self._turns
        self._turns += 1

    def _forget_if_idle(self, client: str) -> None:
        place = self._clients.get(client)
        if place is not None and not place.waiting and not place.holding:
            del self._clients[client]


class _Lane:
    """One child process and the fair queue in front of it."""

    def __init__(self, memory_mib: float, deadline_s: float,
                 queued_per_client: int = DEFAULT_QUEUED_PER_CLIENT) -> None:
        self.memory_mib = memory_mib
        self.deadline_s = deadline_s
        self._pool: ProcessPoolExecutor | None = None
        self.turns = FairTurns(queued_per_client)

    async def _current_pool(self) -> ProcessPoolExecutor:
        """The lane's pool, its child started (start-up is not part of any deadline)."""
        if self._pool is None:
            pool = ProcessPoolExecutor(
                1, mp_context=multiprocessing.get_context("spawn"),
                initializer=_start_child, initargs=(self.memory_mib, os.getpid()))
            started: Future[bool] = pool.submit(_started)
            self._pool = pool
            with anyio.fail_after(max(STARTUP_S, self.deadline_s)):
                await anyio.to_thread.run_sync(started.result, abandon_on_cancel=True)
        return self._pool

    async def prepare(self, body: bytes, threshold: int, client: str) -> Prepared:
        """`body` checked in the child once `client`'s turn comes (see FairTurns)."""
        try:
            await self.turns.acquire(client)
        except QueueFull as full:
            return _queue_full(body, full.waiting, self.turns.queued_per_client)
        try:
            await anyio.lowlevel.checkpoint_if_cancelled()  # its client left meanwhile
            return await self.check(body, threshold)
        finally:
            self.turns.release(client)

    async def check(self, body: bytes, threshold: int) -> Prepared:
        """`prepare(body)` in the child, within the deadline (the caller holds the turn)."""
        for _ in range(2):
            try:
                pool = await self._current_pool()
            except (BrokenProcessPool, TimeoutError):
                log.warning("the argument-checking process did not start")
                if self._pool is not None:
                    self._discard(self._pool)
                continue
            future: Future[Prepared] | None = None
            ends = anyio.current_time() + self.deadline_s
            try:
                future = pool.submit(prepare, body, threshold)
                with anyio.fail_after(self.deadline_s):
                    return await anyio.to_thread.run_sync(future.result,
                                                          abandon_on_cancel=True)
            except anyio.get_cancelled_exc_class():
                if future is not None:
                    await self._finish_abandoned(pool, future, ends)
                raise
            except BrokenProcessPool:
                log.warning("the argument-checking process died; starting a new one")
                self._discard(pool)
            except TimeoutError:
                log.warning("the argument-checking process did not answer within %g s "
                            "(stopped or stuck); killing it and starting a new one",
                            self.deadline_s)
                self._discard(pool)
                return _late(body, self.deadline_s)
        return Prepared(refusal=f"Request of {len(body)} bytes could not be parsed within "
                                "one call's memory: send a smaller request")

    async def _finish_abandoned(self, pool: ProcessPoolExecutor, future: Future[Prepared],
                                deadline: float) -> None:
        """The caller left (its client disconnected) while the child checks its body:
        the child goes on with it, so the turn is kept until it is done, within the same
        deadline, else a client could post bodies and leave at once to queue them in
        the child past every other client's turn."""
        with anyio.CancelScope(shield=True):
            with anyio.move_on_after(max(0.0, deadline - anyio.current_time())) as waited:
                await anyio.to_thread.run_sync(wait, [future])
            if waited.cancelled_caught:
                log.warning("the argument-checking process did not finish an abandoned body "
                            "within %g s; killing it and starting a new one", self.deadline_s)
                self._discard(pool)

    def _discard(self, pool: ProcessPoolExecutor) -> None:
        """Kill `pool`'s child (the next body starts a new one); a waiting caller's
        future fails at once, so its worker thread ends too."""
        children = _children(pool)
        if self._pool is pool:
            self._pool = None
        pool.shutdown(wait=False, cancel_futures=True)
        for child in children:
            child.kill()

    def children(self) -> list[multiprocessing.process.BaseProcess]:
        return _children(self._pool)

    def close(self) -> None:
        if self._pool is not None:
            self._discard(self._pool)


def _children(pool: ProcessPoolExecutor | None) -> list[multiprocessing.process.BaseProcess]:
    # The pool's own table (Python 3.14 adds kill_workers() for this).
    processes = getattr(pool, "_processes", None) or {}
    return list(processes.values())


def _late(body: bytes, deadline_s: float) -> Prepared:
    """The answer to a body whose checker missed its deadline (the id, if it is among
    the first bytes: the body is not parsed here)."""
    request_id = top_level_id(body[:ID_SCAN_BYTES].decode("utf-8", errors="replace"))
    return Prepared(refusal=f"The server could not check this request's arguments within "
                            f"{deadline_s:g} s (its checking process was stuck and has been "
                            "replaced): send the request again", request_id=request_id,
                    status=503)


def _queue_full(body: bytes, waiting: int, limit: int) -> Prepared:
    """The answer to a body beyond its client's share of a lane's queue."""
    request_id = top_level_id(body[:ID_SCAN_BYTES].decode("utf-8", errors="replace"))
    return Prepared(refusal=f"Too many large requests from this client: {waiting} of its "
                            f"bodies already wait for their argument check, at most {limit} "
                            "per client; wait for their answers, then send this request "
                            "again", request_id=request_id, status=503,
                    reason=QUEUE_FULL_REASON)


class ArgumentChecker:
    """The server's child processes for large bodies (one per HTTP server).

    Two lanes, each a child process with a fair queue in front (FairTurns): bodies up
    to LANE_SPLIT_BYTES, and larger ones. A client may have `queued_per_client` bodies
    waiting in each lane; one more is refused (503). Each body's check has
    `deadline_s`: a child that has not answered by then (stopped, stuck) is killed and
    replaced, and its caller told so (503)."""

    def __init__(self, memory_mib: float = DEFAULT_MEMORY_MIB,
                 deadline_s: float = DEFAULT_DEADLINE_S,
                 lane_split_bytes: int = LANE_SPLIT_BYTES,
                 queued_per_client: int = DEFAULT_QUEUED_PER_CLIENT) -> None:
        self.lane_split_bytes = lane_split_bytes
        self._lanes = (_Lane(memory_mib, deadline_s, queued_per_client),
                       _Lane(memory_mib, deadline_s, queued_per_client))

    async def prepare(self, body: bytes, threshold: int, client: str = "") -> Prepared:
        """`prepare(body)` in a child, in `client`'s turn; the caller waits without
        holding the loop.

        A child that died (killed, or out of memory on an earlier body) is replaced and
        the body tried once more; a body that takes the new child down too is refused."""
        return await self._lane(len(body)).prepare(body, threshold, client)

    def _lane(self, size: int) -> _Lane:
        return self._lanes[0 if size <= self.lane_split_bytes else 1]

    def waiting(self) -> int:
        """Bodies waiting for their turn, in both lanes."""
        return sum(lane.turns.waiting() for lane in self._lanes)

    def children(self) -> list[multiprocessing.process.BaseProcess]:
        return [child for lane in self._lanes for child in lane.children()]

    def close(self) -> None:
        """Stop the children now (at server shutdown); a later call starts new ones."""
        for lane in self._lanes:
            lane.close()
