"""Ending an arm episode releases everything it opened: every PyBullet client and the
memory behind it, so open/end rounds leave the server as large as after the first one.

The rounds run in a fresh Python process (the real tool layer with a server arm), so
the PyBullet client table and the RSS belong to this scenario alone.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from arm_deps import require

require("pybullet")

ROOT = Path(__file__).resolve().parents[2]
ROUNDS = 5
RSS_BOUND_MIB = 60.0

SCRIPT = """
import json, sys
import pybullet as pb
from verigraph.arm import parse_arm_config
from verigraph.tools import Toolbox, ToolConfig
from verigraph.tools.executors import ArmSetup

def rss_mib():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    raise RuntimeError("no VmRSS")

def clients():
    # pybullet has at most MAX_PHYSICS_CLIENTS (1024) client slots; ask each one.
    return [i for i in range(1024)
            if pb.getConnectionInfo(physicsClientId=i)["isConnected"]]

arm = ArmSetup(parse_arm_config({"driver": "pybullet", "mode": sys.argv[1]}))
box = Toolbox(config=ToolConfig(arm=arm))

def round_trip():
    episode = box.call("load_scene", {"scene_id": "three_blocks",
                                      "executor": "arm:pybullet"}).episode_id
    during = clients()
    box.call("end_episode", {"episode_id": episode})
    return during, clients()

before = clients()
warm_during, warm_after = round_trip()
start = rss_mib()
rounds = [round_trip() for _ in range(int(sys.argv[2]))]
print(json.dumps({"before": before, "warm_during": warm_during, "warm_after": warm_after,
                  "rounds": rounds, "rss_start": start, "rss_end": rss_mib()}))
"""


def run_rounds(mode: str, rounds: int) -> dict[str, object]:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(ROOT), os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run([sys.executable, "-c", SCRIPT, mode, str(rounds)], env=env,
                          capture_output=True, text=True, timeout=300, check=True)
    result: dict[str, object] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


@pytest.mark.parametrize("mode", ["dry-run", "sim"])
def test_end_episode_disconnects_every_pybullet_client_and_rss_stays_flat(mode: str) -> None:
    found = run_rounds(mode, ROUNDS)
    assert found["before"] == []
    # The cell, the driver's IK and the whole-arm check each hold a client while open ...
    warm_during = found["warm_during"]
    assert isinstance(warm_during, list) and len(warm_during) >= 3
    # ... and none is left after end_episode, in the warm-up round or any later one.
    assert found["warm_after"] == []
    rounds = found["rounds"]
    assert isinstance(rounds, list) and len(rounds) == ROUNDS
    for during, after in rounds:
        assert len(during) == len(warm_during)
        assert after == []
    start, end = found["rss_start"], found["rss_end"]
    assert isinstance(start, float) and isinstance(end, float)
    assert end - start < RSS_BOUND_MIB, f"RSS grew {end - start:.0f} MiB in {ROUNDS} rounds"
