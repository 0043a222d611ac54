"""`verigraph serve --executor / --arm-config`: bad arms stop the server before it starts
(exit 2, the field and the fix on stderr), and a good one serves over stdio."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from arm_deps import require
from arm_server_helpers import LAYOUT
from mcp import Client, StdioServerParameters
from mcp_helpers import REPO, structured, verigraph_command

from verigraph.arm import load_arm_config
from verigraph.cli import main

require("pybullet")


def write(tmp_path: Path, name: str, config: dict[str, object]) -> str:
    path = tmp_path / name
    path.write_text(json.dumps(config) if name.endswith(".json") else
                    "\n".join(f"{k}: {json.dumps(v)}" for k, v in config.items()))
    return str(path)


@pytest.mark.parametrize(("args", "config", "needles"), [
    (["--executor", "arm:ur5"], None, ["--executor: unknown arm executor 'arm:ur5'",
                                       "fix: use arm:pybullet, arm:rosbridge, arm:xarm"]),
    (["--executor", "robot"], None, ["--executor: unknown executor 'robot'"]),
    ([], {"driver": "xarm", "speed_m_s": 3}, ["speed_m_s (3.0) exceeds max_speed_m_s"]),
    ([], {"driver": "xarm", "mode": "rea1"}, ["mode: bad arm config", "dry-run"]),
    ([], {"driver": "pybullet", "mode": "real", "audit_log": "a.jsonl"},
     ["mode 'real' with the pybullet driver"]),
    (["--executor", "arm:pybullet"], {"driver": "xarm"},
     ["--arm-config: --executor arm:pybullet but the arm config's driver is xarm"]),
    ([], {"driver": "xarm", "mode": "real", "host": "192.168.1.185", "audit_log": "a.jsonl"},
     ["layout: the xarm driver has no camera of its own", "fix: add a layout"]),
    ([], {"driver": "xarm", "mode": "real", "host": "127.0.0.1", "audit_log": "a.jsonl",
          "connect_timeout_s": 1, "layout": LAYOUT},
     ["host: cannot reach the xarm controller at 127.0.0.1:502 within 1 s",
      "fix: check the address"]),
])
def test_bad_arms_exit_2_before_serving(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                        args: list[str], config: dict[str, object] | None,
                                        needles: list[str]) -> None:
    if config is not None:
        args = [*args, "--arm-config", write(tmp_path, "arm.yaml", config)]
    assert main(["serve", *args]) == 2
    err = capsys.readouterr().err
    for needle in needles:
        assert needle in err
    assert err.startswith("error: ")


def test_missing_config_file_exits_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["serve", "--arm-config", "/nonexistent/arm.yaml"]) == 2
    assert "cannot read arm config" in capsys.readouterr().err


@pytest.mark.anyio
@pytest.mark.parametrize("anyio_backend", ["asyncio"])
async def test_stdio_server_runs_episodes_on_the_configured_panda(tmp_path: Path) -> None:
    config = write(tmp_path, "arm.json", {"driver": "pybullet", "mode": "sim",
                                          "audit_log": str(tmp_path / "audit.jsonl")})
    command, *prefix = verigraph_command()
    params = StdioServerParameters(command=command, args=[*prefix, "serve", "--arm-config",
                                                          config])
    async with Client(params) as client:
        state = structured(await client.call_tool("load_scene", {"scene_id": "three_blocks"}))
        assert state["executor"] == "arm:pybullet" and state["arm_mode"] == "sim"
        plan = structured(await client.call_tool("solve", {"episode_id": state["episode_id"]}))
        out = structured(await client.call_tool("execute_actions", {
            "episode_id": state["episode_id"], "actions": plan["plan"]}))
        assert out["ok"] and out["goal_satisfied"]
        graph_only = structured(await client.call_tool("load_scene", {
            "scene_id": "three_blocks", "executor": "graph"}))
        assert graph_only["executor"] == "graph" and graph_only["arm_mode"] is None
    records = [json.loads(line) for line in (tmp_path / "audit.jsonl").read_text().splitlines()]
    assert [r["command"] for r in records if r["outcome"] == "done"] == [
        "connect", "pick", "place"]


@pytest.mark.parametrize("name", ["pybullet_sim.yaml", "xarm_real.yaml"])
def test_example_arm_configs_are_valid(name: str) -> None:
    config = load_arm_config(REPO / "examples" / "arm_configs" / name)
    assert config.mode in ("sim", "real")
    if config.driver == "xarm":
        assert config.host and config.layout and config.audit_log is not None
