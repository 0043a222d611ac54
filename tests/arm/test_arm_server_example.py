"""examples/arm_stack_blocks_mcp.py runs: planned and executed through the server, with
the arm camera's frames written as PNGs."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import cv2
import pytest
from arm_deps import require

require("pybullet")

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "arm_stack_blocks_mcp.py"


def test_example_stacks_the_blocks_through_the_server(tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    spec = importlib.util.spec_from_file_location("arm_stack_blocks_mcp", EXAMPLE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.main(["--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "episode on arm:pybullet (sim): the cameras see the graph" in out
    assert "verdict: goal_reached" in out
    frames = sorted(tmp_path.glob("frame_*.png"))
    assert [f.name for f in frames] == ["frame_00.png", "frame_01.png", "frame_02.png"]
    images = [cv2.imread(str(f)) for f in frames]
    assert all(i is not None and i.shape == (480, 640, 3) for i in images)
    assert cv2.absdiff(images[0], images[2]).mean() > 1  # the scene changed on camera
    audit = [json.loads(line) for line in (tmp_path / "audit.jsonl").read_text().splitlines()]
    assert [r["command"] for r in audit if r["outcome"] == "done"] == [
        "connect", "pick", "place", "pick", "place"]
