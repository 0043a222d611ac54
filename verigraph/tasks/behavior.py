"""BEHAVIOR-1K's activities as installed by the `bddl` package (the `household` extra).

The activity definitions are read from the installed package, never downloaded: each
activity is a folder `bddl/activity_definitions/<activity>/problem0.bddl`. The package
is located with `find_spec` and not imported (importing it loads its simulator
back-end classes; only its files are needed here).
"""

from __future__ import annotations

import importlib.util
import time
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from functools import cache
from pathlib import Path
from typing import Any

from verigraph.errors import VeriGraphError
from verigraph.extras import require
from verigraph.tasks.task import Task

MAX_PROBLEM_BYTES = 262_144


@cache
def definitions_dir() -> Path:
    """`bddl/activity_definitions` of the installed package (ExtraMissingError without it)."""
    require("household", "bddl")
    spec = importlib.util.find_spec("bddl")
    assert spec is not None and spec.submodule_search_locations is not None
    return Path(next(iter(spec.submodule_search_locations))) / "activity_definitions"


@cache
def activities() -> tuple[str, ...]:
    """Every activity name, sorted (1,016 in bddl 3.6.0)."""
    root = definitions_dir()
    return tuple(sorted(d.name for d in root.iterdir() if (d / "problem0.bddl").is_file()))


def activity_text(name: str) -> str:
    """The BDDL problem of one activity, or a VeriGraphError naming the nearest names."""
    path = definitions_dir() / name / "problem0.bddl"
    if "/" in name or "\\" in name or name.startswith(".") or not path.is_file():
        import difflib

        near = difflib.get_close_matches(name, activities(), n=3, cutoff=0.6)
        raise VeriGraphError(f"no BEHAVIOR activity named '{name[:80]}'", field="activity",
                             value=name[:80],
                             fix=f"use an activity name such as {', '.join(near)}" if near else
                                 "give a .bddl file, or an activity name from "
                                 "bddl/activity_definitions (verigraph bench behavior lists "
                                 "them)")
    return path.read_text()


def problem_text(activity_or_file: str) -> tuple[str, str]:
    """(activity name, BDDL text) of an activity name or a .bddl file path."""
    path = Path(activity_or_file)
    if path.suffix == ".bddl" or path.is_file():
        if not path.is_file():
            raise VeriGraphError(f"no file {activity_or_file[:120]}", field="activity",
                                 value=activity_or_file[:120],
                                 fix="give an existing .bddl file or an activity name")
        if path.stat().st_size > MAX_PROBLEM_BYTES:
            raise VeriGraphError(f"{activity_or_file[:120]} is over {MAX_PROBLEM_BYTES} bytes",
                                 field="activity", value=activity_or_file[:120],
                                 fix="give one BDDL problem")
        try:
            text = path.read_text()
        except UnicodeDecodeError:
            raise VeriGraphError(f"{activity_or_file[:120]} is not text", field="activity",
                                 value=activity_or_file[:120],
                                 fix="give a BDDL problem file") from None
        name = path.parent.name if path.name.startswith("problem") else path.stem
        return name, text
    return activity_or_file, activity_text(activity_or_file)


@dataclass
class ActivityOutcome:
    """One activity through the whole path: import, solve, validate, execute, check.

    `status`: `refused` (a predicate outside the supported set, named in `predicate`),
    `solved` (a plan the verifier accepts and whose execution reaches the goal),
    `budget` (the solver's budget ran out before any plan), `unreachable` (the solver
    proved no plan exists), `invalid` (a plan the verifier refused: never expected),
    `paper` (the validator says the goal is reached, the executed episode says not:
    never expected).
    """

    activity: str
    status: str
    predicate_class: str | None = None
    predicate: str | None = None
    objects: int = 0
    plan: list[str] = field(default_factory=list)
    optimal: bool = False
    lower_bound: int | None = None
    reason: str | None = None
    seconds: dict[str, float] = field(default_factory=dict)

    def as_json(self) -> dict[str, Any]:
        return asdict(self)


