"""Validation and execution semantics (docs/design.md section 6, the paper's Algorithm 1 core).

`validate_action` checks one action against the constraints and changes nothing;
`apply_action` is the graph edit of a valid action; `execute_until_violation` runs a
list of actions until the first violation, keeping the valid prefix applied.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from pydantic import BaseModel, Field

from verigraph.actions.constraints import (
    GATE_CHECKS,
    MOVE_CHECKS,
    check_align,
    check_capacity,
)
from verigraph.actions.feedback import Violation
from verigraph.actions.model import AlignAction, AnyAction, DoneAction, MoveAction
from verigraph.graph.model import Edge, SceneGraph
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


def apply_action_fast(state: WorldState, action: AnyAction) -> None:
    """apply_action without building the edit record: the hot path of plan validation."""
    if isinstance(action, MoveAction):
        state.set_support(action.object, action.relation, action.target)
    elif isinstance(action, AlignAction):
        state.detach_contacts(action.object)
        state.add_contact((action.object, action.side), (action.target, action.target_side))


class ExecutionResult(BaseModel):
    """What execute_until_violation returns: the prefix that ran, the graph, the feedback."""

    executed: list[AnyAction]
    graph: SceneGraph
    violation: Violation | None = None
    done: bool = Field(default=False, description="the end token was reached")
    edits: list[GraphEdit] = Field(default_factory=list)


def run_until_violation(state: WorldState, actions: Iterable[AnyAction], *,
                        first_step: int = 1, record_edits: bool = True
                        ) -> tuple[list[AnyAction], list[GraphEdit], Violation | None, bool]:
    """In-place core of execute_until_violation, for callers that keep a WorldState.

    With `record_edits=False` no per-step edit is built (about twice as fast).
    """
    executed: list[AnyAction] = []
    edits: list[GraphEdit] = []
    for offset, action in enumerate(actions):
        if isinstance(action, DoneAction):
            return executed, edits, None, True
        violation = validate_action(state, action, first_step + offset)
        if violation is not None:
            return executed, edits, violation, False
        if record_edits:
            edits.append(apply_action(state, action))
        else:
            apply_action_fast(state, action)
        executed.append(action)
    return executed, edits, None, False


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
    executed, edits, violation, done = run_until_violation(state, actions)
    return ExecutionResult(executed=executed, graph=state.to_graph(), violation=violation,
                           done=done, edits=edits)
