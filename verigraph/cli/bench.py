"""`verigraph bench NAME [ARGS]`: the benchmarks, from an installed package or a checkout.

`verigraph bench plan` (the paper's Table 2 setting) and `verigraph bench report
RESULTS.jsonl [--plot DIR]` run from the installed package: their flags are parsed
here and the work is `verigraph.agent.evaluation`. Every other benchmark is a script
`benchmarks/bench_NAME.py` beside the package (so its code and result tables stay out
of the installed library); this command finds it in a source checkout and runs it.

`bench plan` prints its report; it writes a file only when asked: `--out FILE`, or
`--update-results` for the committed table in the checkout's benchmarks/results/
(plan.md, or plan_ground_truth.md with --ground-truth-graphs). Neither replaces a file
that holds a larger run (more episodes) unless `--force` is given, so a quick check
never overwrites the committed figures.
"""

from __future__ import annotations

import argparse
import runpy
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from verigraph.cli.exits import EXIT_OK
from verigraph.errors import VeriGraphError
from verigraph.extras import require

if TYPE_CHECKING:  # the evaluation loads only when a benchmark runs (fast `--help`)
    from verigraph.agent.evaluation.engine import RunOptions
    from verigraph.agent.evaluation.plan_bench import PlanConfig
    from verigraph.jobs.limiter import BackendLimits

BUILTIN = ("plan", "report")


def benchmarks_dir() -> Path | None:
    here = Path(__file__).resolve().parents[2] / "benchmarks"
    for candidate in (here, Path.cwd() / "benchmarks"):
        if candidate.is_dir():
            return candidate
    return None


def available() -> list[str]:
    root = benchmarks_dir()
    scripts = set() if root is None else {p.stem.removeprefix("bench_")
                                          for p in root.glob("bench_*.py")}
    return sorted(scripts | set(BUILTIN))


def register(sub: Any) -> None:
    p = sub.add_parser("bench", help="run a benchmark and write its table to "
                                     "benchmarks/results/",
                       description=f"Benchmarks: {', '.join(available())}; "
                                   "`report RESULTS.jsonl [--plot DIR]` renders a results file.")
    p.add_argument("name", help="benchmark name, e.g. validate, plan, or report")
    p.add_argument("args", nargs=argparse.REMAINDER, help="passed to the benchmark")
    p.set_defaults(handler=run_bench)


# -- bench plan ---------------------------------------------------------------------------
def add_engine_arguments(p: argparse.ArgumentParser) -> None:
    """The options of the execution engine (`RunOptions`), shared by every benchmark
    that uses it."""
    g = p.add_argument_group("execution (serial by default; Ray with --ray)")
    g.add_argument("--ray", nargs="?", const="local", metavar="ADDRESS",
                   help="run episodes on Ray: without ADDRESS a local Ray with this "
                        "machine's cores; 'auto', 'HOST:PORT' or 'ray://HOST:10001' joins "
                        "a running cluster")
    g.add_argument("--results", metavar="FILE.jsonl",
                   help="append one JSON line per finished episode; a rerun skips the "
                        "episodes already there (render with `verigraph bench report`)")
    g.add_argument("--concurrency", type=int,
                   help="with --ray: episodes in flight (default: the cluster's cores)")
    g.add_argument("--rpm", type=int, help="requests per minute allowed per planner backend, "
                                           "shared by every worker")
    g.add_argument("--max-concurrent", type=int,
                   help="planner requests in flight allowed per backend")
    g.add_argument("--limit", action="append", default=[], metavar="BACKEND=RPM[/IN_FLIGHT]",
                   help="a named backend's own budget, e.g. openai:gpt-4o-mini=500/16 "
                        "(repeatable; the backend name is the record's `planner`)")
    g.add_argument("--retries", type=int, default=4,
                   help="retries of a planner request on HTTP 429/5xx (default 4)")
    g.add_argument("--backoff", type=float, default=0.5,
                   help="first retry delay in seconds, doubled each retry (default 0.5)")
    g.add_argument("--simulated-latency", type=float, default=0.0, metavar="SECONDS",
                   help="wait this long before every planner answer (a stand-in for a "
                        "model API, to measure concurrency)")
    g.add_argument("--traces", metavar="DIR", help="write each episode's trace JSON here")
    g.add_argument("--no-progress-bar", action="store_true", help="no progress bar on stderr")


