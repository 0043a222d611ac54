"""Recording and replaying planner transcripts, so a paid LLM run can be re-scored offline.

`RecordingPlanner` wraps any planner and appends one JSON line per call to
`DIR/<key>.jsonl`: the prompt it was shown and the reply it gave (actions, parse error,
raw text, calls, token usage). `ReplayingPlanner` answers from such a file, in order,
without any network: the loop, verifier and scoring run again for real. Each replayed
call checks that the prompt is the recorded one, so a transcript cannot silently be
scored against a different episode (a changed suite, scene or loop setting); a mismatch
or a transcript that runs out raises `TranscriptError`, which the loop records as a
planner error. The backends themselves are untouched: this is a wrapper.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

from verigraph.planning.models import PlannerReply, PlannerRequest
from verigraph.planning.planner import Planner, is_privileged

VERSION = 1


class TranscriptError(RuntimeError):
    """A replayed transcript does not fit the episode being run."""


def transcript_path(directory: str | Path, key: str) -> Path:
    """`DIR/<key>.jsonl` with the key reduced to safe file-name characters."""
    safe = re.sub(r"[^A-Za-z0-9_.=-]+", "_", key).strip("_") or "episode"
    return Path(directory) / f"{safe}.jsonl"


class RecordingPlanner:
    """Passes calls to `inner` and writes each prompt and reply to a transcript file."""

    def __init__(self, inner: Planner, directory: str | Path, key: str, *,
                 close_inner: bool = True) -> None:
        self.inner = inner
        self.name = inner.name
        self.privileged = is_privileged(inner)
        self.path = transcript_path(directory, key)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.path.write_text(json.dumps({"transcript": VERSION, "planner": inner.name,
                                         "key": key}) + "\n")
        self.close_inner = close_inner

    def propose(self, request: PlannerRequest) -> PlannerReply:
        reply = self.inner.propose(request)
        line: dict[str, Any] = {"iteration": request.iteration, "mode": request.mode,
                                "k": request.k, "prompt": request.prompt,
                                "reply": reply.model_dump(mode="json")}
        with self.path.open("a") as out:
            out.write(json.dumps(line) + "\n")
        return reply

    def close(self) -> None:
        if self.close_inner:
            self.inner.close()


class ReplayingPlanner:
    """Answers each call with the next recorded reply, after checking the prompt."""

    def __init__(self, directory: str | Path, key: str) -> None:
        self.path = transcript_path(directory, key)
        self.name = "replay"
        self.calls: list[dict[str, Any]] | None = None
        self.position = 0
        if self.path.is_file():
            self._load()

    def _load(self) -> list[dict[str, Any]]:
        """The recorded calls; a missing or foreign file fails the episode, not the run."""
        if not self.path.is_file():
            raise TranscriptError(f"no transcript {self.path} to replay (record one with "
                                  "--record)")
        lines = [json.loads(x) for x in self.path.read_text().splitlines() if x.strip()]
        if not lines or lines[0].get("transcript") != VERSION:
            raise TranscriptError(f"{self.path} is not a version-{VERSION} transcript")
        self.name = f"replay({lines[0].get('planner', '?')})"
        self.calls = lines[1:]
        return self.calls

    def propose(self, request: PlannerRequest) -> PlannerReply:
        calls = self.calls if self.calls is not None else self._load()
        if self.position >= len(calls):
            raise TranscriptError(f"{self.path} has only {len(calls)} recorded call(s); "
                                  "the episode asked for more")
        call = calls[self.position]
        self.position += 1
        if call["prompt"] != request.prompt:
            raise TranscriptError(f"call {self.position} of {self.path}: the prompt differs "
                                  "from the recorded one (another episode, suite version or "
                                  "loop setting)")
        return PlannerReply.model_validate(call["reply"])

    def close(self) -> None:
        return None
