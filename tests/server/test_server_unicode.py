"""Non-ASCII ids in submit_scene_graph: folded when possible, else a structured problem;
the reply always satisfies the tool's own output schema."""

from __future__ import annotations

import pytest
from mcp import Client
from mcp_helpers import structured

from verigraph.server import build_server
from verigraph.tools import Toolbox

pytestmark = [pytest.mark.fast, pytest.mark.anyio]


def submission(*ids: str) -> dict:
    nodes = [{"id": "table", "label": "table"}] + [{"id": i, "label": "cup"} for i in ids]
    edges = [{"source": i, "relation": "on", "target": "table"} for i in ids]
    return {"graph": {"nodes": nodes, "edges": edges, "dictionary": "tableware"}}


async def test_accented_ids_are_folded_to_ascii() -> None:
    async with Client(build_server(Toolbox())) as client:
        reply = structured(await client.call_tool("submit_scene_graph",
                                                  submission("tasse_é", "Café Cup")))
    assert reply["accepted"] is True
    assert sorted(n["id"] for n in reply["graph"]["nodes"]) == ["cafe_cup", "table", "tasse_e"]
    assert {"field": "nodes[1].id", "before": "tasse_é", "after": "tasse_e",
            "reading": None} in reply["normalised"]


@pytest.mark.parametrize("bad_id", ["杯子", "🍵", "\u0301"])
async def test_ids_without_ascii_letters_are_a_structured_problem(bad_id: str) -> None:
    async with Client(build_server(Toolbox())) as client:
        result = await client.call_tool("submit_scene_graph", submission(bad_id))
    reply = structured(result)  # not a tool error: the output schema holds
    assert reply["accepted"] is False
    problem = next(p for p in reply["problems"] if p["rule"] == "invalid_id")
    assert problem["field"] == "nodes[1].id" and problem["node"] == bad_id
    assert "invalid_id_1" in [n["id"] for n in reply["graph"]["nodes"]]
    assert reply["graph"]["edges"][0]["source"] == "invalid_id_1"
