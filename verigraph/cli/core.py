"""`verigraph validate`, `verigraph solve` and `verigraph export-pddl`: the offline verifier."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from verigraph.cli.validating import (
    EXIT_NEGATIVE,
    EXIT_OK,
    emit_error,
    load_goal_arg,
    register_validate,
)
from verigraph.errors import VeriGraphError


def register(sub: Any) -> None:
    register_validate(sub)

    s = sub.add_parser("solve", help="an optimal reference plan by A* search",
                       description="Exit 0 with a plan, 1 when the goal is unreachable, "
                                   "2 bad input.")
    s.add_argument("--scene", required=True)
    s.add_argument("--goal", required=True, help="goal file, or a predicate name (single_stack)")
    s.add_argument("--json", action="store_true")
    s.add_argument("--max-expansions", type=int, default=200_000)
    s.set_defaults(handler=run_solve)

    e = sub.add_parser("export-pddl", help="write a STRIPS domain and problem")
    e.add_argument("--scene", required=True)
    e.add_argument("--goal", required=True)
    e.add_argument("--domain-out", required=True)
    e.add_argument("--problem-out", required=True)
    e.set_defaults(handler=run_export_pddl)


def run_solve(args: argparse.Namespace) -> int:
    from verigraph.graph.io import load_scene
    from verigraph.solver import solve

    try:
        scene = load_scene(args.scene)
        goal = load_goal_arg(args.goal)
        result = solve(scene, goal, max_expansions=args.max_expansions)
    except VeriGraphError as exc:
        return emit_error(exc, args.json)
    if args.json:
        print(result.model_dump_json())
    else:
        print(result.text())
    return EXIT_OK if result.reachable else EXIT_NEGATIVE


def run_export_pddl(args: argparse.Namespace) -> int:
    from verigraph.graph.io import load_scene
    from verigraph.graph.state import WorldState
    from verigraph.solver.pddl import domain_pddl, problem_pddl

    try:
        state = WorldState.from_graph(load_scene(args.scene))
        goal = load_goal_arg(args.goal)
        problem = problem_pddl(state, goal)
    except VeriGraphError as exc:
        return emit_error(exc, False)
    Path(args.domain_out).write_text(domain_pddl())
    Path(args.problem_out).write_text(problem)
    print(f"wrote {args.domain_out} and {args.problem_out}")
    return EXIT_OK
