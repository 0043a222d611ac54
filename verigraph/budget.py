"""Budgets for long computations: wall clock, memory growth, cancellation.

Long loops anywhere in VeriGraph (plan validation, search, simulation) call
`checkpoint()` now and then. Outside a budget it does nothing. Inside `run_within(budget, ...)`
(the MCP server runs every heavy tool call in one, on its worker thread) it raises
BudgetExceeded once the call has run longer than its wall-clock budget, once the
process has grown by more than its memory budget since the call started, or once
the caller has been cancelled (the client went away, or the server is stopping).
The checks are rate-limited, so a checkpoint in a hot loop costs a clock read.

The command line has a budget too (`command_line_budget`): each check of `verigraph
validate` (a plan, each `--batch` item) and each plan of `verigraph val` may use
`--cpu-seconds` (or $VERIGRAPH_CPU_SECONDS; default `DEFAULT_CLI_CPU_S`, 0: none) of the
CPU of its thread, and no wall-clock or memory limit: a busy machine does not make a
check fail, and a file the command reads may legitimately need gigabytes.

Code that never reaches a checkpoint is stopped all the same: a watchdog thread looks
at every running budget every WATCH_EVERY_S and interrupts a call that is over its
wall clock by more than WATCH_GRACE_S, or over its memory budget, with an exception
raised in the call's own thread at its next Python bytecode (a C call that runs for
long, such as one large allocation, finishes first). `run_within` turns that into the
same BudgetExceeded; it is a function, not a context manager, because an interrupt could
land in a context manager's own exit, where nothing catches it. Cancellation stays with
the checkpoints: only the call's own thread can ask whether its caller has gone.
"""

from __future__ import annotations

import ctypes
import math
import os
import threading
import time
from collections.abc import Callable
from contextvars import ContextVar
from dataclasses import dataclass
from typing import TypeVar, cast

from verigraph.errors import VeriGraphError

T = TypeVar("T")
_PAGE = os.sysconf("SC_PAGE_SIZE") if hasattr(os, "sysconf") else 4096
CHECK_EVERY_S = 0.02
WATCH_EVERY_S = 0.05
WATCH_GRACE_S = 0.25  # a checkpoint gets this long to stop an overrun call itself
LANDING_S = 1.0  # how long a sent interrupt is given to land before it is withdrawn
DEFAULT_WALL_S = 30.0  # `verigraph serve --tool-seconds`
DEFAULT_MEMORY_MIB = 512.0  # `verigraph serve --tool-mib`
DEFAULT_CLI_CPU_S = 60.0  # `verigraph validate --cpu-seconds`, $VERIGRAPH_CPU_SECONDS
CPU_SECONDS_ENV = "VERIGRAPH_CPU_SECONDS"


class BudgetExceeded(VeriGraphError):
    """A call ran out of its time or memory budget, or its caller was cancelled."""


@dataclass(frozen=True)
class CallBudget:
    """Limits of one call: seconds of wall clock, MiB of process growth and, when set,
    seconds of its thread's CPU (the command line's budget)."""

    wall_s: float = DEFAULT_WALL_S
    memory_mib: float = DEFAULT_MEMORY_MIB
    cpu_s: float | None = None


def command_line_budget(seconds: float | None) -> CallBudget | None:
    """The budget of one command-line check: `seconds` of CPU (the `--cpu-seconds` flag;
    None: $VERIGRAPH_CPU_SECONDS, else DEFAULT_CLI_CPU_S), no wall-clock or memory limit
    (module docstring); None for 0, no limit."""
    if seconds is None:
        given = os.environ.get(CPU_SECONDS_ENV)
        if given is None:
            seconds = DEFAULT_CLI_CPU_S
        else:
            try:
                seconds = float(given)
            except ValueError:
                seconds = math.nan
            if not (math.isfinite(seconds) and seconds >= 0):
                raise VeriGraphError(f"${CPU_SECONDS_ENV} is '{given[:40]}', not a number of "
                                     "seconds", field=CPU_SECONDS_ENV, value=given[:40],
                                     fix=f"set {CPU_SECONDS_ENV} to seconds of CPU per "
                                         "check, such as 60 (0: no limit), or unset it")
    if seconds == 0:
        return None
    return CallBudget(wall_s=math.inf, memory_mib=math.inf, cpu_s=seconds)


def rss_bytes() -> int:
    """Resident set size of this process (Linux /proc; 0 where unavailable)."""
    try:
        with open("/proc/self/statm", "rb") as f:
            return int(f.read().split()[1]) * _PAGE
    except (OSError, IndexError, ValueError):
        return 0


class _Interrupted(BaseException):  # noqa: N818 - raised by the watchdog, never seen
    """What the watchdog raises in an overrun call's thread; `within` turns it into
    BudgetExceeded. A BaseException, so a tool's `except Exception` does not keep it."""


