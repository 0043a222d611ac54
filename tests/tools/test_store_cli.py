"""`verigraph episodes list|show|purge` on a SQLite store a tool host wrote."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

from mcp_helpers import verigraph_command

from verigraph.tools import Toolbox, ToolConfig


def episodes(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*verigraph_command(), "episodes", *args], capture_output=True,
                          text=True, timeout=60)


def test_list_show_and_purge(tmp_path: Path) -> None:
    url = f"sqlite:///{tmp_path / 'episodes.db'}"
    box = Toolbox(config=ToolConfig(store=url))
    kept = box.call("load_scene", {"scene_id": "cup_on_book"}).episode_id
    box.call("execute_actions", {"episode_id": kept, "actions": ["move(cup, desk)"]})
    other = box.call("load_scene", {"scene_id": "three_blocks"}).episode_id

    listed = json.loads(episodes("list", "--store", url, "--json").stdout)
    assert {e["id"]: e["version"] for e in listed} == {kept: 2, other: 1}
    assert {e["owner"] for e in listed} == {"local"}  # in-process calls: the local caller
    assert "caller local" in episodes("list", "--store", url).stdout
    shown = episodes("show", kept, "--store", url)
    assert shown.returncode == 0
    assert "executed: move(cup, on, desk)" in shown.stdout and "cup on desk" in shown.stdout
    record = json.loads(episodes("show", kept, "--store", url, "--json").stdout)
    assert record["schema_version"] == 1 and record["tau"] == 0

    assert "purged 1 episode(s)" in episodes("purge", other, "--store", url).stdout
    assert "purged 0 episode(s)" in episodes("purge", "--store", url).stdout  # none idle
    missing = episodes("show", other, "--store", url)
    assert missing.returncode == 2 and "verigraph episodes list" in missing.stderr
    assert "purged 1 episode(s)" in episodes("purge", "--all", "--store", url).stdout
    assert "0 episode(s)" in episodes("list", "--store", url).stdout


def test_a_memory_store_cannot_be_inspected() -> None:
    done = episodes("list", "--store", "memory://")
    assert done.returncode == 2 and "--store" in done.stderr
