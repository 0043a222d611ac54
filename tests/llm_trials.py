"""The recorded model sessions the tests replay (tests/data/llm_trials/, one folder a task)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

TRIALS = Path(__file__).parent / "data" / "llm_trials"


def start(task: str) -> dict[str, Any]:
    """The scene the user attached to `task` (its start.json)."""
    data: dict[str, Any] = json.loads((TRIALS / task / "start.json").read_text())
    return data
