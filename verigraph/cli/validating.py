"""`verigraph validate`: a plan against a scene graph, a PDDL blocks-world problem, or a batch.

Three inputs, one report form (`verigraph.reporting`: what `--json` prints, and its one text):

* `--scene S --plan P [--goal G]`: a scene graph and a move/align plan;
* `--domain D --problem P --plan PLAN`: PDDL: the native blocks world for any domain that
  is one (under any names), the general engine for the rest of classical PDDL;
  `--planbench` adds PlanBench task 3's verdict and explanation;
* `--batch FILE.jsonl`: one item per line, one JSON line out per item, errors per item.

Heavy modules are imported where used, so validating a small plan starts quickly.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Callable
from contextvars import ContextVar
from pathlib import Path
from typing import Any, TypeVar

from verigraph.cli.exits import EXIT_BAD_INPUT, EXIT_NEGATIVE, EXIT_OK
from verigraph.errors import InputFileError, VeriGraphError

MAX_PLAN_BYTES = 64 * 1024 * 1024
T = TypeVar("T")


def register(sub: Any) -> None:
    """Add `verigraph validate` to the subparsers `sub`."""
    p = sub.add_parser(
        "validate", help="check a plan against a scene (and a goal), a PDDL problem, or a batch",
        description="Per-step report; exit 0 valid (and goal reached), 1 invalid or goal "
                    "missed, 2 bad input. Give --scene/--plan[/--goal], or --domain/--problem/"
                    "--plan (PDDL), or --batch FILE.jsonl. For VAL's interface see "
                    "`verigraph val`.")
    p.add_argument("--scene", help="scene graph file (.json or .yaml) or a built-in scene id "
                                   "(its goal applies unless --goal is given)")
    p.add_argument("--plan", help="plan file: text (one action per line) or JSON; with "
                                  "--domain: (op args) lines or PlanBench sentences")
    p.add_argument("--goal", help="goal file: a scene graph, {graph, partial}, {predicate}, "
                   "{formula} or a BDDL formula as text; or a formula '(forall ...)'")
    p.add_argument("--dictionary", metavar="NAME|FILE.json",
                   help="the scene's dictionary D: a built-in name, all, or a JSON file of "
                        "your own labels {extends, objects} (see docs/worlds.md)")
    p.add_argument("--domain", help="PDDL domain file: any blocks world (native), or other "
                                    "classical PDDL (see docs/validator.md)")
    p.add_argument("--problem", help="PDDL problem file for --domain")
    p.add_argument("--batch", help="JSON Lines file: one {id, domain, problem, plan} or "
                                   "{id, scene, plan, goal} per line (paths relative to the "
                                   "file); prints one JSON report line per item")
    p.add_argument("--json", action="store_true", help="print the report as JSON")
    p.add_argument("--planbench", action="store_true",
                   help="PDDL: PlanBench task 3's verdict (valid / the action and its unmet "
                        "precondition / the unmet goal); in JSON under 'planbench'")
    p.add_argument("--engine", choices=("auto", "blocksworld", "strips"), default="auto",
                   help="PDDL engine (default auto: native blocks world when the domain is "
                        "one, else STRIPS)")
    p.add_argument("--all-errors", action="store_true",
                   help="continue past violations (skipping failed actions) to list all")
    p.add_argument("--no-progress", action="store_true", help="batch: no progress bar")
    p.add_argument("--cpu-seconds", type=_seconds, default=None, metavar="S",
                   help="CPU seconds each check may use (the plan; each --batch item); "
                        "default $VERIGRAPH_CPU_SECONDS, else 60; 0: no limit")
    p.add_argument("--html", metavar="FILE", help="also write a self-contained HTML report "
                   "with a drawing per step (scene plans; see docs/viewer.md)")
    p.set_defaults(handler=run_validate)


def _seconds(text: str) -> float:
    """`--cpu-seconds`: a finite number >= 0."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value >= 0):
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of seconds >= 0")
    return value


