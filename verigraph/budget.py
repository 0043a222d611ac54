"""Cooperative budgets for long computations: wall clock, memory growth, cancellation.

Long loops anywhere in VeriGraph (plan validation, search, simulation) call
`checkpoint()` now and then. Outside a budget it does nothing. Inside `within(budget)`
(the MCP server wraps every heavy tool call in one, on its worker thread) it raises
BudgetExceeded once the call has run longer than its wall-clock budget, once the
process has grown by more than its memory budget since the call started, or once
the caller has been cancelled (the client went away, or the server is stopping).
The checks are rate-limited, so a checkpoint in a hot loop costs a clock read.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

from verigraph.errors import VeriGraphError

_PAGE = os.sysconf("SC_PAGE_SIZE") if hasattr(os, "sysconf") else 4096
CHECK_EVERY_S = 0.02


class BudgetExceeded(VeriGraphError):
    """A call ran out of its time or memory budget, or its caller was cancelled."""


@dataclass(frozen=True)
class CallBudget:
    """Limits of one call: seconds of wall clock and MiB of process growth."""

    wall_s: float = 30.0
    memory_mib: float = 512.0


def rss_bytes() -> int:
    """Resident set size of this process (Linux /proc; 0 where unavailable)."""
    try:
        with open("/proc/self/statm", "rb") as f:
            return int(f.read().split()[1]) * _PAGE
    except (OSError, IndexError, ValueError):
        return 0


class _Meter:
    def __init__(self, budget: CallBudget, name: str, cancelled: Callable[[], None] | None) -> None:
        self.budget = budget
        self.name = name
        self.cancelled = cancelled
        self.start = time.monotonic()
        self.rss0 = rss_bytes()
        self.next_check = self.start + CHECK_EVERY_S

    def check(self) -> None:
        now = time.monotonic()
        if now < self.next_check:
            return
        self.next_check = now + CHECK_EVERY_S
        if self.cancelled is not None:
            try:
                self.cancelled()
            except BaseException:
                raise BudgetExceeded(f"{self.name} was cancelled (the client went away or "
                                     "the server is stopping)", field=self.name, value=None,
                                     fix="send the request again if you still need it") from None
        if now - self.start > self.budget.wall_s:
            raise BudgetExceeded(
                f"{self.name} ran longer than its {self.budget.wall_s:g} s budget",
                field=self.name, value=round(now - self.start, 2),
                fix="make the request smaller (fewer objects or actions), or ask the operator "
                    "for a larger budget (verigraph serve --tool-seconds)")
        grown = (rss_bytes() - self.rss0) / (1024 * 1024)
        if grown > self.budget.memory_mib:
            raise BudgetExceeded(
                f"{self.name} grew the server by {grown:.0f} MiB, more than its "
                f"{self.budget.memory_mib:g} MiB budget", field=self.name, value=round(grown),
                fix="make the request smaller, or ask the operator for a larger budget "
                    "(verigraph serve --tool-mib)")


_METER: ContextVar[_Meter | None] = ContextVar("verigraph_budget", default=None)


def checkpoint() -> None:
    """Raise BudgetExceeded if the current call is over budget or cancelled."""
    meter = _METER.get()
    if meter is not None:
        meter.check()


@contextmanager
def within(budget: CallBudget, name: str, cancelled: Callable[[], None] | None = None
           ) -> Iterator[None]:
    """Run the block under `budget`; `cancelled` raises when the caller has gone."""
    token = _METER.set(_Meter(budget, name, cancelled))
    try:
        yield
    finally:
        _METER.reset(token)
