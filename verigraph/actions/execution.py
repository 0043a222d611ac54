"""Execute until violation: the paper's Algorithm 1 core, one loop for every caller.

`run_actions` validates each action on the current graph and applies the valid ones;
it stops at the first violation (or goes on past it with `all_errors`) or at the end
token. With a `World` (the sim2d simulator, an arm adapter) every accepted action is
also performed there and the world is observed again: a world that ends somewhere else
than predicted makes its observed graph the truth and reports `execution_failed`. An
aligned piece that also lands against new neighbours is not a failure: those contacts
are added to the prediction as observed (`new_contacts`).

Every action of the action table (`verigraph.actions.schemas`) on the graph alone takes
its row's fast path: the row's `accepted` (every precondition's test compiled into one
function, given the action's fields, which the loop reads once: a pydantic field read
costs about three plain ones), then the row's `apply`, keeping per step only a compact
record (step, action, what the effect replaced); a refusal goes through the row's
preconditions one by one, which also produces the feedback. `execute_until_violation` (the
library's form, a model), `execute_in_world` (episodes and the simulator) and the plan
validator (`verigraph.actions.report`) are views of the same run.
"""

from __future__ import annotations

import gc
from collections.abc import Sequence
from contextlib import nullcontext
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

from pydantic import BaseModel, Field

from verigraph.actions.constraints import NO_GOAL, Wanted, with_goal_note
from verigraph.actions.feedback import Violation
from verigraph.actions.model import AlignAction, AnyAction, DoneAction, MoveAction, StateAction
from verigraph.actions.schemas import MOVE, REFUSED, Place, schema_of
from verigraph.actions.validator import GraphEdit, apply_action, edit_from, validate_action
from verigraph.budget import checkpoint
from verigraph.graph.bulk import LARGE_GRAPH_ITEMS, collector_paused, promote_young_objects
from verigraph.graph.goal import Goal, check_goal, diff, wanted_placements
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.reporting import PlanReport

# (step, action, payload): payload is what the row's effect replaced (a move's old
# placement, tuple or None; a state action's old value) for an action of the table
# applied on the fast path, a GraphEdit for other accepted actions, or the Violation of
# a rejected one.
Record = tuple[int, AnyAction, Any]


@runtime_checkable
class World(Protocol):
    """Something that can carry out a validated action and report what it observes.

    A world that opens, closes and switches things has `perform_state(action)` too
    (same contract as `perform`); any other is never asked to (the run refuses)."""

    def perform(self, action: MoveAction | AlignAction) -> Violation | None:
        """Carry out an action that already passed the symbolic validator.

        Returns a Violation only when the world itself refuses before anything moves
        (e.g. tangram `overlap`); in that case nothing may have changed.
        """
        ...

    def observe(self) -> SceneGraph:
        """The scene graph of the current state, read from the world (not bookkeeping)."""
        ...


@dataclass
class Run:
    """What one run of `run_actions` did.

    `records` hold every step checked, accepted or not; `state` is the graph it ends
    in (the prediction, or what the world observed after a mismatch). `world_acted` is
    True when the last failing action was carried out by the world, which then ended
    elsewhere (`execution_failed`): that action counts as executed.
    """

    records: list[Record] = field(default_factory=list)
    violations: list[Violation] = field(default_factory=list)
    done: bool = False
    not_checked: int = 0
    world_acted: bool = False
    state: WorldState | None = None

    def executed(self) -> list[AnyAction]:
        """The actions that ran, in order."""
        ran = [a for _, a, payload in self.records if not isinstance(payload, Violation)]
        if self.world_acted:
            ran.append(self.records[-1][1])
        return ran

    def edits(self) -> list[GraphEdit]:
        """The graph edit of every accepted action, in order."""
        edits = []
        for _, action, payload in self.records:
            if isinstance(payload, GraphEdit):
                edits.append(payload)
            elif not isinstance(payload, Violation):  # a row's effect on the fast path
                row = schema_of(action)
                assert row is not None
                edits.append(edit_from(row, row.args(action), payload))
        return edits


def run_actions(state: WorldState, actions: Sequence[AnyAction], *,
                world: World | None = None, all_errors: bool = False,
                first_step: int = 1, wanted: Wanted = NO_GOAL) -> Run:
    """Validate and apply `actions` on `state` in place until a violation or `done`.

    With `all_errors` a refused action is skipped and checking goes on (like VAL's -c),
    to list every problem; a world never runs past a refusal, so the two do not mix.
    `wanted`: the goal's placements, which rank a refusal's fix (`validate_action`).
    """
    if world is not None and all_errors:
        raise ValueError("all_errors checks a plan on the graph; a world stops at a refusal")
    run = Run(state=state)
    records, violations = run.records, run.violations
    move_step, refused = MOVE.step, REFUSED
    for index, action in enumerate(actions, start=first_step):
        if not index & 63:
            checkpoint()  # the server's per-call budget (and cancellation), cheap when unset
        if world is None:
            if type(action) is MoveAction:
                payload = move_step(state, action)
            else:
                row = schema_of(action)
                payload = row.step(state, action) if row is not None else refused
            if payload is not refused:
                records.append((index, action, payload))
                continue
        if isinstance(action, DoneAction):
            run.done = True
            return run
        violation = validate_action(state, action, index, wanted=wanted)
        if violation is None and world is not None:
            violation = _perform(run, world, action, index)
            assert run.state is not None
            if violation is not None and wanted:
                violation = with_goal_note(state, violation, wanted)
            state = run.state  # the prediction, or the observation after a mismatch
            if violation is None:
                continue
        elif violation is None:
            records.append((index, action, apply_action(state, action)))
            continue
        elif world is not None:
            record = getattr(world, "record_rejection", None)  # an arm logs every attempt
            if record is not None:
                record(action, violation)
        violations.append(violation)
        records.append((index, action, violation))
        if not all_errors:
            offset = index - first_step + 1
            run.not_checked = sum(not isinstance(a, DoneAction) for a in actions[offset:])
            return run
    return run


