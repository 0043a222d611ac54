"""The job engine's rate limiter (verigraph.jobs.limiter): requests per window and
concurrency per backend, on an injected clock, and the gate that waits for a slot."""

from __future__ import annotations

import pytest

from verigraph.jobs.limiter import BackendLimits, Gate, RateLimiter

pytestmark = pytest.mark.fast


def test_limiter_grants_at_most_n_per_window_and_respects_concurrency() -> None:
    now = [0.0]
    limiter = RateLimiter(default=BackendLimits(requests=3, window_s=10, concurrency=2),
                          clock=lambda: now[0])
    assert limiter.try_acquire("a") == 0 and limiter.try_acquire("a") == 0
    assert limiter.try_acquire("a") > 0  # two in flight
    limiter.release("a")
    assert limiter.try_acquire("a") == 0  # third in the window
    limiter.release("a")
    limiter.release("a")
    assert limiter.try_acquire("a") == pytest.approx(10.0)  # window full: wait for it
    assert limiter.try_acquire("b") == 0  # budgets are per backend
    now[0] = 10.0
    assert limiter.try_acquire("a") == 0
    assert limiter.granted() == {"a": 4, "b": 1}
    waits: list[float] = []

    def sleep(s: float) -> None:
        waits.append(s)
        now[0] += s

    with Gate(limiter, sleep=sleep).slot("a"), Gate(limiter, sleep=sleep).slot("b"):
        pass
    assert waits == [] and limiter.granted()["a"] == 5
