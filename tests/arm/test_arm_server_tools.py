"""The arm behind the tools: executors, the arm_* tools, and the guarantees of issue 7.

The arm is an xArm whose SDK object is a stand-in (`BlockCellStandIn`, recording every
call), since no controller can run here; the MCP client is the real SDK client with a
user who approves everything, so the confirmation is never what stops a motion here.
"""

from __future__ import annotations

import contextlib
import json
import sys
import threading
import time
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import pytest
from arm_deps import require
from arm_server_helpers import LAYOUT, BlockCellStandIn, loose_blocks, xarm_toolbox
from mcp import Client
from mcp.client.context import ClientRequestContext
from mcp.types import CallToolResult, ElicitRequestParams, ElicitResult
from mcp_helpers import png_b64, structured, text

from verigraph.arm import parse_arm_config
from verigraph.errors import VeriGraphError
from verigraph.server import build_server
from verigraph.tools import TOOL_SPECS, Toolbox, ToolConfig
from verigraph.tools.executors import ArmSetup

require("xarm")

pytestmark = pytest.mark.anyio


class Harness:
    """An in-process server on an xArm stand-in, a client whose user approves all."""

    def __init__(self, tmp_path: Path, mode: str = "real", **overrides: Any) -> None:
        self.api = BlockCellStandIn()
        self.box = xarm_toolbox(tmp_path, self.api, mode=mode, **overrides)
        self.asked: list[str] = []
        self.audit = tmp_path / "audit.jsonl"

    async def approve(self, context: ClientRequestContext,
                      params: ElicitRequestParams) -> ElicitResult:
        self.asked.append(params.message)
        return ElicitResult(action="accept", content={"approve": True})

    def sent(self) -> list[str]:
        if not self.audit.exists():
            return []
        return [r["command"] for r in map(json.loads, self.audit.read_text().splitlines())
                if r["outcome"] == "sent"]


@pytest.fixture()
async def real(tmp_path: Path) -> AsyncIterator[tuple[Harness, Client]]:
    h = Harness(tmp_path)
    async with Client(build_server(h.box), elicitation_callback=h.approve) as client:
        yield h, client


async def call(client: Client, tool: str, **args: Any) -> dict[str, Any]:
    return structured(await client.call_tool(tool, args))


async def load(client: Client, graph: dict[str, Any] | None = None, **args: Any) -> str:
    return str((await call(client, "load_scene", graph=graph or loose_blocks(),
                           **args))["episode_id"])


def edges(graph: dict[str, Any]) -> set[str]:
    return {f"{e['source']} {e['relation']} {e['target']}" for e in graph["edges"]}


LOOSE = edges(loose_blocks())


# -- dry-run ---------------------------------------------------------------------------------
async def test_dry_run_never_calls_the_driver_through_the_tools(tmp_path: Path) -> None:
    h = Harness(tmp_path, mode="dry-run")
    async with Client(build_server(h.box), elicitation_callback=h.approve) as client:
        state = await call(client, "load_scene", graph=loose_blocks(),
                           goal={"predicate": "single_stack"})
        eid = state["episode_id"]
        assert state["arm_mode"] == "dry-run"
        plan = (await call(client, "solve", episode_id=eid))["plan"]
        out = await call(client, "execute_actions", episode_id=eid, actions=plan + ["done"])
        status = await call(client, "arm_status", episode_id=eid)
        await call(client, "arm_stop", episode_id=eid)
        reset = await client.call_tool("arm_reset", {"episode_id": eid})
        await call(client, "end_episode", episode_id=eid)
    # only the operator resets a dry-run or simulated arm (verigraph arm reset)
    assert reset.is_error and "agent_may_reset" in text(reset)
    assert out["ok"] and out["goal_satisfied"]  # the dry run predicts the stack ...
    assert h.api.calls == []  # ... and never talks to the controller, not even to connect
    assert status["commands_sent"] == 0 and not status["connected"]
    assert h.asked == []  # nothing real, nothing to ask
    records = [json.loads(line) for line in h.audit.read_text().splitlines()]
    assert [r["command"] for r in records if r["command"] in ("pick", "place")] == [
        "pick", "place"] * 2
    assert {r["outcome"] for r in records} <= {"recorded", "refused"}
    assert [r["command"] for r in records if r["outcome"] == "refused"] == ["reset"]


# -- nothing unvalidated reaches the driver, whatever the tool -------------------------------
STACKED_GRAPH = loose_blocks()  # what the episode is told ...
STACKED_LAYOUT = {**LAYOUT, "green_block": {"centre": [0.4, -0.12, 0.075],
                                            "size": LAYOUT["green_block"]["size"]}}  # ... and sees