def _perform(run: Run, world: World, action: AnyAction, step: int) -> Violation | None:
    """Carry out one accepted action in the world, observe it, compare with the
    prediction; the run's state becomes the prediction, or the observation after a
    mismatch (returned as `execution_failed`)."""
    assert run.state is not None and isinstance(action, MoveAction | StateAction | AlignAction)
    current = run.state
    if isinstance(action, StateAction):
        perform_state = getattr(world, "perform_state", None)
        if perform_state is None:
            return Violation(
                step=step, action=action.model_dump(), constraint="execution_failed",
                message=f"this world cannot carry out {action.text()} (it has no doors or "
                        "switches); nothing changed",
                suggestion="run household actions on an episode with executor graph")
        refused = perform_state(action)
    else:
        refused = world.perform(action)
    if refused is not None:
        refused.step = step
        return refused
    predicted = current.copy()
    edit = apply_action(predicted, action)
    seen = world.observe()
    observed = WorldState.from_graph(seen, current.dictionary, partial=True)
    if isinstance(action, AlignAction):
        edit.added += new_contacts(predicted, seen, action.object)
    mismatch = diff(observed, predicted.to_graph())
    if not mismatch.satisfied:
        run.world_acted, run.state = True, observed
        return Violation(
            step=step, action=action.model_dump(), constraint="execution_failed",
            message=f"the world did not end as predicted after {action.text()}: "
                    f"{mismatch.summary().removeprefix('goal not reached: ')}",
            blocking=sorted({e.split(' ')[0] for e in mismatch.missing_edges}),
            suggestion="the observed graph is now the current graph; re-plan from it")
    run.records.append((step, action, edit))
    run.state = predicted
    return None


class ExecutionResult(BaseModel):
    """What execute_until_violation returns: the prefix that ran, the graph, the feedback."""

    executed: list[AnyAction]
    graph: SceneGraph
    violation: Violation | None = None
    done: bool = Field(default=False, description="the end token was reached")
    edits: list[GraphEdit] = Field(default_factory=list)


def execute_until_violation(actions: Sequence[AnyAction], graph: SceneGraph | WorldState
                            ) -> ExecutionResult:
    """Validate and apply each action in order; stop at the first violation or `done`.

    The input is never modified: a SceneGraph is indexed afresh, a WorldState is copied.

    >>> from verigraph.graph.builtin_scenes import cup_on_book
    >>> r = execute_until_violation([MoveAction(object="book", target="shelf")], cup_on_book())
    >>> r.violation.constraint, r.violation.blocking
    ('object_not_clear', ['cup'])
    """
    state = graph.copy() if isinstance(graph, WorldState) else WorldState.from_graph(graph)
    run = run_actions(state, actions)
    return ExecutionResult(executed=run.executed(), graph=state.to_graph(),
                           violation=run.violations[0] if run.violations else None,
                           done=run.done, edits=run.edits())


def execute_in_world(state: WorldState, actions: Sequence[AnyAction], world: World | None, *,
                     first_step: int = 1, wanted: Wanted = NO_GOAL
                     ) -> tuple[list[AnyAction], list[GraphEdit], Violation | None, bool,
                                WorldState]:
    """`run_actions` on a copy of `state`, with or without a world.

    Returns (executed, edits, violation, done, new_state). `state` is not modified; the
    returned state is the predicted graph, or the observed graph after a mismatch.
    """
    run = run_actions(state.copy(), actions, world=world, first_step=first_step,
                      wanted=wanted)
    assert run.state is not None
    return (run.executed(), run.edits(), run.violations[0] if run.violations else None,
            run.done, run.state)


def new_contacts(predicted: WorldState, observed: SceneGraph, moved: str) -> list[Edge]:
    """Contacts the aligned piece makes beyond the one asked for (its new neighbours),
    as the world observes them: added to the prediction (in place), not a failure.

    Geometry decides which other sides the moved piece lands against, and the symbolic
    state has no geometry; so they are taken from the observation, and only for the
    moved piece (any other change still counts as the world ending elsewhere).
    """
    known = {e.key() for e in predicted.edges()}
    added = []
    for e in observed.edges:
        if e.relation != "touches" or moved not in (e.source, e.target) or e.key() in known:
            continue
        added.append(predicted.add_contact((e.source, e.source_side or 0),
                                           (e.target, e.target_side or 0)))
    return added


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


def _action_dict(action: AnyAction) -> dict[str, Any]:
    if type(action) is MoveAction:
        return {"action": "move", "object": action.object, "relation": action.relation,
                "target": action.target}
    return action.model_dump()


def _edit_dict(edit: GraphEdit) -> dict[str, Any]:
    return edit.model_dump(mode="json", exclude_none=True)


assert isinstance(MOVE.effect, Place)  # the step builder below writes a placement's edit


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
