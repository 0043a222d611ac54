"""`verigraph bench plan`: the paper's Table 2 setting and its ablations, measured here.

Main table, rows grouped by planner kind: the privileged oracle (ceiling; iterative and
direct), the rule-based translator + solver, the greedy feedback-driven baseline
(iterative with full feedback, the constraint id only, no feedback; direct), the noisy
LLM stand-in (iterative, direct, and the paper's literal rule: only the end token stops,
and it is trusted), and any LLM backend named in `planners`. Then: reliability (pass^k,
with `samples` > 1), the suites' difficulty, the translator's accuracy, the feedback
gap, the noisy planner's t and k ablations, and the paper's own numbers in a table of
their own. Settings that occur in several tables run once. `PlanConfig` is the
benchmark's input as data; the command line that fills it is `verigraph.cli.bench`.
"""

from __future__ import annotations

import time
from collections.abc import Sequence

from pydantic import BaseModel, ConfigDict, Field

from verigraph.agent.evaluation.engine import RunOptions, run_jobs
from verigraph.agent.evaluation.paper import paper_table
from verigraph.agent.evaluation.spec import Setting, jobs_for, suite_version, task_index
from verigraph.agent.evaluation.suite_report import (
    difficulty_table,
    gap_table,
    translation_table,
)
from verigraph.agent.evaluation.tables import (
    GroupStats,
    ablation_table,
    not_run_notes,
    reliability_table,
    stats_by_group,
    success_table,
)
from verigraph.errors import VeriGraphError
from verigraph.planning.factory import PLANNER_NAMES
from verigraph.planning.iteration import DEFAULT_K, DEFAULT_THRESHOLD
from verigraph.tasks.groups import (
    GROUPS,
    SUITE_VERSION,
    GroupName,
    GroupTasks,
    build_groups,
)

T_VALUES = (2, 3, 5, 10)
K_VALUES = (2, 3, 5, 10)
DEFAULT_PLANNERS = ("oracle", "rule-based", "greedy", "noisy")


class PlanConfig(BaseModel):
    """What `bench plan` measures (the how, serial or Ray, is `RunOptions`)."""

    model_config = ConfigDict(extra="forbid")

    episodes: int = Field(default=50, description="episodes (tasks) per group")
    seed: int = Field(default=0, description="task seed")
    groups: list[str] = Field(default_factory=lambda: [str(g) for g in GROUPS])
    planners: list[str] = Field(default_factory=lambda: list(DEFAULT_PLANNERS))
    noise: float = 0.3
    k: int = DEFAULT_K
    threshold: int = DEFAULT_THRESHOLD  # the error threshold t
    max_iterations: int = 30
    no_progress: int = 15
    ground_truth_graphs: bool = False
    simulate: bool = False
    ablations: bool = True
    ablation_episodes: int | None = None
    samples: int = Field(default=1, description="runs per task, each with its own planner "
                                                "seed; > 1 adds pass^k")
    record: str | None = None
    replay: str | None = None

    def check(self) -> None:
        """Refuse values no run can use, naming the flag that set them."""
        for flag, value in (("--episodes", self.episodes), ("--samples", self.samples),
                            ("--ablation-episodes", self.ablation_episodes)):
            if value is not None and value < 1:
                raise VeriGraphError(f"{flag} must be at least 1", field=flag, value=value,
                                     fix=f"use e.g. {flag} {50 if flag != '--samples' else 4}")
        unknown = [p for p in self.planners if p not in PLANNER_NAMES]
        if unknown:
            raise VeriGraphError(f"unknown planner(s): {', '.join(unknown)}",
                                 field="--planners", value=unknown[0],
                                 fix=f"use {', '.join(PLANNER_NAMES)}")
        unknown = [g for g in self.groups if g not in GROUPS]
        if unknown:
            raise VeriGraphError(f"unknown group(s): {', '.join(unknown)}", field="--groups",
                                 value=unknown[0], fix=f"use {', '.join(GROUPS)}")
        if self.record and self.replay:
            raise VeriGraphError("--record and --replay exclude each other", field="--replay",
                                 value=self.replay,
                                 fix="record once, then replay in another run")


KINDS = {
    "oracle": "Privileged ceiling: oracle (reads the true goal, plans optimally)",
    "rule-based": "Rule-based: instruction translator + solver (reads only the prompt)",
    "greedy": "Greedy feedback-driven baseline (no lookahead, reads only the prompt)",
    "noisy": "Noisy solver: offline LLM stand-in (reads only the prompt)",
}
LLM_KIND = "LLM backends"
Sections = list[tuple[str, list[Setting]]]


