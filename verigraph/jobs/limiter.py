"""Per-backend limits on planner requests: how many at once, how many per time window.

One `RateLimiter` holds the budget of every backend. It never blocks: `try_acquire`
either grants a request (and counts it) or says how long to wait, so the same object
works in-process (serial runs, behind a lock) and as a single Ray actor that every
worker on the cluster asks (one clock, one count; a blocking actor method would stall
all the others). `Gate` is the caller's side: it retries until granted.

The request window is a sliding log: at most `requests` grants in any `window_s`
seconds (60 s for a requests-per-minute limit). A slot a worker takes and never gives
back (the worker process died) stays taken until the run ends.
"""

from __future__ import annotations

import contextlib
import threading
import time
from collections import deque
from collections.abc import Callable, Iterator
from typing import Protocol

from pydantic import BaseModel, ConfigDict, Field

MAX_WAIT_STEP_S = 0.25  # re-ask at least this often (a release may free a slot sooner)


class BackendLimits(BaseModel):
    """Limits for one planner backend; None means unlimited."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    concurrency: int | None = Field(default=None, ge=1, description="requests in flight")
    requests: int | None = Field(default=None, ge=1, description="requests per window")
    window_s: float = Field(default=60.0, gt=0, description="the window (60 s: per minute)")


class RateLimiter:
    """The shared budget: in-flight counts and grant times per backend."""

    def __init__(self, limits: dict[str, BackendLimits] | None = None,
                 default: BackendLimits | None = None,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.limits = dict(limits or {})
        self.default = default or BackendLimits()
        self.clock = clock
        self._in_flight: dict[str, int] = {}
        self._granted: dict[str, deque[float]] = {}
        self._total: dict[str, int] = {}
        self._lock = threading.Lock()

    def _limits(self, backend: str) -> BackendLimits:
        return self.limits.get(backend, self.default)

    def try_acquire(self, backend: str) -> float:
        """0.0 when granted (the caller must `release` later), else seconds to wait."""
        limits = self._limits(backend)
        with self._lock:
            now = self.clock()
            in_flight = self._in_flight.get(backend, 0)
            if limits.concurrency is not None and in_flight >= limits.concurrency:
                return MAX_WAIT_STEP_S
            log = self._granted.setdefault(backend, deque())
            while log and log[0] <= now - limits.window_s:
                log.popleft()
            if limits.requests is not None and len(log) >= limits.requests:
                return max(log[0] + limits.window_s - now, 1e-3)
            log.append(now)
            self._in_flight[backend] = in_flight + 1
            self._total[backend] = self._total.get(backend, 0) + 1
            return 0.0

    def release(self, backend: str) -> None:
        with self._lock:
            self._in_flight[backend] = max(0, self._in_flight.get(backend, 0) - 1)

    def granted(self) -> dict[str, int]:
        """Requests granted so far per backend."""
        with self._lock:
            return dict(self._total)


class LimiterLike(Protocol):
    """What a `Gate` needs: the local limiter, or a proxy to the Ray actor."""

    def try_acquire(self, backend: str) -> float: ...

    def release(self, backend: str) -> None: ...


class Gate:
    """Blocks the calling thread until its backend has budget for one more request."""

    def __init__(self, limiter: LimiterLike | None,
                 sleep: Callable[[float], None] = time.sleep) -> None:
        self.limiter = limiter
        self.sleep = sleep

    @contextlib.contextmanager
    def slot(self, backend: str) -> Iterator[None]:
        if self.limiter is None:
            yield
            return
        while (wait := self.limiter.try_acquire(backend)) > 0:
            self.sleep(min(wait, MAX_WAIT_STEP_S))
        try:
            yield
        finally:
            self.limiter.release(backend)
