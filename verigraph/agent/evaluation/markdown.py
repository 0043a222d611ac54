"""Markdown tables and committed results files: the one formatter every writer uses.

`verigraph bench plan`, `verigraph bench report`, the paper's tables and the scripts in
benchmarks/ all render their tables through `table`, so a table looks the same
wherever it comes from. `write_results` is the one way a run writes a results file
that is kept in the repository: it refuses to replace a larger run with a smaller one
(a quick check must not overwrite the committed 4000-episode table with 3 episodes).
"""

from __future__ import annotations

import os
import platform
import re
from collections.abc import Iterable, Sequence
from pathlib import Path

from verigraph.errors import VeriGraphError

RUN_SIZE = re.compile(r"^Episodes run: (\d+)", re.MULTILINE)


def machine() -> str:
    """The machine a measurement ran on (CPU model, cores, Python, OS), for every table."""
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return (f"{cpu}, {os.cpu_count()} cores, Python {platform.python_version()}, "
            f"{platform.system()} {platform.release()}")


def row(cells: Sequence[str]) -> str:
    """One table row."""
    return "| " + " | ".join(cells) + " |"


def table(header: Sequence[str], rows: Iterable[Sequence[str]]) -> list[str]:
    """A Markdown table as lines: header, rule, one line per row."""
    return [row(header), "|" + "---|" * len(header), *(row(r) for r in rows)]


def section_row(title: str, width: int) -> str:
    """A bold row that opens a block of rows (a planner kind), blank elsewhere."""
    return f"| **{title}** |" + " |" * (width - 1)


def run_size(text: str) -> int | None:
    """The episode count a results file states (`Episodes run: N`), if it states one."""
    match = RUN_SIZE.search(text)
    return int(match.group(1)) if match else None


def write_results(path: str | Path, text: str, *, force: bool = False,
                  flag: str = "--update-results") -> Path:
    """Write a committed results file unless that would replace a larger run.

    The sizes compared are the `Episodes run: N` lines of the old and the new text; a
    file or a text without one is written (nothing to compare). `force` overrides.
    """
    target = Path(path)
    new = run_size(text)
    old = run_size(target.read_text()) if target.is_file() else None
    if not force and old is not None and new is not None and new < old:
        raise VeriGraphError(
            f"{target} holds a run of {old} episodes; this run has {new}", field=flag,
            value=str(target),
            fix="run at least as many episodes, write elsewhere with --out FILE, or pass "
                "--force to replace the larger run")
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(text)
    return target
