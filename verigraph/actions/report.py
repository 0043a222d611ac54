"""The standalone plan validator: a per-step report for a whole plan (VAL-style).

The run is `verigraph.actions.execution.run_actions`; its compact step records become
the report's plain-data form here (`verigraph.reporting`: dicts and lists, the JSON
`verigraph validate --json` prints), with no model object per step: a step is a dict of
the action, its text and its edit (the edges as `{source, relation, target}`). A long
plan's report (a hundred thousand acyclic objects) is built with the cyclic collector
paused, and its objects are then moved to the oldest generation
(`graph.bulk.promote_young_objects`) rather than scanned when the collector resumes.
`ValidationReport` is the model of the same form that the MCP tools return, built from
it at their boundary (`actions.pddl.as_validation_report`).
"""

from __future__ import annotations

import gc
from contextlib import nullcontext
from typing import Any

from pydantic import BaseModel, Field

from verigraph.actions.constraints import NO_GOAL
from verigraph.actions.execution import Record, run_actions
from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction, MoveAction
from verigraph.actions.parser import parse_plan
from verigraph.actions.schemas import MOVE, Place, schema_of
from verigraph.actions.validator import GraphEdit, edit_from
from verigraph.budget import checkpoint
from verigraph.graph.bulk import LARGE_GRAPH_ITEMS, collector_paused, promote_young_objects
from verigraph.graph.goal import Goal, GraphDiff, check_goal, wanted_placements
from verigraph.graph.io import goal_from_data, scene_from_data
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import label_readings

assert isinstance(MOVE.effect, Place)  # the fast path below builds a placement's edit
PlanReport = dict[str, Any]  # the plain form (verigraph.reporting)


class StepReport(BaseModel):
    """One plan step: the action, whether it passed, the violation or the edit it made."""

    step: int
    ok: bool
    action: dict[str, Any]
    text: str
    violation: Violation | None = None
    edit: GraphEdit | None = Field(default=None, description="edges removed/added if applied")


class ValidationReport(BaseModel):
    """Verdict for a whole plan; `valid` means every action passed (and the goal, if any)."""

    valid: bool = Field(description="every action passed and, with a goal, the goal holds")
    plan_valid: bool = Field(description="every action passed its constraints")
    goal_reached: bool | None = Field(default=None, description="None when no goal was given")
    steps: list[StepReport]
    violations: list[Violation] = Field(default_factory=list)
    not_checked: int = Field(default=0, description="actions after the first violation")
    done: bool = Field(default=False, description="the plan ended with the end token")
    goal_diff: GraphDiff | None = None
    final_graph: SceneGraph
    # How the labels of the graphs the caller wrote were read (`box read as block`):
    # a normalisation is never silent, here as in load_scene's result.
    label_readings: list[str] = Field(default_factory=list)


def validate_plan(scene: SceneGraph | dict[str, Any] | WorldState,
                  plan: str | list[Any] | dict[str, Any] | list[AnyAction],
                  goal: Goal | SceneGraph | dict[str, Any] | str | None = None, *,
                  all_errors: bool = False) -> PlanReport:
    """Check a plan step by step on a scene (nothing passed in is modified); the report
    in its plain form (`verigraph.reporting`; `reporting.report_text` writes it out).

    Stops at the first violation unless `all_errors`, which skips the failed action and
    goes on, to list every problem (like VAL's -c). An empty plan is valid input: it
    changes nothing, and with a goal the goal check decides the verdict.

    >>> from verigraph.graph.builtin_scenes import cup_on_book
    >>> r = validate_plan(cup_on_book(), "move(book, on, shelf)")
    >>> r["valid"], r["violations"][0]["constraint"]
    (False, 'object_not_clear')
    """
    written: SceneGraph | None = None
    if isinstance(scene, WorldState):
        state = scene.copy()
    else:
        written = scene if isinstance(scene, SceneGraph) else scene_from_data(scene)
        state = WorldState.from_graph(written)
    goal_model = None if goal is None else goal_from_data(goal)
    readings = label_readings(written, state.dictionary,
                              goal_model.graph if goal_model is not None else None)
    if isinstance(plan, list) and _is_parsed(plan):
        actions: list[AnyAction] = list(plan)
    else:
        size = len(plan) if isinstance(plan, list) else plan.count("\n") + 1 \
            if isinstance(plan, str) else 0
        with collector_paused(size):  # a long plan's text makes many acyclic objects
            actions = parse_plan(plan, allow_empty=True)
    return check_plan(state, actions, goal_model, all_errors=all_errors, readings=readings)


