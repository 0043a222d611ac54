"""The safety gate, end to end through execute_in_world, with the xArm driver.

No xArm controller can run here, so the SDK's API object is replaced by
`XArmAPIStandIn` (named as such), which records every call. Everything above it is
the real code: ArmWorld, receipts, the controller, the xArm driver.
"""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable
from pathlib import Path

import anyio
import anyio.to_thread
import pytest
from arm_deps import require

require("xarm")

from xarm_standin import XArmAPIStandIn  # noqa: E402

from verigraph.actions.execution import execute_in_world  # noqa: E402
from verigraph.actions.feedback import Violation  # noqa: E402
from verigraph.actions.model import MoveAction  # noqa: E402
from verigraph.arm import (  # noqa: E402
    ArmConfig,
    ArmConfigError,
    ArmConnectionError,
    ArmController,
    ArmWorld,
    ConfirmationRequest,
    ConfirmHook,
    DeclaredObject,
    KeepOutZone,
    LayoutLocator,
    ObjectLocation,
    UnauthorizedMotionError,
    ValidatedAction,
    authorize,
    confirm_scope,
    open_arm_world,
    parse_arm_config,
    scoped_confirm,
)
from verigraph.arm.drivers.xarm import XArmDriver  # noqa: E402
from verigraph.arm.planning import plan_motion  # noqa: E402
from verigraph.graph.model import Edge, Node, SceneGraph  # noqa: E402
from verigraph.graph.state import WorldState  # noqa: E402

BLOCK = (0.05, 0.05, 0.05)
LAYOUT = {
    "table": DeclaredObject(centre=(0.45, 0.0, -0.01), size=(1.0, 1.2, 0.02)),
    "red": DeclaredObject(centre=(0.4, -0.12, 0.025), size=BLOCK),
    "green": DeclaredObject(centre=(0.4, 0.0, 0.025), size=BLOCK),
    "blue": DeclaredObject(centre=(0.4, 0.12, 0.025), size=BLOCK),
}
MOTION_CALLS = ("set_position", "set_gripper_position", "open_lite6_gripper",
                "close_lite6_gripper")
STACK = [MoveAction(object="green", target="red"), MoveAction(object="blue", target="green")]


def blocks_graph(stacked: bool = False) -> SceneGraph:
    edges = [Edge(source="red", relation="on", target="table"),
             Edge(source="green", relation="on", target="red" if stacked else "table"),
             Edge(source="blue", relation="on", target="table")]
    return SceneGraph(nodes=[Node(id="table", label="table")] + [
        Node(id=c, label="block") for c in ("red", "green", "blue")], edges=edges,
        dictionary="blocks")


def stacked_layout() -> dict[str, DeclaredObject]:
    return {**LAYOUT, "green": DeclaredObject(centre=(0.4, -0.12, 0.075), size=BLOCK)}


class Cell:
    """An ArmWorld on the xArm driver with a stand-in API and a declared layout."""

    def __init__(self, tmp_path: Path, *, mode: str = "real",
                 confirm: Callable[[ConfirmationRequest], object] | None = None,
                 layout: dict[str, DeclaredObject] | None = None, time_scale: float = 0.0,
                 graph: SceneGraph | None = None, hook: ConfirmHook | None = None,
                 **overrides: object) -> None:
        self.audit_path = tmp_path / "audit.jsonl"
        self.config = parse_arm_config({"driver": "xarm", "mode": mode, "host": "192.168.1.185",
                                        "audit_log": str(self.audit_path), **overrides})
        self.api = XArmAPIStandIn(time_scale=time_scale)
        self.graph = graph or blocks_graph()
        self.asked: list[ConfirmationRequest] = []

        def ask(request: ConfirmationRequest) -> object:
            self.asked.append(request)
            return confirm(request) if confirm is not None else True

        self.world: ArmWorld = open_arm_world(
            self.config, self.graph,
            confirm=hook or (ask if confirm is not False else None),
            locator=LayoutLocator(layout or LAYOUT),
            driver=XArmDriver(self.config, api_factory=lambda host: self.api))

    def run(self, actions: list[MoveAction]) -> tuple[Violation | None, WorldState]:
        _, _, violation, _, state = execute_in_world(WorldState.from_graph(self.graph),
                                                     actions, self.world)
        return violation, state

    def motions(self) -> list[str]:
        return [name for name, _, _ in self.api.calls if name in MOTION_CALLS]


