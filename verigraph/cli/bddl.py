"""`verigraph bddl import ACTIVITY_OR_FILE -o DIR`: a BEHAVIOR-1K activity as scene and goal.

Writes DIR/scene.json (the scene graph over the `behavior` dictionary) and DIR/goal.json
(`{"formula": "..."}`, the activity's goal in BDDL over the scene's ids), then prints what
it wrote. An activity needing a predicate VeriGraph does not support exits 2 naming the
predicate and the activity, and writes nothing. Needs the `household` extra for an
activity name (its definitions come from the installed `bddl`); a .bddl file needs none.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from verigraph.cli.exits import EXIT_OK


def register(sub: Any) -> None:
    p = sub.add_parser("bddl", help="BEHAVIOR-1K activities (BDDL) as scenes and goals",
                       description=__doc__)
    inner = p.add_subparsers(dest="bddl_command", required=True)
    imp = inner.add_parser("import", help="write scene.json and goal.json of an activity",
                           description=__doc__)
    imp.add_argument("activity", metavar="ACTIVITY_OR_FILE",
                     help="an activity name (e.g. putting_dishes_away_after_cleaning) or a "
                          ".bddl problem file")
    imp.add_argument("-o", "--out", required=True, metavar="DIR",
                     help="directory for scene.json and goal.json (created if missing)")
    imp.add_argument("--json", action="store_true", help="print a JSON summary")
    imp.set_defaults(handler=run_import)


def run_import(args: argparse.Namespace) -> int:
    from verigraph.errors import VeriGraphError
    from verigraph.graph.bddl_problem import import_problem
    from verigraph.tasks.behavior import problem_text

    name, text = problem_text(args.activity)
    imported = import_problem(text, activity=name)
    graph = imported.scene_graph()  # refused before anything is written
    out = Path(args.out)
    try:
        out.mkdir(parents=True, exist_ok=True)
        (out / "scene.json").write_text(json.dumps(imported.scene, indent=1) + "\n")
        (out / "goal.json").write_text(json.dumps(imported.goal, indent=1) + "\n")
    except OSError as exc:
        raise VeriGraphError(f"cannot write to {args.out}: {exc.strerror}", field="--out",
                             value=str(args.out)[:120], fix="give a writable directory") from None
    rooms = sum(1 for n in imported.scene["nodes"] if n["id"] not in imported.ids.values())
    summary = {"activity": imported.activity, "class": imported.predicate_class,
               "objects": len(graph.nodes) - rooms, "rooms": rooms, "edges": len(graph.edges),
               "scene": str(out / "scene.json"), "goal": str(out / "goal.json"),
               "formula": imported.formula}
    if args.json:
        print(json.dumps(summary))
    else:
        print(f"imported {imported.activity} ({imported.predicate_class}): "
              f"{summary['objects']} objects in {rooms} room{'s' if rooms != 1 else ''}, "
              f"{len(graph.edges)} edges -> "
              f"{summary['scene']}, {summary['goal']}")
        print(f"goal: {imported.formula}")
    return EXIT_OK
