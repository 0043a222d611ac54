"""The recorded model sessions the tests replay (tests/data/llm_trials/, one folder a task)."""

from __future__ import annotations

import base64
import json
from pathlib import Path
from typing import Any

TRIALS = Path(__file__).parent / "data" / "llm_trials"


def start(task: str) -> dict[str, Any]:
    """The scene the user attached to `task` (its start.json)."""
    data: dict[str, Any] = json.loads((TRIALS / task / "start.json").read_text())
    return data


# The second set of recorded sessions: the user's own world, PDDL plans, longer goals.
# Its transcripts mark a refused call by its text (`Error executing tool ...`) and write
# an attached text file as `@text:./F`.
SECOND_SET = TRIALS / "round2"


def transcript(folder: Path) -> list[dict[str, Any]]:
    """The tool calls of one recorded task, in order (`tool`, `args`, `shown`)."""
    return [json.loads(line) for line in (folder / "transcript.jsonl").read_text().splitlines()
            if line.strip()]


def with_attachments(folder: Path, value: Any) -> Any:
    """A recorded argument with `@json:./f`, `@png:./f` and `@text:./f` replaced by the
    attached file (parsed JSON, base64 PNG, text)."""
    if isinstance(value, dict):
        return {k: with_attachments(folder, v) for k, v in value.items()}
    if isinstance(value, list):
        return [with_attachments(folder, v) for v in value]
    if isinstance(value, str):
        for mark in ("@json:./", "@png:./", "@text:./"):
            if value.startswith(mark):
                path = folder / value.removeprefix(mark)
                if mark == "@json:./":
                    return json.loads(path.read_text())
                if mark == "@png:./":
                    return base64.b64encode(path.read_bytes()).decode()
                return path.read_text()
    return value


def shown(entry: dict[str, Any]) -> str:
    """The text the model read back for one recorded call."""
    return "\n".join(s.get("text", "") for s in entry["shown"])


def refused(entry: dict[str, Any]) -> bool:
    """Whether the recorded call was a tool error."""
    return bool(entry.get("is_error", shown(entry).startswith("Error executing tool")))


# The third set: a garage cabinet in words, ADL and costed PDDL plans, a simulated run, a
# colleague's plan to repair, a catalogue photo, a party table, a storage puzzle, a
# tangram from a picture and a stove that holds two.
THIRD_SET = TRIALS / "round3"