def _settings(args: PlanConfig) -> tuple[Sections, list[Setting], list[Setting]]:
    planners = args.planners
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
    io = {"record_dir": args.record, "replay_dir": args.replay}
    if args.record or args.replay:
        sections = {title: [s.model_copy(update=io) for s in rows]
                    for title, rows in sections.items()}
        t_rows = [s.model_copy(update=io) for s in t_rows]
        k_rows = [s.model_copy(update=io) for s in k_rows]
    return list(sections.items()), t_rows, k_rows


def _groups(args: PlanConfig, n: int) -> list[GroupTasks]:
    chosen: tuple[GroupName, ...] = tuple(g for g in GROUPS if g in args.groups)
    return build_groups(chosen, n, args.seed, ground_truth=args.ground_truth_graphs,
                        simulate=args.simulate)


def run_plan(args: PlanConfig, options: RunOptions | None = None) -> str:
    """Run the benchmark and return the Markdown report (it ends `Episodes run: N; ...`,
    the size `markdown.write_results` compares before replacing a committed file)."""
    args.check()
    options = options or RunOptions()
    started = time.perf_counter()
    sections, t_rows, k_rows = _settings(args)
    main = [s for _, rows in sections for s in rows]
    groups = _groups(args, args.episodes)
    ablation_n = args.ablation_episodes or args.episodes
    ablation_groups = groups if ablation_n == args.episodes else _groups(args, ablation_n)
    setup_s = time.perf_counter() - started

    plan: list[tuple[Setting, list[GroupTasks]]] = [(s, groups) for s in main]
    if args.ablations:
        plan += [(s, ablation_groups) for s in (*t_rows, *k_rows)]
    unique: dict[tuple[Setting, int], list[GroupTasks]] = {}
    for setting, gs in plan:
        unique.setdefault((setting, id(gs)), gs)
    suite = suite_version(args.seed, ground_truth=args.ground_truth_graphs,
                          simulate=args.simulate)
    jobs = {key: jobs_for(key[0], gs, suite, args.samples) for key, gs in unique.items()}
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

    sampled = (f"{args.samples} samples per task (pass@1 counts every sample); "
               if args.samples > 1 else "")
    graphs = "; ".join(f"{g.group}: {g.graphs}" for g in groups if g.not_run is None)
    lines = [
        "## Planning success (the paper's Table 2 setting)", "",
        f"Suite version {SUITE_VERSION}; {args.episodes} episodes per group, task seed "
        f"{args.seed}; noisy planner: {args.noise:.0%} of proposed actions wrong; loop: "
        f"stop when the goal holds, no-progress stop after {args.no_progress} iterations, "
        f"at most {args.max_iterations} iterations; graphs: {graphs or 'none'}; "
        f"{sampled}"
        f"{'simulated' if args.simulate else 'graph-only'} execution"
        f"{f'; planner answers replayed from {args.replay}' if args.replay else ''}"
        f"{f'; transcripts recorded to {args.record}' if args.record else ''}. Wall time is "
        "the sum of episode times of the row.", "",
        *success_table([(title, rows(settings, groups)) for title, settings in sections],
                       groups), "",
    ]
    if args.samples > 1:
        lines += [f"### Reliability: pass^k (all k = {args.samples} samples of a task succeed)",
                  "", "pass@1 is the success rate over every sample; pass^k counts a task "
                  "only when all its samples succeed (tau-bench's reliability measure).", "",
                  *reliability_table([(s, results[(s, id(groups))]) for s in main], groups),
                  ""]
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
    if args.ablations:
        lines += [*ablation_table(f"Ablation: error threshold t (noisy {args.noise:.0%}, "
                                  f"k={args.k})", rows(t_rows, ablation_groups),
                                  ablation_groups, "t"), "",
                  *ablation_table(f"Ablation: actions per iteration k (noisy {args.noise:.0%}, "
                                  f"t={args.threshold})", rows(k_rows, ablation_groups),
                                  ablation_groups, "k"), ""]
    lines += ["### The paper's numbers (Table 2)", "", *paper_table(), ""]
    lines += [f"Episodes run: {total}; task generation {setup_s:.1f} s; total wall time "
              f"{wall:.1f} s."]
    return "\n".join(lines) + "\n"
