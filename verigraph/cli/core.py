"""`verigraph validate`, `verigraph solve` and `verigraph export-pddl`: the offline verifier."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from verigraph.cli.scenes import scene_graph
from verigraph.errors import InputFileError, VeriGraphError

EXIT_OK, EXIT_NEGATIVE, EXIT_BAD_INPUT = 0, 1, 2
MAX_PLAN_BYTES = 64 * 1024 * 1024


def register(sub: Any) -> None:
    p = sub.add_parser("validate", help="check a plan against a scene (and a goal)",
                       description="Per-step report; exit 0 valid (and goal reached), "
                                   "1 invalid or goal missed, 2 bad input.")
    p.add_argument("--scene", required=True, help="scene graph file (.json or .yaml) or a "
                                                  "built-in scene id (its goal applies "
                                                  "unless --goal is given)")
    p.add_argument("--plan", required=True, help="plan file: text (one action per line) or JSON")
    p.add_argument("--goal", help="goal file: a scene graph, {graph, partial} or {predicate}")
    p.add_argument("--json", action="store_true", help="print the report as JSON")
    p.add_argument("--all-errors", action="store_true",
                   help="continue past violations (skipping failed actions) to list all")
    p.set_defaults(handler=run_validate)

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


def read_plan_file(path: str) -> str:
    p = Path(path)
    if not p.is_file():
        raise InputFileError(f"plan file '{p}' does not exist", field="plan", value=path,
                             fix="give the path of a text or JSON plan")
    if p.stat().st_size > MAX_PLAN_BYTES:
        raise InputFileError("plan file is too large", field="plan", value=path,
                             fix=f"keep plans under {MAX_PLAN_BYTES} bytes")
    try:
        return p.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise InputFileError("plan file is not UTF-8 text", field="plan", value=path,
                             fix="save it as UTF-8") from None


def _load_goal_arg(goal: str) -> Any:
    from verigraph.graph.goal import PREDICATES, Goal
    from verigraph.graph.io import load_goal

    if goal in PREDICATES:
        return Goal.parse(goal)
    return load_goal(goal)


def _emit_error(exc: VeriGraphError, as_json: bool) -> int:
    if as_json:
        print(json.dumps({"ok": False, **exc.to_dict()}))
    print(f"error: {exc}", file=sys.stderr)
    for problem in getattr(exc, "problems", [])[1:]:
        print(f"  also [{problem.rule}] {problem.message} (fix: {problem.fix})", file=sys.stderr)
    return EXIT_BAD_INPUT


def run_validate(args: argparse.Namespace) -> int:
    from verigraph.actions.report import validate_plan

    try:
        scene, goal = scene_graph(args.scene)
        plan = read_plan_file(args.plan)
        goal = _load_goal_arg(args.goal) if args.goal else goal
        report = validate_plan(scene, plan, goal, all_errors=args.all_errors)
    except VeriGraphError as exc:
        return _emit_error(exc, args.json)
    if args.json:
        print(report.model_dump_json(exclude_none=True))
    else:
        print(report.text())
    return EXIT_OK if report.valid else EXIT_NEGATIVE


def run_solve(args: argparse.Namespace) -> int:
    from verigraph.graph.io import load_scene
    from verigraph.solver import solve

    try:
        scene = load_scene(args.scene)
        goal = _load_goal_arg(args.goal)
        result = solve(scene, goal, max_expansions=args.max_expansions)
    except VeriGraphError as exc:
        return _emit_error(exc, args.json)
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
        goal = _load_goal_arg(args.goal)
        problem = problem_pddl(state, goal)
    except VeriGraphError as exc:
        return _emit_error(exc, False)
    Path(args.domain_out).write_text(domain_pddl())
    Path(args.problem_out).write_text(problem)
    print(f"wrote {args.domain_out} and {args.problem_out}")
    return EXIT_OK