def assert_unchanged(cell: Cell, state: WorldState) -> None:
    assert state.to_graph().edge_keys() == cell.graph.edge_keys()


# -- modes -----------------------------------------------------------------------------------
def test_dry_run_never_calls_the_driver(tmp_path: Path) -> None:
    cell = Cell(tmp_path, mode="dry-run")
    violation, state = cell.run(STACK)
    assert violation is None
    assert {e.sentence() for e in state.edges()} == {
        "red on table", "green on red", "blue on green"}
    assert cell.api.calls == []  # not even connect: dry-run never talks to the controller
    records = cell.world._controller.audit.records
    assert [r.command for r in records if r.command in ("pick", "place")] == ["pick", "place"] * 2
    assert all(r.outcome != "sent" for r in records)
    status = cell.world.status()
    assert status.commands_sent == 0 and status.mode == "dry-run" and not status.connected


def test_sim_mode_is_refused_for_hardware_drivers() -> None:
    with pytest.raises(ArmConfigError, match="drives hardware"):
        parse_arm_config({"driver": "xarm", "mode": "sim", "host": "192.168.1.185"})


# -- confirmation ------------------------------------------------------------------------------
@pytest.mark.parametrize(("confirm", "reason"), [
    (lambda request: False, "declined"),
    (False, "no confirmation hook"),  # a client that cannot ask
    (lambda request: "yes", "not True"),
    (lambda request: 1 / 0, "hook failed"),
])
def test_declined_or_impossible_confirmation_moves_nothing(
        tmp_path: Path, confirm: Callable[[ConfirmationRequest], object] | bool,
        reason: str) -> None:
    cell = Cell(tmp_path, confirm=confirm)  # type: ignore[arg-type]
    violation, state = cell.run(STACK[:1])
    assert violation is not None and violation.step == 1
    assert "not confirmed" in violation.message and reason in violation.message
    assert cell.motions() == []
    assert_unchanged(cell, state)


def test_an_async_hook_is_refused_and_moves_nothing(tmp_path: Path) -> None:
    """Hooks are synchronous: a coroutine is not a yes, and it is never awaited."""
    async def approve(request: ConfirmationRequest) -> bool:
        return True

    cell = Cell(tmp_path, confirm=approve)  # type: ignore[arg-type]
    violation, state = cell.run(STACK[:1])
    assert violation is not None and "asynchronous" in violation.message
    assert cell.motions() == []
    assert_unchanged(cell, state)


def test_a_confirmation_in_a_worker_thread_is_asked_there(tmp_path: Path) -> None:
    """How the server plugs it: execute_in_world in a worker thread, a synchronous hook."""
    asked_in: list[str] = []

    def approve(request: ConfirmationRequest) -> bool:
        asked_in.append(threading.current_thread().name)
        return True

    cell = Cell(tmp_path, confirm=approve)

    async def main() -> tuple[Violation | None, WorldState]:
        return await anyio.to_thread.run_sync(cell.run, STACK[:1])

    violation, state = anyio.run(main)
    assert len(asked_in) == 1 and asked_in[0] != threading.main_thread().name
    assert "set_position" in cell.motions()
    # Closed loop: the declared layout never sees the block move, so the world reports
    # what it observes instead of the prediction.
    assert violation is not None and violation.constraint == "execution_failed"
    assert "did not end as predicted" in violation.message
    assert_unchanged(cell, state)


