"""The wire form of tools/list, kept under tests/snapshots so a schema change is a diff.

Regenerate after an intended change with:
    VERIGRAPH_UPDATE_SNAPSHOTS=1 pytest tests/server/test_server_snapshot.py
"""

from __future__ import annotations

import difflib
import json
import os
from pathlib import Path

import pytest
from mcp import Client

from verigraph.server import build_server

pytestmark = pytest.mark.fast

SNAPSHOT = Path(__file__).parents[1] / "snapshots" / "tools_list.json"
UPDATE_ENV = "VERIGRAPH_UPDATE_SNAPSHOTS"


async def wire_tools_list() -> str:
    async with Client(build_server()) as client:
        tools = (await client.list_tools()).tools
    wire = [t.model_dump(mode="json", by_alias=True, exclude_none=True) for t in tools]
    return json.dumps({"tools": wire}, indent=2, sort_keys=True) + "\n"


@pytest.mark.anyio
async def test_tools_list_matches_the_snapshot() -> None:
    current = await wire_tools_list()
    if os.environ.get(UPDATE_ENV) == "1" or not SNAPSHOT.exists():
        SNAPSHOT.parent.mkdir(exist_ok=True)
        SNAPSHOT.write_text(current)
        if os.environ.get(UPDATE_ENV) != "1":
            pytest.fail(f"wrote a new snapshot to {SNAPSHOT}; review and commit it")
        return
    expected = SNAPSHOT.read_text()
    if current != expected:
        diff = "".join(difflib.unified_diff(expected.splitlines(True), current.splitlines(True),
                                            "snapshot", "server", n=2))
        pytest.fail(f"tools/list changed; if intended, rerun with {UPDATE_ENV}=1 and commit "
                    f"{SNAPSHOT.name}:\n{diff[:6000]}")
