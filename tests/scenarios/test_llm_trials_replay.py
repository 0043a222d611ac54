"""Sessions of a real language model, replayed against a fresh server.

tests/data/llm_trials/ holds ten tasks a vision-capable LLM did as a chat assistant with
only this server: the user's message, the attached files and every tool call it made
with the text it read back. Each transcript's calls run again, in order, over the SDK
client (episode ids mapped to the new ones, `@json:` and `@png:` replaced by the
attached files). Every call must end as it did (same error or success, the same final
verdict), and the text the model reads must now carry what it lacked then: the
executor, every violation with a fix for every blocker, and the full goal.
"""

from __future__ import annotations

import base64
import json
import re
from typing import Any

import pytest
from mcp import Client
from mcp.types import CallToolResult
from mcp_helpers import text

from llm_trials import TRIALS
from verigraph.server import build_server
from verigraph.tools import Toolbox

pytestmark = pytest.mark.anyio
TASKS = sorted(p.name for p in TRIALS.iterdir() if (p / "transcript.jsonl").exists())
REPORTS_STATE = ("load_scene", "execute_actions", "get_state", "end_episode",
                 "validate_action")


def attached(task: str, value: Any) -> Any:
    """The transcript's argument with `@json:./f` and `@png:./f` replaced by the file."""
    if isinstance(value, dict):
        return {k: attached(task, v) for k, v in value.items()}
    if isinstance(value, list):
        return [attached(task, v) for v in value]
    if isinstance(value, str) and value.startswith("@json:./"):
        return json.loads((TRIALS / task / value.removeprefix("@json:./")).read_text())
    if isinstance(value, str) and value.startswith("@png:./"):
        return base64.b64encode((TRIALS / task / value.removeprefix("@png:./")).read_bytes()
                                ).decode()
    return value


def shown_text(entry: dict[str, Any]) -> str:
    return "\n".join(s.get("text", "") for s in entry["shown"])


def check_text_carries_what_was_missing(tool: str, result: CallToolResult) -> None:
    said = text(result)
    out = result.structured_content or {}
    if tool in REPORTS_STATE:
        assert re.search(r"\bexecutor: (graph|sim2d|arm:\w+) \(", said), said
    violations = out.get("violations") or ([out["violation"]] if out.get("violation") else [])
    for v in violations:
        assert f"[{v['constraint']}] {v['message']}" in said, (v, said)
        assert v["suggestion"] in said
        if v["constraint"] == "object_not_clear":
            assert all(b in v["suggestion"] for b in v["blocking"]), v
    if tool == "set_goal" and out.get("accepted") and out.get("goal", {}).get("graph"):
        edges = "; ".join(f"{e['source']} {e['relation']} {e['target']}"
                          for e in out["goal"]["graph"]["edges"])
        assert edges in said, said


@pytest.mark.parametrize("task", TASKS)
async def test_the_transcript_replays_and_reads_fully(task: str) -> None:
    entries = [json.loads(line) for line in
               (TRIALS / task / "transcript.jsonl").read_text().splitlines() if line.strip()]
    ids: dict[str, str] = {}
    async with Client(build_server(Toolbox())) as client:
        for number, entry in enumerate(entries, 1):
            args = attached(task, entry["args"])
            if isinstance(args.get("episode_id"), str):
                args["episode_id"] = ids.get(args["episode_id"], args["episode_id"])
            result = await client.call_tool(entry["tool"], args)
            where = f"{task} call {number} ({entry['tool']})"
            assert bool(result.is_error) == entry["is_error"], (where, text(result))
            if result.is_error:
                assert "fix: " in text(result) or "give " in text(result), where
                continue
            old = shown_text(entry)
            if entry["tool"] == "load_scene":
                then = re.match(r"episode (ep_[\w-]+):", old)
                assert then is not None and result.structured_content is not None
                ids[then.group(1)] = result.structured_content["episode_id"]
            for verdict in ("SUCCESS: goal reached", "VALID:", "INVALID:", "goal reached;"):
                if old.startswith(verdict) or f"; {verdict}" in old:
                    assert verdict in text(result), (where, text(result))
            check_text_carries_what_was_missing(entry["tool"], result)


async def test_the_first_check_plan_call_now_shows_every_blocker_and_the_fix() -> None:
    entry = json.loads((TRIALS / "check_plan" / "transcript.jsonl").read_text().splitlines()[0])
    async with Client(build_server(Toolbox())) as client:
        result = await client.call_tool("validate_plan", attached("check_plan", entry["args"]))
    said = text(result)
    assert "move knife somewhere else first" in shown_text(entry)  # what the model read then
    assert "move knife, spoon and lid somewhere else first" in said  # what it reads now
    assert re.search(r"^\s*2 ok\s+move\(knife, on, counter\)   -knife \w+ \w+, \+knife on counter$",
                     said, re.M)


async def test_the_arm_refusal_now_names_the_servers_executors() -> None:
    last = json.loads((TRIALS / "lang_stack_order" / "transcript.jsonl").read_text()
                      .splitlines()[-1])
    assert last["args"]["executor"] == "arm" and last["is_error"]
    async with Client(build_server(Toolbox())) as client:
        result = await client.call_tool("load_scene", attached("lang_stack_order", last["args"]))
    assert result.is_error
    assert "this server runs graph (verified only, default), sim2d (simulated)" in text(result)