def test_confirmed_motion_uses_sdk_units_and_the_controller_fence(tmp_path: Path) -> None:
    cell = Cell(tmp_path, speed_m_s=0.1, max_speed_m_s=0.2)
    cell.run(STACK[:1])
    request = cell.asked[0]
    assert "move(green, on, red)" in request.summary() and request.force_n == 20.0
    ws = cell.config.workspace
    assert cell.api.reduced_tcp_boundary == pytest.approx(
        [ws.max[0] * 1000, ws.min[0] * 1000, ws.max[1] * 1000, ws.min[1] * 1000,
         ws.max[2] * 1000, ws.min[2] * 1000])
    assert cell.api.fence_mode and cell.api.reduced_mode
    assert cell.api.reduced_max_tcp_speed == pytest.approx(200.0)
    moves = [kw for _, kw in cell.api.called("set_position")]
    assert moves[1]["x"] == pytest.approx(400.0) and moves[1]["z"] == pytest.approx(25.0)
    assert all(m["speed"] == pytest.approx(100.0) and m["roll"] == 180.0 and m["wait"]
               for m in moves)
    # grasp green at (0.4, 0, 0.025), release on red 5 mm above its top
    assert moves[4]["y"] == pytest.approx(-120.0) and moves[4]["z"] == pytest.approx(80.0)


# -- the stop ------------------------------------------------------------------------------------
def test_stop_stays_latched_across_calls_until_reset(tmp_path: Path) -> None:
    cell = Cell(tmp_path)
    status = cell.world.stop("operator pressed stop")
    assert status.stop_latched and status.stop_reason == "operator pressed stop"
    assert cell.api.called("emergency_stop")
    for _ in range(2):
        violation, state = cell.run(STACK[:1])
        assert violation is not None and "stop is latched" in violation.message
        assert "arm_reset" in violation.suggestion
        assert_unchanged(cell, state)
    assert cell.world.status().stop_latched
    assert cell.motions() == [] and cell.asked == []
    cell.world.reset()
    assert not cell.world.status().stop_latched
    cell.run(STACK[:1])
    assert "set_position" in cell.motions()


def test_timeout_stops_the_arm_and_latches(tmp_path: Path) -> None:
    cell = Cell(tmp_path, time_scale=1.0, motion_timeout_s=0.3)
    started = time.monotonic()
    violation, state = cell.run(STACK[:1])
    assert time.monotonic() - started < 5
    assert cell.world.last_outcome is not None
    assert cell.world.last_outcome.status == "timeout"
    assert cell.api.called("emergency_stop")
    status = cell.world.status()
    assert status.stop_latched and "motion_timeout_s" in (status.stop_reason or "")
    # the world is observed, not assumed: nothing moved, so the edge is missing
    assert violation is not None and violation.constraint == "execution_failed"
    moves = len(cell.motions())
    again, _ = cell.run(STACK[:1])
    assert again is not None and "stop is latched" in again.message
    assert len(cell.motions()) == moves


def test_one_motion_at_a_time(tmp_path: Path) -> None:
    cell = Cell(tmp_path, time_scale=1.0, speed_m_s=0.1, max_speed_m_s=0.1)
    first = threading.Thread(target=cell.run, args=(STACK[:1],))
    first.start()
    deadline = time.monotonic() + 5
    while not cell.api.called("set_position") and time.monotonic() < deadline:
        time.sleep(0.01)
    assert cell.world.status().busy
    violation, state = cell.run([MoveAction(object="blue", target="green")])
    assert violation is not None and "another motion is in progress" in violation.message
    cell.world.stop()
    first.join(10)
    assert not first.is_alive()


# -- bad input -------------------------------------------------------------------------------
def test_target_outside_the_workspace_is_rejected(tmp_path: Path) -> None:
    far = {**LAYOUT, "red": DeclaredObject(centre=(0.95, -0.12, 0.025), size=BLOCK)}
    cell = Cell(tmp_path, layout=far)
    violation, state = cell.run(STACK[:1])
    assert violation is not None and "outside the workspace" in violation.message
    assert cell.motions() == [] and cell.asked == []  # never asked about an unsafe motion
    assert_unchanged(cell, state)


