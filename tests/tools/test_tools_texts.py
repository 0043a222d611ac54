"""The text content alone is enough: objects with label and role, every edge, refusals."""

from __future__ import annotations

import pytest
from mcp import Client
from mcp_helpers import structured, text

from verigraph.reporting import report_text
from verigraph.server import build_server
from verigraph.tools import Toolbox
from verigraph.tools.acting import SHOWN_FIRST_STEPS, SHOWN_MAX_FAILURES, report_summary

pytestmark = pytest.mark.fast


def nine_object_kitchen() -> dict[str, object]:
    nodes = [("table", "table"), ("shelf", "shelf"), ("tray", "tray"), ("plate_1", "plate"),
             ("plate_2", "plate"), ("cup_1", "cup"), ("cup_2", "mug"), ("bowl", "bowl"),
             ("spoon", "spoon")]
    edges = [("tray", "table"), ("plate_1", "tray"), ("plate_2", "table"), ("cup_1", "shelf"),
             ("cup_2", "plate_2"), ("bowl", "shelf"), ("spoon", "bowl")]
    return {"nodes": [{"id": i, "label": label} for i, label in nodes],
            "edges": [{"source": s, "relation": "in" if t == "bowl" else "on", "target": t}
                      for s, t in edges]}


@pytest.mark.anyio
async def test_load_scene_text_names_every_object_role_and_edge() -> None:
    graph = nine_object_kitchen()
    async with Client(build_server()) as client:
        result = await client.call_tool("load_scene", {"graph": graph})
        said = text(result)
        for node in graph["nodes"]:  # type: ignore[attr-defined]
            assert f"{node['id']} ({node['label']}:" in said
        assert "table (table: fixed surface" in said and "shelf (shelf: fixed surface" in said
        assert "cup_2 (mug: movable" in said and "capacity" in said
        for edge in graph["edges"]:  # type: ignore[attr-defined]
            assert f"{edge['source']} {edge['relation']} {edge['target']}" in said
        structured_keys = set(result.structured_content or {})
        assert {"graph", "goal", "episode_id"} <= structured_keys


@pytest.mark.anyio
async def test_refusals_and_progress_read_in_text() -> None:
    async with Client(build_server()) as client:
        loaded = await client.call_tool("load_scene", {"scene_id": "cup_on_book"})
        eid = (loaded.structured_content or {})["episode_id"]
        assert "goal: book on shelf; cup on desk" in text(loaded)
        refused = text(await client.call_tool("execute_actions", {
            "episode_id": eid, "actions": ["move(book, on, shelf)"]}))
        assert "[object_not_clear]" in refused and "Suggestion: move cup" in refused
        assert "graph now: book on desk; cup on book" in refused
        state = text(await client.call_tool("get_state", {"episode_id": eid}))
        assert "last refusal: step 1: [object_not_clear]" in state
        ended = text(await client.call_tool("end_episode", {"episode_id": eid}))
        assert "final graph: book on desk; cup on book" in ended


@pytest.mark.anyio
async def test_a_plan_report_text_is_rendered_from_its_structured_content() -> None:
    """validate_plan's text and structured content come from one dump of the report: the
    text is `report_text` over the very dict the client receives, and the tool's summary
    renders the dict it is handed rather than dumping the report again."""
    arguments = {"scene_id": "cup_on_book", "goal": "book on shelf", "all_errors": True,
                 "plan": "move(book, on, shelf)\nmove(cup, on, desk)\nmove(book, on, shelf)"}
    async with Client(build_server()) as client:
        result = await client.call_tool("validate_plan", arguments)
    data = structured(result)
    rendered = report_text(data, max_steps=SHOWN_FIRST_STEPS, max_failures=SHOWN_MAX_FAILURES)
    assert text(result).startswith(rendered + "\nbuilt-in properties applied (dictionary: "
                                   "tableware): book: movable surface")
    assert text(result).startswith("INVALID: 3 step(s) checked, 1 violation(s); goal reached")
    report = Toolbox().call("validate_plan", arguments)
    assert report_summary(report) == text(result)
    data["steps"][0]["text"] = "move(book, onto, shelf)"
    assert "  1 FAIL  move(book, onto, shelf): [object_not_clear]" in \
        report_summary(report, data)
