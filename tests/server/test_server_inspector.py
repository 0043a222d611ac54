"""A client nobody here wrote: the official MCP Inspector CLI against `verigraph serve`.

The Inspector and the Node it needs are installed by `bash scripts/install_inspector.sh`
(into .tools/); CI exports VERIGRAPH_INSPECTOR with the path it prints. Without the
Inspector these tests skip locally and FAIL when CI=true.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any

import pytest
from mcp_helpers import REPO, http_server, verigraph_command

from verigraph.tools import TOOL_SPECS

TOKEN = "inspector-token"


def inspector() -> str:
    configured = os.environ.get("VERIGRAPH_INSPECTOR")
    candidate = Path(configured) if configured else REPO / ".tools" / "bin" / "mcp-inspector"
    if candidate.is_file() and os.access(candidate, os.X_OK):
        return str(candidate)
    message = (f"MCP Inspector not found at {candidate}; install it with "
               "`bash scripts/install_inspector.sh` and export the VERIGRAPH_INSPECTOR it prints")
    if os.environ.get("CI", "").lower() == "true":
        pytest.fail(message)
    pytest.skip(message)


def run(*args: str) -> tuple[int, Any, str]:
    done = subprocess.run([inspector(), "--cli", *args, "--format", "json"],
                          capture_output=True, text=True, timeout=120)
    payload = json.loads(done.stdout) if done.stdout.strip() else None
    return done.returncode, payload, done.stderr


def stdio_target() -> list[str]:
    return [*verigraph_command(), "serve"]


def test_inspector_lists_the_tools_over_stdio() -> None:
    code, payload, err = run(*stdio_target(), "--method", "tools/list")
    assert code == 0, err
    tools = payload["result"]["tools"]
    assert [t["name"] for t in tools] == [s.name for s in TOOL_SPECS]
    by_name = {t["name"]: t for t in tools}
    assert by_name["validate_action"]["annotations"]["readOnlyHint"] is True
    # destructiveHint defaults to true in MCP, so it is sent only when false.
    assert by_name["execute_actions"]["annotations"].get("destructiveHint", True) is True
    assert "readOnlyHint" not in by_name["execute_actions"]["annotations"]
    assert "outputSchema" in by_name["validate_plan"]
    assert "outputSchema" not in by_name["render_scene"]


def test_inspector_calls_a_tool_over_stdio() -> None:
    args = json.dumps({"scene_id": "cup_on_book", "plan": "move(cup, desk)\nmove(book, shelf)"})
    code, payload, err = run(*stdio_target(), "--method", "tools/call", "--tool-name",
                             "validate_plan", "--tool-args-json", args)
    assert code == 0, err
    result = payload["result"]
    assert result["isError"] is False
    assert result["structuredContent"]["valid"] is True
    assert result["content"][0]["text"] == (
        "VALID: 2 step(s) checked; goal reached (a check only, nothing was executed)\n"
        "  1 ok    move(cup, on, desk)   -cup on book, +cup on desk\n"
        "  2 ok    move(book, on, shelf)   -book on desk, +book on shelf\n"
        "built-in properties applied (dictionary: tableware): book: movable surface, "
        "capacity 2 (tableware dictionary); cup: movable container, capacity 1 (tableware "
        "dictionary); desk: fixed surface, capacity unlimited (tableware dictionary); shelf: "
        "fixed surface, capacity 3 (tableware dictionary). These are built-in defaults, "
        "assumed: confirm them with the user; a node's attrs win over them")


def test_inspector_sees_tool_errors_over_stdio() -> None:
    code, payload, err = run(*stdio_target(), "--method", "tools/call", "--tool-name",
                             "get_state", "--tool-args-json", '{"episode_id": "ep_nope"}')
    assert code == 5 and "tool_is_error" in err
    assert "no open episode" in payload["result"]["content"][0]["text"]


def test_inspector_over_http_with_and_without_the_token() -> None:
    with http_server(token=TOKEN) as server:
        code, payload, err = run(server.url, "--transport", "http", "--header",
                                 f"Authorization: Bearer {TOKEN}", "--method", "tools/call",
                                 "--tool-name", "load_scene", "--tool-args-json",
                                 '{"scene_id": "three_blocks"}')
        assert code == 0, err
        assert payload["result"]["structuredContent"]["episode_id"].startswith("ep_")
        code, _, err = run(server.url, "--transport", "http", "--method", "tools/list")
        assert code == 3 and "auth_required" in err
