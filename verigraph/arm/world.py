"""ArmWorld: the `World` of `execute_in_world` backed by an arm, a locator and the gate.

`perform` never trusts its caller: it locates every object, rebuilds the graph the
arm observes, validates the action on *that* graph to get a receipt, plans the
motion from fresh locations and hands it to the ArmController. Refusals before any
motion come back as a Violation (the episode stays unchanged); once a command was
sent, failures are left to `observe`, which reports the graph the world really is in,
so `execute_in_world` flags `execution_failed` and adopts it.
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from verigraph.actions.feedback import ConstraintId, Violation
from verigraph.actions.model import AlignAction, MoveAction
from verigraph.arm.approval import authorize
from verigraph.arm.config import ArmConfig
from verigraph.arm.controller import ArmController, MotionOutcome
from verigraph.arm.errors import ArmError, ArmRefusal, ObjectNotFoundError
from verigraph.arm.locators import DryRunLocator
from verigraph.arm.models import (
    ArmStatus,
    AuditOutcome,
    ConfirmationRequest,
    ObjectLocation,
    Pose,
)
from verigraph.arm.planning import MotionPlan, plan_motion
from verigraph.arm.protocols import ObjectLocator
from verigraph.arm.scene_inference import InferenceTolerances, infer_graph
from verigraph.graph.dictionary import Dictionary, load_dictionary
from verigraph.graph.goal import GraphDiff, diff
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState

# A refusal before anything moved (safety limit, latched stop, stale location, declined
# confirmation) is its own constraint, distinct from execution_failed after a motion.
REFUSED: ConstraintId = "arm_refused"


@dataclass(frozen=True, slots=True)
class RelationCheck:
    """The closed-loop check after one action: does `object relation target` hold?"""

    action: str
    holds: bool
    observed: str  # the support edge seen, or why none was


class ArmWorld:
    """A World whose actions move an arm and whose observations come from a locator."""

    def __init__(self, graph: SceneGraph, controller: ArmController, locator: ObjectLocator,
                 *, dictionary: Dictionary | str | None = None,
                 tolerances: InferenceTolerances | None = None,
                 on_close: Callable[[], None] | None = None,
                 render: Callable[..., np.ndarray] | None = None) -> None:
        self._graph = graph.model_copy(update={"edges": []})
        self._dictionary = load_dictionary(dictionary if dictionary is not None
                                           else graph.dictionary)
        self._controller = controller
        self._dry = DryRunLocator(locator) if controller.mode == "dry-run" else None
        self._locator: ObjectLocator = self._dry or locator
        self._tolerances = tolerances or InferenceTolerances()
        self._on_close = on_close
        self.last_check: RelationCheck | None = None
        self.last_outcome: MotionOutcome | None = None
        # `render(width=, height=) -> BGR array` (OpenCV order, like sim2d's) when the
        # cell has a camera to show (the scene tools look for it); None otherwise.
        self.render = render

    # -- World protocol ----------------------------------------------------------------------
    def perform(self, action: MoveAction | AlignAction) -> Violation | None:
        """Validate on the observed graph, check, (confirm,) move, then re-locate."""
        if not isinstance(action, MoveAction):
            return Violation(action=action.model_dump(), constraint=REFUSED,
                             message="the arm adapter carries out move actions only",
                             suggestion="use the sim2d tangram world for align actions")
        try:
            planned = self._plan(action)
            if isinstance(planned, Violation):
                return self._logged(action, planned)
            approval = None
            if self._controller.mode == "real":
                approval = self._controller.confirm_plan(planned)
                planned = self._plan(action)  # the scene may have changed while asking
                if isinstance(planned, Violation):
                    return self._logged(action, planned)
            outcome = self._controller.execute(planned, approval=approval)
        except ArmRefusal as exc:
            return self._logged(action, _refusal(action, exc), audited=exc.audited)
        self.last_outcome = outcome
        if self._dry is not None and outcome.status == "recorded":
            self._dry.record(planned.predicted_location(time.time()))
        self.last_check = self._check(action)
        return None

    def record_rejection(self, action: object, violation: Violation) -> None:
        """Log an action the episode's validator rejected before it reached the arm."""
        text = action.text() if isinstance(action, MoveAction | AlignAction) else repr(action)
        with contextlib.suppress(ArmError):  # a write failure stopped and latched the arm
            self._controller.log_refusal(text, f"rejected by the episode's validator: "
                                               f"[{violation.constraint}] {violation.message}")

    def _logged(self, action: MoveAction, violation: Violation, *,
                audited: bool = False) -> Violation:
        """Every refusal goes into the audit log, in every mode."""
        if not audited:
            with contextlib.suppress(ArmError):  # a write failure stopped and latched the arm
                self._controller.log_refusal(action.text(), violation.message)
        return violation

    def observe(self) -> SceneGraph:
        """The scene graph rebuilt from fresh locations of every object."""
        return infer_graph(self._graph, self._dictionary,
                           self._locator.locate(self._graph.node_ids()), self._tolerances)

    # -- the server's arm_* tools ------------------------------------------------------------
    def status(self) -> ArmStatus:
        return self._controller.status()

    def stop(self, reason: str = "stop requested") -> ArmStatus:
        """Halt now and latch (never waits on the driver's status or a running call)."""
        return self._controller.stop(reason)

    @property
    def stop_latched(self) -> bool:
        return self._controller.stop_latched

    def extras_to_keep(self) -> dict[str, object]:
        """What a stored episode keeps of this world: whether its stop is latched (the
        flag, never a poll of the driver). The driver connection itself is never stored."""
        return {"arm_latched": self.stop_latched}

    def restore_extras(self, extras: dict[str, object]) -> None:
        """On a fresh connection in the process that reloads the episode: latch the stop
        again if it was latched when the record was written."""
        if extras.get("arm_latched"):
            self.stop("stop latched before the episode was reloaded")

    def log_confirmation(self, question: str, outcome: AuditOutcome, detail: str) -> None:
        """Record a human's answer given outside this world (MCP elicitation)."""
        self._controller.log_confirmation(question, outcome, detail)

    def touch(self) -> None:
        """A call from the client arrived (the deadman's heartbeat)."""
        self._controller.touch()

    def home(self) -> MotionOutcome:
        """Go to the configured home pose (confirmed first in real mode)."""
        approval = self._controller.confirm_home() if self._controller.mode == "real" else None
        return self._controller.home(approval=approval)

    def reset(self) -> ArmStatus:
        """The agent's reset: a human approves it on a real arm; in sim and dry-run only
        if the operator set `agent_may_reset` (else `verigraph arm reset`)."""
        return self._controller.agent_reset()

    @property
    def config(self) -> ArmConfig:
        return self._controller.config

    def preview(self, actions: Sequence[object]) -> list[ConfirmationRequest]:
        """The confirmation requests a real run of `actions` would make, in order.

        Moves nothing and asks nothing. Each motion is planned from fresh locations with
        the predicted results of the earlier ones laid over them (as in dry-run). The
        preview ends before the first action that is not a move or that the arm would
        refuse: a refused motion is never put to the human.
        """
        overlay = DryRunLocator(self._locator)
        start: Pose | None = None
        requests: list[ConfirmationRequest] = []
        for action in actions:
            if not isinstance(action, MoveAction):
                break
            try:
                planned = self._plan(action, overlay)
                if isinstance(planned, Violation):
                    break
                request, start = self._controller.preview(planned, start)
            except ArmRefusal:
                break
            requests.append(request)
            overlay.record(planned.predicted_location(time.time()))
        return requests

    def reset_request(self) -> ConfirmationRequest | None:
        """What `reset` would ask the human (None: it asks nothing)."""
        return self._controller.reset_request()

    def close(self) -> None:
        try:
            self._controller.close()
        finally:
            if self._on_close is not None:
                self._on_close()

    def verify_scene(self, expected: SceneGraph) -> GraphDiff:
        """How the observed scene differs from `expected` (check it before an episode)."""
        observed = WorldState.from_graph(self.observe(), self._dictionary, partial=True)
        return diff(observed, expected)

    # -- internals ---------------------------------------------------------------------------
    def _plan(self, action: MoveAction, locator: ObjectLocator | None = None
              ) -> MotionPlan | Violation:
        locations = (locator or self._locator).locate(self._graph.node_ids())
        observed = WorldState.from_graph(
            infer_graph(self._graph, self._dictionary, locations, self._tolerances),
            self._dictionary, partial=True)
        receipt = authorize(observed, action)
        if isinstance(receipt, Violation):
            return receipt.model_copy(update={
                "message": f"in the scene the arm observes, {receipt.message}"})
        held = _required(locations, action.object, "object")
        target = _required(locations, action.target, "target")
        return plan_motion(receipt, held, target, list(locations.values()),
                           self._controller.config, time.time())

    def _check(self, action: MoveAction) -> RelationCheck:
        graph = self.observe()
        support = next((e for e in graph.edges if e.source == action.object), None)
        holds = support is not None and (support.relation, support.target) == (
            action.relation, action.target)
        seen = support.sentence() if support is not None else \
            f"no support seen for {action.object}"
        return RelationCheck(action=action.text(), holds=holds, observed=seen)


def _required(locations: dict[str, ObjectLocation], object_id: str,
              role: str) -> ObjectLocation:
    if object_id not in locations:
        raise ObjectNotFoundError(f"the locator cannot see {object_id}", field=role,
                                  value=object_id,
                                  fix="make sure it is in view and not hidden, and that the "
                                      "id matches the scene")
    return locations[object_id]


def _refusal(action: MoveAction, exc: ArmError) -> Violation:
    blocking = [str(exc.value)] if isinstance(exc, ObjectNotFoundError) else []
    return Violation(action=action.model_dump(), constraint=REFUSED,
                     message=f"the arm refused before moving: {exc.message}",
                     blocking=blocking, suggestion=exc.fix or "check arm_status")