def run_activity(name: str, *, time_limit: float = 10.0, tools: Any = None,
                 text: str | None = None) -> ActivityOutcome:
    """Import one activity, solve it within `time_limit` CPU seconds (optimal A* first,
    then the anytime search with the same budget), validate the plan against the goal
    formula, execute it in an episode on the graph executor and check the goal there."""
    from verigraph.graph.bddl_problem import UnsupportedActivityError, import_problem
    from verigraph.planning.tool_calls import InProcessTools

    seconds: dict[str, float] = {}
    start = time.perf_counter()
    try:
        imported = import_problem(text if text is not None else activity_text(name),
                                  activity=name)
        graph = imported.scene_graph()
    except UnsupportedActivityError as exc:
        return ActivityOutcome(name, "refused", predicate=exc.predicate, reason=exc.message)
    seconds["import"] = time.perf_counter() - start
    outcome = ActivityOutcome(name, "solved", predicate_class=imported.predicate_class,
                              objects=len(imported.ids), seconds=seconds)
    scene = graph.model_dump(mode="json", exclude_none=True)
    goal = imported.goal
    tools = tools or InProcessTools()
    clock = time.perf_counter()
    solved = tools.call("solve", {"graph": scene, "goal": goal, "time_limit": time_limit,
                                  "max_expansions": 2_000_000})
    if solved["reachable"] is None:
        solved = tools.call("solve", {"graph": scene, "goal": goal, "time_limit": time_limit,
                                      "max_expansions": 2_000_000, "anytime": True})
    seconds["solve"] = time.perf_counter() - clock
    outcome.optimal = bool(solved.get("optimal"))
    outcome.lower_bound = solved.get("lower_bound")
    if not solved["reachable"]:
        outcome.status = "budget" if solved["reachable"] is None else "unreachable"
        outcome.reason = solved.get("reason")
        return outcome
    outcome.plan = list(solved["plan"])
    clock = time.perf_counter()
    report = tools.call("validate_plan", {"graph": scene, "goal": goal,
                                          "plan": outcome.plan or ["done"]})
    seconds["validate"] = time.perf_counter() - clock
    if not report["plan_valid"] or not report["goal_reached"]:
        outcome.status = "invalid"
        outcome.reason = "; ".join(v.get("message", "") for v in report["violations"])[:300] \
            or "the validator says the goal is not reached"
        return outcome
    clock = time.perf_counter()
    episode = tools.call("load_scene", {"graph": scene, "goal": goal, "k": 50,
                                        "executor": "graph"})
    episode_id = episode["episode_id"]
    final = episode["graph"]
    try:
        for at in range(0, len(outcome.plan), 50):
            run = tools.call("execute_actions", {"episode_id": episode_id,
                                                 "actions": outcome.plan[at:at + 50]})
            final = run["graph"]
            if not run["ok"]:
                outcome.status = "invalid"
                outcome.reason = f"execution refused: {run['violation']}"[:300]
                return outcome
        reached = tools.call("check_goal", {"episode_id": episode_id})
    finally:
        tools.call("end_episode", {"episode_id": episode_id})
    seconds["execute"] = time.perf_counter() - clock
    if not reached["satisfied"] or not formula_holds(final, imported.formula):
        outcome.status = "paper"
        outcome.reason = "the executed episode does not reach the goal"
    return outcome


def formula_holds(graph: dict[str, Any], formula: str) -> bool:
    """Whether the goal formula holds on a graph, by the formula evaluator itself."""
    from verigraph.graph.formula import parse_formula
    from verigraph.graph.formula_eval import facts_of, holds
    from verigraph.graph.model import SceneGraph
    from verigraph.graph.state import WorldState

    state = WorldState.from_graph(SceneGraph.model_validate(graph))
    return holds(parse_formula(formula), facts_of(state))


# An activity becomes a task of `verigraph/behavior-v0` when the reference solver finds
# its optimal plan this fast here (the oracle solves it again, with its default budget,
# on every call: a margin keeps a slower machine from turning a task unsolvable).
TASK_SOLVE_SECONDS = 1.0


def behavior_tasks(max_solve_s: float = TASK_SOLVE_SECONDS,
                   names: Sequence[str] | None = None) -> list[Task]:
    """One task per activity that imports and that the reference solver solves optimally
    within `max_solve_s`: the scene, its goal formula, its class as the kind and the
    optimal plan length. Ids are `behavior/<activity>`; splits follow the content hash,
    so each activity is wholly in train or in test. `names`: only these activities."""
    from verigraph.graph.bddl_problem import UnsupportedActivityError, import_problem
    from verigraph.graph.goal import Goal
    from verigraph.solver import solve

    tasks = []
    for name in names if names is not None else activities():
        try:
            imported = import_problem(activity_text(name), activity=name)
            graph = imported.scene_graph()
        except UnsupportedActivityError:
            continue
        result = solve(graph, Goal(formula=imported.formula), time_limit=max_solve_s)
        if not result.reachable or not result.optimal:
            continue
        tasks.append(Task.create(
            task_id=f"behavior/{name}",
            load={"graph": graph.model_dump(mode="json", exclude_none=True)},
            set_goal={"formula": imported.formula}, family="behavior", group="behavior",
            kind=imported.predicate_class, optimal_length=len(result.plan),
            show_goal_graph=True))
    return tasks