INVALID_ACTIONS: list[Any] = [
    "move(red_block, on, red_block)",  # same_object
    "move(table, on, red_block)",  # not_movable
    "move(purple_block, on, red_block)",  # unknown_object
    {"action": "move", "object": "green_block", "relation": "in", "target": "red_block"},
    {"action": "move", "object": "green_block", "relation": "under", "target": "red_block"},
    "align(red_block, 0, green_block, 1)",  # the arm carries out moves only
    '{"action": "teleport", "object": "red_block"}',
    "move(red_block; on; blue_block)",
    "pick(red_block)",
    ["move(red_block, on, blue_block)"],  # a list where an action belongs
    {"action": "move", "object": "red_block", "relation": "on", "target": "blue_block",
     "waypoints": [[0, 0, 0]]},  # extra fields are not a way in
    "move(red_block, on, blue_block)",  # valid on the graph; the arm sees green on red
]


def every_call(eid: str, action: Any) -> dict[str, dict[str, Any]]:
    """One call per tool, each carrying the (invalid) action where the tool takes one."""
    plan = action if isinstance(action, str) else [action]
    return {
        "load_scene": {"graph": loose_blocks(), "goal": {"predicate": "single_stack"},
                       "instruction": str(action)},
        "set_goal": {"episode_id": eid, "instruction": str(action)},
        "get_state": {"episode_id": eid},
        "validate_action": {"episode_id": eid, "action": action},
        "execute_actions": {"episode_id": eid, "actions": [action]},
        "validate_plan": {"episode_id": eid, "plan": plan},
        "check_goal": {"episode_id": eid, "goal": {"predicate": "single_stack"}},
        "generate_scene_graph": {"episode_id": eid},
        "render_scene": {"episode_id": eid, "width": 64, "height": 64},
        "solve": {"episode_id": eid},
        "get_scene_image": {"episode_id": eid, "task": str(action), "width": 64,
                            "height": 64},
        "submit_scene_graph": {"episode_id": eid, "graph": loose_blocks()},
        "arm_status": {"episode_id": eid},
        "arm_reset": {"episode_id": eid},
        "arm_stop": {"episode_id": eid, "reason": str(action)[:200]},
        "end_episode": {"episode_id": eid},
    }


async def test_an_unvalidated_action_reaches_no_driver_through_any_tool(tmp_path: Path) -> None:
    h = Harness(tmp_path)
    h.api.boxes["green_block"][0][:] = STACKED_LAYOUT["green_block"]["centre"]
    async with Client(build_server(h.box), elicitation_callback=h.approve) as client:
        eid = await load(client, STACKED_GRAPH, t=100)  # every failed call counts in tau
        state = await call(client, "get_state", episode_id=eid)
        assert not state["scene_check"]["matches"]  # reported at the start ...
        assert "WARNING: the arm observes a different scene" in text(
            await client.call_tool("get_state", {"episode_id": eid}))
        assert state["scene_check"]["not_observed"] == ["green_block on table"]
        assert state["scene_check"]["observed_instead"] == ["green_block on red_block"]
        calls = every_call(eid, INVALID_ACTIONS[0])
        assert set(calls) == {s.name for s in TOOL_SPECS}  # a new tool must be added here
        results: list[CallToolResult] = []
        for action in INVALID_ACTIONS:
            for tool, args in every_call(eid, action).items():
                if tool not in ("arm_stop", "end_episode"):  # they come last
                    results.append(await client.call_tool(tool, args))
            # the same through the transport-free toolbox, bypassing MCP
            with contextlib.suppress(VeriGraphError):
                h.box.call("execute_actions", {"episode_id": eid, "actions": [action]})
        ran = [structured(r) for r in results if not r.is_error and r.structured_content
               and "executed" in r.structured_content and "episode_id" in
               r.structured_content and "not_executed" in r.structured_content]
        assert ran and all(r["executed"] == [] and r["violation"] for r in ran)
        observed = [r["violation"] for r in ran
                    if "the arm observes" in r["violation"]["message"]]
        assert observed and observed[0]["constraint"] == "object_not_clear"
        for tool in ("arm_stop", "end_episode"):
            results.append(await client.call_tool(tool, every_call(eid, "x")[tool]))
    assert h.api.motions() == []
    assert h.asked == []  # never asked to approve an action that would be refused
    assert "pick" not in h.sent() and "place" not in h.sent()


