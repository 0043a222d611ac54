"""The tables of planning results: per-group aggregates, the main and ablation tables
of `verigraph bench plan`, the reliability (pass^k) table, and the whole report of a
results file (`verigraph bench report RESULTS.jsonl`).

Every number comes from `BenchRecord`s, so `bench plan` and `bench report` render the
same thing from the same records. The outcome tables depend only on what the episodes
did, never on the order they finished in or how long they took, so a resumed run
renders the same tables as an uninterrupted one; wall time, requests and retries go to
a separate "Timing" section. The paper's numbers have their own table (paper.py).

pass^k (tau-bench's reliability measure): with n samples of a task, of which c
succeeded, a task contributes C(c, k) / C(n, k), the chance that k samples drawn from
the n all succeed; with k = n that is 1 when every sample succeeded, else 0. pass@1 is
the plain success rate over all samples.
"""

from __future__ import annotations

import math
import statistics
from collections import defaultdict
from collections.abc import Iterable, Sequence
from typing import Any

from pydantic import BaseModel, Field

from verigraph.agent.evaluation.markdown import row, section_row, table
from verigraph.agent.evaluation.paper import GROUP_TITLES, paper_table
from verigraph.agent.evaluation.results import BenchRecord
from verigraph.agent.evaluation.spec import Setting
from verigraph.tasks.groups import GROUPS, GroupName, GroupTasks

TIMING_HEADING = "## Timing"


class GroupStats(BaseModel):
    """Aggregates of one setting on one group."""

    group: GroupName
    episodes: int
    success_rate: float = Field(description="pass@1: successes over all episodes")
    mean_llm_calls: float
    mean_actions: float
    violations_caught: int
    errors: int
    seconds: float
    tasks: int = Field(default=0, description="distinct tasks")
    samples: int = Field(default=1, description="k of pass^k: fewest samples of a task")
    pass_k: float = Field(default=0.0, description="pass^k over the group's tasks")


def pass_hat_k(successes: int, samples: int, k: int) -> float:
    """tau-bench's pass^k of one task: C(c, k) / C(n, k) for c successes in n samples."""
    return math.comb(successes, k) / math.comb(samples, k) if 0 < k <= samples else 0.0


def aggregate(group: GroupName, records: Sequence[BenchRecord]) -> GroupStats:
    n = len(records)
    per_task: dict[str, list[bool]] = defaultdict(list)
    for record in records:
        per_task[record.task_id].append(record.success)
    k = min((len(v) for v in per_task.values()), default=1)
    pass_k = statistics.fmean(pass_hat_k(sum(v), len(v), k) for v in per_task.values()) \
        if per_task else 0.0
    return GroupStats(
        group=group, episodes=n,
        success_rate=sum(r.success for r in records) / n if n else 0.0,
        mean_llm_calls=statistics.fmean(r.planner_calls for r in records) if n else 0.0,
        mean_actions=statistics.fmean(r.actions for r in records) if n else 0.0,
        violations_caught=sum(r.violations for r in records),
        errors=sum(r.error is not None for r in records),
        seconds=sum(r.wall_s for r in records),
        tasks=len(per_task), samples=k, pass_k=pass_k)


def stats_by_group(records: Iterable[BenchRecord]) -> dict[GroupName, GroupStats]:
    """GroupStats per group, in the benchmark's group order."""
    by_group: dict[GroupName, list[BenchRecord]] = defaultdict(list)
    for record in records:
        by_group[record.group].append(record)
    return {g: aggregate(g, by_group[g]) for g in GROUPS if g in by_group}


Row = tuple[Setting, dict[GroupName, GroupStats]]


def _cell(stats: GroupStats | None, group: GroupTasks | None) -> str:
    if group is not None and group.not_run is not None:
        return "not run"
    if stats is None or stats.episodes == 0:
        return "-"
    return f"{100 * stats.success_rate:.0f}%"


def _totals(stats: dict[GroupName, GroupStats]) -> tuple[float, float, int, float, int]:
    values = list(stats.values())
    n = sum(s.episodes for s in values) or 1
    calls = sum(s.mean_llm_calls * s.episodes for s in values) / n
    actions = sum(s.mean_actions * s.episodes for s in values) / n
    violations = sum(s.violations_caught for s in values)
    seconds = sum(s.seconds for s in values)
    errors = sum(s.errors for s in values)
    return calls, actions, violations, seconds, errors


