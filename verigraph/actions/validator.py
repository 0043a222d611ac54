"""Validation and execution semantics (docs/design.md section 6, the paper's Algorithm 1 core).

`validate_action` checks one action against its row's preconditions in the action table
(`verigraph.actions.schemas`) and changes nothing; `apply_action` is the row's effect
as a graph edit. Running a list of actions until the first violation is
`verigraph.actions.execution`. The tangram `align` action is checked and applied here
outside the table (see the table's docstring).
"""

from __future__ import annotations

import operator
from typing import Any

from pydantic import BaseModel, Field

from verigraph.actions.constraints import NO_GOAL, Wanted, check_align
from verigraph.actions.feedback import Violation
from verigraph.actions.model import AlignAction, AnyAction
from verigraph.actions.schemas import ActionSchema, Precondition, schema_of
from verigraph.graph.model import Edge
from verigraph.graph.state import WorldState
from verigraph.reporting import edit_text


class StateChange(BaseModel):
    """One state an applied action changed: `fridge` `open` false -> true."""

    object: str
    key: str
    before: bool
    after: bool


class GraphEdit(BaseModel):
    """The edges an applied action removed and added, and the states it changed."""

    removed: list[Edge] = Field(default_factory=list)
    added: list[Edge] = Field(default_factory=list)
    # Set and written only when an action changed a state, so a move's edit dumps as
    # before (and a long plan's report allocates nothing for it); `operator.not_` leaves
    # an empty value out without a Python call per dumped edit.
    states: list[StateChange] | None = Field(default=None,
                                             exclude_if=operator.not_)

    def text(self) -> str:
        """`-cup on book, +cup on desk` (`reporting.edit_text`, as every report text)."""
        return edit_text(self.model_dump(exclude_none=True))


def _refusal(pre: Precondition, state: WorldState, action: AnyAction, wanted: Wanted
             ) -> Violation:
    """The refusal of a failed precondition, its fix ranked by the goal when one is known."""
    if wanted and pre.goal_aware:
        return pre.explain(state, action, wanted=wanted)  # type: ignore[call-arg]
    return pre.explain(state, action)


def validate_action(state: WorldState, action: AnyAction, step: int | None = None, *,
                    wanted: Wanted = NO_GOAL) -> Violation | None:
    """The first constraint `action` breaks on `state`, or None. Never mutates `state`.

    `wanted`: the goal's placements (`graph.goal.wanted_placements`), which rank the fix
    (it keeps goal edges that hold, and moves a blocker toward the goal)."""
    violation: Violation | None = None
    row = schema_of(action)
    if row is not None:
        args = row.args(action)
        if not row.accepted(state, *args):
            pre = next(p for p in row.preconditions if not p.holds(state, *args))
            violation = _refusal(pre, state, action, wanted)
    elif isinstance(action, AlignAction):
        violation = check_align(state, action, wanted=wanted)
    if violation is not None and step is not None:
        violation.step = step
    return violation


def all_violations(state: WorldState, action: AnyAction, step: int | None = None, *,
                   wanted: Wanted = NO_GOAL) -> list[Violation]:
    """Every constraint `action` breaks on `state`, in check order. Never mutates `state`.

    Execution needs only the first; a reader fixing the action needs them all (a move of
    a covered board onto a pot breaks object_not_clear AND target_not_surface, and
    clearing the board alone would not make it valid). A gate precondition (unknown
    object or relation, an object moved onto itself) makes the others meaningless, so
    its failure is reported alone. `wanted` as for `validate_action`.
    """
    row = schema_of(action)
    if row is None:
        first = validate_action(state, action, step, wanted=wanted)
        return [first] if first is not None else []
    args = row.args(action)
    found: list[Violation] = []
    for pre in row.preconditions:
        if pre.skip_after and found and found[-1].constraint in pre.skip_after:
            continue  # a target that is not a surface (container) has no room to report
        if pre.holds(state, *args):
            continue
        violation = _refusal(pre, state, action, wanted)
        violation.step = step
        if pre.gate:
            return [violation]
        found.append(violation)
    return found


def edit_from(row: ActionSchema, args: tuple[Any, ...], payload: Any) -> GraphEdit:
    """The GraphEdit of an applied row: its `changes` as models."""
    removed, added, states = row.changes(args, payload)
    return GraphEdit(removed=[Edge(source=s, relation=r, target=t) for s, r, t in removed],
                     added=[Edge(source=s, relation=r, target=t) for s, r, t in added],
                     states=[StateChange(object=o, key=k, before=b, after=a)
                             for o, k, b, a in states] or None)


def apply_action(state: WorldState, action: AnyAction) -> GraphEdit:
    """Apply a validated action in place and return the edit (edges removed and added)."""
    row = schema_of(action)
    if row is not None:
        args = row.args(action)
        return edit_from(row, args, row.apply(state, *args))
    if isinstance(action, AlignAction):
        removed_contacts = state.detach_contacts(action.object)
        added = state.add_contact((action.object, action.side),
                                  (action.target, action.target_side))
        return GraphEdit(removed=removed_contacts, added=[added])
    return GraphEdit()
