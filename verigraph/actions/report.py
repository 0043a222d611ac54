"""The standalone plan validator: a per-step report for a whole plan (VAL-style).

The run is `verigraph.actions.execution.run_actions`; its compact step records become
`StepReport`s here, at the edge, with `trusted`: pydantic objects built without
re-validating data the run already checked, through the setters of pydantic's own slots;
the frozen `Edge` a block leaves is the one an earlier step added. A long plan's report
(a hundred thousand acyclic objects) is built with the cyclic collector paused, and its
objects are then moved to the oldest generation (`graph.bulk.promote_young_objects`)
rather than scanned when the collector resumes.
"""

from __future__ import annotations

import gc
from typing import Any, TypeVar

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
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import label_readings, readings_line

assert isinstance(MOVE.effect, Place)  # the fast path below builds a placement's edit
M = TypeVar("M", bound=BaseModel)
# Setters of the four slots every pydantic model instance fills (`BaseModel.__slots__`:
# the field values, the fields set, extras, private attributes), called on the slot
# descriptors themselves: what `object.__setattr__` ends in, without its per-call lookup.
_SLOTS = vars(BaseModel)
_set_values = _SLOTS["__dict__"].__set__
_set_fields_set = _SLOTS["__pydantic_fields_set__"].__set__
_set_extra = _SLOTS["__pydantic_extra__"].__set__
_set_private = _SLOTS["__pydantic_private__"].__set__
EDGE_FIELDS = frozenset({"source", "relation", "target"})
STEP_FIELDS = frozenset({"step", "ok", "action", "text", "violation", "edit"})
EDIT_FIELDS = frozenset({"removed", "added", "states"})


def trusted(cls: type[M], values: dict[str, Any], fields_set: frozenset[str]) -> M:
    """A model instance from values the caller guarantees are valid (no validation).

    Same result as `cls.model_construct(**values)` for models without private
    attributes, extras or post-init hooks, at a fraction of the cost.
    """
    m = cls.__new__(cls)
    _set_values(m, values)
    _set_fields_set(m, set(fields_set))
    _set_extra(m, None)
    _set_private(m, None)
    return m


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

    def text(self) -> str:
        """One readable line per step; the failing step explained in full."""
        lines = []
        for s in self.steps:
            if s.ok:
                edit = f"   {s.edit.text()}" if s.edit and (
                    s.edit.added or s.edit.removed or s.edit.states) else ""
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
        if self.label_readings:
            lines.append(readings_line(self.label_readings))
        return "\n".join(lines)


