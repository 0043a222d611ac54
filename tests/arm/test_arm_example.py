"""examples/arm_stack_blocks.py runs: the Panda stacks the blocks and writes frames."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest
from arm_deps import require

require("pybullet")

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "arm_stack_blocks.py"


def test_example_stacks_the_blocks_and_writes_frames(tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    spec = importlib.util.spec_from_file_location("arm_stack_blocks", EXAMPLE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.main(["--out", str(tmp_path), "--every", "480"]) == 0
    out = capsys.readouterr().out
    assert "goal single_stack: goal reached" in out
    assert "blue_block in contact with green_block" in out
    frames = sorted(tmp_path.glob("frame_*.png"))
    assert len(frames) >= 3
    assert all(f.read_bytes()[:4] == b"\x89PNG" for f in frames)
    audit = [json.loads(line) for line in (tmp_path / "audit.jsonl").read_text().splitlines()]
    assert [r["command"] for r in audit if r["outcome"] == "done"] == [
        "connect", "pick", "place", "pick", "place"]
