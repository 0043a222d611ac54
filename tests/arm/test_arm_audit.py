"""The audit log is the arm's safety record: complete, chained, and failing safe.

The arm is a real-mode xArm whose SDK object is `BlockCellStandIn` (a stand-in: no
controller can run here), driven through the real MCP client and server.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import pytest
from arm_deps import require
from arm_server_helpers import BlockCellStandIn, User, loose_blocks, xarm_toolbox
from mcp import Client
from mcp_helpers import structured

from verigraph.arm.audit import verify_audit_file
from verigraph.cli import main as cli_main
from verigraph.server import build_server

require("xarm")

STACK = ["move(green_block, on, red_block)"]


def audit(tmp_path: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in (tmp_path / "audit.jsonl").read_text().splitlines()]


class AuditFailsMidPick(BlockCellStandIn):
    """The cell stand-in; when the gripper closes on the block, the audit log's disk
    goes away (the file is replaced by a directory, so every later write fails)."""

    def __init__(self, audit_path: Path) -> None:
        super().__init__()
        self.audit_path = audit_path

    def set_gripper_position(self, pos: float, *args: Any, **kwargs: Any) -> int:
        code = super().set_gripper_position(pos, *args, **kwargs)
        if pos == 0 and self.audit_path.is_file():
            self.audit_path.unlink()
            self.audit_path.mkdir()
        return code


@pytest.mark.anyio
async def test_an_audit_write_failure_stops_and_latches_the_arm(tmp_path: Path) -> None:
    api = AuditFailsMidPick(tmp_path / "audit.jsonl")
    box = xarm_toolbox(tmp_path, api)
    async with Client(build_server(box), elicitation_callback=User()) as client:
        eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
            "episode_id"]
        out = structured(await client.call_tool("execute_actions", {"episode_id": eid,
                                                                    "actions": STACK}))
        moved = len(api.motions())
        status = structured(await client.call_tool("arm_status", {"episode_id": eid}))
        again = structured(await client.call_tool("execute_actions", {"episode_id": eid,
                                                                      "actions": STACK}))
    assert api.held == "green_block"  # the pick closed on it before the write failed
    assert api.called("emergency_stop")
    assert status["stop_latched"] and "audit log write failed" in status["stop_reason"]
    # the graph is what the arm observes: green is in the gripper, on nothing
    assert out["violation"]["constraint"] == "execution_failed"
    assert not any(e["source"] == "green_block" for e in out["graph"]["edges"])
    assert again["violation"]["constraint"] == "arm_refused"
    assert len(api.motions()) == moved  # the place never went out


@pytest.mark.anyio
@pytest.mark.parametrize(("user", "outcome"), [(User(approve=False), "declined"),
                                               (User(action="cancel"), "declined"),
                                               (None, "refused")],
                         ids=["no", "cancel", "cannot-ask"])
async def test_declines_and_refusals_are_in_the_audit_log(
        tmp_path: Path, user: User | None, outcome: str) -> None:
    api = BlockCellStandIn()
    box = xarm_toolbox(tmp_path, api)
    async with Client(build_server(box), elicitation_callback=user) as client:
        eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
            "episode_id"]
        declined = await client.call_tool("execute_actions", {"episode_id": eid,
                                                              "actions": STACK})
        del api.boxes["red_block"]  # the camera no longer sees the target
        unseen = structured(await client.call_tool("execute_actions", {
            "episode_id": eid, "actions": STACK}))
        invalid = structured(await client.call_tool("execute_actions", {
            "episode_id": eid, "actions": ["move(table, on, green_block)"]}))
    assert invalid["violation"]["constraint"] == "not_movable"
    assert declined.is_error and api.motions() == []
    assert "cannot see red_block" in unseen["violation"]["message"]
    records = audit(tmp_path)
    confirm = [r for r in records if r["command"] == "confirm"]
    assert [r["outcome"] for r in confirm] == [outcome]
    assert "move(green_block, on, red_block)" in confirm[0]["question"]
    refused = [r for r in records if r["command"] == "motion" and r["outcome"] == "refused"]
    assert len(refused) == 2 and "cannot see red_block" in refused[0]["detail"]
    assert refused[1]["params"]["what"] == "move(table, on, green_block)"
    assert "rejected by the episode's validator: [not_movable]" in refused[1]["detail"]
    for record in confirm + refused:
        assert record["episode_id"] == eid and record["pid"] > 0 and record["client"]
        assert record["mode"] == "real"


WRITER = textwrap.dedent("""
    import sys
    from verigraph.arm.audit import AuditLog
    from verigraph.arm.models import AuditRecord
    log = AuditLog(sys.argv[1])
    print("ready", flush=True)
    sys.stdin.readline()  # start together
    for i in range(int(sys.argv[2])):
        log.record(AuditRecord(mode="sim", driver="pybullet", command="stop",
                               outcome="recorded", detail=f"{sys.argv[3]} {i}"))
