"""The verifiers taskset (integrations/verifiers, in the separate environment that
scripts/install_integration.sh verifiers builds): verifiers' own loader finds it by taskset id, its
tasks are episodes of a real VeriGraph environment server on loopback, and verifiers'
own evaluation (`vf-eval`, its chat harness in a subprocess runtime, its model proxy)
plays them multi-turn against a model endpoint, the verifier's feedback coming back as
the user's turns and the reward being VeriGraph's.

In the default run (not `slow`): scripts/test.sh builds the environment with uv, a few
seconds, and downloads the chat harness program's wheels. The children run offline
(tests/venv_helpers.py: proxies that refuse, uv's only index those wheels) with a home
of their own, so `vf-eval` prepares its harness program afresh from the wheels alone.
"""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

from optional import require

require("openenv", "pip install 'verigraph-mcp[env]'")

from env_doubles import ScriptedPlannerEndpointForTests  # noqa: E402
from openenv_helpers import serving_app  # noqa: E402
from venv_helpers import (  # noqa: E402
    OUTSIDE,
    assert_reaches_loopback_only,
    child_env,
    harness_wheels,
    venv_python,
)

from verigraph.env.openenv_server import create_openenv_app  # noqa: E402
from verigraph.env.procedural import ProceduralEnv  # noqa: E402
from verigraph.env.rollout import REFUSED_ACTION, make_policy  # noqa: E402

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


def test_the_children_cannot_reach_an_index_but_have_the_harness_wheels() -> None:
    """What makes the `vf-eval` run below an offline one: a request to PyPI from the
    verifiers environment fails at once, and uv resolves the harness program there from
    .tools/verifiers-wheels alone."""
    python, wheels = verifiers_python(), harness_wheels()
    assert_reaches_loopback_only(python)
    resolved = subprocess.run(
        [str(python.parent / "uv"), "pip", "compile", "--no-cache", "--quiet", "--python",
         str(python), str(wheels / "chat_program.py")],
        capture_output=True, text=True, timeout=120, env=child_env(), cwd=OUTSIDE)
    assert resolved.returncode == 0, resolved.stderr[-2000:]
    assert "mcp==2.0.0" in resolved.stdout and "openai==" in resolved.stdout


def refuse_then_oracle(level: int, seeds: range) -> dict[str, str]:
    """observation -> answer: a refused action first, then the oracle's steps (the
    server's episodes are these: the same generator, level and seeds)."""
    env, oracle, script = ProceduralEnv("blocks", level=level), make_policy("oracle"), {}
    for seed in seeds:
        observation, info = env.reset(seed=seed)
        answer = REFUSED_ACTION
        while True:
            script[observation] = answer
            observation, _, terminated, truncated, info = env.step(answer)
            if terminated or truncated:
                break
            answer = oracle(env, observation, info)
    return script


def test_vf_eval_plays_multi_turn_episodes_with_the_verifiers_feedback(tmp_path: Path
                                                                       ) -> None:
    python, wheels = verifiers_python(), harness_wheels()
    home = tmp_path / "home"  # empty caches: the harness program is prepared in this run
    env = child_env(PATH=f"{python.parent}:{child_env()['PATH']}", HOME=str(home),
                    UV_CACHE_DIR=str(home / ".cache" / "uv"), UV_PYTHON=str(python))
    assert env["UV_DEFAULT_INDEX"] == wheels.as_uri() and "127.0.0.1" in env["HTTPS_PROXY"]
    endpoint = ScriptedPlannerEndpointForTests(refuse_then_oracle(2, range(2)))
    with endpoint, serving_app(create_openenv_app(family="blocks", level=1)) as url:
        out = subprocess.run(
            [str(python.parent / "vf-eval"), "verigraph-verifiers",
             "--env.taskset.base-url", url, "--env.taskset.level", "2",
             "--env.taskset.size", "2", "--env.player.runtime.type", "subprocess",
             "--env.player.harness.id", "null", "-m", "scripted",
             "--client.base-url", endpoint.base_url, "--no-push", "--no-rich",
             "-o", str(tmp_path / "out")],
            capture_output=True, text=True, timeout=600, cwd=OUTSIDE, env=env)
    assert out.returncode == 0, (out.stdout + out.stderr)[-3000:]
    # the harness program was prepared here, offline: its script and uv environment
    assert list((home / ".cache" / "verifiers" / "runtimes" / "scripts").glob("*.py"))
    assert list((home / ".cache" / "uv" / "environments-v2").iterdir())
    [traces] = list((tmp_path / "out").glob("*/traces.jsonl"))
    episodes = [json.loads(line) for line in traces.read_text().splitlines()]
    assert len(episodes) == 2
    for episode in episodes:
        assert episode["ok"] and episode["task"]["data"]["name"].startswith("blocks-L2/")
        [trace] = episode["traces"] if isinstance(episode["traces"], list) \
            else list(episode["traces"].values())
        assert trace["rewards"]["verigraph_reward"]["score"] == 1.0
        assert trace["info"]["verigraph_success"] is True
        messages = [node["message"] for node in trace["nodes"]]
        roles = [m["role"] for m in messages]
        assert roles[:5] == ["system", "user", "assistant", "user", "assistant"]
        assert messages[2]["content"] == REFUSED_ACTION
        assert "unknown_object" in messages[3]["content"]  # the verifier's feedback turn
