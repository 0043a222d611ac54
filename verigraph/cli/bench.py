"""`verigraph bench NAME [ARGS]`: run `benchmarks/bench_NAME.py` from a source checkout.

Benchmarks live beside the package (not inside it) so their code and result tables
stay out of the installed library; this command only finds and runs them.
"""

from __future__ import annotations

import argparse
import runpy
import sys
from pathlib import Path
from typing import Any

from verigraph.errors import VeriGraphError


def benchmarks_dir() -> Path | None:
    here = Path(__file__).resolve().parents[2] / "benchmarks"
    for candidate in (here, Path.cwd() / "benchmarks"):
        if candidate.is_dir():
            return candidate
    return None


def available() -> list[str]:
    root = benchmarks_dir()
    if root is None:
        return []
    return sorted(p.stem.removeprefix("bench_") for p in root.glob("bench_*.py"))


def register(sub: Any) -> None:
    p = sub.add_parser("bench", help="run a benchmark and write its table to "
                                     "benchmarks/results/",
                       description=f"Benchmarks: {', '.join(available()) or 'none found'}.")
    p.add_argument("name", help="benchmark name, e.g. validate")
    p.add_argument("args", nargs=argparse.REMAINDER, help="passed to the benchmark")
    p.set_defaults(handler=run_bench)


def run_bench(args: argparse.Namespace) -> int:
    root = benchmarks_dir()
    if root is None:
        raise VeriGraphError("no benchmarks/ directory found", field="name",
                             fix="run from a source checkout of VeriGraph")
    script = root / f"bench_{args.name}.py"
    if not script.is_file():
        raise VeriGraphError(f"no benchmark named '{args.name}'", field="name", value=args.name,
                             fix=f"use one of: {', '.join(available())}")
    sys.argv = [str(script), *args.args]
    try:
        runpy.run_path(str(script), run_name="__main__")
    except SystemExit as exc:
        return int(exc.code or 0)
    return 0
