"""The verifiers taskset (integrations/verifiers, in the separate environment that
scripts/install_verifiers.sh builds): verifiers' own loader finds it by taskset id and
its tasks are episodes of a real VeriGraph environment server on loopback.

Slow: the environment's install (verifiers and its dependencies) takes over two minutes.
"""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

from optional import require

require("openenv", "pip install 'verigraph-mcp[env]'")

from openenv_helpers import serving_app  # noqa: E402
from venv_helpers import OUTSIDE, child_env, venv_python  # noqa: E402

from verigraph.env.openenv_server import create_openenv_app  # noqa: E402

pytestmark = pytest.mark.slow

LOAD = """
import json, sys
import verifiers.v1 as vf
from verigraph_verifiers import VeriGraphEnv, load_environment
url = sys.argv[1]
config = vf.resolve_env_config({"taskset": {"id": "verigraph-verifiers", "base_url": url,
                                            "level": 3, "size": 3}})
env = vf.load_environment(config)           # verifiers' own loader, by taskset id
tasks = list(env.taskset)
again = list(load_environment(base_url=url, level=3, size=3).taskset)
print(json.dumps({"env": type(env).__name__, "ours": isinstance(env, VeriGraphEnv),
                  "bounded": env.taskset.bounded,
                  "names": [t.data.name for t in tasks],
                  "again": [t.data.name for t in again],
                  "prompts": [t.data.prompt for t in tasks],
                  "resets": [t.data.reset for t in tasks],
                  "mcp": __import__("importlib.metadata").metadata.version("mcp")}))
"""


def verifiers_python() -> Path:
    return venv_python("verifiers", "VERIGRAPH_VERIFIERS_PYTHON")


def test_verifiers_loads_the_taskset_and_its_tasks_are_verigraph_episodes() -> None:
    python = verifiers_python()
    with serving_app(create_openenv_app(family="kitchen", level=1)) as url:
        out = subprocess.run([str(python), "-c", LOAD, url], capture_output=True, text=True,
                             timeout=180, env=child_env(), cwd=OUTSIDE)
    assert out.returncode == 0, out.stderr[-3000:]
    loaded = json.loads(out.stdout.strip().splitlines()[-1])
    assert loaded["env"] == "VeriGraphEnv" and loaded["ours"] and loaded["bounded"]
    assert len(loaded["names"]) == 3 and all(n.startswith("kitchen-L3/") for n in
                                             loaded["names"])
    assert loaded["names"] == loaded["again"]  # seeded: the same episodes every load
    assert all("## Goal" in p for p in loaded["prompts"])
    assert loaded["resets"] == [{"seed": s, "level": 3} for s in range(3)]
    assert loaded["mcp"] == "2.0.0"  # verifiers' pin: why it has its own environment