# -- the stop --------------------------------------------------------------------------------
async def test_the_stop_stays_latched_across_calls_until_arm_reset(
        real: tuple[Harness, Client]) -> None:
    h, client = real
    eid = await load(client)
    stopped = await call(client, "arm_stop", episode_id=eid, reason="operator pressed stop")
    assert stopped["stop_latched"] and stopped["stop_reason"] == "operator pressed stop"
    again = await call(client, "arm_stop", episode_id=eid, reason="second press")
    assert again["stop_reason"] == "operator pressed stop" and "already latched" in again["note"]
    for _ in range(2):
        out = await call(client, "execute_actions", episode_id=eid,
                         actions=["move(green_block, on, red_block)"])
        assert out["violation"]["constraint"] == "arm_refused"
        assert "stop is latched (operator pressed stop)" in out["violation"]["message"]
        assert "arm_reset" in out["violation"]["suggestion"]
        assert edges(out["graph"]) == LOOSE
    assert (await call(client, "arm_status", episode_id=eid))["stop_latched"]
    assert h.api.motions() == [] and len(h.asked) == 0
    reset = await call(client, "arm_reset", episode_id=eid)
    assert not reset["stop_latched"] and len(h.asked) == 1
    out = await call(client, "execute_actions", episode_id=eid,
                     actions=["move(green_block, on, red_block)"])
    assert out["ok"] and "set_position" in h.api.motions()


async def test_stop_answers_while_a_motion_holds_the_episode(tmp_path: Path) -> None:
    """arm_stop and arm_status do not wait for the running call's lock."""
    import anyio

    h = Harness(tmp_path, speed_m_s=0.05)
    h.api.time_scale = 1.0  # linear moves take their real duration on the stand-in
    async with Client(build_server(h.box), elicitation_callback=h.approve) as client:
        eid = await load(client)
        running: list[dict[str, Any]] = []

        async def execute() -> None:
            running.append(await call(client, "execute_actions", episode_id=eid,
                                      actions=["move(green_block, on, red_block)"]))

        async with anyio.create_task_group() as tg:
            tg.start_soon(execute)
            with anyio.fail_after(10):
                while not h.api.called("set_position"):
                    await anyio.sleep(0.02)
            started = time.monotonic()
            busy = await call(client, "arm_status", episode_id=eid)
            stopped = await call(client, "arm_stop", episode_id=eid, reason="test stop")
            answered = time.monotonic() - started
    assert busy["busy"] and answered < 2  # the motion alone takes several seconds
    assert stopped["stop_latched"] and h.api.called("emergency_stop")
    out = running[0]
    assert out["violation"]["constraint"] == "execution_failed"
    assert "green_block on red_block" not in json.dumps(out["graph"])


# -- bad input -------------------------------------------------------------------------------
async def test_targets_outside_the_workspace_are_refused(tmp_path: Path) -> None:
    h = Harness(tmp_path, workspace={"min": [0.2, -0.1, 0.01], "max": [0.8, 0.45, 0.65]})
    async with Client(build_server(h.box), elicitation_callback=h.approve) as client:
        eid = await load(client)
        out = await call(client, "execute_actions", episode_id=eid,
                         actions=["move(green_block, on, red_block)"])
        state = await call(client, "get_state", episode_id=eid)
    violation = out["violation"]
    assert violation["constraint"] == "arm_refused"
    assert "outside the workspace" in violation["message"] and "-0.120" in violation["message"]
    assert edges(state["graph"]) == LOOSE and state["executed"] == []
    assert h.api.motions() == [] and h.asked == []


async def test_episodes_without_an_arm_get_a_clear_error(real: tuple[Harness, Client]) -> None:
    _, client = real
    plain = await call(client, "load_scene", scene_id="cup_on_book", executor="graph")
    assert plain["executor"] == "graph" and plain["arm_mode"] is None
    for tool in ("arm_status", "arm_stop", "arm_reset"):
        result = await client.call_tool(tool, {"episode_id": plain["episode_id"]})
        assert result.is_error
        assert f"episode {plain['episode_id']} runs on graph, not on an arm" in text(result)
        assert "fix: load the scene with executor arm:<driver>" in text(result)


async def test_a_graph_episode_on_an_arm_server_never_enters_the_arm(
        real: tuple[Harness, Client]) -> None:
    h, client = real
    plain = await call(client, "load_scene", scene_id="cup_on_book", executor="graph")
    entered: set[str] = set()

    def profile(frame: Any, event: str, arg: Any) -> None:
        module = frame.f_globals.get("__name__") or ""
        if event == "call" and module.startswith("verigraph.arm"):
            entered.add(module)

    sys.setprofile(profile)
    threading.setprofile(profile)
    try:
        await call(client, "validate_action", episode_id=plain["episode_id"],
                   action="move(cup, on, desk)")
        await call(client, "execute_actions", episode_id=plain["episode_id"],
                   actions=["move(cup, on, desk)"])
    finally:
        sys.setprofile(None)
        threading.setprofile(None)  # type: ignore[arg-type]
    assert entered == set() and h.asked == [] and h.sent() == []


