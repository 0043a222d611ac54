"""PNG figures from a results file (`verigraph bench report RESULTS.jsonl --plot DIR`).

- `success_by_group.png`: success rate per task group, one bar per setting of the main
  comparison (the settings at the most common k and t; ablation-only rows are left to
  the curves);
- `ablation_t.png`, `ablation_k.png`: success against the error threshold t and against
  actions per iteration k, one line per group plus all groups together;
- `iterations_hist.png`: planner iterations per episode, successes and failures
  stacked, for the iterative settings.

matplotlib runs on its headless Agg backend, so no display is needed.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from verigraph.agent.evaluation.paper import GROUP_TITLES  # noqa: E402
from verigraph.agent.evaluation.results import BenchRecord  # noqa: E402
from verigraph.agent.evaluation.spec import Setting  # noqa: E402
from verigraph.agent.evaluation.tables import by_setting, families, stats_by_group  # noqa: E402
from verigraph.tasks.groups import GROUPS  # noqa: E402

DPI = 110


def _save(fig: Figure, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return path


def _rate(records: Sequence[BenchRecord]) -> float:
    return 100 * sum(r.success for r in records) / len(records) if records else 0.0


def success_by_group(rows: dict[Setting, list[BenchRecord]], path: Path) -> Path:
    common = Counter((s.k, s.threshold) for s in rows).most_common(1)[0][0]
    main = {s: rs for s, rs in rows.items() if (s.k, s.threshold) == common or s.mode == "direct"}
    groups = [g for g in GROUPS if any(r.group == g for rs in main.values() for r in rs)]
    fig, ax = plt.subplots(figsize=(max(6.0, 1.6 * len(groups) + 2), 4.5 + 0.18 * len(main)))
    width = 0.8 / max(len(main), 1)
    for i, (setting, records) in enumerate(main.items()):
        stats = stats_by_group(records)
        values = [100 * stats[g].success_rate if g in stats else 0.0 for g in groups]
        xs = [j + (i - (len(main) - 1) / 2) * width for j in range(len(groups))]
        ax.bar(xs, values, width, label=setting.label())
    ax.set_xticks(range(len(groups)), [GROUP_TITLES[g] for g in groups])
    ax.set_ylabel("success (%)")
    ax.set_ylim(0, 105)
    ax.set_title("Planning success by task group")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2)
    ax.grid(axis="y", alpha=0.3)
    return _save(fig, path)


def ablation(rows: dict[Setting, list[BenchRecord]], knob: str, path: Path) -> Path | None:
    found = families(list(rows), knob)
    if not found:
        return None
    fig, axes = plt.subplots(1, len(found), figsize=(6 * len(found), 4.2), squeeze=False)
    name = "error threshold t" if knob == "threshold" else "actions per iteration k"
    for ax, family in zip(axes[0], found, strict=True):
        xs = [getattr(s, knob) for s in family]
        groups = [g for g in GROUPS if any(r.group == g for s in family for r in rows[s])]
        for group in groups:
            ax.plot(xs, [_rate([r for r in rows[s] if r.group == group]) for s in family],
                    marker="o", label=GROUP_TITLES[group])
        ax.plot(xs, [_rate(rows[s]) for s in family], marker="s", color="black",
                linewidth=2.2, label="all groups")
        ax.set_xscale("log", base=2)
        ax.set_xticks(xs, [str(x) for x in xs])
        ax.set_xlabel(name)
        ax.set_ylabel("success (%)")
        ax.set_ylim(0, 105)
        fixed = f"k={family[0].k}" if knob == "threshold" else f"t={family[0].threshold}"
        ax.set_title(f"{family[0].label().split(',')[0]}, {family[0].mode}, {fixed}")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    return _save(fig, path)


def iterations_histogram(records: Sequence[BenchRecord], path: Path) -> Path:
    iterative = [r for r in records if r.settings.get("mode") == "iterative"] or list(records)
    top = max((r.iterations for r in iterative), default=1)
    bins = range(0, top + 2)
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.hist([[r.iterations for r in iterative if r.success],
             [r.iterations for r in iterative if not r.success]], bins=bins, stacked=True,
            label=["success", "failure"], color=["tab:green", "tab:red"], align="left")
    ax.set_xlabel("planner iterations per episode")
    ax.set_ylabel("episodes")
    ax.set_title(f"Iterations per episode ({len(iterative)} iterative episodes)")
    ax.legend()
    ax.grid(axis="y", alpha=0.3)
    return _save(fig, path)


def write_plots(records: Sequence[BenchRecord], directory: str | Path) -> list[Path]:
    """Every figure that the records support; returns the files written."""
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    if not records:
        return []
    rows = by_setting(records)
    written = [success_by_group(rows, out / "success_by_group.png")]
    for knob, name in (("threshold", "ablation_t.png"), ("k", "ablation_k.png")):
        path = ablation(rows, knob, out / name)
        if path is not None:
            written.append(path)
    written.append(iterations_histogram(records, out / "iterations_hist.png"))
    return written
