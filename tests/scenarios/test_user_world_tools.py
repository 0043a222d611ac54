"""Every other tool on a user's world: validate_plan, a photo with the user's dictionary
(the client's vision model answers, prompted with the user's labels), generate_scene_graph,
and the command line (validate --html, solve --anytime, export-pddl)."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
from mcp import Client
from mcp_helpers import png_b64, structured, text, verigraph_command
from user_worlds import GOAL, HOME_OFFICE, inline_scene, open_label_scene

from verigraph.server import build_server
from verigraph.tools import Toolbox

pytestmark = pytest.mark.anyio


async def test_validate_plan_on_an_inline_dictionary() -> None:
    async with Client(build_server(Toolbox())) as c:
        report = structured(await c.call_tool("validate_plan", {
            "graph": inline_scene(), "goal": GOAL,
            "plan": ["move(laptop, on, shelf)", "move(mug, on, desk)",
                     "move(laptop, on, shelf)"]}))
        assert report["valid"] is False
        assert report["steps"][0]["violation"]["constraint"] == "object_not_clear"
        fixed = await c.call_tool("validate_plan", {
            "graph": open_label_scene(), "goal": GOAL,
            "plan": ["move(mug, on, desk)", "move(laptop, on, shelf)"]})
        assert structured(fixed)["valid"] is True and structured(fixed)["goal_reached"] is True


async def test_a_photo_with_the_users_dictionary_waits_for_the_clients_graph() -> None:
    async with Client(build_server(Toolbox())) as c:
        loaded = structured(await c.call_tool("load_scene", {
            "image": png_b64(64, 48), "dictionary": HOME_OFFICE}))
        ep = loaded["episode_id"]
        assert loaded["awaiting_scene_graph"] and loaded["dictionary"] == "home_office"
        image = await c.call_tool("get_scene_image", {"episode_id": ep})
        prompt = text(image)
        assert "## Dictionary: home_office" in prompt
        assert "- laptop (your label): movable, surface, capacity 1" in prompt
        assert "- drawer_unit (your label): fixed, container, capacity 2" in prompt
        assert "- mug: movable, container, capacity 1" in prompt
        served = await c.get_prompt("scene_graph_generation", {"episode_id": ep})
        assert "- laptop (your label): movable, surface, capacity 1" in \
            served.messages[0].content.text  # type: ignore[union-attr]
        generated = await c.call_tool("generate_scene_graph", {"episode_id": ep})
        out = structured(generated)
        assert not out["accepted"]
        assert out["problems"][0]["rule"] == "user_labels_not_perceived"
        assert "cannot see your labels (laptop, pen_holder, drawer_unit)" in text(generated)
        assert "submit_scene_graph" in text(generated)
        assert "- pen_holder (your label)" in out["prompt"]
        graph = inline_scene()
        del graph["dictionary"]
        adopted = structured(await c.call_tool("submit_scene_graph", {
            "episode_id": ep, "graph": graph}))
        assert adopted["accepted"] and adopted["adopted"], adopted["problems"]
        readings = {r["reading"] for r in adopted["normalised"] if r["reading"]}
        assert "Pen Holder read as pen_holder (case and spacing, your label)" in readings
        state = structured(await c.call_tool("get_state", {"episode_id": ep}))
        assert state["dictionary"] == "home_office" and not state["awaiting_scene_graph"]
        check = structured(await c.call_tool("validate_action", {
            "episode_id": ep, "action": "move(mug, in, desk)"}))
        assert check["violation"]["constraint"] == "target_not_container"


def run_cli(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*verigraph_command(), *args], cwd=cwd, capture_output=True,
                          text=True, timeout=120, check=False)


def test_the_command_line_on_a_user_world(tmp_path: Path) -> None:
    (tmp_path / "scene.json").write_text(json.dumps(inline_scene()))
    (tmp_path / "open.json").write_text(json.dumps(open_label_scene()))
    (tmp_path / "goal.json").write_text(json.dumps(GOAL))
    (tmp_path / "plan.txt").write_text("move(mug, on, desk)\nmove(laptop, on, shelf)\ndone\n")
    (tmp_path / "bad.txt").write_text("move(laptop, on, shelf)\n")
    ok = run_cli("validate", "--scene", "scene.json", "--plan", "plan.txt", "--goal",
                 "goal.json", "--html", "report.html", cwd=tmp_path)
    assert ok.returncode == 0, ok.stderr
    assert "goal reached" in ok.stdout
    html = (tmp_path / "report.html").read_text()
    assert "laptop" in html and ("<img" in html or "data:image/png" in html)
    bad = run_cli("validate", "--scene", "open.json", "--plan", "bad.txt", "--json",
                  cwd=tmp_path)
    assert bad.returncode == 1
    assert "object_not_clear" in bad.stdout
    solved = run_cli("solve", "--scene", "open.json", "--goal", "goal.json", "--anytime",
                     cwd=tmp_path)
    assert solved.returncode == 0, solved.stderr
    assert "move(laptop, on, shelf)" in solved.stdout
    exported = run_cli("export-pddl", "--scene", "scene.json", "--goal", "goal.json",
                       "--domain-out", "d.pddl", "--problem-out", "p.pddl", cwd=tmp_path)
    assert exported.returncode == 0, exported.stderr
    problem = (tmp_path / "p.pddl").read_text()
    assert "(container drawers)" in problem and "(surface laptop)" in problem
    assert "(movable laptop)" in problem and "(movable drawers)" not in problem
    assert "(on laptop shelf)" in problem  # the goal


def test_the_viewer_replays_a_user_episode() -> None:
    from verigraph.viewer.views import ViewInput, view

    box = Toolbox()
    ep = box.call("load_scene", {"graph": inline_scene()})
    eid = ep.episode_id  # type: ignore[union-attr]
    box.call("execute_actions", {"episode_id": eid, "actions": ["move(mug, on, desk)"]})
    box.call("execute_actions", {"episode_id": eid, "actions": [
        "move(mug, in, drawers)", "move(book_2, in, drawers)", "move(pens, in, drawers)"]})
    result = view(box.context, ViewInput(episode_id=eid))
    assert [(s.text, s.ok) for s in result.steps] == [
        ("move(mug, on, desk)", True), ("move(mug, in, drawers)", True),
        ("move(book_2, in, drawers)", True), ("move(pens, in, drawers)", False)]
    refused = result.steps[3].violation
    assert refused is not None and refused.constraint == "target_full"
    plan = view(box.context, ViewInput(graph=inline_scene(),  # type: ignore[arg-type]
                                       plan="move(laptop, on, shelf)"))
    assert plan.steps[0].violation is not None
    assert plan.steps[0].violation.constraint == "object_not_clear"
