"""`verigraph bench plan`: the paper's Table 2 and its two ablations, measured here.

Main table: each planner (default: oracle and noisy) iterative and direct, plus the
noisy planner with the paper's literal end-token rule (`trust`), on every task group.
Ablations (noisy planner): error threshold t in {2, 3, 5, 10} at k=3, and actions per
iteration k in {2, 3, 5, 10} at t=5. Settings that occur in several tables run once.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Sequence
from pathlib import Path

from verigraph.agent.evaluation.engine import add_engine_arguments, options_from_args, run_jobs
from verigraph.agent.evaluation.report import (
    ablation_table,
    not_run_notes,
    success_table,
)
from verigraph.agent.evaluation.runner import GroupStats, Setting
from verigraph.agent.evaluation.spec import jobs_for, suite_version, task_index
from verigraph.agent.evaluation.tables import stats_by_group
from verigraph.agent.evaluation.tasks import GROUPS, GroupName, GroupTasks, build_groups
from verigraph.agent.factory import PLANNER_NAMES
from verigraph.errors import VeriGraphError

T_VALUES = (2, 3, 5, 10)
K_VALUES = (2, 3, 5, 10)


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="verigraph bench plan", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--episodes", type=int, default=50, help="episodes per group (default 50)")
    p.add_argument("--seed", type=int, default=0, help="task seed (default 0)")
    p.add_argument("--groups", default=",".join(GROUPS),
                   help=f"comma-separated subset of {', '.join(GROUPS)}")
    p.add_argument("--planners", default="oracle,noisy",
                   help=f"comma-separated planners for the main table ({', '.join(PLANNER_NAMES)})")
    p.add_argument("--noise", type=float, default=0.3, help="noisy planner's mistake rate")
    p.add_argument("--k", type=int, default=3, help="actions per iteration (main table)")
    p.add_argument("--threshold", "-t", type=int, default=5, help="error threshold (main table)")
    p.add_argument("--max-iterations", type=int, default=30,
                   help="stop an episode after this many iterations even if tau < t "
                        "(a planner that keeps making valid but useless moves)")
    p.add_argument("--ground-truth-graphs", action="store_true",
                   help="use true goal graphs instead of perceiving goal images (separates "
                        "planning errors from perception errors)")
    p.add_argument("--simulate", action="store_true",
                   help="also execute every action in the 2D simulator (slower)")
    p.add_argument("--no-ablations", action="store_true", help="skip the t and k ablations")
    p.add_argument("--ablation-episodes", type=int,
                   help="episodes per group in the ablations (default: --episodes)")
    p.add_argument("--out", help="write the Markdown report here")
    add_engine_arguments(p)
    return p


def _settings(args: argparse.Namespace) -> tuple[list[Setting], list[Setting], list[Setting]]:
    planners = [p.strip() for p in args.planners.split(",") if p.strip()]
    unknown = [p for p in planners if p not in PLANNER_NAMES]
    if unknown:
        raise VeriGraphError(f"unknown planner(s): {', '.join(unknown)}", field="--planners",
                             value=unknown[0], fix=f"use {', '.join(PLANNER_NAMES)}")
    main: list[Setting] = []
    for name in planners:
        base = Setting(planner=name, k=args.k, threshold=args.threshold, noise=args.noise,
                       max_iterations=args.max_iterations)
        main += [base, base.model_copy(update={"mode": "direct"})]
        if name == "noisy":
            main.append(base.model_copy(update={"done_policy": "trust"}))
    noisy = Setting(planner="noisy", noise=args.noise, max_iterations=args.max_iterations)
    t_rows = [noisy.model_copy(update={"threshold": t, "k": 3}) for t in T_VALUES]
    k_rows = [noisy.model_copy(update={"k": k, "threshold": 5}) for k in K_VALUES]
    return main, t_rows, k_rows


def _groups(args: argparse.Namespace, n: int) -> list[GroupTasks]:
    names = [g.strip() for g in args.groups.split(",") if g.strip()]
    unknown = [g for g in names if g not in GROUPS]
    if unknown:
        raise VeriGraphError(f"unknown group(s): {', '.join(unknown)}", field="--groups",
                             value=unknown[0], fix=f"use {', '.join(GROUPS)}")
    chosen: tuple[GroupName, ...] = tuple(g for g in GROUPS if g in names)
    return build_groups(chosen, n, args.seed, ground_truth=args.ground_truth_graphs,
                        simulate=args.simulate)


def run(argv: Sequence[str] | None = None) -> str:
    """Run the benchmark and return the Markdown report."""
    args = parser().parse_args(argv)
    if args.episodes < 1:
        raise VeriGraphError("--episodes must be at least 1", field="--episodes",
                             value=args.episodes, fix="use e.g. --episodes 50")
    options = options_from_args(args)
    started = time.perf_counter()
    main, t_rows, k_rows = _settings(args)
    groups = _groups(args, args.episodes)
    ablation_n = args.ablation_episodes or args.episodes
    ablation_groups = groups if ablation_n == args.episodes else _groups(args, ablation_n)
    setup_s = time.perf_counter() - started

    plan: list[tuple[Setting, list[GroupTasks]]] = [(s, groups) for s in main]
    if not args.no_ablations:
        plan += [(s, ablation_groups) for s in (*t_rows, *k_rows)]
    unique: dict[tuple[Setting, int], list[GroupTasks]] = {}
    for setting, gs in plan:
        unique.setdefault((setting, id(gs)), gs)
    suite = suite_version(args.seed, ground_truth=args.ground_truth_graphs,
                          simulate=args.simulate)
    jobs = {key: jobs_for(key[0], gs, suite) for key, gs in unique.items()}
    tasks = {ref: t for gs in unique.values() for ref, t in task_index(gs).items()}
    records = run_jobs([j for js in jobs.values() for j in js], tasks, options)
    by_key = {r.key: r for r in records}
    total = len(by_key)
    results: dict[tuple[Setting, int], dict[GroupName, GroupStats]] = {
        key: stats_by_group([by_key[j.key()] for j in js]) for key, js in jobs.items()}
    wall = time.perf_counter() - started

    def rows(settings: Sequence[Setting], gs: list[GroupTasks]
             ) -> list[tuple[Setting, dict[GroupName, GroupStats]]]:
        return [(s, results[(s, id(gs))]) for s in settings]

    graphs = "; ".join(f"{g.group}: {g.graphs}" for g in groups if g.not_run is None)
    lines = [
        "## Planning success (Table 2)", "",
        f"{args.episodes} episodes per group, task seed {args.seed}; noisy planner mistake "
        f"rate {args.noise:.0%} per planner call; graphs: {graphs or 'none'}; "
        f"{'simulated' if args.simulate else 'graph-only'} execution. Wall time is the sum "
        "of episode times of the row.", "",
        *success_table(rows(main, groups), groups), "",
    ]
    notes = not_run_notes(groups)
    if notes:
        lines += ["Groups not run:", *notes, ""]
    if not args.no_ablations:
        lines += [*ablation_table(f"Ablation: error threshold t (noisy {args.noise:.0%}, k=3)",
                                  rows(t_rows, ablation_groups), ablation_groups, "t"), "",
                  *ablation_table(f"Ablation: actions per iteration k (noisy {args.noise:.0%}, "
                                  "t=5)", rows(k_rows, ablation_groups), ablation_groups, "k"),
                  ""]
    lines += [f"Episodes run: {total}; task generation {setup_s:.1f} s; total wall time "
              f"{wall:.1f} s."]
    text = "\n".join(lines) + "\n"
    if args.out:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        Path(args.out).write_text(text)
    return text