def check_plan(state: WorldState, actions: list[AnyAction], goal: Goal | None = None, *,
               all_errors: bool = False, readings: list[str] | None = None
               ) -> PlanReport:
    """The report for parsed actions run on `state`, which the run edits (the caller's
    own copy, taken once), with a parsed goal: the core of `validate_plan` that the tool
    calls with what it has already read, so nothing is copied, parsed or read twice.
    `readings`: how the labels of the graphs the caller wrote were read."""
    # a long plan, or a large final graph, creates many acyclic objects; a small report
    # leaves the collector alone
    size = len(actions) + len(state.objects)
    with collector_paused(size) if size >= LARGE_GRAPH_ITEMS else nullcontext():
        run = run_actions(state, actions, all_errors=all_errors, wanted=NO_GOAL
                          if goal is None else wanted_placements(goal))
        goal_diff = check_goal(state, goal) if goal is not None else None
        plan_valid = not run.violations
        dumped = {id(v): v.model_dump(mode="json", exclude_none=True) for v in run.violations}
        violations = list(dumped.values())
        report: PlanReport = {"valid": plan_valid and (goal_diff is None or goal_diff.satisfied),
                              "plan_valid": plan_valid}
        if goal_diff is not None:
            report["goal_reached"] = goal_diff.satisfied
        report["steps"] = _steps_from_records(run.records, dumped)
        report["violations"] = violations
        report["not_checked"] = run.not_checked
        report["done"] = run.done
        if goal_diff is not None:
            report["goal_diff"] = goal_diff.model_dump(mode="json", exclude_none=True)
        report["final_graph"] = state.graph_data()
        report["label_readings"] = readings or []
        if size >= LARGE_GRAPH_ITEMS and gc.get_freeze_count() == 0:
            promote_young_objects()  # see there: the report is acyclic
    return report


def _is_parsed(plan: object) -> bool:
    """A non-empty list of models (actions already parsed); checked per kind of item."""
    return isinstance(plan, list) and bool(plan) and all(
        issubclass(kind, BaseModel) for kind in set(map(type, plan)))


def _action_dict(action: AnyAction) -> dict[str, Any]:
    if type(action) is MoveAction:
        return {"action": "move", "object": action.object, "relation": action.relation,
                "target": action.target}
    return action.model_dump()


def _edit_dict(edit: GraphEdit) -> dict[str, Any]:
    return edit.model_dump(mode="json", exclude_none=True)


def _steps_from_records(records: list[Record], violations: dict[int, dict[str, Any]]
                        ) -> list[dict[str, Any]]:
    """The report's steps for the run's records (plain dicts; `violations`: the run's
    violations as dicts, by the id of their model, so a step and the list share one).

    An action of the table applied on the fast path left what its effect replaced; its
    row gives the edit (`validator.edit_from`). Accepted moves, the bulk of any long plan,
    are built inline: the move row's effect replaces the object's placement edge, whose
    old value the record holds. The caller pauses the garbage collector
    (`collector_paused`).
    """
    steps: list[dict[str, Any]] = []
    append = steps.append
    move_type, built_edit, refused, name = MoveAction, GraphEdit, Violation, MOVE.name
    for index, action, payload in records:
        if not index & 63:
            checkpoint()  # the server's per-call budget and cancellation
        kind = type(payload)
        if kind is refused:
            append({"step": index, "ok": False, "action": _action_dict(action),
                    "text": action.text(), "violation": violations.get(id(payload))
                    or payload.model_dump(mode="json", exclude_none=True)})
            continue
        if kind is built_edit:
            append({"step": index, "ok": True, "action": _action_dict(action),
                    "text": action.text(), "edit": _edit_dict(payload)})
            continue
        if type(action) is not move_type:  # a state row: its edit from the row
            row = schema_of(action)
            assert row is not None
            args = row.args(action)
            append({"step": index, "ok": True, "action": row.action_dict(*args),
                    "text": row.text(*args),
                    "edit": _edit_dict(edit_from(row, args, payload))})
            continue
        # The move row, the bulk of any long plan: its placement edge replaced.
        obj, rel, target = action.object, action.relation, action.target
        append({"step": index, "ok": True,
                "action": {"action": name, "object": obj, "relation": rel, "target": target},
                "text": f"{name}({obj}, {rel}, {target})",
                "edit": {"removed": [] if payload is None else [
                    {"source": obj, "relation": payload[0], "target": payload[1]}],
                    "added": [{"source": obj, "relation": rel, "target": target}]}})
    return steps