class _Meter:
    def __init__(self, budget: CallBudget, name: str, cancelled: Callable[[], None] | None) -> None:
        self.budget = budget
        self.name = name
        self.cancelled = cancelled
        self.start = time.monotonic()
        self.rss0 = rss_bytes() if math.isfinite(budget.memory_mib) else 0
        self.next_check = self.start + CHECK_EVERY_S
        self.thread = threading.get_ident()
        # the CPU clock of the call's thread, which the watchdog reads too (Linux; where
        # a thread's clock cannot be had, only the call's own checkpoints read its CPU)
        self.cpu_clock: int | None = None
        if budget.cpu_s is not None:
            try:
                self.cpu_clock = time.pthread_getcpuclockid(self.thread)
            except (AttributeError, OSError):
                self.cpu_clock = None
        self.cpu0 = 0.0
        self.cpu0 = self.cpu_used(mine=True) or 0.0
        self.done = False  # set when the call leaves `within`; the watchdog then lets go
        self.overrun: BudgetExceeded | None = None  # set when the watchdog interrupts it
        self.landed = False  # set when that interrupt has been raised in the call's thread

    def cpu_used(self, mine: bool = False) -> float | None:
        """The CPU seconds of the call's thread (since `cpu0` once set); `mine`: asked in
        that thread. None where it cannot be read from this thread."""
        if self.budget.cpu_s is None:
            return None
        if self.cpu_clock is not None:
            try:
                used = time.clock_gettime(self.cpu_clock)
            except OSError:  # the thread has ended
                return None
        elif mine:
            used = time.thread_time()
        else:
            return None
        return used - self.cpu0

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
        problem = self.over(now, mine=True)
        if problem is not None:
            raise problem

    def over(self, now: float, grace_s: float = 0.0, mine: bool = False
             ) -> BudgetExceeded | None:
        """The error for a call over its budget (wall clock or CPU with `grace_s` more),
        else None; `mine`: asked in the call's thread."""
        cpu = self.cpu_used(mine)
        if cpu is not None and self.budget.cpu_s is not None \
                and cpu > self.budget.cpu_s + grace_s:
            return BudgetExceeded(
                f"{self.name} used more than its {self.budget.cpu_s:g} s of CPU",
                field=self.name, value=round(cpu, 2),
                fix="make the input smaller (fewer objects, bindings or steps), or give "
                    f"each check more CPU time (verigraph validate --cpu-seconds S, or "
                    f"{CPU_SECONDS_ENV}=S; 0: no limit)")
        if now - self.start > self.budget.wall_s + grace_s:
            return BudgetExceeded(
                f"{self.name} ran longer than its {self.budget.wall_s:g} s budget",
                field=self.name, value=round(now - self.start, 2),
                fix="make the request smaller (fewer objects or actions), or ask the operator "
                    "for a larger budget (verigraph serve --tool-seconds)")
        if not math.isfinite(self.budget.memory_mib):
            return None
        grown = (rss_bytes() - self.rss0) / (1024 * 1024)
        if grown > self.budget.memory_mib:
            return BudgetExceeded(
                f"{self.name} grew the server by {grown:.0f} MiB, more than its "
                f"{self.budget.memory_mib:g} MiB budget", field=self.name, value=round(grown),
                fix="make the request smaller, or ask the operator for a larger budget "
                    "(verigraph serve --tool-mib)")
        return None


def _raise_in(thread: int, exc: type[BaseException] | None) -> None:
    """Raise `exc` in the thread `thread` at its next bytecode (None: clear a pending one)."""
    ctypes.pythonapi.PyThreadState_SetAsyncExc(
        ctypes.c_ulong(thread), ctypes.py_object(exc) if exc is not None else None)


class _Watchdog:
    """One daemon thread per process that interrupts overrun calls (module docstring)."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.meters: set[_Meter] = set()
        self.pid: int | None = None  # the process its thread runs in (none after a fork)
        self.wake = threading.Event()

    def add(self, meter: _Meter) -> None:
        with self.lock:
            self.meters.add(meter)
            if self.pid != os.getpid():
                self.pid = os.getpid()
                threading.Thread(target=self._watch, name="verigraph-budget-watchdog",
                                 daemon=True).start()

    def remove(self, meter: _Meter) -> bool:
        """Let go of `meter`; True if the watchdog has interrupted its call."""
        with self.lock:
            meter.done = True
            self.meters.discard(meter)
            return meter.overrun is not None

    def _watch(self) -> None:
        while True:
            self.wake.wait(WATCH_EVERY_S)
            now = time.monotonic()
            with self.lock:
                for meter in list(self.meters):
                    if meter.done or meter.overrun is not None:
                        continue
                    problem = meter.over(now, WATCH_GRACE_S)
                    if problem is not None:
                        meter.overrun = problem
                        _raise_in(meter.thread, _Interrupted)


_WATCHDOG = _Watchdog()
_METER: ContextVar[_Meter | None] = ContextVar("verigraph_budget", default=None)


def checkpoint() -> None:
    """Raise BudgetExceeded if the current call is over budget or cancelled."""
    meter = _METER.get()
    if meter is not None:
        meter.check()


def run_within(budget: CallBudget, name: str, fn: Callable[[], T],
               cancelled: Callable[[], None] | None = None) -> T:
    """`fn()` under `budget`, in this thread; `cancelled` raises when the caller has gone.
    A call that overruns without reaching a checkpoint is interrupted all the same, and
    no interrupt outlives this function (one that lands as `fn` returns still counts:
    the call was over its budget)."""
    meter = _Meter(budget, name, cancelled)
    token = _METER.set(meter)
    try:
        _WATCHDOG.add(meter)
        result: T | None = None
        try:
            result = fn()
        except _Interrupted:
            meter.landed = True
        finally:
            _release(meter)
        if meter.overrun is not None:
            raise meter.overrun from None
        return cast(T, result)
    finally:
        _METER.reset(token)


def _release(meter: _Meter) -> None:
    """Take `meter` off the watchdog and make sure no interrupt it sent is left pending.

    A sent interrupt is let land here (a short loop of bytecode, where the interpreter
    delivers it) rather than withdrawn: CPython withdraws one by leaving its eval-loop
    flag set with no exception behind it, and a profiler installed later in that thread
    (`sys.setprofile`) then never gets past its next call."""
    while True:
        try:
            if _WATCHDOG.remove(meter) and not meter.landed:
                deadline = time.monotonic() + LANDING_S
                while time.monotonic() < deadline:
                    pass  # the pending interrupt lands at one of these backward jumps
                _raise_in(meter.thread, None)  # not landed in time: withdraw it after all
            return
        except _Interrupted:
            meter.landed = True
