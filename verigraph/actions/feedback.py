"""Violation feedback: which constraint failed, why, what blocks it and what would fix it."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, Field

from verigraph.reporting import violation_text

ConstraintId = Literal[
    "unknown_object", "unknown_relation", "same_object", "not_movable", "object_not_clear",
    "target_full", "target_not_surface", "target_not_container", "would_create_cycle",
    "already_there", "unknown_side", "side_occupied", "overlap", "execution_failed",
    "arm_refused", "no_room", "malformed_action", "hand_full", "not_held", "wrong_source",
    "precondition_unsatisfied", "wrong_type", "container_closed", "target_not_furniture",
    "target_is_room", "not_openable", "already_open", "already_closed", "not_toggleable",
    "already_on", "already_off", "not_cookable", "not_heatable", "not_freezable",
    "already_cooked", "already_hot", "already_frozen", "already_cool", "already_thawed",
    "no_heat_source", "no_cold_source", "heat_source_off", "cold_source_off", "still_heated",
    "still_cold",
]

CONSTRAINT_DESCRIPTIONS: dict[str, str] = {
    "unknown_object": "the object or target is not in the scene",
    "unknown_relation": "the relation is not one the scene's relation set R allows for move",
    "same_object": "an object cannot be put on or in itself",
    "not_movable": "fixed objects (table, counter, stove, shelf) cannot be moved",
    "object_not_clear": "something is on or in the object; clear it first",
    "target_full": "the target already carries as many objects as its capacity allows",
    "target_not_surface": "`on` needs a target that is a surface",
    "target_not_container": "`in` needs a target that is a container",
    "would_create_cycle": "the target rests (directly or indirectly) on the object",
    "already_there": "the object already stands in that relation to the target",
    "unknown_side": "tangram: the side index does not exist on that piece, or the object "
                    "is not a tangram piece",
    "side_occupied": "tangram: the target side already touches another piece",
    "overlap": "tangram (sim2d): the moved piece would intersect another piece",
    "execution_failed": "the simulator or arm did not end in the predicted graph",
    "no_room": "the simulator found no place where the object fits and rests stably "
               "(sizes, which capacities do not capture); nothing moved",
    "arm_refused": "the arm adapter refused before moving (safety limit, stop latched, "
                   "stale location, confirmation declined)",
    "malformed_action": "the action does not match the action schema",
    "hand_full": "blocks world with a hand: a grasp while the hand already holds a block",
    "not_held": "blocks world with a hand: a release of a block the hand does not hold",
    "wrong_source": "blocks world: the action names a place the block is not taken from "
                    "(pick-up of a block on a block, unstack from the wrong block)",
    "precondition_unsatisfied": "PDDL (STRIPS): a precondition of the action is false now",
    "wrong_type": "PDDL (STRIPS): an argument's type is not the parameter's type",
    "container_closed": "nothing goes in or comes out of a closed openable container "
                        "(no state given: closed); open it first",
    "target_not_furniture": "`under` needs a target that is furniture (a fixed surface)",
    "target_is_room": "`nextto` needs an object, not a room (furniture stands `inroom`)",
    "not_openable": "open and close act only on openable objects",
    "already_open": "the object is open already",
    "already_closed": "the object is closed already (no state given: closed)",
    "not_toggleable": "toggle_on and toggle_off act only on toggleable objects",
    "already_on": "the object is on already",
    "already_off": "the object is off already (no state given: off)",
    # physical processes (verigraph.actions.processes)
    "not_cookable": "cook acts only on cookable objects",
    "not_heatable": "heat and cool act only on heatable objects",
    "not_freezable": "freeze and thaw act only on freezable objects",
    "already_cooked": "the object is cooked already",
    "already_hot": "the object is hot already",
    "already_frozen": "the object is frozen already",
    "already_cool": "the object is not hot (no state given: not hot)",
    "already_thawed": "the object is not frozen (no state given: not frozen)",
    "no_heat_source": "cook and heat need the object on or in a heat source (a stove, an "
                      "oven), directly or in what stands there",
    "no_cold_source": "freeze needs the object on or in a cold source (a fridge, a freezer)",
    "heat_source_off": "the heat source is off; toggle_on it first",
    "cold_source_off": "the cold source is off; toggle_on it first",
    "still_heated": "cool: the object stands on a heat source that is on; move it off or "
                    "toggle_off the source",
    "still_cold": "thaw: the object stands in a cold source that is on; take it out",
}


class Violation(BaseModel):
    """Feedback for one rejected action (docs/design.md section 5)."""

    ok: Literal[False] = False
    step: int | None = Field(default=None, description="1-based index of the action in the plan")
    action: dict[str, Any]
    constraint: ConstraintId
    message: str
    blocking: list[str] = Field(default_factory=list,
                                description="objects that stand in the way")
    suggestion: str

    def text(self, with_step: bool = True) -> str:
        """`step 2: [c] message. Suggestion: ...` (`reporting.violation_text`)."""
        return violation_text(self.model_dump(), with_step)