def test_keep_out_zone_is_rejected(tmp_path: Path) -> None:
    post = KeepOutZone(name="camera_post", min=(0.35, -0.08, 0.0), max=(0.45, -0.04, 0.6))
    cell = Cell(tmp_path, keep_out=[post.model_dump()])
    violation, state = cell.run(STACK[:1])
    assert violation is not None and "keep-out zone 'camera_post'" in violation.message
    assert cell.motions() == []


def test_object_the_locator_cannot_see_is_refused(tmp_path: Path) -> None:
    cell = Cell(tmp_path, layout={k: v for k, v in LAYOUT.items() if k != "red"})
    violation, state = cell.run(STACK[:1])
    assert violation is not None and violation.blocking == ["red"]
    assert "cannot see red" in violation.message
    assert cell.motions() == []
    assert_unchanged(cell, state)


def test_stale_locations_are_refused(tmp_path: Path) -> None:
    class SlowCamera:
        def locate(self, ids: object) -> dict[str, ObjectLocation]:
            fresh = LayoutLocator(LAYOUT).locate(LAYOUT)
            return {k: v.model_copy(update={"timestamp": v.timestamp - 10}) for k, v in
                    fresh.items()}

    cell = Cell(tmp_path)
    cell.world._locator = SlowCamera()
    violation, _ = cell.run(STACK[:1])
    assert violation is not None and "s old" in violation.message
    assert cell.motions() == []


def test_unreachable_xarm_host_is_a_clear_bounded_error(tmp_path: Path) -> None:
    """The real SDK against a loopback address where no controller listens."""
    config = parse_arm_config({"driver": "xarm", "mode": "real", "host": "127.0.0.1",
                               "connect_timeout_s": 2, "audit_log": str(tmp_path / "a.jsonl")})
    started = time.monotonic()
    with pytest.raises(ArmConnectionError) as err:
        open_arm_world(config, blocks_graph(), confirm=lambda r: True,
                       locator=LayoutLocator(LAYOUT))
    assert time.monotonic() - started < 4
    assert err.value.field == "host" and "127.0.0.1" in str(err.value)


# -- the validator is the only way in --------------------------------------------------------
def test_action_invalid_on_the_observed_scene_never_reaches_the_driver(tmp_path: Path) -> None:
    # The arm sees green on red; moving red is invalid there, whatever the caller claims.
    cell = Cell(tmp_path, layout=stacked_layout())
    violation = cell.world.perform(MoveAction(object="red", target="blue"))
    assert violation is not None and violation.constraint == "object_not_clear"
    assert "the arm observes" in violation.message and violation.blocking == ["green"]
    assert cell.motions() == [] and cell.asked == []


def test_receipts_cannot_be_forged_reused_or_kept(tmp_path: Path) -> None:
    config = ArmConfig(driver="xarm", mode="dry-run", max_location_age_s=1.0)
    api = XArmAPIStandIn()
    controller = ArmController(config, XArmDriver(config, api_factory=lambda host: api))
    state = WorldState.from_graph(blocks_graph())
    action = MoveAction(object="green", target="red")
    with pytest.raises(UnauthorizedMotionError):
        ValidatedAction(action, "forged", time.time())
    receipt = authorize(state, action)
    assert isinstance(receipt, ValidatedAction)
    where = LayoutLocator(LAYOUT).locate(LAYOUT)

    def plan_for(r: ValidatedAction):  # type: ignore[no-untyped-def]
        return plan_motion(r, where["green"], where["red"], list(where.values()), config,
                           time.time())

    plan = plan_for(receipt)
    assert controller.execute(plan).status == "recorded"
    with pytest.raises(UnauthorizedMotionError, match="no unused receipt"):
        controller.execute(plan)  # single use
    forged = object.__new__(ValidatedAction)
    forged.action, forged.fingerprint, forged.issued_at = action, "x", time.time()
    with pytest.raises(UnauthorizedMotionError):
        controller.execute(plan.model_copy(update={"receipt": forged}))
    old = authorize(state, action)
    assert isinstance(old, ValidatedAction)
    old.issued_at -= 5
    with pytest.raises(UnauthorizedMotionError, match="s old"):
        controller.execute(plan_for(old))
    invalid = authorize(state, MoveAction(object="table", target="red"))
    assert isinstance(invalid, Violation) and invalid.constraint == "not_movable"
    assert api.calls == []
    refused = [r for r in controller.audit.records if r.outcome == "refused"]
    assert len(refused) == 3


