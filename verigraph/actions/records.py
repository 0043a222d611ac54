"""The plan-checking hot loop on compact records, and the one place they become models.

`check_plan` validates and applies actions and keeps, per step, only a tuple
(step, action, old support or violation). Accepted moves take a fused fast path
(`move_accepted`: every move constraint's pass condition in one function); anything
else goes through the full constraint list, which also produces the feedback.
`verigraph.actions.report` turns the tuples into `StepReport`s at the edge with
`trusted`, building the pydantic objects without re-validating checked data.
"""

from __future__ import annotations

from typing import Any, TypeVar

from pydantic import BaseModel

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction, DoneAction, MoveAction
from verigraph.actions.validator import apply_action, validate_action
from verigraph.budget import checkpoint
from verigraph.graph.state import WorldState

M = TypeVar("M", bound=BaseModel)
_setattr = object.__setattr__
EDGE_FIELDS = frozenset({"source", "relation", "target"})
STEP_FIELDS = frozenset({"step", "ok", "action", "text", "violation", "edit"})
EDIT_FIELDS = frozenset({"removed", "added"})

# (step, action, payload): payload is the old support (tuple or None) of an accepted move,
# a GraphEdit for other accepted actions, or the Violation of a rejected one.
Record = tuple[int, AnyAction, Any]


def trusted(cls: type[M], values: dict[str, Any], fields_set: frozenset[str]) -> M:
    """A model instance from values the caller guarantees are valid (no validation).

    Same result as `cls.model_construct(**values)` for models without private
    attributes, extras or post-init hooks, at a fraction of the cost.
    """
    m = cls.__new__(cls)
    _setattr(m, "__dict__", values)
    _setattr(m, "__pydantic_fields_set__", set(fields_set))
    _setattr(m, "__pydantic_extra__", None)
    _setattr(m, "__pydantic_private__", None)
    return m


def move_accepted(state: WorldState, a: MoveAction) -> bool:
    """True exactly when every check in MOVE_CHECKS passes (the common case, fused)."""
    objects = state.objects
    obj, target, relation = a.object, a.target, a.relation
    info = objects.get(obj)
    t = objects.get(target)
    if info is None or t is None or obj == target or not info.props.movable:
        return False
    if relation not in state.move_relations or state.carried[obj]:
        return False  # a carried object fails check_clear (or check_cycle) anyway
    if state.support.get(obj) == (relation, target):
        return False
    props = t.props
    if not (props.surface if relation == "on" else props.container):
        return False
    return props.capacity is None or len(state.carried[target]) < props.capacity


def check_plan(state: WorldState, actions: list[AnyAction], all_errors: bool
               ) -> tuple[list[Record], list[Violation], bool, int]:
    """Validate and apply in place; returns (records, violations, done, not_checked)."""
    records: list[Record] = []
    violations: list[Violation] = []
    support = state.support
    carried = state.carried
    for index, action in enumerate(actions, start=1):
        if not index & 63:
            checkpoint()  # the server's per-call budget (and cancellation), cheap when unset
        if type(action) is MoveAction and move_accepted(state, action):
            obj = action.object
            old = support.get(obj)
            if old is not None:
                del carried[old[1]][obj]
            support[obj] = (action.relation, action.target)
            carried[action.target][obj] = action.relation
            records.append((index, action, old))
            continue
        if isinstance(action, DoneAction):
            return records, violations, True, 0
        violation = validate_action(state, action, index)
        if violation is None:
            records.append((index, action, apply_action(state, action)))
            continue
        violations.append(violation)
        records.append((index, action, violation))
        if not all_errors:
            rest = sum(not isinstance(a, DoneAction) for a in actions[index:])
            return records, violations, False, rest
    return records, violations, False, 0
