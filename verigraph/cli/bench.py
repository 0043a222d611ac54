"""`verigraph bench NAME [ARGS]`: run `benchmarks/bench_NAME.py` from a source checkout.

Benchmarks live beside the package (not inside it) so their code and result tables
stay out of the installed library; this command only finds and runs them.
`verigraph bench report RESULTS.jsonl [--plot DIR]` renders the Markdown tables (and
PNG figures) of a results file written by `verigraph bench plan --results`.
"""

from __future__ import annotations

import argparse
import runpy
import sys
from pathlib import Path
from typing import Any

from verigraph.errors import VeriGraphError
from verigraph.extras import require


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
                       description=f"Benchmarks: {', '.join(available()) or 'none found'}; "
                                   "`report RESULTS.jsonl [--plot DIR]` renders a results file.")
    p.add_argument("name", help="benchmark name, e.g. validate, or report")
    p.add_argument("args", nargs=argparse.REMAINDER, help="passed to the benchmark")
    p.set_defaults(handler=run_bench)


def report_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="verigraph bench report",
                                description="Markdown tables and PNG figures from a results "
                                            "file of `verigraph bench plan --results`.")
    p.add_argument("results", help="the JSONL results file")
    p.add_argument("--plot", metavar="DIR", help="also write PNG figures into DIR")
    p.add_argument("--out", help="write the Markdown here too")
    return p


def run_report(argv: list[str]) -> int:
    from verigraph.agent.evaluation.results import ResultsFile
    from verigraph.agent.evaluation.tables import render_report

    args = report_parser().parse_args(argv)
    if not Path(args.results).is_file():
        raise VeriGraphError(f"no results file at {args.results}", field="results",
                             value=args.results,
                             fix="give a file written by verigraph bench plan --results FILE")
    records = ResultsFile(args.results).load()
    text = render_report(records)
    print(text)
    if args.out:
        Path(args.out).write_text(text)
    if args.plot:
        require("scale", "matplotlib")
        from verigraph.agent.evaluation.plots import write_plots

        for path in write_plots(records, args.plot):
            print(f"wrote {path}", file=sys.stderr)
    return 0


def run_bench(args: argparse.Namespace) -> int:
    if args.name == "report":
        return run_report(list(args.args))
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
