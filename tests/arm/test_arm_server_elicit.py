"""Before a real arm acts, the server asks the user through MCP elicitation.

Driven with the real SDK client, in-process, on the default protocol (2026-07-28, where
the question rides an InputRequiredResult and the client's retry) and on the legacy
handshake (a pushed elicitation request). The arm is an xArm in mode `real` whose SDK
object is `BlockCellStandIn`, a stand-in for hardware that cannot run here.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from arm_deps import require
from arm_server_helpers import BlockCellStandIn, User, loose_blocks, xarm_toolbox
from mcp import Client
from mcp.types import CallToolResult
from mcp_helpers import structured, text

from verigraph.arm import ConfirmationRequest, Pose, PreApproved, confirm_scope
from verigraph.server import build_server
from verigraph.server import tools as server_tools
from verigraph.tools import Toolbox, registry
from verigraph.tools.acting import ExecutionOutput
from verigraph.tools.arm import preview_execute
from verigraph.tools.registry import TOOLS, ToolSpec

require("xarm")

pytestmark = pytest.mark.anyio


async def episode(client: Client) -> str:
    state = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))
    assert state["executor"] == "arm:xarm" and state["arm_mode"] == "real"
    assert state["scene_check"]["matches"] is True
    return str(state["episode_id"])


async def stack_green(client: Client, eid: str) -> CallToolResult:
    return await client.call_tool("execute_actions", {
        "episode_id": eid, "actions": ["move(green_block, on, red_block)"]})


def audit(tmp_path: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in (tmp_path / "audit.jsonl").read_text().splitlines()]


@pytest.mark.parametrize("mode", ["auto", "legacy"])
async def test_approved_motion_moves_the_arm(tmp_path: Path, mode: str) -> None:
    api = BlockCellStandIn()
    user = User()
    box = xarm_toolbox(tmp_path, api)
    async with Client(build_server(box), elicitation_callback=user, mode=mode) as client:
        assert client.protocol_version == ("2026-07-28" if mode == "auto" else "2025-11-25")
        eid = await episode(client)
        out = structured(await stack_green(client, eid))
    assert out["ok"] and out["executed"] == ["move(green_block, on, red_block)"]
    assert "green_block on red_block" in {f"{e['source']} on {e['target']}"
                                          for e in out["graph"]["edges"]}
    assert len(user.asked) == 1  # one question per call, asked once across the retry
    question = user.asked[0]
    assert "REAL arm (xarm at 192.168.1.185)" in question
    assert "1. move(green_block, on, red_block): pick green_block at (0.400, 0.000, 0.025)" \
        in question and "release it on red_block at (0.400, -0.120, 0.080)" in question
    moves = [kw for _, kw in api.called("set_position")]
    assert len(moves) == 6 and moves[4]["y"] == pytest.approx(-120.0)
    assert api.boxes["green_block"][0][2] == pytest.approx(0.075)  # it rests on red
    records = audit(tmp_path)
    confirmed = [r for r in records if r["command"] == "confirm"]
    # the user's answer to the question shown, then the gate's check of the motion
    assert [r["outcome"] for r in confirmed] == ["done", "done"]
    assert confirmed[0]["question"] == question and confirmed[0]["episode_id"] == eid
    assert confirmed[0]["client"] and confirmed[0]["pid"]
    assert [r["command"] for r in records if r["outcome"] == "sent"] == [
        "connect", "pick", "place"]


@pytest.mark.parametrize("user", [User(approve=False), User(action="decline"),
                                  User(action="cancel")], ids=["no", "decline", "cancel"])
async def test_declined_motion_moves_nothing(tmp_path: Path, user: User) -> None:
    api = BlockCellStandIn()
    box = xarm_toolbox(tmp_path, api)
    async with Client(build_server(box), elicitation_callback=user) as client:
        eid = await episode(client)
        before = structured(await client.call_tool("get_state", {"episode_id": eid}))
        result = await stack_green(client, eid)
        after = structured(await client.call_tool("get_state", {"episode_id": eid}))
    assert result.is_error and len(user.asked) == 1
    message = text(result)
    assert "the user " in message and "nothing moved and the episode is unchanged" in message
    assert "move(green_block, on, red_block)" in message
    assert api.motions() == []
    assert after == before  # graph, tau, calls, trace: all as they were


async def test_a_client_that_cannot_ask_moves_nothing(tmp_path: Path) -> None:
    api = BlockCellStandIn()
    box = xarm_toolbox(tmp_path, api)
    async with Client(build_server(box)) as client:  # no elicitation callback
        eid = await episode(client)
        result = await stack_green(client, eid)
        state = structured(await client.call_tool("get_state", {"episode_id": eid}))
    assert result.is_error
    assert "this client cannot ask the user to confirm (it declared no elicitation support)" \
        in text(result)
    assert "fix: use an MCP client that supports elicitation" in text(result)
    assert api.motions() == []
    assert state["calls"] == 0 and state["tau"] == 0 and state["executed"] == []


def test_the_library_without_a_hook_moves_nothing(tmp_path: Path) -> None:
    """Toolbox callers (CLI, scripts) have no user to ask unless they install a hook."""
    api = BlockCellStandIn()
    box = xarm_toolbox(tmp_path, api)
    eid = box.call("load_scene", {"graph": loose_blocks()}).episode_id
    out = box.call("execute_actions", {"episode_id": eid,
                                       "actions": ["move(green_block, on, red_block)"]})
    assert out.violation is not None and out.violation.constraint == "arm_refused"
    assert "not confirmed" in out.violation.message and "cannot ask" in out.violation.message
    assert api.motions() == []


async def test_invalid_and_unsafe_actions_are_never_put_to_the_user(tmp_path: Path) -> None:
    api = BlockCellStandIn()
    user = User()
    box = xarm_toolbox(tmp_path, api, workspace={"min": [0.2, -0.1, 0.01],
                                                 "max": [0.8, 0.45, 0.65]})
    async with Client(build_server(box), elicitation_callback=user) as client:
        eid = await episode(client)
        invalid = structured(await client.call_tool("execute_actions", {
            "episode_id": eid, "actions": ["move(table, on, red_block)"]}))
        unsafe = structured(await stack_green(client, eid))  # red is outside this workspace
    assert invalid["violation"]["constraint"] == "not_movable"
    assert unsafe["violation"]["constraint"] == "arm_refused"
    assert "outside the workspace" in unsafe["violation"]["message"]
    assert user.asked == [] and api.motions() == []


async def test_several_motions_are_asked_about_once_and_run_in_order(tmp_path: Path) -> None:
    api = BlockCellStandIn()
    user = User()
    async with Client(build_server(xarm_toolbox(tmp_path, api)),
                      elicitation_callback=user) as client:
        eid = await episode(client)
        out = structured(await client.call_tool("execute_actions", {
            "episode_id": eid, "actions": ["move(green_block, on, red_block)",
                                           "move(blue_block, on, green_block)", "done"]}))
    assert out["ok"] and out["done"] and len(out["executed"]) == 2
    assert len(user.asked) == 1 and "2 motions" in user.asked[0]
    assert "2. move(blue_block, on, green_block): pick blue_block at (0.400, 0.120, 0.025)" \
        in user.asked[0]
    assert api.boxes["blue_block"][0][2] == pytest.approx(0.125)  # on green, on red


async def test_reset_of_a_real_arm_is_asked_and_a_no_keeps_the_stop(tmp_path: Path) -> None:
    api = BlockCellStandIn()
    no, yes = User(approve=False), User()
    box = xarm_toolbox(tmp_path, api)
    server = build_server(box)
    async with Client(server, elicitation_callback=no) as client:
        eid = await episode(client)
        stopped = structured(await client.call_tool("arm_stop", {"episode_id": eid,
                                                                 "reason": "person in cell"}))
        assert stopped["stop_latched"] and api.called("emergency_stop")
        refused = await client.call_tool("arm_reset", {"episode_id": eid})
        assert refused.is_error and "the stop stays latched" in text(refused)
        status = structured(await client.call_tool("arm_status", {"episode_id": eid}))
        assert status["stop_latched"] and status["stop_reason"] == "person in cell"
    assert len(no.asked) == 1 and no.asked[0].startswith(
        "VeriGraph asks before the REAL arm (xarm at 192.168.1.185) acts: "
        f"arm_reset on episode {eid}.\n1. reset: clear the latched stop (person "
        "in cell) and re-enable the motors; nothing moves now\nApprove?\n(Answer within 120 s")
    async with Client(server, elicitation_callback=yes) as client:
        reset = structured(await client.call_tool("arm_reset", {"episode_id": eid}))
        assert not reset["stop_latched"] and "stop cleared" in reset["note"]
        out = structured(await stack_green(client, eid))
    assert out["ok"] and len(yes.asked) == 2 and "set_position" in api.motions()


def test_a_motion_that_changed_since_it_was_approved_is_refused(tmp_path: Path) -> None:
    """The approval covers the motion shown; if the block moves by more than 1 cm, no."""
    api = BlockCellStandIn()
    box: Toolbox = xarm_toolbox(tmp_path, api)
    eid = box.call("load_scene", {"graph": loose_blocks()}).episode_id
    params = registry.parse_arguments(TOOLS["execute_actions"], {
        "episode_id": eid, "actions": ["move(green_block, on, red_block)"]})
    question = preview_execute(box.context, params)
    assert question is not None and len(question.requests) == 1
    api.boxes["red_block"][0][1] += 0.02  # someone nudged the target after the yes
    with confirm_scope(PreApproved(question.requests)):
        out = box.run(TOOLS["execute_actions"], params)
    assert isinstance(out, ExecutionOutput)
    violation = out.violation
    assert violation is not None and violation.constraint == "arm_refused"
    assert "the scene changed since the user approved" in violation.message
    assert api.motions() == []


def test_pre_approval_is_single_use_and_in_order() -> None:
    def request(x: float) -> ConfirmationRequest:
        return ConfirmationRequest(driver="xarm", host="h", motion=f"m{x}", speed_m_s=0.2,
                                   waypoints=[Pose(x=x, y=0.0, z=0.1)], force_n=20.0)

    hook = PreApproved([request(0.4), request(0.5)])
    assert hook(request(0.405)) is True  # within 1 cm of what was shown
    with pytest.raises(Exception, match="differs from the approved one"):
        hook(request(0.4))  # the second approval was for x = 0.5
    with pytest.raises(Exception, match="not asked about this motion"):
        hook(request(0.5))
    assert hook.remaining == 0


@pytest.mark.parametrize(("mode", "rounds"), [("auto", 2), ("legacy", 1)])
async def test_a_confirmed_call_checks_its_input_once_per_request(
        tmp_path: Path, mode: str, rounds: int, monkeypatch: pytest.MonkeyPatch) -> None:
    """The server checks a confirmed call's input once per request (step 1); the
    resolvers that ask the user and the tool's body read that check, not their own (on
    2026-07-28 the question takes two requests, the call and the client's retry)."""
    parsed: list[str] = []
    parse = registry.parse_arguments

    def counted(spec: ToolSpec, *args: Any, **kwargs: Any) -> Any:
        parsed.append(spec.name)
        return parse(spec, *args, **kwargs)

    async with Client(build_server(xarm_toolbox(tmp_path, BlockCellStandIn())),
                      elicitation_callback=User(), mode=mode) as client:
        eid = await episode(client)
        for module in (registry, server_tools):  # every name the server calls it by
            monkeypatch.setattr(module, "parse_arguments", counted)
        out = structured(await stack_green(client, eid))
    assert out["ok"]
    assert parsed == ["execute_actions"] * rounds