def test_only_move_actions_reach_the_arm(tmp_path: Path) -> None:
    from verigraph.actions.model import AlignAction

    cell = Cell(tmp_path)
    violation = cell.world.perform(AlignAction(object="red", side=0, target="green",
                                               target_side=1))
    assert violation is not None and "move actions only" in violation.message
    assert cell.motions() == []


# -- audit -----------------------------------------------------------------------------------
def test_audit_log_is_append_only_json_lines(tmp_path: Path) -> None:
    cell = Cell(tmp_path)
    cell.run(STACK[:1])
    cell.world.close()
    first = cell.audit_path.read_text().splitlines()
    again = Cell(tmp_path)  # a second session appends to the same file
    again.world.stop()
    lines = cell.audit_path.read_text().splitlines()
    assert lines[:len(first)] == first and len(lines) > len(first)
    records = [json.loads(line) for line in lines]
    sent = [r["command"] for r in records[:len(first)] if r["outcome"] == "sent"]
    assert sent[:3] == ["connect", "pick", "place"] and sent[-1] == "disconnect"
    assert records[-1]["command"] == "stop" and records[-1]["mode"] == "real"
    pick = next(r for r in records if r["command"] == "pick" and r["outcome"] == "sent")
    assert pick["params"]["object_id"] == "green" and pick["params"]["force_n"] == 20.0
    # the graph the arm observed when it validated the action
    assert "green on table" in pick["params"]["validated_on"].split(";")


def test_request_scoped_confirmation_follows_the_call_into_the_worker_thread(
        tmp_path: Path) -> None:
    """The server's wiring: one ArmWorld per episode, one elicitation hook per tool call."""
    cell = Cell(tmp_path, hook=scoped_confirm)
    asked: list[str] = []

    def elicit(request: ConfirmationRequest) -> bool:
        asked.append(request.motion)
        return False

    async def tool_call() -> Violation | None:
        with confirm_scope(elicit):
            return (await anyio.to_thread.run_sync(cell.run, STACK[:1]))[0]

    declined = anyio.run(tool_call)
    assert asked == ["move(green, on, red): pick green at (0.400, 0.000, 0.025) m, yaw 0 deg, "
                     "release it on red at (0.400, -0.120, 0.080) m, yaw 0 deg"]
    assert declined is not None and "declined" in declined.message
    outside, _ = cell.run(STACK[:1])  # no scope: this caller has no way to ask
    assert outside is not None and "cannot ask" in outside.message
    assert cell.motions() == []


def test_home_is_gated_like_any_motion(tmp_path: Path) -> None:
    from verigraph.arm import ArmStoppedError, ConfirmationError

    cell = Cell(tmp_path, confirm=lambda request: False)
    with pytest.raises(ConfirmationError, match="declined"):
        cell.world.home()
    assert cell.motions() == [] and "go home" in cell.asked[0].motion
    cell.world.stop()
    with pytest.raises(ArmStoppedError):
        cell.world.home()
    assert cell.world.render is None  # no camera of its own to show


def test_unknown_object_is_the_validator_s_answer(tmp_path: Path) -> None:
    cell = Cell(tmp_path)
    violation = cell.world.perform(MoveAction(object="purple", target="red"))
    assert violation is not None and violation.constraint == "unknown_object"
    assert cell.motions() == []
