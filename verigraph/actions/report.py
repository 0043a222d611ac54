"""The standalone plan validator: a per-step report for a whole plan (VAL-style).

`validate_plan` reads a scene, a plan and a goal in any accepted form and hands them,
read once, to `verigraph.actions.execution.check_plan`, which runs them and builds the
report's plain-data form (`verigraph.reporting`: dicts and lists, the JSON
`verigraph validate --json` prints) with no model object per step. `ValidationReport`
is the model of the same form that the MCP tools return, built from it at their
boundary (`actions.pddl.as_validation_report`).
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, Field

from verigraph.actions.execution import check_plan
from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction
from verigraph.actions.parser import parse_plan
from verigraph.actions.validator import GraphEdit
from verigraph.graph.bulk import collector_paused
from verigraph.graph.goal import Goal, GraphDiff
from verigraph.graph.io import goal_from_data, scene_from_data
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import label_readings
from verigraph.reporting import PlanReport


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


def _is_parsed(plan: object) -> bool:
    """A non-empty list of models (actions already parsed); checked per kind of item."""
    return isinstance(plan, list) and bool(plan) and all(
        issubclass(kind, BaseModel) for kind in set(map(type, plan)))
