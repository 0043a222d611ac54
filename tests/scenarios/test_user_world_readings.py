"""Label normalisations are never silent: validate_plan and set_goal report how the
graphs the client wrote were read, as load_scene does; the CLI takes the scene's
dictionary with --dictionary NAME|FILE.json; solve's text names the executor."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
from mcp import Client
from mcp_helpers import structured, text, verigraph_command

from verigraph.server import build_server
from verigraph.tools import Toolbox

pytestmark = pytest.mark.anyio
CUBE = "cube read as block (synonym, blocks dictionary)"
GRAPH = {"nodes": [{"id": "t", "label": "table"}, {"id": "a", "label": "cube"},
                   {"id": "b", "label": "block"}],
         "edges": [{"source": "a", "relation": "on", "target": "t"},
                   {"source": "b", "relation": "on", "target": "t"}]}


async def test_validate_plan_reports_the_readings_in_text_and_structure() -> None:
    async with Client(build_server(Toolbox())) as c:
        out = await c.call_tool("validate_plan", {"graph": GRAPH, "plan": "move(a, on, b)"})
        assert structured(out)["label_readings"] == [CUBE]
        assert f"labels read: {CUBE}" in text(out)
        plain = await c.call_tool("validate_plan", {"scene_id": "three_blocks", "plan": "done"})
        assert structured(plain)["label_readings"] == [] and "labels read" not in text(plain)


async def test_set_goal_reports_the_readings_of_its_goal_graph() -> None:
    async with Client(build_server(Toolbox())) as c:
        eid = structured(await c.call_tool("load_scene", {"graph": GRAPH}))["episode_id"]
        goal = {"nodes": [{"id": "a", "label": "Block"}, {"id": "b", "label": "block"}],
                "edges": [{"source": "a", "relation": "on", "target": "b"}]}
        out = await c.call_tool("set_goal", {"episode_id": eid, "graph": goal,
                                             "partial": True})
        reading = "Block read as block (case and spacing, blocks dictionary)"
        assert structured(out)["label_readings"] == [reading]
        assert f"labels read: {reading}" in text(out)


async def test_solve_names_the_executor_of_an_episode() -> None:
    async with Client(build_server(Toolbox())) as c:
        stateless = await c.call_tool("solve", {"scene_id": "cup_on_book"})
        assert text(stateless).endswith("\nplanned only, nothing was executed")
        eid = structured(await c.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
            "episode_id"]
        out = await c.call_tool("solve", {"episode_id": eid})
        assert structured(out)["runs_on"] == "graph (verified only, nothing physical moved)"
        assert "; episode executor: graph (verified only, nothing physical moved)\nto run " \
               "it: execute_actions" in text(out)


def run_cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*verigraph_command(), *args], capture_output=True, text=True,
                          timeout=120)


def test_the_cli_takes_the_scene_s_dictionary_as_a_name_or_a_file(tmp_path: Path) -> None:
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps({
        "nodes": [{"id": "desk", "label": "desk"}, {"id": "laptop", "label": "laptop"},
                  {"id": "mug", "label": "mug"}],
        "edges": [{"source": "laptop", "relation": "on", "target": "desk"},
                  {"source": "mug", "relation": "on", "target": "desk"}]}))
    plan = tmp_path / "plan.txt"
    plan.write_text("move(mug, on, laptop)\n")
    office = tmp_path / "office.json"
    office.write_text(json.dumps({"extends": "tableware", "objects": {
        "desk": {"surface": True, "movable": False},
        "laptop": {"surface": True, "capacity": 1}}}))
    without = run_cli("validate", "--scene", str(scene), "--plan", str(plan))
    assert without.returncode == 2 and "'laptop'" in without.stderr
    valid = run_cli("validate", "--scene", str(scene), "--plan", str(plan),
                    "--dictionary", str(office))
    assert valid.returncode == 0, valid.stderr
    assert "VALID" in valid.stdout
    goal = tmp_path / "goal.json"
    goal.write_text(json.dumps({"graph": {"nodes": [{"id": "mug", "label": "mug"},
                                                    {"id": "laptop", "label": "laptop"}],
                                          "edges": [{"source": "mug", "relation": "on",
                                                     "target": "laptop"}]},
                                "partial": True}))
    solved = run_cli("solve", "--scene", str(scene), "--goal", str(goal), "--dictionary",
                     str(office), "--json")
    assert solved.returncode == 0, solved.stderr
    assert json.loads(solved.stdout)["plan"] == [
        {"action": "move", "object": "mug", "relation": "on", "target": "laptop"}]
    for bad, reason in (("kitchenn", "neither a built-in dictionary nor a file"),
                        ("/etc/hostname", "not a dictionary: not JSON")):
        refused = run_cli("validate", "--scene", str(scene), "--plan", str(plan),
                          "--dictionary", bad)
        assert refused.returncode == 2 and "--dictionary" in refused.stderr, refused.stderr
        assert reason in refused.stderr and "Traceback" not in refused.stderr


def test_the_cli_reports_every_label_it_read_as_another_name(tmp_path: Path) -> None:
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps(GRAPH))
    plan = tmp_path / "plan.txt"
    plan.write_text("move(a, on, b)\n")
    shown = run_cli("validate", "--scene", str(scene), "--plan", str(plan))
    assert shown.returncode == 0, shown.stderr
    assert shown.stdout.rstrip().endswith(f"labels read: {CUBE}")
    as_json = run_cli("validate", "--scene", str(scene), "--plan", str(plan), "--json")
    assert json.loads(as_json.stdout)["label_readings"] == [CUBE]
    plain = tmp_path / "plain.json"
    plain.write_text(json.dumps(GRAPH).replace('"cube"', '"block"'))
    batch = tmp_path / "batch.jsonl"
    batch.write_text(json.dumps({"scene": str(scene), "plan": str(plan)}) + "\n"
                     + json.dumps({"scene": str(plain), "plan": str(plan)}) + "\n")
    lines = run_cli("validate", "--batch", str(batch)).stdout.splitlines()
    assert [json.loads(line).get("label_readings") for line in lines] == [[CUBE], []]