# `--cpu-seconds` of this run (None: $VERIGRAPH_CPU_SECONDS, else the default); read by
# every check, also each item of a batch
_CPU_SECONDS: ContextVar[float | None] = ContextVar("verigraph_cpu_seconds", default=None)


def within_cpu_budget(fn: Callable[[], T], name: str = "validate") -> T:
    """`fn()` (one check) within the command line's CPU budget
    (verigraph.budget.command_line_budget): BudgetExceeded beyond it."""
    from verigraph.budget import command_line_budget, run_within

    budget = command_line_budget(_CPU_SECONDS.get())
    return fn() if budget is None else run_within(budget, name, fn)


def read_text_file(path: str | Path, field: str, limit: int = MAX_PLAN_BYTES) -> str:
    p = Path(path)
    if not p.is_file():
        raise InputFileError(f"{field} file '{p}' does not exist", field=field, value=str(path),
                             fix=f"give the path of the {field} file")
    if p.stat().st_size > limit:
        raise InputFileError(f"{field} file is too large", field=field, value=str(path),
                             fix=f"keep it under {limit} bytes")
    try:
        return p.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise InputFileError(f"{field} file is not UTF-8 text", field=field, value=str(path),
                             fix="save it as UTF-8") from None


def load_goal_arg(goal: str) -> Any:
    from verigraph.graph.goal import PREDICATES, Goal
    from verigraph.graph.io import load_goal

    if goal in PREDICATES or goal.lstrip().startswith("("):  # a predicate, a formula
        return Goal.parse(goal)
    return load_goal(goal)


def emit_error(exc: VeriGraphError, as_json: bool) -> int:
    if as_json:
        print(json.dumps({"ok": False, **exc.to_dict()}))
    print(f"error: {exc}", file=sys.stderr)
    for problem in getattr(exc, "problems", [])[1:]:
        print(f"  also [{problem.rule}] {problem.message} (fix: {problem.fix})", file=sys.stderr)
    return EXIT_BAD_INPUT


MAX_CACHED_TEXTS = 64  # paths
MAX_CACHED_CHARS = 1 << 20  # a larger file is read for every item that names it


def _cached_text(path: str | Path, field: str, cache: dict[str, str] | None) -> str:
    """A domain or problem file's text; a batch reads each path once (its items repeat
    a few domains and problems), keeping the last `MAX_CACHED_TEXTS` paths of files
    under `MAX_CACHED_CHARS` (at most 64 MiB held)."""
    if cache is None:
        return read_text_file(path, field)
    key = f"{field} {path}"
    text = cache.get(key)
    if text is None:
        text = read_text_file(path, field)
        if len(text) <= MAX_CACHED_CHARS:
            cache[key] = text
            if len(cache) > MAX_CACHED_TEXTS:
                del cache[next(iter(cache))]
    return text


def pddl_item_report(domain: str | Path, problem: str | Path, plan: str | Path,
                cache: dict[str, str] | None = None, *, engine: str = "auto",
                planbench: bool = False, all_errors: bool = False) -> dict[str, Any]:
    """The JSON-ready report for a PDDL item (domain and problem texts cached per path
    in a batch)."""
    from verigraph.pddl.text import planbench_verdict
    from verigraph.pddl.validate import validate_pddl_dict

    texts = (_cached_text(domain, "domain", cache), _cached_text(problem, "problem", cache),
             read_text_file(plan, "plan"))
    data = within_cpu_budget(lambda: validate_pddl_dict(*texts, engine=engine,
                                                        all_errors=all_errors))
    if planbench:
        data["planbench"] = planbench_verdict(data)
    return data


def scene_and_goal(scene: str | Path, goal: str | Path | None) -> tuple[Any, Any]:
    """The scene (a file or a built-in id) and the goal: `goal` if given, else a built-in
    scene's own goal, else None."""
    from verigraph.cli.scenes import scene_graph

    graph, builtin_goal = scene_graph(str(scene))
    return graph, load_goal_arg(str(goal)) if goal else builtin_goal


