"""Tables about the suites themselves and about the planners' ingredients: difficulty per
group, the translator's accuracy, and what feedback is worth to the greedy baseline."""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping, Sequence

from verigraph.agent.evaluation.paper import GROUP_TITLES
from verigraph.agent.evaluation.runner import GroupStats
from verigraph.agent.evaluation.tasks import GroupName, GroupTasks, suite_stats
from verigraph.agent.translator import TranslationError, same_goal, translate
from verigraph.graph.model import SceneGraph


def difficulty_table(groups: Sequence[GroupTasks]) -> list[str]:
    """Mean optimal plan length per group, its distribution and the task kinds."""
    lines = ["| group | episodes | mean optimal length | distribution (length: count) | "
             "kinds |", "|---|---|---|---|---|"]
    for group in groups:
        if group.not_run is not None:
            continue
        s = suite_stats(group)
        dist = ", ".join(f"{k}: {v}" for k, v in s.distribution.items())
        kinds = ", ".join(f"{k} {v}" for k, v in s.kinds.items())
        lines.append(f"| {GROUP_TITLES[group.group]} | {s.episodes} | {s.mean_optimal:.2f} | "
                     f"{dist} | {kinds} |")
    return lines


def translation_accuracy(group: GroupTasks) -> dict[str, tuple[int, int]]:
    """(correct, total) per language category, plus "all"."""
    correct: Counter[str] = Counter()
    total: Counter[str] = Counter()
    for task in group.tasks:
        if task.truth is None or task.instruction is None:
            continue
        graph = SceneGraph.model_validate(task.spec.load["graph"])
        try:
            ok = same_goal(translate(task.instruction, graph), task.truth)
        except TranslationError:
            ok = False
        for key in (task.category or "?", "all"):
            total[key] += 1
            correct[key] += ok
    return {k: (correct[k], total[k]) for k in sorted(total, key=lambda k: (k == "all", k))}


def translation_table(group: GroupTasks) -> list[str]:
    lines = ["| category | translated exactly | accuracy |", "|---|---|---|"]
    for key, (ok, n) in translation_accuracy(group).items():
        lines.append(f"| {key} | {ok}/{n} | {100 * ok / n:.0f}% |")
    return lines


def gap_table(full: Mapping[GroupName, GroupStats],
              others: Sequence[tuple[str, Mapping[GroupName, GroupStats]]]) -> list[str]:
    """Success with full feedback minus success with less, per group (percentage points)."""
    shown = list(full)
    header = ["greedy: full feedback minus", *[GROUP_TITLES[g] for g in shown], "all groups"]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]

    def overall(stats: Mapping[GroupName, GroupStats]) -> float:
        n = sum(s.episodes for s in stats.values()) or 1
        return sum(s.success_rate * s.episodes for s in stats.values()) / n

    for name, stats in others:
        cells = [f"{100 * (full[g].success_rate - stats[g].success_rate):+.0f} pp"
                 for g in shown if g in stats]
        lines.append(f"| {name} | " + " | ".join(cells) +
                     f" | {100 * (overall(full) - overall(stats)):+.0f} pp |")
    return lines
