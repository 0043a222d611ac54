"""A CPU-time, memory and expansion budget that every search checks as it goes.

Time is the CPU time of the searching thread (`time.thread_time`), not the wall clock:
a search gets the same number of expansions on an idle machine and on a busy one, so
a plan found within the budget does not depend on what else runs beside it, and the
limit bounds what the search costs. The wall time is still reported (`elapsed`).

Memory is the growth of the process's resident set since the budget started (read from
/proc/self/statm on Linux, ru_maxrss elsewhere), so the limit is what the search itself
allocates, not the interpreter and libraries already loaded. Checking costs a clock read
every `clock_every` calls and a /proc read every `memory_every` calls.
"""

from __future__ import annotations

import resource
import time
from dataclasses import dataclass, field

from verigraph.budget import checkpoint, rss_bytes

DEFAULT_TIME_LIMIT_S = 5.0
DEFAULT_MEMORY_LIMIT_MB = 200
DEFAULT_MAX_EXPANSIONS = 200_000


def resident_mb() -> float:
    """Current resident set size in MiB (the peak, ru_maxrss, where /proc is missing)."""
    rss = rss_bytes()
    return rss / 2**20 if rss else resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


class SearchBudgetSpent(Exception):  # noqa: N818 - a control-flow signal, not an error
    """Raised inside a search when a limit is reached; carries the reason."""


@dataclass(slots=True)
class SearchBudget:
    """Limits for one solve call; `check()` raises SearchBudgetSpent when one is passed."""

    time_limit_s: float = DEFAULT_TIME_LIMIT_S
    memory_limit_mb: float = DEFAULT_MEMORY_LIMIT_MB
    max_expansions: int = DEFAULT_MAX_EXPANSIONS
    memory_every: int = 256
    clock_every: int = 8
    expansions: int = 0
    started: float = field(default_factory=time.perf_counter)
    started_cpu: float = field(default_factory=time.thread_time)
    base_mb: float = field(default_factory=resident_mb)
    peak_mb: float = 0.0
    _calls: int = 0

    def elapsed(self) -> float:
        return time.perf_counter() - self.started

    def used_mb(self) -> float:
        used = max(0.0, resident_mb() - self.base_mb)
        self.peak_mb = max(self.peak_mb, used)
        return used

    def reason(self, what: str) -> str:
        return (f"budget exhausted ({what}) after {self.expansions} expansions / "
                f"{self.elapsed():.1f} s / {self.peak_mb:.0f} MB")

    def check(self, *, memory: bool = False) -> None:
        """Call often (per expansion and inside large successor loops); `memory` forces
        the resident-set read (for loops whose every step allocates a lot). The server's
        per-call budget and cancellation (verigraph.budget) are checked first."""
        checkpoint()
        self._calls += 1
        if self.expansions > self.max_expansions:
            raise SearchBudgetSpent(self.reason(f"{self.max_expansions} expansions"))
        if self._calls % self.clock_every == 0 \
                and time.thread_time() - self.started_cpu > self.time_limit_s:
            raise SearchBudgetSpent(self.reason(f"time limit {self.time_limit_s:g} s CPU"))
        if (memory or self._calls % self.memory_every == 0) \
                and self.used_mb() > self.memory_limit_mb:
            raise SearchBudgetSpent(self.reason(f"memory limit {self.memory_limit_mb:g} MB"))
