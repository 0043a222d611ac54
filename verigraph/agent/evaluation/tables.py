"""Markdown rendered from a results file (`verigraph bench report RESULTS.jsonl`).

The outcome tables depend only on what the episodes did, never on the order they
finished in or how long they took, so a resumed run renders the same tables as an
uninterrupted one; wall time, requests and retries go to a separate "Timing" section.
Rows are settings (a planner with its loop parameters), sorted; the t and k ablation
tables appear for every family of settings that differs only in t (or only in k).
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable, Sequence
from typing import Any

from verigraph.agent.evaluation.paper import GROUP_TITLES, paper_table
from verigraph.agent.evaluation.report import ablation_table
from verigraph.agent.evaluation.results import EpisodeRecord
from verigraph.agent.evaluation.runner import GroupStats, aggregate
from verigraph.agent.evaluation.spec import Setting
from verigraph.agent.evaluation.tasks import GROUPS, GroupName, GroupTasks

TIMING_HEADING = "## Timing"


def stats_by_group(records: Iterable[EpisodeRecord]) -> dict[GroupName, GroupStats]:
    """GroupStats per group, in the benchmark's group order."""
    by_group: dict[GroupName, list[EpisodeRecord]] = defaultdict(list)
    for record in records:
        by_group[record.group].append(record)
    return {g: aggregate(g, [r.to_result() for r in by_group[g]]) for g in GROUPS
            if g in by_group}


def _order(setting: Setting) -> tuple[Any, ...]:
    return (setting.planner, setting.mode, setting.feedback, setting.done_policy,
            setting.stop_on_goal, setting.noise, setting.k, setting.threshold,
            setting.max_iterations, setting.no_progress)


def by_setting(records: Iterable[EpisodeRecord]) -> dict[Setting, list[EpisodeRecord]]:
    """Records per setting, settings sorted (not in file order)."""
    rows: dict[Setting, list[EpisodeRecord]] = defaultdict(list)
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


def _outcome_table(rows: dict[Setting, list[EpisodeRecord]], shown: list[GroupName]
                   ) -> list[str]:
    tokens = any(r.total_tokens is not None for rs in rows.values() for r in rs)
    header = ["planner / mode", *[GROUP_TITLES[g] for g in shown], "episodes",
              "mean planner calls", "mean iterations", "mean actions", "violations caught",
              "errors", *(["mean tokens"] if tokens else [])]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for setting, records in rows.items():
        stats = stats_by_group(records)
        cells = [f"{100 * stats[g].success_rate:.0f}%" if g in stats else "-" for g in shown]
        row = [setting.label(), *cells, str(len(records)),
               f"{_mean([r.planner_calls for r in records]):.2f}",
               f"{_mean([r.iterations for r in records]):.2f}",
               f"{_mean([r.actions for r in records]):.2f}",
               str(sum(r.violations for r in records)),
               str(sum(r.error is not None for r in records))]
        if tokens:
            row.append(f"{_mean([r.total_tokens or 0 for r in records]):.0f}")
        lines.append("| " + " | ".join(row) + " |")
    return lines


def _timing_table(rows: dict[Setting, list[EpisodeRecord]]) -> list[str]:
    lines = ["| planner / mode | episode time (sum) | mean per episode | requests | retries |",
             "|---|---|---|---|---|"]
    for setting, records in rows.items():
        seconds = sum(r.wall_s for r in records)
        lines.append(f"| {setting.label()} | {seconds:.1f} s | {seconds / len(records):.3f} s "
                     f"| {sum(r.requests for r in records)} | "
                     f"{sum(r.retries for r in records)} |")
    return lines


def render_report(records: Sequence[EpisodeRecord]) -> str:
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
