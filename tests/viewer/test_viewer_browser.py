"""The viewer in real headless Chromium: as an MCP App in a minimal host page fed by a
running `verigraph serve --transport http`, as the `verigraph view` page, and as the
`verigraph validate --html` file opened from disk. Screenshots go to
$VERIGRAPH_SCREENSHOTS (default out/screenshots)."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from pathlib import Path
from typing import Any

import cv2
import httpx2
import numpy as np
import pytest
from browser_helpers import RequestLog, browser_page, require_browser, screenshot_path
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp_helpers import (
    APP_MIME,
    REPO,
    apps_extension,
    free_port,
    http_server,
    structured,
    verigraph_command,
)

from verigraph.server.apps import EPISODE_UI
from verigraph.tools.drawing import OUTLINE_COLOR

TOKEN = "viewer-test-token"
HOST_PAGE = REPO / "tests" / "viewer_host" / "host.html"


@pytest.fixture(autouse=True)
def _browser() -> None:
    require_browser()


def wire(result: Any) -> dict[str, Any]:
    dumped: dict[str, Any] = result.model_dump(mode="json", by_alias=True, exclude_none=True)
    return dumped


@asynccontextmanager
async def app_client() -> AsyncIterator[Client]:
    """A client that advertises MCP Apps, on a running `verigraph serve --transport http`."""
    ui = apps_extension()
    with http_server(token=TOKEN) as server:
        async with httpx2.AsyncClient(headers={"Authorization": f"Bearer {TOKEN}"},
                                      timeout=60) as http, \
                Client(streamable_http_client(server.url, http_client=http),
                       extensions=[ui]) as client:
            yield client


@asynccontextmanager
async def app_in_host(client: Client, html: str, tool: str, arguments: dict[str, Any],
                      result: Any, csp: Any = None, proxied: list[str] | None = None
                      ) -> AsyncIterator[tuple[Any, Any, RequestLog]]:
    """(page, the view's frame, request log) of the host page showing the view of one tool
    result. The host forwards the view's tool calls to the real server through `client`,
    noting each name in `proxied` when given."""

    async def host_call_tool(name: str, args: dict[str, Any]) -> dict[str, Any]:
        if proxied is not None:
            proxied.append(name)
        return wire(await client.call_tool(name, args))

    async with browser_page() as (page, log):
        await page.expose_function("hostCallTool", host_call_tool)  # type: ignore[attr-defined]
        await page.goto(HOST_PAGE.as_uri())  # type: ignore[attr-defined]
        await page.evaluate(  # type: ignore[attr-defined]
            "([html, csp, tool, args, result]) => window.showApp(html, csp, tool, args, "
            "result)", [html, {} if csp is None else csp, tool, arguments, wire(result)])
        yield page, page.frame_locator("#view"), log  # type: ignore[attr-defined]


@pytest.mark.anyio
async def test_mcp_app_in_a_host_page_shows_a_real_execute_actions_result() -> None:
    async with app_client() as client:
        tools = {t.name: t for t in (await client.list_tools()).tools}
        assert (tools["execute_actions"].meta or {})["ui"]["resourceUri"] == EPISODE_UI
        resource = (await client.read_resource(EPISODE_UI)).contents[0]
        assert resource.mime_type == APP_MIME and resource.meta is not None
        csp = resource.meta["ui"]["csp"]
        eid = structured(await client.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
            "episode_id"]
        for actions in (["move(cup, on, desk)"], ["move(cup, on, book)"]):
            await client.call_tool("execute_actions", {"episode_id": eid, "actions": actions})
        arguments = {"episode_id": eid, "actions": ["move(book, on, shelf)"]}
        result = await client.call_tool("execute_actions", arguments)
        assert structured(result)["violation"]["constraint"] == "object_not_clear"
        proxied: list[str] = []  # the host forwards the view's calls to the real server
        async with app_in_host(client, getattr(resource, "text", ""), "execute_actions",
                               arguments, result, csp=csp, proxied=proxied) as (page, app, log):
            steps = app.locator("#steps li.step")
            await steps.nth(2).wait_for(timeout=30_000)
            assert await steps.count() == 3
            refused = app.locator("#steps li.step.refused")
            assert await refused.count() == 1
            assert await refused.locator(".constraint").inner_text() == "object_not_clear"
            assert "move cup somewhere else first" in await refused.locator(
                ".suggestion").inner_text()
            assert await refused.locator(".blocking").inner_text() == "blocking: cup"
            assert await app.locator("#graph svg g.node").count() == 4
            assert await app.locator('#graph g[data-node="cup"] rect').get_attribute(
                "stroke") == "#c5221f"  # the blocking object is outlined
            await page.locator("#view").screenshot(  # type: ignore[attr-defined]
                path=str(screenshot_path("viewer_mcp_app.png")))
            render = app.locator("#render")
            refused_src = await render.get_attribute("src")
            await app.locator("#slider").fill("1")
            assert await render.get_attribute("src") != refused_src
            assert (await app.locator("#caption").inner_text()).startswith(
                "after step 1: move(cup, on, desk)")
            assert await app.locator(
                "#graph line.edge-added").count() == 1  # cup on desk, highlighted
            policy = await page.locator("#view").get_attribute(  # type: ignore[attr-defined]
                "data-csp")
            assert "connect-src 'none'" in policy and "default-src 'none'" in policy
            frame = page.frames[1]  # type: ignore[attr-defined]
            blocked = await frame.evaluate(
                f"fetch('http://127.0.0.1:{free_port()}/').then(() => 'sent', "
                "e => 'refused: ' + e.message)")
            assert blocked.startswith("refused")
            assert proxied == ["view_episode"]
            assert log.off_loopback() == [] and log.blocked == []
            assert not [u for u in log.urls if u.startswith("http")]


@pytest.mark.anyio
async def test_view_page_checks_a_pasted_plan() -> None:
    port = free_port()
    proc = subprocess.Popen([*verigraph_command(), "view", "--port", str(port), "--token",
                             TOKEN], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()  # printed once the server listens
        url = line.split(": ", 1)[1].strip()
        assert url == f"http://127.0.0.1:{port}/#token={TOKEN}"
        async with browser_page() as (page, log):
            response = await page.goto(url)  # type: ignore[attr-defined]
            assert "connect-src 'self'" in response.headers["content-security-policy"]
            await page.evaluate(  # type: ignore[attr-defined]
                """() => {  // drop a file onto the scene box, as a person would
                  const data = new DataTransfer();
                  data.items.add(new File(["three_blocks"], "scene.yaml"));
                  document.getElementById("field-scene").dispatchEvent(
                    new DragEvent("drop", {dataTransfer: data, bubbles: true}));
                }""")
            scene_box = page.locator("#field-scene")  # type: ignore[attr-defined]
            await page.wait_for_function(  # type: ignore[attr-defined]
                "document.getElementById('field-scene').value === 'three_blocks'")
            assert await scene_box.input_value() == "three_blocks"
            await page.fill("#field-scene", "cup_on_book")  # type: ignore[attr-defined]
            await page.fill("#field-plan",  # type: ignore[attr-defined]
                            "move(cup, on, desk)\nmove(book, on, cup)\nmove(book, on, shelf)")
            await page.click("#check")  # type: ignore[attr-defined]
            steps = page.locator("#steps li.step")  # type: ignore[attr-defined]
            await steps.nth(1).wait_for(timeout=30_000)
            assert await steps.count() == 2
            refused = page.locator("#steps li.step.refused")  # type: ignore[attr-defined]
            assert await refused.locator(".constraint").inner_text() == "target_not_surface"
            assert "1 later action(s) not checked" in await page.locator(  # type: ignore[attr-defined]
                "#steps").inner_text()
            await page.screenshot(path=str(screenshot_path(  # type: ignore[attr-defined]
                "viewer_page.png")), full_page=True)
            await page.fill("#field-scene", "{nodes: [")  # type: ignore[attr-defined]
            await page.click("#check")  # type: ignore[attr-defined]
            error = page.locator("#error")  # type: ignore[attr-defined]
            await error.filter(has_text="invalid YAML").wait_for(timeout=30_000)
            assert log.off_loopback() == []
    finally:
        proc.terminate()
        proc.wait(timeout=10)


@pytest.mark.anyio
async def test_html_report_file_opens_from_disk_without_network(tmp_path: Path) -> None:
    from verigraph.graph.builtin_scenes import cup_on_book
    from verigraph.graph.io import save_graph

    save_graph(cup_on_book(), tmp_path / "scene.json")
    (tmp_path / "plan.txt").write_text("move(cup, on, desk)\nmove(desk, on, shelf)\n")
    report = tmp_path / "report.html"
    done = subprocess.run([*verigraph_command(), "validate", "--scene",
                           str(tmp_path / "scene.json"), "--plan", str(tmp_path / "plan.txt"),
                           "--html", str(report)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 1, done.stderr  # the plan is invalid
    async with browser_page() as (page, log):
        await page.goto(report.as_uri())  # type: ignore[attr-defined]
        steps = page.locator("#steps li.step")  # type: ignore[attr-defined]
        await steps.nth(1).wait_for(timeout=30_000)
        assert await steps.count() == 2
        assert await page.locator(  # type: ignore[attr-defined]
            "#steps li.refused .constraint").inner_text() == "not_movable"
        assert (await page.locator("#verdict").inner_text()).startswith(  # type: ignore[attr-defined]
            "INVALID")
        render = page.locator("#render")  # type: ignore[attr-defined]
        before = await render.get_attribute("src")
        assert before.startswith("data:image/png;base64,")
        await page.locator("#slider").fill("0")  # type: ignore[attr-defined]
        assert await render.get_attribute("src") != before
        await page.locator("#slider").fill("2")  # type: ignore[attr-defined]
        await page.screenshot(path=str(screenshot_path(  # type: ignore[attr-defined]
            "viewer_report.png")), full_page=True)
        fetched = await page.evaluate(  # type: ignore[attr-defined]
            f"fetch('http://127.0.0.1:{free_port()}/').then(() => 'sent', e => 'refused')")
        assert fetched == "refused"
        assert [u for u in log.urls if not u.startswith(("file:", "data:"))] == []
    assert sys.executable  # the CLI ran in this interpreter's environment


@pytest.mark.anyio
async def test_mcp_app_follows_validate_plan_and_render_scene_results() -> None:
    async with app_client() as client:
        html = getattr((await client.read_resource(EPISODE_UI)).contents[0], "text", "")
        eid = structured(await client.call_tool("load_scene", {
            "scene_id": "cup_on_book", "simulate": True}))["episode_id"]
        await client.call_tool("execute_actions", {"episode_id": eid,
                                                   "actions": ["move(book, on, shelf)"]})
        plan_args = {"scene_id": "cup_on_book",
                     "plan": "move(cup, on, desk)\nmove(book, on, shelf)"}
        cases = [
            ("validate_plan", plan_args, await client.call_tool("validate_plan", plan_args),
             "VeriGraph plan check", 2, 0),
            ("render_scene", {"episode_id": eid},
             await client.call_tool("render_scene", {"episode_id": eid}),
             "VeriGraph episode (scene_id:cup_on_book)", 1, 1),
        ]
        for tool, args, result, title, count, refused in cases:
            async with app_in_host(client, html, tool, args, result) as (_, app, log):
                await app.locator("h1").filter(has_text=title).wait_for(timeout=30_000)
                assert await app.locator("#steps li.step").count() == count
                assert await app.locator("#steps li.step.refused").count() == refused
                if tool == "render_scene":  # a simulated episode: its render is shown too
                    assert (await app.locator("#scene-render").get_attribute(
                        "src")).startswith("data:image/png;base64,")
                assert log.off_loopback() == []


def red_pixels(png: bytes) -> int:
    """Pixels close to the outline red in a screenshot (scaled, so not exact)."""
    image = cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_COLOR)
    assert image is not None
    red = np.array(OUTLINE_COLOR, dtype=np.int16)
    count = int((np.abs(image.astype(np.int16) - red).max(axis=2) < 40).sum())
    return count


@pytest.mark.anyio
async def test_mcp_app_slider_steps_through_the_simulator_pictures() -> None:
    async with app_client() as client:
        html = getattr((await client.read_resource(EPISODE_UI)).contents[0], "text", "")
        eid = structured(await client.call_tool("load_scene", {
            "scene_id": "cup_on_book", "simulate": True}))["episode_id"]
        for move in ("move(cup, on, desk)", "move(book, on, shelf)", "move(cup, on, book)"):
            await client.call_tool("execute_actions", {"episode_id": eid,
                                                       "actions": [move]})
        arguments = {"episode_id": eid, "actions": ["move(book, on, desk)"]}
        result = await client.call_tool("execute_actions", arguments)
        assert structured(result)["violation"]["blocking"] == ["cup"]
        async with app_in_host(client, html, "execute_actions", arguments, result) as (
                page, app, log):
            await app.locator("#steps li.step").nth(3).wait_for(timeout=30_000)
            sim = app.locator("#scene-render")
            await page.locator("#view").screenshot(  # type: ignore[attr-defined]
                path=str(screenshot_path("viewer_mcp_app_sim.png")))
            sources, shots = [], []
            for index in range(5):  # as loaded, three moves, the refused step
                await app.locator("#slider").fill(str(index))
                sources.append(await sim.get_attribute("src"))
                shots.append(await sim.screenshot())
                assert await sim.get_attribute("alt") == (
                    f"simulator picture after step {index}" if index
                    else "simulator picture as loaded")
            assert all(s.startswith("data:image/png;base64,") for s in sources)
            assert len(set(sources)) == 5 and len(set(shots)) == 5
            # Only the refused step frames the object in the way (the cup) in red.
            assert [red_pixels(s) > 300 for s in shots] == [False] * 4 + [True]
            assert log.off_loopback() == []
