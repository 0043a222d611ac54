"""The standalone plan validator: a per-step report for a whole plan (VAL-style)."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, Field

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction, DoneAction
from verigraph.actions.parser import parse_plan
from verigraph.actions.validator import GraphEdit, apply_action, validate_action
from verigraph.budget import checkpoint
from verigraph.graph.goal import Goal, GraphDiff, check_goal
from verigraph.graph.io import goal_from_data, scene_from_data
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState


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

    def text(self) -> str:
        """One readable line per step; the failing step explained in full."""
        lines = []
        for s in self.steps:
            if s.ok:
                edit = f"   {s.edit.text()}" if s.edit and (s.edit.added or s.edit.removed) else ""
                lines.append(f"{s.step:>4} ok    {s.text}{edit}")
            else:
                assert s.violation is not None
                v = s.violation
                lines.append(f"{s.step:>4} FAIL  {s.text}   [{v.constraint}] {v.message}")
                lines.append(f"{'':>10}fix: {v.suggestion}")
        if self.not_checked:
            lines.append(f"      ... {self.not_checked} later action(s) not checked "
                         "(use --all-errors to check them)")
        if self.goal_diff is not None:
            lines.append(self.goal_diff.summary())
        verdict = "VALID" if self.valid else "INVALID"
        reason = []
        if not self.plan_valid:
            reason.append(f"{len(self.violations)} violation(s)")
        if self.goal_reached is False:
            reason.append("goal not reached")
        lines.append(f"{verdict}: {len(self.steps)} step(s) checked"
                     + (f", {', '.join(reason)}" if reason else ""))
        return "\n".join(lines)


def validate_plan(scene: SceneGraph | dict[str, Any] | WorldState,
                  plan: str | list[Any] | dict[str, Any] | list[AnyAction],
                  goal: Goal | SceneGraph | dict[str, Any] | str | None = None, *,
                  all_errors: bool = False) -> ValidationReport:
    """Check a plan step by step on a scene (nothing passed in is modified).

    Stops at the first violation unless `all_errors`, which skips the failed action and
    goes on, to list every problem (like VAL's -c).

    >>> from verigraph.graph.builtin_scenes import cup_on_book
    >>> r = validate_plan(cup_on_book(), "move(book, on, shelf)")
    >>> r.valid, r.violations[0].constraint
    (False, 'object_not_clear')
    """
    if isinstance(scene, WorldState):
        state = scene.copy()
    else:
        graph = scene if isinstance(scene, SceneGraph) else scene_from_data(scene)
        state = WorldState.from_graph(graph)
    actions: list[AnyAction] = (list(plan) if isinstance(plan, list) and _is_parsed(plan)
                                else parse_plan(plan))
    goal_model = None if goal is None else goal_from_data(goal)
    steps: list[StepReport] = []
    violations: list[Violation] = []
    done = False
    not_checked = 0
    for index, action in enumerate(actions, start=1):
        checkpoint()
        if isinstance(action, DoneAction):
            done = True
            break
        violation = validate_action(state, action, index)
        if violation is None:
            edit = apply_action(state, action)
            steps.append(StepReport.model_construct(step=index, ok=True, action=action.model_dump(),
                                                    text=action.text(), violation=None, edit=edit))
            continue
        violations.append(violation)
        steps.append(StepReport.model_construct(step=index, ok=False, action=action.model_dump(),
                                                text=action.text(), violation=violation,
                                                edit=None))
        if not all_errors:
            not_checked = sum(not isinstance(a, DoneAction) for a in actions[index:])
            break
    goal_diff = check_goal(state, goal_model) if goal_model is not None else None
    plan_valid = not violations
    goal_reached = None if goal_diff is None else goal_diff.satisfied
    return ValidationReport(
        valid=plan_valid and goal_reached is not False, plan_valid=plan_valid,
        goal_reached=goal_reached, steps=steps, violations=violations, not_checked=not_checked,
        done=done, goal_diff=goal_diff, final_graph=state.to_graph())


def _is_parsed(plan: object) -> bool:
    return isinstance(plan, list) and all(isinstance(a, BaseModel) for a in plan) and bool(plan)