@pytest.mark.parametrize(("args", "needles"), [
    ({"executor": "arm:ur5"}, ["executor: unknown arm executor 'arm:ur5'", "arm:pybullet"]),
    ({"executor": "robot"}, ["executor: unknown executor 'robot'", "sim2d"]),
    ({"executor": "arm:pybullet"}, ["this server's arm is arm:xarm, not arm:pybullet"]),
    ({"executor": "arm:xarm", "simulate": True}, ["simulate: simulate=true runs the 2D"]),
    ({"executor": "arm:xarm", "generator": {"family": "tangram"}},
     ["executor: the arm adapter carries out move actions only", "use executor sim2d"]),
])
async def test_bad_executors_are_tool_errors_and_store_nothing(
        real: tuple[Harness, Client], args: dict[str, Any], needles: list[str]) -> None:
    h, client = real
    source = {} if "generator" in args else {"graph": loose_blocks()}
    result = await client.call_tool("load_scene", {**source, **args})
    assert result.is_error
    for needle in needles:
        assert needle in text(result)
    assert len(h.box.context.store) == 0 and len(h.box.context.arms) == 0
    assert h.api.calls == []


async def test_unreachable_arm_is_a_bounded_tool_error(tmp_path: Path) -> None:
    """The real xArm SDK against a loopback address where no controller listens."""
    config = parse_arm_config({"driver": "xarm", "mode": "real", "host": "127.0.0.1",
                               "connect_timeout_s": 2, "layout": LAYOUT,
                               "audit_log": str(tmp_path / "audit.jsonl")})
    box = Toolbox(config=ToolConfig(executor="arm:xarm", arm=ArmSetup(config)))
    async with Client(build_server(box)) as client:
        started = time.monotonic()
        result = await client.call_tool("load_scene", {"graph": loose_blocks()})
        elapsed = time.monotonic() - started
    assert result.is_error and elapsed < 5
    assert "host: cannot" in text(result) and "127.0.0.1" in text(result)
    assert "fix: check the" in text(result)
    assert len(box.context.store) == 0 and len(box.context.arms) == 0


async def test_one_episode_per_physical_arm_and_end_episode_disconnects(
        real: tuple[Harness, Client]) -> None:
    h, client = real
    eid = await load(client)
    second = await client.call_tool("load_scene", {"graph": loose_blocks()})
    assert second.is_error and "in use by another episode" in text(second)
    assert "fix: call end_episode on that episode first" in text(second)
    assert h.api.connected
    await call(client, "end_episode", episode_id=eid)
    assert not h.api.connected and h.api.called("disconnect")
    assert len(h.box.context.arms) == 0
    await load(client)  # the arm is free again


async def test_an_image_episode_gets_its_arm_with_its_scene_graph(
        real: tuple[Harness, Client]) -> None:
    h, client = real
    state = await call(client, "load_scene", image=png_b64())
    eid = state["episode_id"]
    assert state["executor"] == "arm:xarm" and state["awaiting_scene_graph"]
    waiting = await client.call_tool("arm_status", {"episode_id": eid})
    assert waiting.is_error and "waits for its scene graph" in text(waiting)
    assert h.api.calls == []
    submitted = await call(client, "submit_scene_graph", episode_id=eid, graph=loose_blocks())
    assert submitted["adopted"] and submitted["scene_check"]["matches"]
    status = await call(client, "arm_status", episode_id=eid)
    assert status["connected"] and status["mode"] == "real"


async def test_which_calls_the_arm_s_scope_takes(tmp_path: Path) -> None:
    """On a server with an arm: a new episode and an id the store does not have (the tool
    reports it) are the arm's; an episode on the graph alone is not."""
    from pydantic import BaseModel

    from verigraph.server.heavy import HeavyCalls
    from verigraph.server.tools import ToolCalls

    class Call(BaseModel):
        episode_id: str | None = None

    h = Harness(tmp_path, mode="dry-run")
    calls = ToolCalls(h.box, HeavyCalls())
    async with Client(build_server(h.box), elicitation_callback=h.approve) as client:
        on_graph = (await call(client, "load_scene", graph=loose_blocks(),
                               executor="graph"))["episode_id"]
        on_arm = await load(client, loose_blocks())
        assert not calls.arm_involved(Call(episode_id=on_graph))
        assert calls.arm_involved(Call(episode_id=on_arm))
        assert calls.arm_involved(Call(episode_id="ep_no_such_episode"))
        assert calls.arm_involved(Call())
    assert not ToolCalls(Toolbox(), HeavyCalls()).arm_involved(Call(episode_id=on_arm))