def validate_plan(scene: SceneGraph | dict[str, Any] | WorldState,
                  plan: str | list[Any] | dict[str, Any] | list[AnyAction],
                  goal: Goal | SceneGraph | dict[str, Any] | str | None = None, *,
                  all_errors: bool = False) -> ValidationReport:
    """Check a plan step by step on a scene (nothing passed in is modified).

    Stops at the first violation unless `all_errors`, which skips the failed action and
    goes on, to list every problem (like VAL's -c). An empty plan is valid input: it
    changes nothing, and with a goal the goal check decides the verdict.

    >>> from verigraph.graph.builtin_scenes import cup_on_book
    >>> r = validate_plan(cup_on_book(), "move(book, on, shelf)")
    >>> r.valid, r.violations[0].constraint
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
               ) -> ValidationReport:
    """The report for parsed actions run on `state`, which the run edits (the caller's
    own copy, taken once), with a parsed goal: the core of `validate_plan` that the tool
    calls with what it has already read, so nothing is copied, parsed or read twice.
    `readings`: how the labels of the graphs the caller wrote were read. A long plan
    creates many acyclic objects: its report is built with the cyclic collector paused,
    and they are then promoted rather than scanned (see the module docstring)."""
    if len(actions) < LARGE_GRAPH_ITEMS:
        return _checked(state, actions, goal, all_errors, readings)
    with collector_paused():
        report = _checked(state, actions, goal, all_errors, readings)
        if gc.get_freeze_count() == 0:
            promote_young_objects()  # see there: the report is acyclic
    return report


def _checked(state: WorldState, actions: list[AnyAction], goal: Goal | None,
             all_errors: bool, readings: list[str] | None) -> ValidationReport:
    run = run_actions(state, actions, all_errors=all_errors, wanted=NO_GOAL
                      if goal is None else wanted_placements(goal))
    goal_diff = check_goal(state, goal) if goal is not None else None
    plan_valid = not run.violations
    goal_reached = None if goal_diff is None else goal_diff.satisfied
    return ValidationReport.model_construct(
        valid=plan_valid and goal_reached is not False, plan_valid=plan_valid,
        goal_reached=goal_reached, steps=_steps_from_records(run.records),
        violations=run.violations, not_checked=run.not_checked, done=run.done,
        goal_diff=goal_diff, final_graph=state.to_graph(), label_readings=readings or [])


def _is_parsed(plan: object) -> bool:
    """A non-empty list of models (actions already parsed); checked per kind of item."""
    return isinstance(plan, list) and bool(plan) and all(
        issubclass(kind, BaseModel) for kind in set(map(type, plan)))


def _action_dict(action: AnyAction) -> dict[str, Any]:
    if type(action) is MoveAction:
        return {"action": "move", "object": action.object, "relation": action.relation,
                "target": action.target}
    return action.model_dump()


def _steps_from_records(records: list[Record]) -> list[Any]:
    """StepReports for the records (the edge where compact tuples become models).

    An action of the table applied on the fast path left what its effect replaced; its
    row gives the edit (`validator.edit_from`). Accepted moves, the bulk of any long plan,
    are built inline (the move row's effect replaces the object's placement edge) with
    `object.__new__` and the setters of the model's own slots (what `model_construct`
    does, minus its per-call bookkeeping). The caller
    pauses the garbage collector (`collector_paused`). One fields-set object serves all
    instances of a class: StepReport's and GraphEdit's name every field, so an
    assignment adds nothing to them, and Edge is frozen. Frozen, an Edge is shared too:
    the edge an object leaves is the one the step that put it there added (`placed`,
    valid while only the table's actions ran since; any other edit empties it).
    """
    steps: list[Any] = []
    new = object.__new__
    values, fields_set, extra, private = _set_values, _set_fields_set, _set_extra, _set_private
    edge_set, edit_set, step_set = set(EDGE_FIELDS), set(EDIT_FIELDS), set(STEP_FIELDS)
    placed: dict[str, Edge] = {}  # object -> the Edge of its current placement
    move_type, built_edit, refused, name = MoveAction, GraphEdit, Violation, MOVE.name
    for index, action, payload in records:
        if not index & 63:
            checkpoint()  # the server's per-call budget and cancellation
        kind = type(payload)
        if kind is built_edit or kind is refused:  # built already
            ok = kind is built_edit
            if ok:
                placed.clear()
            steps.append(trusted(StepReport, {
                "step": index, "ok": ok, "action": _action_dict(action), "text": action.text(),
                "violation": None if ok else payload, "edit": payload if ok else None},
                STEP_FIELDS))
            continue
        if type(action) is not move_type:  # a state row: its edit as models
            row = schema_of(action)
            assert row is not None
            args = row.args(action)
            steps.append(trusted(StepReport, {
                "step": index, "ok": True, "action": row.action_dict(*args),
                "text": row.text(*args), "violation": None,
                "edit": edit_from(row, args, payload)}, STEP_FIELDS))
            continue
        # The move row, the bulk of any long plan: its placement edge replaced.
        obj, rel, target = action.object, action.relation, action.target
        added = new(Edge)
        values(added, {"source": obj, "relation": rel, "target": target,
                       "source_side": None, "target_side": None})
        fields_set(added, edge_set)
        extra(added, None)
        private(added, None)
        removed = []
        if payload is not None:
            old = placed.get(obj)
            if old is None:
                old = new(Edge)
                values(old, {"source": obj, "relation": payload[0], "target": payload[1],
                             "source_side": None, "target_side": None})
                fields_set(old, edge_set)
                extra(old, None)
                private(old, None)
            removed.append(old)
        placed[obj] = added
        edit = new(GraphEdit)
        values(edit, {"removed": removed, "added": [added], "states": None})
        fields_set(edit, edit_set)
        extra(edit, None)
        private(edit, None)
        step = new(StepReport)
        values(step, {
            "step": index, "ok": True,
            "action": {"action": name, "object": obj, "relation": rel, "target": target},
            "text": f"{name}({obj}, {rel}, {target})", "violation": None, "edit": edit})
        fields_set(step, step_set)
        extra(step, None)
        private(step, None)
        steps.append(step)
    return steps
