"""BEHAVIOR-1K benchmark: every activity of the installed `bddl` imported or refused (by
predicate), solved within a per-activity budget, its plan validated against the goal
formula, executed in an episode on the graph executor and the goal checked there.

Needs the `household` extra (`pip install 'verigraph-mcp[household]'`).
Run: verigraph bench behavior [--budget 10] [--activities a,b,...] [--jsonl FILE]
     verigraph bench behavior --from FILE.jsonl [FILE.jsonl ...]   (table only)

Each activity gets `--budget` CPU seconds for optimal A*; when that runs out, the same
again for the anytime search (greedy best-first search for a plan, its detours dropped,
then A* pruned by its length to shorten it or prove it optimal). Writes
benchmarks/results/behavior.md (with `--out`, another file). `--activities a,b` runs only those.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).parent))

from common import RESULTS, machine  # noqa: E402

from verigraph.agent.evaluation.markdown import table  # noqa: E402
from verigraph.graph.bddl_problem import HOUSEHOLD, SPATIAL, SUPPORTED, THERMAL  # noqa: E402
from verigraph.tasks.behavior import activities, run_activity  # noqa: E402

CLASSES = ("spatial", "household", "thermal")
CLASS_TEXT = {"spatial": f"spatial ({', '.join(SPATIAL)})",
              "household": f"+ household ({', '.join(HOUSEHOLD)})",
              "thermal": f"+ thermal ({', '.join(THERMAL)})"}


def run(names: list[str], budget: float, jsonl: Path | None) -> list[dict[str, Any]]:
    records = []
    out = jsonl.open("a") if jsonl is not None else None
    for i, name in enumerate(names, start=1):
        start = time.perf_counter()
        try:
            record = run_activity(name, time_limit=budget).as_json()
        except Exception as exc:  # reported per activity: the table says what broke
            record = {"activity": name, "status": "error", "predicate_class": _class(name),
                      "reason": f"{type(exc).__name__}: {exc}".replace("\n", " ")[:300]}
        record["wall_s"] = round(time.perf_counter() - start, 3)
        records.append(record)
        if out is not None:
            out.write(json.dumps(record) + "\n")
            out.flush()
        print(f"[{i}/{len(names)}] {name}: {record['status']}", file=sys.stderr)
    if out is not None:
        out.close()
    return records


def _class(name: str) -> str | None:
    from verigraph.graph.bddl_problem import import_problem
    from verigraph.tasks.behavior import activity_text

    try:
        return import_problem(activity_text(name), activity=name).predicate_class
    except Exception:  # the record's reason says what failed
        return None


def _lengths(rows: list[dict[str, Any]]) -> str:
    lengths = sorted(len(r["plan"]) for r in rows)
    if not lengths:
        return "-"
    return f"{lengths[0]} / {statistics.median(lengths):g} / {lengths[-1]}"


def _times(rows: list[dict[str, Any]]) -> str:
    times = sorted(r.get("seconds", {}).get("solve", 0.0) for r in rows)
    if not times:
        return "-"
    return f"{statistics.median(times):.2f} / {times[-1]:.2f}"


def report(records: list[dict[str, Any]], budget: float | None, note: str | None = None
           ) -> str:
    refused = [r for r in records if r["status"] == "refused"]
    imported = [r for r in records if r["status"] != "refused"]
    header = ["class", "activities", "solved (optimal)", "budget", "unreachable", "invalid",
              "reached only on paper", "error", "plan length min / median / max",
              "solve s median / max"]
    rows = []
    for name in CLASSES:
        mine = [r for r in imported if r.get("predicate_class") == name]
        solved = [r for r in mine if r["status"] == "solved"]
        count = Counter(r["status"] for r in mine)
        rows.append([CLASS_TEXT[name], str(len(mine)),
                     f"{len(solved)} ({sum(1 for r in solved if r.get('optimal'))})",
                     str(count["budget"]), str(count["unreachable"]), str(count["invalid"]),
                     str(count["paper"]), str(count["error"]), _lengths(solved),
                     _times(solved)])
    errors = [r for r in imported if r.get("predicate_class") is None]
    by_predicate = Counter(str(r.get("predicate")) for r in refused)
    total = len(records)
    lines = [
        "# BEHAVIOR-1K activities: imported, solved, validated, executed", "",
        f"Machine: {machine()}  ", f"Date: {time.strftime('%Y-%m-%d')}  ",
        f"Budget: {budget:g} CPU s per activity for optimal A*, then as much for the anytime "
        "search (greedy best-first, its detours dropped, then A* pruned by its plan)"
        if budget is not None else "Budget: as recorded", "",
        *([note, ""] if note else []),
        f"{total} activities (bddl's `activity_definitions`, problem0 of each): "
        f"{len(imported)} imported, {len(refused)} refused naming a predicate outside "
        f"the supported set ({', '.join(SUPPORTED)}).", "",
        "## Imported activities by class", "",
        *table(header, rows), "",
        "A class holds the activities whose widest predicate is of that class. *solved*: "
        "the solver's plan passes every action check in `validate_plan`, its goal formula "
        "holds at the end there, the plan runs in an episode on the graph executor and "
        "`check_goal` and the formula evaluator both find the goal reached there; "
        "*(optimal)*: A* proved no shorter plan (every action one step); the rest came from "
        "the anytime search (greedy best-first search, its detours dropped, then A* pruned "
        "by that plan's length, "
        "stopped by the budget before it proved the plan shortest). *reached only on "
        "paper*: validated as reaching the goal, not "
        "reached when executed. Times are wall-clock seconds of the `solve` call.", "",
        "## Refused, by the first unsupported predicate named", "",
        *table(["predicate", "activities"],
               [[p, str(n)] for p, n in by_predicate.most_common()]), "",
    ]
    unsolved = [r for r in imported if r["status"] != "solved"]
    if unsolved or errors:
        lines += ["## Imported but not solved: why", "",
                  *table(["activity", "class", "objects", "status", "why"],
                         [[r["activity"], str(r.get("predicate_class")),
                           str(r.get("objects", "")), r["status"],
                           str(r.get("reason") or "").replace("|", "/")[:200]]
                          for r in sorted(unsolved, key=lambda r: r["activity"])]), ""]
    lines += ["## Every imported activity", "",
              *table(["activity", "class", "objects", "status", "plan length", "optimal",
                      "solve s"],
                     [[r["activity"], str(r.get("predicate_class")), str(r.get("objects", "")),
                       r["status"], str(len(r.get("plan", []))) if r["status"] == "solved"
                       else "-", "yes" if r.get("optimal") else "no",
                       f"{r.get('seconds', {}).get('solve', 0.0):.2f}"]
                      for r in sorted(imported, key=lambda r: r["activity"])])]
    return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--budget", type=float, default=10.0,
                        help="CPU seconds per activity for each search (default 10)")
    parser.add_argument("--activities", default=None, help="comma-separated names (default all)")
    parser.add_argument("--jsonl", type=Path, default=None,
                        help="append one JSON record per activity here")
    parser.add_argument("--from", dest="sources", type=Path, nargs="+", default=None,
                        help="build the table from these JSONL records instead of running")
    parser.add_argument("--out", type=Path, default=RESULTS / "behavior.md")
    parser.add_argument("--note", default=None,
                        help="a paragraph under the header (e.g. which rows were re-measured)")
    args = parser.parse_args()
    if args.sources:
        records = [json.loads(line) for path in args.sources
                   for line in path.read_text().splitlines() if line.strip()]
        latest = {r["activity"]: r for r in records}
        text = report(sorted(latest.values(), key=lambda r: r["activity"]), args.budget,
                      args.note)
    else:
        names = args.activities.split(",") if args.activities else list(activities())
        text = report(run(names, args.budget, args.jsonl), args.budget, args.note)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