def plan_parser() -> argparse.ArgumentParser:
    from verigraph.agent.evaluation import plan_bench
    from verigraph.planning.factory import PLANNER_NAMES
    from verigraph.planning.iteration import DEFAULT_K, DEFAULT_THRESHOLD
    from verigraph.tasks.groups import GROUPS

    p = argparse.ArgumentParser(prog="verigraph bench plan", description=plan_bench.__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--episodes", type=int, default=50, help="episodes per group (default 50)")
    p.add_argument("--seed", type=int, default=0, help="task seed (default 0)")
    p.add_argument("--groups", default=",".join(GROUPS),
                   help=f"comma-separated subset of {', '.join(GROUPS)}")
    p.add_argument("--planners", default=",".join(plan_bench.DEFAULT_PLANNERS),
                   help=f"comma-separated planners for the main table ({', '.join(PLANNER_NAMES)})")
    p.add_argument("--noise", type=float, default=0.3, help="noisy planner's mistake rate")
    p.add_argument("--k", type=int, default=DEFAULT_K,
                   help="actions per iteration (main table)")
    p.add_argument("--threshold", "-t", type=int, default=DEFAULT_THRESHOLD,
                   help="error threshold (main table)")
    p.add_argument("--max-iterations", type=int, default=30,
                   help="stop an episode after this many iterations even if tau < t "
                        "(a planner that keeps making valid but useless moves)")
    p.add_argument("--no-progress", type=int, default=15,
                   help="stop an episode after this many iterations without a new lowest "
                        "distance to the goal (0 = never)")
    p.add_argument("--samples", type=int, default=1, metavar="K",
                   help="run every task K times, each with its own planner seed, and report "
                        "pass^K (all K succeed) next to pass@1 (default 1)")
    p.add_argument("--ground-truth-graphs", action="store_true",
                   help="use true goal graphs instead of perceiving goal images (separates "
                        "planning errors from perception errors)")
    p.add_argument("--simulate", action="store_true",
                   help="also execute every action in the 2D simulator (slower)")
    p.add_argument("--no-ablations", action="store_true", help="skip the t and k ablations")
    p.add_argument("--record", metavar="DIR",
                   help="write every episode's planner transcript (prompts and replies) to "
                        "DIR, one JSONL file per row and task")
    p.add_argument("--replay", metavar="DIR",
                   help="answer from transcripts recorded with --record instead of calling "
                        "the planners (re-scores a paid run offline; no key needed)")
    p.add_argument("--ablation-episodes", type=int,
                   help="episodes per group in the ablations (default: --episodes)")
    p.add_argument("--out", help="write the Markdown report here")
    p.add_argument("--update-results", action="store_true",
                   help="write the committed table benchmarks/results/plan.md (or "
                        "plan_ground_truth.md) of the source checkout")
    p.add_argument("--force", action="store_true",
                   help="let --out or --update-results replace a file holding a larger run")
    add_engine_arguments(p)
    return p


def _check_flags(args: argparse.Namespace) -> None:
    checks = (("--concurrency", args.concurrency, 1), ("--rpm", args.rpm, 1),
              ("--max-concurrent", args.max_concurrent, 1), ("--retries", args.retries, 0),
              ("--backoff", args.backoff, 0), ("--simulated-latency", args.simulated_latency, 0))
    for flag, value, least in checks:
        if value is not None and value < least:
            raise VeriGraphError(f"{flag} must be at least {least}", field=flag, value=value,
                                 fix=f"give {flag} a value >= {least}, or leave it out")
    if args.retries > 20:
        raise VeriGraphError("--retries must be at most 20", field="--retries",
                             value=args.retries, fix="use e.g. --retries 4")


def parse_limit(text: str) -> tuple[str, BackendLimits]:
    """`NAME=RPM` or `NAME=RPM/IN_FLIGHT` (RPM may be empty: `NAME=/4`)."""
    from verigraph.jobs.limiter import BackendLimits

    name, sep, budget = text.rpartition("=")
    rpm, _, in_flight = budget.partition("/")
    try:
        if not (sep and name) or not (rpm or in_flight):
            raise ValueError(text)
        return name, BackendLimits(requests=int(rpm) if rpm else None,
                                   concurrency=int(in_flight) if in_flight else None)
    except ValueError:
        raise VeriGraphError(f"not a backend limit: {text!r}", field="--limit", value=text,
                             fix="write BACKEND=RPM or BACKEND=RPM/IN_FLIGHT with positive "
                                 "whole numbers, e.g. openai:gpt-4o-mini=500/16") from None


def options_from_args(args: argparse.Namespace) -> RunOptions:
    """The engine's `RunOptions` of parsed `add_engine_arguments` flags."""
    from verigraph.agent.evaluation.engine import RunOptions
    from verigraph.agent.evaluation.guard import RetryPolicy
    from verigraph.agent.evaluation.worker import EngineConfig
    from verigraph.jobs.limiter import BackendLimits
    from verigraph.planning.factory import PlannerOptions

    _check_flags(args)
    return RunOptions(
        ray=args.ray, results=args.results, concurrency=args.concurrency,
        limits=BackendLimits(concurrency=args.max_concurrent, requests=args.rpm),
        backend_limits=dict(parse_limit(text) for text in args.limit),
        engine=EngineConfig(retry=RetryPolicy(retries=args.retries, backoff_s=args.backoff),
                            latency_s=args.simulated_latency, traces_dir=args.traces,
                            planner_options=PlannerOptions()),
        progress=not args.no_progress_bar)


def _names(text: str) -> list[str]:
    return [name.strip() for name in text.split(",") if name.strip()]


def plan_config(args: argparse.Namespace) -> PlanConfig:
    """The benchmark's `PlanConfig` of parsed `plan_parser` flags."""
    from verigraph.agent.evaluation.plan_bench import PlanConfig

    return PlanConfig(
        episodes=args.episodes, seed=args.seed, groups=_names(args.groups),
        planners=_names(args.planners), noise=args.noise, k=args.k, threshold=args.threshold,
        max_iterations=args.max_iterations, no_progress=args.no_progress,
        ground_truth_graphs=args.ground_truth_graphs, simulate=args.simulate,
        ablations=not args.no_ablations, ablation_episodes=args.ablation_episodes,
        samples=args.samples, record=args.record, replay=args.replay)


def plan_title(ground_truth: bool) -> str:
    if ground_truth:
        return ("# Planning benchmark with true goal graphs "
                "(verigraph bench plan --ground-truth-graphs)")
    return "# Planning benchmark (verigraph bench plan)"


def committed_plan_file(ground_truth: bool) -> Path:
    """benchmarks/results/plan[_ground_truth].md of the source checkout."""
    root = benchmarks_dir()
    if root is None:
        raise VeriGraphError("--update-results needs a source checkout (no benchmarks/ "
                             "directory found)", field="--update-results",
                             fix="run from a checkout of VeriGraph, or write with --out FILE")
    return root / "results" / ("plan_ground_truth.md" if ground_truth else "plan.md")


def plan_report(argv: Sequence[str]) -> str:
    """Run `bench plan` with these flags; the full Markdown text (written to --out and,
    with --update-results, to the committed table). Bad flags raise VeriGraphError."""
    from verigraph.agent.evaluation.markdown import machine, write_results
    from verigraph.agent.evaluation.plan_bench import run_plan

    args = plan_parser().parse_args(list(argv))
    options = options_from_args(args)
    config = plan_config(args)
    config.check()
    targets = [(Path(args.out), "--out")] if args.out else []
    if args.update_results:
        targets.append((committed_plan_file(args.ground_truth_graphs), "--update-results"))
    report = run_plan(config, options)
    text = f"{plan_title(args.ground_truth_graphs)}\n\nMachine: {machine()}\n\n{report}"
    for path, flag in targets:
        write_results(path, text, force=args.force, flag=flag)
        print(f"written to {path}", file=sys.stderr)
    return text


def run_plan_command(argv: Sequence[str]) -> int:
    print(plan_report(argv))
    return EXIT_OK


# -- bench report -------------------------------------------------------------------------
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
    return EXIT_OK


def run_bench(args: argparse.Namespace) -> int:
    if args.name == "report":
        return run_report(list(args.args))
    if args.name == "plan":
        return run_plan_command(list(args.args))
    root = benchmarks_dir()
    if root is None:
        raise VeriGraphError("no benchmarks/ directory found", field="name",
                             fix="run from a source checkout of VeriGraph (built in: "
                                 f"{', '.join(BUILTIN)})")
    script = root / f"bench_{args.name}.py"
    if not script.is_file():
        raise VeriGraphError(f"no benchmark named '{args.name}'", field="name", value=args.name,
                             fix=f"use one of: {', '.join(available())}")
    sys.argv = [str(script), *args.args]
    try:
        runpy.run_path(str(script), run_name="__main__")
    except SystemExit as exc:
        return int(exc.code or EXIT_OK)
    return EXIT_OK
