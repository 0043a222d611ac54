"""Build verigraph/env/data/behavior.jsonl, the tasks of `verigraph/behavior-v0`, from
the installed `bddl` (`pip install 'verigraph-mcp[household]'`):

    python scripts/build_behavior_suite.py [--from benchmarks-records.jsonl]

One task per activity the reference solver solves optimally within 1 s here
(verigraph.tasks.behavior.behavior_tasks). With `--from` (the JSONL that
`verigraph bench behavior --jsonl FILE` writes) only the activities that run solved
optimally are tried, which saves solving the rest again.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from verigraph.env.dataset import suite_path, write_jsonl
from verigraph.tasks.behavior import behavior_tasks


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--from", dest="records", type=Path, default=None)
    args = parser.parse_args()
    names = None
    if args.records is not None:
        rows = [json.loads(line) for line in args.records.read_text().splitlines() if line]
        names = sorted({r["activity"] for r in rows
                        if r["status"] == "solved" and r.get("optimal")})
    tasks = [t.model_copy(update={"task_id": f"behavior/0/{t.task_id.split('/', 1)[1]}"})
             for t in behavior_tasks(names=names)]
    path = suite_path("behavior")
    write_jsonl(tasks, path)
    print(f"wrote {len(tasks)} tasks to {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