""")


def test_seq_is_unique_across_processes_and_the_chain_verifies(tmp_path: Path) -> None:
    path, per_process = tmp_path / "audit.jsonl", 150
    writers = [subprocess.Popen([sys.executable, "-c", WRITER, str(path), str(per_process),
                                 name], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                text=True) for name in ("a", "b")]
    for w in writers:
        assert w.stdout is not None and w.stdout.readline().strip() == "ready"
    for w in writers:
        assert w.stdin is not None
        w.stdin.write("go\n")
        w.stdin.flush()
    for w in writers:
        assert w.wait(60) == 0
    records = [json.loads(line) for line in path.read_text().splitlines()]
    assert [r["seq"] for r in records] == list(range(1, 2 * per_process + 1))
    assert len({r["pid"] for r in records}) == 2
    assert verify_audit_file(path) == (2 * per_process, [])


@pytest.mark.parametrize("line", [1, -1], ids=["a middle record", "the last record"])
def test_audit_verify_accepts_the_log_and_rejects_one_changed_byte(
        tmp_path: Path, line: int, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "audit.jsonl"
    writer_args = [str(path), "5", "x"]
    subprocess.run([sys.executable, "-c", WRITER, *writer_args], input="go\n", text=True,
                   check=True, capture_output=True)
    assert cli_main(["arm", "audit-verify", str(path)]) == 0
    assert "OK" in capsys.readouterr().out
    lines = path.read_bytes().splitlines(keepends=True)
    target = bytearray(lines[line])
    at = target.index(b'"detail":"x ') + len(b'"detail":"x ')
    target[at] = ord("7") if target[at] != ord("7") else ord("8")  # one byte
    lines[line] = bytes(target)
    path.write_bytes(b"".join(lines))
    assert cli_main(["arm", "audit-verify", str(path)]) == 1
    assert "hash does not match" in capsys.readouterr().out


def test_operator_commands_refuse_what_they_cannot_do(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    real = tmp_path / "real.json"
    real.write_text(json.dumps({"driver": "xarm", "mode": "real", "host": "192.168.1.185",
                                "audit_log": str(tmp_path / "audit.jsonl")}))
    assert cli_main(["arm", "reset", "--config", str(real)]) == 2  # the user confirms those
    assert "mode: a real arm's stop is reset through arm_reset" in capsys.readouterr().err
    memory = tmp_path / "sim.json"
    memory.write_text(json.dumps({"driver": "pybullet", "mode": "sim"}))
    assert cli_main(["arm", "reset", "--config", str(memory)]) == 2
    assert "audit_log: this arm's latch lives in the server's memory" in \
        capsys.readouterr().err
    assert cli_main(["arm", "audit-verify", str(tmp_path / "missing.jsonl")]) == 2
    assert "cannot read the audit log" in capsys.readouterr().err
