"""The scripted cup-on-book client, the client configs and server.json stay in sync."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from mcp_helpers import REPO

import verigraph


def test_cup_on_book_client_plays_the_example(tmp_path: Path) -> None:
    image = tmp_path / "scene.png"
    done = subprocess.run([sys.executable, str(REPO / "examples" / "cup_on_book_client.py"),
                           "--image", str(image)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    out = done.stdout
    assert out.index("[object_not_clear]") < out.index("tau after a failed call: 1")
    assert "new graph: book on shelf; cup on desk" in out
    assert "SUCCESS: goal reached" in out
    assert image.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("name", ["claude_desktop_config.json", "claude_code.mcp.json",
                                  "vscode.mcp.json", "cursor.mcp.json"])
def test_client_configs_start_verigraph_serve(name: str) -> None:
    config = json.loads((REPO / "examples" / "clients" / name).read_text())
    servers = config.get("mcpServers") or config["servers"]
    stdio = servers["verigraph"]
    assert stdio["command"] == "uvx" and stdio["args"][-2:] == ["verigraph", "serve"]
    if "verigraph-http" in servers:
        assert servers["verigraph-http"]["url"] == "http://127.0.0.1:8000/mcp"
        assert servers["verigraph-http"]["headers"]["Authorization"].startswith("Bearer ")


def test_registry_server_json_matches_the_package() -> None:
    data = json.loads((REPO / "server.json").read_text())
    assert data["version"] == verigraph.__version__ and len(data["description"]) <= 100
    (package,) = data["packages"]
    assert package["identifier"] == "verigraph-mcp" and package["version"] == verigraph.__version__
    assert package["transport"] == {"type": "stdio"}
    assert package["packageArguments"] == [{"type": "positional", "value": "serve"}]
