"""`verigraph bench plan`: the paper's Table 2 setting and its ablations, measured here.

Main table, rows grouped by planner kind: the privileged oracle (ceiling; iterative and
direct), the rule-based translator + solver, the greedy feedback-driven baseline
(iterative with full feedback, the constraint id only, no feedback; direct), the noisy
LLM stand-in (iterative, direct, and the paper's literal rule: only the end token stops,
and it is trusted), and any LLM backend named in --planners. Then: the suites'
difficulty, the translator's accuracy, the feedback gap, the noisy planner's t and k
ablations, and the paper's own numbers in a table of their own.
Settings that occur in several tables run once.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Sequence
from pathlib import Path

from verigraph.agent.evaluation.engine import add_engine_arguments, options_from_args, run_jobs
from verigraph.agent.evaluation.paper import paper_table
from verigraph.agent.evaluation.report import (
    ablation_table,
    not_run_notes,
    success_table,
)
from verigraph.agent.evaluation.runner import GroupStats, Setting
from verigraph.agent.evaluation.spec import jobs_for, suite_version, task_index
from verigraph.agent.evaluation.suite_report import (
    difficulty_table,
    gap_table,
    translation_table,
)
from verigraph.agent.evaluation.tables import stats_by_group
from verigraph.agent.evaluation.tasks import (
    GROUPS,
    SUITE_VERSION,
    GroupName,
    GroupTasks,
    build_groups,
)
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
    p.add_argument("--planners", default="oracle,rule-based,greedy,noisy",
                   help=f"comma-separated planners for the main table ({', '.join(PLANNER_NAMES)})")
    p.add_argument("--noise", type=float, default=0.3, help="noisy planner's mistake rate")
    p.add_argument("--k", type=int, default=3, help="actions per iteration (main table)")
    p.add_argument("--threshold", "-t", type=int, default=5, help="error threshold (main table)")
    p.add_argument("--max-iterations", type=int, default=30,
                   help="stop an episode after this many iterations even if tau < t "
                        "(a planner that keeps making valid but useless moves)")
    p.add_argument("--no-progress", type=int, default=15,
                   help="stop an episode after this many iterations without a new lowest "
                        "distance to the goal (0 = never)")
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
    add_engine_arguments(p)
    return p


KINDS = {
    "oracle": "Privileged ceiling: oracle (reads the true goal, plans optimally)",
    "rule-based": "Rule-based: instruction translator + solver (reads only the prompt)",
    "greedy": "Greedy feedback-driven baseline (no lookahead, reads only the prompt)",
    "noisy": "Noisy solver: offline LLM stand-in (reads only the prompt)",
}
LLM_KIND = "LLM backends"
Sections = list[tuple[str, list[Setting]]]


def _settings(args: argparse.Namespace) -> tuple[Sections, list[Setting], list[Setting]]:
    planners = [p.strip() for p in args.planners.split(",") if p.strip()]
    unknown = [p for p in planners if p not in PLANNER_NAMES]
    if unknown:
        raise VeriGraphError(f"unknown planner(s): {', '.join(unknown)}", field="--planners",
                             value=unknown[0], fix=f"use {', '.join(PLANNER_NAMES)}")
    sections: dict[str, list[Setting]] = {}
    for name in planners:
        base = Setting(planner=name, k=args.k, threshold=args.threshold, noise=args.noise,
                       max_iterations=args.max_iterations, no_progress=args.no_progress)
        direct = base.model_copy(update={"mode": "direct"})
        if name == "oracle":
            rows = [base, direct]
        elif name == "rule-based":
            rows = [base]
        elif name == "greedy":
            rows = [base, base.model_copy(update={"feedback": "constraint"}),
                    base.model_copy(update={"feedback": "none"}), direct]
        elif name == "noisy":
            rows = [base, direct, base.model_copy(update={"done_policy": "trust",
                                                          "stop_on_goal": False})]
        else:
            rows = [base, direct]
        sections.setdefault(KINDS.get(name, LLM_KIND), []).extend(rows)
    noisy = Setting(planner="noisy", noise=args.noise, max_iterations=args.max_iterations,
                    no_progress=args.no_progress)
    t_rows = [noisy.model_copy(update={"threshold": t, "k": args.k}) for t in T_VALUES]
    k_rows = [noisy.model_copy(update={"k": k, "threshold": args.threshold})
              for k in K_VALUES]
    if args.record and args.replay:
        raise VeriGraphError("--record and --replay exclude each other", field="--replay",
                             value=args.replay, fix="record once, then replay in another run")
    io = {"record_dir": args.record, "replay_dir": args.replay}
    if args.record or args.replay:
        sections = {title: [s.model_copy(update=io) for s in rows]
                    for title, rows in sections.items()}
        t_rows = [s.model_copy(update=io) for s in t_rows]
        k_rows = [s.model_copy(update=io) for s in k_rows]
    return list(sections.items()), t_rows, k_rows


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
    sections, t_rows, k_rows = _settings(args)
    main = [s for _, rows in sections for s in rows]
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
        "## Planning success (the paper's Table 2 setting)", "",
        f"Suite version {SUITE_VERSION}; {args.episodes} episodes per group, task seed "
        f"{args.seed}; noisy planner: {args.noise:.0%} of proposed actions wrong; loop: "
        f"stop when the goal holds, no-progress stop after {args.no_progress} iterations, "
        f"at most {args.max_iterations} iterations; graphs: {graphs or 'none'}; "
        f"{'simulated' if args.simulate else 'graph-only'} execution"
        f"{f'; planner answers replayed from {args.replay}' if args.replay else ''}"
        f"{f'; transcripts recorded to {args.record}' if args.record else ''}. Wall time is "
        "the sum of episode times of the row.", "",
        *success_table([(title, rows(settings, groups)) for title, settings in sections],
                       groups), "",
    ]
    notes = not_run_notes(groups) + [f"- {g.group}: {g.note}" for g in groups if g.note]
    if notes:
        lines += ["Notes:", *notes, ""]
    lines += ["### Task difficulty (optimal plan length, reference solver)", "",
              *difficulty_table(groups), ""]
    language = next((g for g in groups if g.group == "language" and g.not_run is None), None)
    if language is not None:
        lines += ["### Rule-based translator: instruction to goal", "",
                  "An instruction counts as translated when the translator's goal has "
                  "exactly the ground-truth goal's edges; the colloquial wordings are "
                  "outside its grammar.", "", *translation_table(language), ""]
    greedy = [s for s in main if s.planner == "greedy"]
    if len(greedy) == 4:
        full, constraint, none, direct = (results[(s, id(groups))] for s in greedy)
        lines += ["### What feedback is worth (greedy baseline)", "",
                  *gap_table(full, [("constraint id only", constraint),
                                    ("no feedback", none), ("direct (one shot)", direct)]),
                  ""]
    if not args.no_ablations:
        lines += [*ablation_table(f"Ablation: error threshold t (noisy {args.noise:.0%}, "
                                  f"k={args.k})", rows(t_rows, ablation_groups),
                                  ablation_groups, "t"), "",
                  *ablation_table(f"Ablation: actions per iteration k (noisy {args.noise:.0%}, "
                                  f"t={args.threshold})", rows(k_rows, ablation_groups),
                                  ablation_groups, "k"), ""]
    lines += ["### The paper's numbers (Table 2)", "", *paper_table(), ""]
    lines += [f"Episodes run: {total}; task generation {setup_s:.1f} s; total wall time "
              f"{wall:.1f} s."]
    text = "\n".join(lines) + "\n"
    if args.out:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        Path(args.out).write_text(text)
    return text