def success_table(sections: Sequence[tuple[str, Sequence[Row]]],
                  groups: Sequence[GroupTasks]) -> list[str]:
    """Success rate per group plus mean LLM calls, mean actions, violations, wall time and
    episodes ended by a planner error; a bold row opens each planner kind."""
    by_name = {g.group: g for g in groups}
    shown = [g for g in GROUPS if g in by_name]
    header = ["planner / mode", *[GROUP_TITLES[g] for g in shown], "mean LLM calls",
              "mean actions", "violations caught", "planner errors", "wall time"]
    lines = table(header, [])
    for title, rows in sections:
        if not rows:
            continue
        lines.append(section_row(title, len(header)))
        for setting, stats in rows:
            calls, actions, violations, seconds, errors = _totals(stats)
            cells = [_cell(stats.get(g), by_name[g]) for g in shown]
            lines.append(row([setting.label(), *cells, f"{calls:.2f}", f"{actions:.2f}",
                              str(violations), str(errors), f"{seconds:.1f} s"]))
    return lines


def reliability_table(rows: Sequence[Row], groups: Sequence[GroupTasks]) -> list[str]:
    """pass@1 and pass^k per group for each setting (k = samples per task)."""
    by_name = {g.group: g for g in groups}
    shown = [g for g in GROUPS if g in by_name and by_name[g].not_run is None]
    header = ["planner / mode", "k", *[f"{GROUP_TITLES[g]} pass@1 / pass^k" for g in shown],
              "all groups pass@1 / pass^k"]
    body = []
    for setting, stats in rows:
        present = [stats[g] for g in shown if g in stats]
        if not present:
            continue
        n = sum(s.episodes for s in present) or 1
        t = sum(s.tasks for s in present) or 1
        pass1 = sum(s.success_rate * s.episodes for s in present) / n
        passk = sum(s.pass_k * s.tasks for s in present) / t
        cells = [f"{100 * stats[g].success_rate:.0f}% / {100 * stats[g].pass_k:.0f}%"
                 if g in stats else "-" for g in shown]
        body.append([setting.label(), str(min(s.samples for s in present)), *cells,
                     f"{100 * pass1:.0f}% / {100 * passk:.0f}%"])
    return table(header, body)


def ablation_table(title: str, rows: Sequence[Row], groups: Sequence[GroupTasks],
                   knob: str) -> list[str]:
    """One row per value of the ablated knob (t or k)."""
    by_name = {g.group: g for g in groups}
    shown = [g for g in GROUPS if g in by_name and by_name[g].not_run is None]
    header = [knob, *[GROUP_TITLES[g] for g in shown], "all groups", "mean LLM calls",
              "mean actions", "violations caught"]
    body = []
    for setting, stats in rows:
        calls, actions, violations, _, _ = _totals(stats)
        n = sum(s.episodes for s in stats.values()) or 1
        overall = sum(s.success_rate * s.episodes for s in stats.values()) / n
        value = setting.threshold if knob == "t" else setting.k
        body.append([str(value), *[_cell(stats.get(g), by_name[g]) for g in shown],
                     f"{100 * overall:.0f}%", f"{calls:.2f}", f"{actions:.2f}",
                     str(violations)])
    return [f"**{title}**", "", *table(header, body)]


def not_run_notes(groups: Sequence[GroupTasks]) -> list[str]:
    return [f"- {GROUP_TITLES[g.group]}: not run ({g.not_run})" for g in groups
            if g.not_run is not None]


def _order(setting: Setting) -> tuple[Any, ...]:
    return (setting.planner, setting.mode, setting.feedback, setting.done_policy,
            setting.stop_on_goal, setting.noise, setting.k, setting.threshold,
            setting.max_iterations, setting.no_progress)


def by_setting(records: Iterable[BenchRecord]) -> dict[Setting, list[BenchRecord]]:
    """Records per setting, settings sorted (not in file order)."""
    rows: dict[Setting, list[BenchRecord]] = defaultdict(list)
    for record in records:
        rows[Setting.model_validate(record.settings)].append(record)
    return {s: rows[s] for s in sorted(rows, key=_order)}


