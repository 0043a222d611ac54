"""Shared helpers for benchmarks: machine description, medians, Markdown tables.

Tables and the machine line come from `verigraph.agent.evaluation.markdown`, the one
formatter every results writer (these scripts, `bench plan`, `bench report`) uses.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from pathlib import Path

from verigraph.agent.evaluation.markdown import machine, table

RESULTS = Path(__file__).parent / "results"

__all__ = ["RESULTS", "machine", "median_time", "write_table"]


def median_time(fn: Callable[[], object], runs: int = 7,
                before: Callable[[], object] | None = None) -> tuple[float, list[float]]:
    """Median wall time of `runs` calls after one warm-up call; `before` runs untimed
    ahead of each (dropping a cache, so each call starts cold)."""
    if before is not None:
        before()
    fn()
    times = []
    for _ in range(runs):
        if before is not None:
            before()
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times), times


def write_table(name: str, title: str, header: list[str], rows: list[list[str]],
                notes: str = "") -> Path:
    RESULTS.mkdir(parents=True, exist_ok=True)
    lines = [f"# {title}", "", f"Machine: {machine()}  ", f"Date: {time.strftime('%Y-%m-%d')}",
             "", *table(header, rows)]
    if notes:
        lines += ["", notes]
    path = RESULTS / f"{name}.md"
    path.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return path
