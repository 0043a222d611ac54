"""Markdown tables for `verigraph bench plan`: success per group, rows grouped by planner
kind, and the t/k ablations. The paper's numbers have their own table (paper.py)."""

from __future__ import annotations

from collections.abc import Sequence

from verigraph.agent.evaluation.paper import GROUP_TITLES
from verigraph.agent.evaluation.runner import GroupStats, Setting
from verigraph.agent.evaluation.tasks import GROUPS, GroupName, GroupTasks

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
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for title, rows in sections:
        if not rows:
            continue
        lines.append(f"| **{title}** |" + " |" * (len(header) - 1))
        for setting, stats in rows:
            calls, actions, violations, seconds, errors = _totals(stats)
            cells = [_cell(stats.get(g), by_name[g]) for g in shown]
            lines.append(f"| {setting.label()} | " + " | ".join(cells) +
                         f" | {calls:.2f} | {actions:.2f} | {violations} | {errors} | "
                         f"{seconds:.1f} s |")
    return lines


def ablation_table(title: str, rows: Sequence[Row], groups: Sequence[GroupTasks],
                   knob: str) -> list[str]:
    """One row per value of the ablated knob (t or k)."""
    by_name = {g.group: g for g in groups}
    shown = [g for g in GROUPS if g in by_name and by_name[g].not_run is None]
    header = [knob, *[GROUP_TITLES[g] for g in shown], "all groups", "mean LLM calls",
              "mean actions", "violations caught"]
    lines = [f"**{title}**", "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for setting, stats in rows:
        calls, actions, violations, _, _ = _totals(stats)
        n = sum(s.episodes for s in stats.values()) or 1
        overall = sum(s.success_rate * s.episodes for s in stats.values()) / n
        value = setting.threshold if knob == "t" else setting.k
        cells = [_cell(stats.get(g), by_name[g]) for g in shown]
        lines.append(f"| {value} | " + " | ".join(cells) +
                     f" | {100 * overall:.0f}% | {calls:.2f} | {actions:.2f} | {violations} |")
    return lines


def not_run_notes(groups: Sequence[GroupTasks]) -> list[str]:
    return [f"- {GROUP_TITLES[g.group]}: not run ({g.not_run})" for g in groups
            if g.not_run is not None]