def families(settings: Sequence[Setting], knob: str) -> list[list[Setting]]:
    """Groups of settings equal except for `knob` ('threshold' or 'k'), 2+ values each."""
    grouped: dict[tuple[Any, ...], list[Setting]] = defaultdict(list)
    for setting in settings:
        rest = setting.model_dump(exclude={knob})
        grouped[tuple(sorted(rest.items()))].append(setting)
    return [sorted(group, key=lambda s: getattr(s, knob)) for group in grouped.values()
            if len(group) >= 2]


def _mean(values: Sequence[float]) -> float:
    return sum(values) / len(values) if values else 0.0


def _outcome_table(rows: dict[Setting, list[BenchRecord]], shown: list[GroupName]
                   ) -> list[str]:
    tokens = any(r.total_tokens is not None for rs in rows.values() for r in rs)
    header = ["planner / mode", *[GROUP_TITLES[g] for g in shown], "episodes",
              "mean planner calls", "mean iterations", "mean actions", "violations caught",
              "errors", *(["mean tokens"] if tokens else [])]
    body = []
    for setting, records in rows.items():
        stats = stats_by_group(records)
        cells = [f"{100 * stats[g].success_rate:.0f}%" if g in stats else "-" for g in shown]
        line = [setting.label(), *cells, str(len(records)),
               f"{_mean([r.planner_calls for r in records]):.2f}",
               f"{_mean([r.iterations for r in records]):.2f}",
               f"{_mean([r.actions for r in records]):.2f}",
               str(sum(r.violations for r in records)),
               str(sum(r.error is not None for r in records))]
        if tokens:
            line.append(f"{_mean([r.total_tokens or 0 for r in records]):.0f}")
        body.append(line)
    return table(header, body)


def _timing_table(rows: dict[Setting, list[BenchRecord]]) -> list[str]:
    header = ["planner / mode", "episode time (sum)", "mean per episode", "requests",
              "retries"]
    body = []
    for setting, records in rows.items():
        seconds = sum(r.wall_s for r in records)
        body.append([setting.label(), f"{seconds:.1f} s", f"{seconds / len(records):.3f} s",
                     str(sum(r.requests for r in records)),
                     str(sum(r.retries for r in records))])
    return table(header, body)


def sampled(records: Iterable[BenchRecord]) -> bool:
    """Whether any task was sampled more than once (then pass^k is reported)."""
    return any(r.sample > 0 for r in records)


def render_report(records: Sequence[BenchRecord]) -> str:
    """The whole Markdown report of a results file."""
    if not records:
        return "No episodes in the results file yet.\n"
    rows = by_setting(records)
    present = {r.group for r in records}
    shown = [g for g in GROUPS if g in present]
    groups = [GroupTasks(group=g) for g in shown]
    suites = sorted({r.suite for r in records})
    errors: dict[str, int] = defaultdict(int)
    for record in records:
        if record.error_kind:
            errors[record.error_kind] += 1
    lines = ["## Planning success", "",
             f"{len(records)} episodes; suite {', '.join(suites)}.", "",
             *_outcome_table(rows, shown), ""]
    if errors:
        lines += ["Episodes that ended in an error: " + ", ".join(
            f"{n} {kind}" for kind, n in sorted(errors.items())), ""]
    if sampled(records):
        lines += ["### Reliability: pass^k (all k samples of a task succeed)", "",
                  *reliability_table([(s, stats_by_group(rs)) for s, rs in rows.items()],
                                     groups), ""]
    for knob, name, title in (("threshold", "t", "error threshold t"),
                              ("k", "k", "actions per iteration k")):
        for family in families(list(rows), knob):
            base = family[0]
            fixed = f"k={base.k}" if knob == "threshold" else f"t={base.threshold}"
            caption = f"Ablation: {title} ({base.label().split(',')[0]}, {base.mode}, {fixed})"
            stats_rows = [(s, stats_by_group(rows[s])) for s in family]
            lines += [*ablation_table(caption, stats_rows, groups, name), ""]
    lines += ["### The paper's numbers (Table 2)", "", *paper_table(), ""]
    lines += [TIMING_HEADING, "", *_timing_table(rows), ""]
    return "\n".join(lines)


def outcome_part(report: str) -> str:
    """The report without its timing section (what reruns must reproduce)."""
    return report.split(TIMING_HEADING, 1)[0]
