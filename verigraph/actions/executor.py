"""Where validated actions really happen: the contract between the verifier and a world.

The verifier predicts the next graph; a `World` (the sim2d simulator, or an arm adapter)
performs the action and reports the graph it really ends in. `execute_in_world` is the
one place that joins the two: only actions that passed `validate_action` on the current
graph reach `World.perform`, and a world that ends somewhere else than predicted makes
its observed graph the truth and reports `execution_failed`. An aligned piece that also
lands against new neighbours is not a failure: those contacts are added to the
prediction as observed (`new_contacts`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol, runtime_checkable

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AlignAction, AnyAction, DoneAction, MoveAction
from verigraph.actions.validator import GraphEdit, apply_action, validate_action
from verigraph.graph.goal import diff
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.state import WorldState


@runtime_checkable
class World(Protocol):
    """Something that can carry out a validated action and report what it observes."""

    def perform(self, action: MoveAction | AlignAction) -> Violation | None:
        """Carry out an action that already passed the symbolic validator.

        Returns a Violation only when the world itself refuses before anything moves
        (e.g. tangram `overlap`); in that case nothing may have changed.
        """
        ...

    def observe(self) -> SceneGraph:
        """The scene graph of the current state, read from the world (not bookkeeping)."""
        ...


def execute_in_world(state: WorldState, actions: Sequence[AnyAction], world: World | None, *,
                     first_step: int = 1
                     ) -> tuple[list[AnyAction], list[GraphEdit], Violation | None, bool,
                                WorldState]:
    """execute_until_violation against a world: validate, perform, observe, compare.

    Returns (executed, edits, violation, done, new_state). `state` is not modified; the
    returned state is the predicted graph, or the observed graph after a mismatch.
    """
    current = state.copy()
    executed: list[AnyAction] = []
    edits: list[GraphEdit] = []
    for offset, action in enumerate(actions):
        step = first_step + offset
        if isinstance(action, DoneAction):
            return executed, edits, None, True, current
        violation = validate_action(current, action, step)
        if violation is not None:
            record = getattr(world, "record_rejection", None)  # an arm logs every attempt
            if record is not None:
                record(action, violation)
            return executed, edits, violation, False, current
        if world is None:
            edits.append(apply_action(current, action))
            executed.append(action)
            continue
        refused = world.perform(action)
        if refused is not None:
            refused.step = step
            return executed, edits, refused, False, current
        predicted = current.copy()
        edit = apply_action(predicted, action)
        seen = world.observe()
        observed = WorldState.from_graph(seen, current.dictionary, partial=True)
        if isinstance(action, AlignAction):
            edit.added += new_contacts(predicted, seen, action.object)
        mismatch = diff(observed, predicted.to_graph())
        executed.append(action)
        if not mismatch.satisfied:
            return executed, edits, Violation(
                step=step, action=action.model_dump(), constraint="execution_failed",
                message=f"the world did not end as predicted after {action.text()}: "
                        f"{mismatch.summary().removeprefix('goal not reached: ')}",
                blocking=sorted({e.split(' ')[0] for e in mismatch.missing_edges}),
                suggestion="the observed graph is now the current graph; re-plan from it"
            ), False, observed
        edits.append(edit)
        current = predicted
    return executed, edits, None, False, current


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
