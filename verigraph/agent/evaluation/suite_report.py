"""Tables about the suites themselves and about the planners' ingredients: difficulty per
group, the translator's accuracy, and what feedback is worth to the greedy baseline."""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping, Sequence

from verigraph.agent.evaluation.markdown import table
from verigraph.agent.evaluation.paper import GROUP_TITLES
from verigraph.agent.evaluation.tables import GroupStats
from verigraph.graph.model import SceneGraph
from verigraph.graph.translator import TranslationError, same_goal, translate
from verigraph.tasks.groups import GroupName, GroupTasks, suite_stats


def difficulty_table(groups: Sequence[GroupTasks]) -> list[str]:
    """Mean optimal plan length per group, its distribution and the task kinds."""
    body = []
    for group in groups:
        if group.not_run is not None:
            continue
        s = suite_stats(group)
        dist = ", ".join(f"{k}: {v}" for k, v in s.distribution.items())
        kinds = ", ".join(f"{k} {v}" for k, v in s.kinds.items())
        body.append([GROUP_TITLES[group.group], str(s.episodes), f"{s.mean_optimal:.2f}",
                     dist, kinds])
    return table(["group", "episodes", "mean optimal length",
                  "distribution (length: count)", "kinds"], body)


def translation_accuracy(group: GroupTasks) -> dict[str, tuple[int, int]]:
    """(correct, total) per language category, plus "all"."""
    correct: Counter[str] = Counter()
    total: Counter[str] = Counter()
    for task in group.tasks:
        truth = task.goal
        if truth is None or task.instruction is None:
            continue
        graph = SceneGraph.model_validate(task.load["graph"])
        try:
            ok = same_goal(translate(task.instruction, graph), truth)
        except TranslationError:
            ok = False
        for key in (task.category or "?", "all"):
            total[key] += 1
            correct[key] += ok
    return {k: (correct[k], total[k]) for k in sorted(total, key=lambda k: (k == "all", k))}


def translation_table(group: GroupTasks) -> list[str]:
    return table(["category", "translated exactly", "accuracy"],
                 [[key, f"{ok}/{n}", f"{100 * ok / n:.0f}%"]
                  for key, (ok, n) in translation_accuracy(group).items()])


def gap_table(full: Mapping[GroupName, GroupStats],
              others: Sequence[tuple[str, Mapping[GroupName, GroupStats]]]) -> list[str]:
    """Success with full feedback minus success with less, per group (percentage points)."""
    shown = list(full)
    header = ["greedy: full feedback minus", *[GROUP_TITLES[g] for g in shown], "all groups"]
    body = []

    def overall(stats: Mapping[GroupName, GroupStats]) -> float:
        n = sum(s.episodes for s in stats.values()) or 1
        return sum(s.success_rate * s.episodes for s in stats.values()) / n

    for name, stats in others:
        cells = [f"{100 * (full[g].success_rate - stats[g].success_rate):+.0f} pp"
                 for g in shown if g in stats]
        body.append([name, *cells, f"{100 * (overall(full) - overall(stats)):+.0f} pp"])
    return table(header, body)