def scene_report(scene: str | Path, plan: str | Path, goal: str | Path | None,
                 all_errors: bool = False) -> dict[str, Any]:
    """The scene plan's report in its plain form (`verigraph.reporting`)."""
    from verigraph.actions.report import validate_plan

    graph, goal_value = scene_and_goal(scene, goal)
    text = read_text_file(plan, "plan")
    return within_cpu_budget(lambda: validate_plan(graph, text, goal_value,
                                                   all_errors=all_errors))


def write_html_report(path: str, graph: Any, plan_text: str, goal: Any,
                      all_errors: bool) -> None:
    """The viewer's self-contained report of this validation (drawings embedded), from
    the scene, plan and goal the text report was made from."""
    from verigraph.tools.registry import Toolbox
    from verigraph.viewer.inputs import write_report

    write_report(Toolbox().context, path, graph, plan_text, goal, all_errors=all_errors)
    print(f"wrote {path}", file=sys.stderr)


def _usage_error(message: str, fix: str) -> VeriGraphError:
    return VeriGraphError(message, field="arguments", value=None, fix=fix)


def run_validate(args: argparse.Namespace) -> int:
    """`verigraph validate`: its `--cpu-seconds` holds for this command only (reset on the
    way out, so a caller running commands in process keeps its own budget)."""
    token = _CPU_SECONDS.set(args.cpu_seconds)
    try:
        return _run_validate(args)
    finally:
        _CPU_SECONDS.reset(token)


def _run_validate(args: argparse.Namespace) -> int:
    try:
        if args.batch:
            if args.scene or args.domain or args.plan or args.dictionary:
                raise _usage_error("--batch takes no other input", "give only --batch FILE")
            from verigraph.cli.batch import run_batch

            return run_batch(Path(args.batch), progress=not args.no_progress,
                             planbench=args.planbench, engine=args.engine)
        if args.domain or args.problem:
            if not (args.domain and args.problem and args.plan) or args.scene or args.goal:
                raise _usage_error("PDDL input needs --domain, --problem and --plan (no --scene "
                                   "or --goal: the goal is in the problem)",
                                   "verigraph validate --domain D.pddl --problem P.pddl --plan F")
            if args.html or args.dictionary:
                raise _usage_error("--html and --dictionary apply to scene plans only",
                                   "drop --html and --dictionary for a PDDL plan")
            data = pddl_item_report(args.domain, args.problem, args.plan, engine=args.engine,
                               planbench=args.planbench, all_errors=args.all_errors)
            if args.json:
                print(json.dumps(data))
            else:
                from verigraph.reporting import report_text

                print(data["planbench"]["message"] if args.planbench else report_text(data))
            return EXIT_OK if data["valid"] else EXIT_NEGATIVE
        else:
            if args.planbench:
                raise _usage_error("--planbench applies to PDDL input",
                                   "give --domain, --problem and --plan")
            if not (args.scene and args.plan):
                raise _usage_error("give --scene and --plan (or --domain/--problem/--plan, or "
                                   "--batch)", "verigraph validate --scene S.json --plan P.txt")
            from verigraph.actions.report import validate_plan

            graph, goal = scene_and_goal(args.scene, args.goal)
            if args.dictionary:
                from verigraph.cli.scenes import with_dictionary

                graph = with_dictionary(graph, args.dictionary)
            plan_text = read_text_file(args.plan, "plan")
            report = within_cpu_budget(lambda: validate_plan(graph, plan_text, goal,
                                                             all_errors=args.all_errors))
            if args.html:
                write_html_report(args.html, graph, plan_text, goal, args.all_errors)
            if args.json:  # as pydantic wrote it: compact, not ASCII-escaped
                print(json.dumps(report, separators=(",", ":"), ensure_ascii=False))
                return EXIT_OK if report["valid"] else EXIT_NEGATIVE
    except VeriGraphError as exc:
        return emit_error(exc, args.json)
    from verigraph.reporting import report_text

    print(report_text(report))
    return EXIT_OK if report["valid"] else EXIT_NEGATIVE
