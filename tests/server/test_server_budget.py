"""A heavy call's budget holds while it runs, also in code that never reaches a
checkpoint: the watchdog interrupts it in its own thread, and no interrupt outlives it."""

from __future__ import annotations

import contextlib
import subprocess
import sys
import threading
import time

import pytest

from verigraph.budget import BudgetExceeded, CallBudget, rss_bytes, run_within

pytestmark = pytest.mark.fast


def spin(seconds: float) -> int:
    """Pure Python for `seconds`, never calling checkpoint()."""
    end = time.monotonic() + seconds
    n = 0
    while time.monotonic() < end:
        n += 1
    return n


def test_a_loop_without_checkpoints_is_stopped_near_its_wall_clock_budget() -> None:
    start = time.monotonic()
    with pytest.raises(BudgetExceeded) as err:
        run_within(CallBudget(wall_s=0.2), "spin", lambda: spin(10))
    took = time.monotonic() - start
    assert took < 1.5, took
    assert "ran longer than its 0.2 s budget" in err.value.message
    assert "--tool-seconds" in (err.value.fix or "")


def test_memory_growth_without_checkpoints_is_stopped() -> None:
    assert rss_bytes() > 0  # Linux: /proc/self/statm
    held: list[bytes] = []

    def grow() -> None:
        end = time.monotonic() + 10
        while time.monotonic() < end and len(held) < 400:  # at most 400 MiB
            held.append(b"x" * (1 << 20))
            time.sleep(0.002)

    with pytest.raises(BudgetExceeded) as err:
        run_within(CallBudget(wall_s=30, memory_mib=40), "grow", grow)
    assert "MiB budget" in err.value.message and len(held) < 400
    held.clear()


def test_a_call_within_budget_is_untouched_and_leaves_no_interrupt_behind() -> None:
    assert run_within(CallBudget(wall_s=5), "short", lambda: 42) == 42
    # A call that ends just as its budget runs out: whatever happens, nothing lands later.
    for _ in range(6):
        with contextlib.suppress(BudgetExceeded):
            run_within(CallBudget(wall_s=0.01), "edge", lambda: spin(0.26))
    spin(0.4)  # an interrupt left pending would land here and fail the test


def test_calls_on_other_threads_keep_their_own_budgets() -> None:
    results: dict[str, object] = {}

    def worker(name: str, budget: float, seconds: float) -> None:
        try:
            results[name] = run_within(CallBudget(wall_s=budget), name, lambda: spin(seconds))
        except BudgetExceeded as exc:
            results[name] = exc

    threads = [threading.Thread(target=worker, args=("slow", 0.2, 10)),
               threading.Thread(target=worker, args=("fine", 5, 0.5))]
    for t in threads:
        t.start()
    for t in threads:
        t.join(15)
    assert isinstance(results["slow"], BudgetExceeded)
    assert isinstance(results["fine"], int)


def test_a_profiler_installed_after_an_interrupted_call_still_runs() -> None:
    """An interrupt is let land, never withdrawn behind the interpreter's back: a
    withdrawn one leaves CPython's eval-loop flag set, and a profiler installed later in
    that thread then spins at its first call (checked in a fresh interpreter, which would
    hang, so the subprocess has a timeout)."""
    code = (
        "import sys, threading, time\n"
        "from verigraph.budget import BudgetExceeded, CallBudget, run_within\n"
        "def spin():\n"
        "    t = time.monotonic()\n"
        "    while time.monotonic() - t < 10: pass\n"
        "try:\n"
        "    run_within(CallBudget(wall_s=0.1), 'spin', spin)\n"
        "except BudgetExceeded:\n"
        "    print('stopped')\n"
        "sys.setprofile(lambda frame, event, arg: None)\n"
        "threading.setprofile(lambda frame, event, arg: None)\n"
        "sys.setprofile(None)\n"
        "print('profiled')\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=60)
    assert out.stdout.split() == ["stopped", "profiled"], out.stderr
