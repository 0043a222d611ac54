"""What wraps every planner call in the evaluation: limits, retries, usage, latency.

`GuardedPlanner` asks the limiter for a slot before each request (retries included,
so the limiter sees every request a model API sees), retries transient endpoint
failures (HTTP 429, 5xx, connection errors) with exponential backoff and jitter, and
adds up the token counts and cost the backend reports. The LLM backends are built
with their own HTTP retries off, so this policy is the only one in force.

`SimulatedLatencyPlanner` waits a fixed time before each answer: a stand-in for a
model API's response time, used to measure how the engine overlaps waiting episodes.
"""

from __future__ import annotations

import random
import re
import time
from collections.abc import Callable
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from verigraph.jobs.limiter import Gate
from verigraph.llm.http import RETRY_STATUS, LLMEndpointError
from verigraph.planning.models import PlannerReply, PlannerRequest
from verigraph.planning.planner import Planner, is_privileged

_STATUS = re.compile(r"HTTP (\d{3})")


class RetryPolicy(BaseModel):
    """Retries of transient failures: attempt n waits backoff * 2**n (with jitter)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    retries: int = Field(default=4, ge=0, le=20)
    backoff_s: float = Field(default=0.5, ge=0)
    max_backoff_s: float = Field(default=20.0, ge=0)

    def delay(self, attempt: int, rng: random.Random) -> float:
        base = min(self.backoff_s * (2 ** attempt), self.max_backoff_s)
        return base * (0.5 + rng.random() / 2)


def is_transient(exc: BaseException) -> bool:
    """An endpoint failure worth retrying: 408/409/425/429/5xx/529 or no connection.

    The HTTP client raises with the status as `value` only for answers retrying cannot
    fix (400, 401, 404, ...); a transient failure that used up the client's own
    attempts carries the URL instead and names the status in its message.
    """
    if not isinstance(exc, LLMEndpointError) or isinstance(exc.value, int):
        return False
    match = _STATUS.search(exc.message)
    return match is None or int(match.group(1)) in RETRY_STATUS


class Usage(BaseModel):
    """Token counts and cost summed over an episode's replies (None: not reported)."""

    prompt_tokens: int | None = None
    completion_tokens: int | None = None
    total_tokens: int | None = None
    cost_usd: float | None = None

    def add(self, usage: dict[str, Any] | None) -> None:
        if not usage:
            return
        prompt = usage.get("prompt_tokens", usage.get("input_tokens"))
        completion = usage.get("completion_tokens", usage.get("output_tokens"))
        total = usage.get("total_tokens")
        if total is None and isinstance(prompt, int) and isinstance(completion, int):
            total = prompt + completion
        for name, value in (("prompt_tokens", prompt), ("completion_tokens", completion),
                            ("total_tokens", total)):
            if isinstance(value, int):
                setattr(self, name, (getattr(self, name) or 0) + value)
        cost = usage.get("cost")
        if isinstance(cost, int | float):
            self.cost_usd = (self.cost_usd or 0.0) + float(cost)


class GuardedPlanner:
    """A planner behind the limiter and the retry policy, counting what it used."""

    def __init__(self, inner: Planner, gate: Gate, policy: RetryPolicy, *,
                 backend: str | None = None, seed: int = 0,
                 sleep: Callable[[float], None] = time.sleep) -> None:
        self.inner = inner
        self.name = inner.name
        self.privileged = is_privileged(inner)
        self.backend = backend or inner.name
        self.gate = gate
        self.policy = policy
        self.sleep = sleep
        self.rng = random.Random(seed)
        self.requests = 0
        self.retries = 0
        self.usage = Usage()

    def propose(self, request: PlannerRequest) -> PlannerReply:
        reply = self._propose(request)
        self.usage.add(reply.usage)
        return reply

    def _propose(self, request: PlannerRequest) -> PlannerReply:
        for attempt in range(self.policy.retries + 1):
            try:
                with self.gate.slot(self.backend):
                    self.requests += 1
                    return self.inner.propose(request)
            except LLMEndpointError as exc:
                if not is_transient(exc) or attempt == self.policy.retries:
                    raise
                self.retries += 1
                self.sleep(self.policy.delay(attempt, self.rng))
        raise AssertionError("unreachable: the last attempt returns or raises")

    def close(self) -> None:
        self.inner.close()


class SimulatedLatencyPlanner:
    """Waits `latency_s` before answering (a stand-in for a model API's response time)."""

    def __init__(self, inner: Planner, latency_s: float,
                 sleep: Callable[[float], None] = time.sleep) -> None:
        self.inner = inner
        self.name = inner.name
        self.privileged = is_privileged(inner)
        self.latency_s = latency_s
        self.sleep = sleep

    def propose(self, request: PlannerRequest) -> PlannerReply:
        self.sleep(self.latency_s)
        return self.inner.propose(request)

    def close(self) -> None:
        self.inner.close()
