"""The current OpenEnv (openenv 0.10): the verigraph-openenv package's own server and
client (OpenEnv's `create_app` and `EnvClient`, in the separate environment that
scripts/install_integration.sh openenv builds) against VeriGraph's environment server, on loopback.

VeriGraph's served environment (procedural blocks, level 1) runs in this process; the
OpenEnv 0.10 server runs as a child in its own virtual environment and forwards every
session to it; OpenEnv 0.10's client, in a second child, plays an episode: a refused
action first (the verifier's violation comes back), then the oracle's plan (reward 1.0,
done), a level moved on reset, and a refused reset reported as an error. The children
reach loopback only (tests/venv_helpers.py): nothing is fetched at test time.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from optional import require

require("openenv", "pip install 'verigraph-mcp[env]'")

import httpx  # noqa: E402
from mcp_helpers import free_port  # noqa: E402
from openenv_helpers import serving_app  # noqa: E402
from venv_helpers import (  # noqa: E402
    OUTSIDE,
    ROOT,
    assert_reaches_loopback_only,
    child_env,
    venv_python,
)

from verigraph.env.openenv_server import create_openenv_app  # noqa: E402
from verigraph.graph.model import SceneGraph  # noqa: E402
from verigraph.graph.state import WorldState  # noqa: E402
from verigraph.solver import solve  # noqa: E402
from verigraph.tasks.procedural import generate_task  # noqa: E402


def openenv_python() -> Path:
    return venv_python("openenv", "VERIGRAPH_OPENENV_PYTHON")


@pytest.fixture(scope="module")
def openenv_url() -> Iterator[str]:
    python = openenv_python()
    with serving_app(create_openenv_app(family="blocks", level=1)) as verigraph_url:
        port = free_port()
        server = subprocess.Popen(
            [str(python), "-m", "verigraph_openenv.server.app", "--port", str(port)],
            env=child_env(VERIGRAPH_URL=verigraph_url, ENABLE_WEB_INTERFACE="false"),
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        url = f"http://127.0.0.1:{port}"
        try:
            deadline = time.monotonic() + 60
            while True:
                assert server.poll() is None, server.stderr.read().decode()[-2000:] \
                    if server.stderr else "the OpenEnv server exited"
                try:
                    if httpx.get(f"{url}/health", timeout=2).status_code == 200:
                        break
                except httpx.TransportError:
                    pass
                assert time.monotonic() < deadline, "the OpenEnv 0.10 server did not start"
                time.sleep(0.2)
            yield url
        finally:
            server.terminate()
            server.wait(timeout=20)


class Driver:
    """OpenEnv 0.10's client in the other environment (verigraph_openenv.drive)."""

    def __init__(self, url: str) -> None:
        self.process = subprocess.Popen(
            [str(openenv_python()), "-m", "verigraph_openenv.drive", url],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=child_env())

    def __call__(self, command: dict[str, Any]) -> dict[str, Any]:
        assert self.process.stdin and self.process.stdout
        self.process.stdin.write(json.dumps(command) + "\n")
        self.process.stdin.flush()
        line = self.process.stdout.readline()
        assert line, "the OpenEnv client exited"
        return dict(json.loads(line))

    def close(self) -> None:
        if self.process.stdin:
            self.process.stdin.close()
        self.process.wait(timeout=30)


def oracle_plan(task_id: str) -> str:
    family_level, seed, index = task_id.split("/")
    family, level = family_level.split("-L")
    task = generate_task(family, int(level), int(index), int(seed))
    assert task.goal is not None
    plan = solve(WorldState.from_graph(SceneGraph.model_validate(task.load["graph"])),
                 task.goal).plan
    return "\n".join([*(a.text() for a in plan), "done"])


def test_openenv_010_client_plays_an_episode_through_the_010_server(openenv_url: str
                                                                     ) -> None:
    health = httpx.get(f"{openenv_url}/health", timeout=5).json()
    assert health.get("status") == "healthy"
    schema = httpx.get(f"{openenv_url}/schema", timeout=5).json()
    assert "actions" in json.dumps(schema["action"])
    drive = Driver(openenv_url)
    try:
        first = drive({"reset": {"seed": 3}})
        observation = first["observation"]
        assert observation["task_id"].startswith("blocks-L1/") and "## Goal" in \
            observation["prompt"]
        assert first["done"] is False
        refused = drive({"step": "move(no_such_block, on, table)"})
        assert refused["observation"]["verdict"] == "violation" and refused["reward"] == 0.0
        assert refused["observation"]["violation"]["constraint"]
        # k=3 actions per step (the environment's default): the plan in chunks
        lines = oracle_plan(observation["task_id"]).splitlines()
        result: dict[str, Any] = {}
        while lines:
            chunk, lines = lines[:3], lines[3:]
            if lines == ["done"]:
                chunk, lines = [*chunk, "done"], []
            result = drive({"step": "\n".join(chunk)})
            if result["done"]:
                break
        assert result["done"] is True and result["reward"] == 1.0
        assert result["observation"]["success"] is True
        harder = drive({"reset": {"seed": 3, "level": 4}})
        assert harder["observation"]["task_id"].startswith("blocks-L4/")
        bad = drive({"reset": {"seed": 3, "level": 99}})
        assert "levels 1 to" in bad["error"]
    finally:
        drive.close()


def test_the_openenv_environment_cannot_import_verigraph() -> None:
    """The separate environment is needed: its mcp is below 2, VeriGraph's 2.3 or newer."""
    out = subprocess.run(
        [str(openenv_python()), "-c", "import importlib.metadata as m, importlib.util as u; "
         "print(m.version('openenv'), m.version('mcp'), u.find_spec('verigraph') is None)"],
        capture_output=True, text=True, timeout=60, check=True, env=child_env(),
        cwd=OUTSIDE).stdout.split()
    assert out[0] == "0.10.0" and int(out[1].split(".")[0]) < 2 and out[2] == "True"
    assert sys.version_info >= (3, 10)


def test_the_openenv_children_reach_loopback_only() -> None:
    """The server, the client and `openenv validate` above run with child_env(): a
    request to PyPI from this environment is refused, and they pass all the same."""
    assert_reaches_loopback_only(openenv_python())


def test_openenv_validate_passes_the_package_and_the_running_server(openenv_url: str
                                                                    ) -> None:
    """OpenEnv's own quality bar: the manifest (static) and the served API (runtime)."""
    cli = str(openenv_python().parent / "openenv")
    for target in (["integrations/openenv", "--level", "static", "--skip-build"],
                   ["--url", openenv_url, "--level", "runtime"]):
        out = subprocess.run([cli, "validate", *target], capture_output=True, text=True,
                             timeout=300, env=child_env(), cwd=ROOT)
        assert "Verdict: PASS" in out.stdout, (out.stdout + out.stderr)[-3000:]
