"""`verigraph solve` and `verigraph export-pddl`: the offline solver and the PDDL export.

(`verigraph validate` is verigraph/cli/validating.py, registered on its own so that
validating a plan does not import the solver.)
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from verigraph.cli.exits import EXIT_BUDGET, EXIT_NEGATIVE, EXIT_OK
from verigraph.cli.validating import emit_error, load_goal_arg
from verigraph.errors import VeriGraphError
from verigraph.solver.budget import (
    DEFAULT_MAX_EXPANSIONS,
    DEFAULT_MEMORY_LIMIT_MB,
    DEFAULT_TIME_LIMIT_S,
)


def register(sub: Any) -> None:
    s = sub.add_parser("solve", help="a reference plan by A* search, under a time/memory budget",
                       description="Exit 0 with a plan, 1 when the goal is unreachable, "
                                   "2 bad input, 3 when the budget ran out before any plan "
                                   "was found (the JSON reason says after how many "
                                   "expansions, seconds and MB).")
    s.add_argument("--scene", required=True)
    s.add_argument("--goal", required=True, help="goal file, or a predicate name (single_stack)")
    s.add_argument("--dictionary", metavar="NAME|FILE.json",
                   help="the scene's dictionary D: a built-in name, all, or a JSON file of "
                        "your own labels {extends, objects} (see docs/worlds.md)")
    s.add_argument("--json", action="store_true")
    s.add_argument("--max-expansions", type=int, default=DEFAULT_MAX_EXPANSIONS,
                   help=f"search nodes to expand at most (default {DEFAULT_MAX_EXPANSIONS:,})")
    s.add_argument("--time-limit", type=float, default=DEFAULT_TIME_LIMIT_S, metavar="SECONDS",
                   help=f"CPU-time budget in seconds (default {DEFAULT_TIME_LIMIT_S:g})")
    s.add_argument("--memory-limit", type=float, default=DEFAULT_MEMORY_LIMIT_MB, metavar="MB",
                   help="memory budget in MiB that the search may add to the process "
                        f"(default {DEFAULT_MEMORY_LIMIT_MB})")
    s.add_argument("--anytime", action="store_true",
                   help="return the fast strategy's plan at once, refine it with weighted A* "
                        "within the budget, and report the proven lower bound")
    s.set_defaults(handler=run_solve)

    e = sub.add_parser("export-pddl", help="write a STRIPS domain and problem")
    e.add_argument("--scene", required=True)
    e.add_argument("--goal", required=True)
    e.add_argument("--domain-out", required=True)
    e.add_argument("--problem-out", required=True)
    e.set_defaults(handler=run_export_pddl)


def run_solve(args: argparse.Namespace) -> int:
    from verigraph.cli.scenes import with_dictionary
    from verigraph.graph.io import load_scene
    from verigraph.solver import solve

    for name, value in (("--time-limit", args.time_limit), ("--memory-limit", args.memory_limit),
                        ("--max-expansions", args.max_expansions)):
        if not value > 0:
            return emit_error(VeriGraphError(f"{name} must be positive", field=name,
                                             value=value, fix=f"give {name} a positive number"),
                              args.json)
    try:
        scene = with_dictionary(load_scene(args.scene), args.dictionary)
        goal = load_goal_arg(args.goal)
        result = solve(scene, goal, max_expansions=args.max_expansions,
                       time_limit=args.time_limit, memory_limit_mb=args.memory_limit,
                       anytime=args.anytime)
    except VeriGraphError as exc:
        return emit_error(exc, args.json)
    except (MemoryError, RecursionError) as exc:  # last resort: an answer, never a traceback
        print(json.dumps({"reachable": None, "status": "budget_exhausted",
                          "reason": f"budget exhausted: {type(exc).__name__}"}))
        return EXIT_BUDGET
    if args.json:
        print(result.model_dump_json())
    else:
        print(result.text())
    if result.status == "budget_exhausted":
        return EXIT_BUDGET
    return EXIT_OK if result.reachable else EXIT_NEGATIVE


def run_export_pddl(args: argparse.Namespace) -> int:
    from verigraph.graph.io import load_scene
    from verigraph.graph.state import WorldState
    from verigraph.solver.pddl import domain_pddl, is_household, problem_pddl

    try:
        state = WorldState.from_graph(load_scene(args.scene))
        goal = load_goal_arg(args.goal)
        problem = problem_pddl(state, goal)
    except VeriGraphError as exc:
        return emit_error(exc, False)
    Path(args.domain_out).write_text(domain_pddl(is_household(state, goal)))
    Path(args.problem_out).write_text(problem)
    print(f"wrote {args.domain_out} and {args.problem_out}")
    return EXIT_OK
