"""Validation and execution semantics (docs/design.md section 6, the paper's Algorithm 1 core).

`validate_action` checks one action against the constraints and changes nothing;
`apply_action` is the graph edit of a valid action. Running a list of actions until
the first violation is `verigraph.actions.execution`.
"""

from __future__ import annotations

from pydantic import BaseModel, Field

from verigraph.actions.constraints import (
    GATE_CHECKS,
    MOVE_CHECKS,
    check_align,
    check_capacity,
)
from verigraph.actions.feedback import Violation
from verigraph.actions.model import AlignAction, AnyAction, MoveAction
from verigraph.graph.model import Edge
from verigraph.graph.state import WorldState


class GraphEdit(BaseModel):
    """The edges an applied action removed and added."""

    removed: list[Edge] = Field(default_factory=list)
    added: list[Edge] = Field(default_factory=list)

    def text(self) -> str:
        parts = [f"-{e.sentence()}" for e in self.removed] + [f"+{e.sentence()}"
                                                               for e in self.added]
        return ", ".join(parts)


def validate_action(state: WorldState, action: AnyAction, step: int | None = None
                    ) -> Violation | None:
    """The first constraint `action` breaks on `state`, or None. Never mutates `state`."""
    violation: Violation | None = None
    if isinstance(action, MoveAction):
        for check in MOVE_CHECKS:
            violation = check(state, action)
            if violation is not None:
                break
    elif isinstance(action, AlignAction):
        violation = check_align(state, action)
    if violation is not None and step is not None:
        violation.step = step
    return violation


TARGET_KINDS = ("target_not_surface", "target_not_container")


def all_violations(state: WorldState, action: AnyAction, step: int | None = None
                   ) -> list[Violation]:
    """Every constraint `action` breaks on `state`, in check order. Never mutates `state`.

    Execution needs only the first; a reader fixing the action needs them all (a move of
    a covered board onto a pot breaks object_not_clear AND target_not_surface, and
    clearing the board alone would not make it valid). The gate checks (unknown object or
    relation, an object moved onto itself) make the others meaningless, so one of them
    failing is reported alone.
    """
    if not isinstance(action, MoveAction):
        first = validate_action(state, action, step)
        return [first] if first is not None else []
    found: list[Violation] = []
    for check in MOVE_CHECKS:
        if check is check_capacity and found and found[-1].constraint in TARGET_KINDS:
            continue  # a target that is not a surface (container) has no room to report
        violation = check(state, action)
        if violation is None:
            continue
        violation.step = step
        if check in GATE_CHECKS:
            return [violation]
        found.append(violation)
    return found


def apply_action(state: WorldState, action: AnyAction) -> GraphEdit:
    """Apply a validated action in place and return the edit (edges removed and added)."""
    if isinstance(action, MoveAction):
        old = state.support.get(action.object)
        state.set_support(action.object, action.relation, action.target)
        return GraphEdit(
            removed=[Edge(source=action.object, relation=old[0], target=old[1])] if old else [],
            added=[Edge(source=action.object, relation=action.relation, target=action.target)])
    if isinstance(action, AlignAction):
        removed_contacts = state.detach_contacts(action.object)
        added = state.add_contact((action.object, action.side),
                                  (action.target, action.target_side))
        return GraphEdit(removed=removed_contacts, added=[added])
    return GraphEdit()
