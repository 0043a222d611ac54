"""`verigraph validate --batch`: one JSON line per item, error lines for bad items."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

from blocksworld_corpus import DATA

EXAMPLES = Path(__file__).parents[2] / "examples" / "scenes"


def test_batch_mixes_pddl_and_scene_items_and_survives_bad_ones(tmp_path):
    for name in ("planbench_domain.pddl", "planbench_instance.pddl", "planbench_plan.txt"):
        shutil.copy(DATA / name, tmp_path / name)
    (tmp_path / "bad_plan.txt").write_text("(unstack d c)\n(stack d b)\n")
    (tmp_path / "arity.txt").write_text("(unstack d)\n")
    pddl = {"domain": "planbench_domain.pddl", "problem": "planbench_instance.pddl"}
    items = [
        {"id": "ok", **pddl, "plan": "planbench_plan.txt"},
        {"id": 7, **pddl, "plan": "bad_plan.txt"},
        {"id": "arity", **pddl, "plan": "arity.txt"},
        {"id": "missing", **pddl, "plan": "nope.txt"},
        {"id": "scene", "scene": str(EXAMPLES / "cup_on_book.json"),
         "plan": str(EXAMPLES / "cup_on_book_fixed.txt"),
         "goal": str(EXAMPLES / "cup_on_book_goal.json")},
        {"id": "neither", "plan": "planbench_plan.txt"},
    ]
    lines = [json.dumps(i) for i in items] + ["{broken"]
    (tmp_path / "batch.jsonl").write_text("\n".join(lines) + "\n")
    r = subprocess.run([sys.executable, "-m", "verigraph", "validate", "--batch",
                        str(tmp_path / "batch.jsonl")], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 1, r.stderr
    out = [json.loads(line) for line in r.stdout.splitlines()]
    assert [o["id"] for o in out] == ["ok", 7, "arity", "missing", "scene", "neither", "line 7"]
    by_id = {o["id"]: o for o in out}
    assert by_id["ok"]["valid"] and len(by_id["ok"]["steps"]) == 4
    assert by_id[7]["violations"][0]["constraint"] == "target_full"
    assert by_id[7]["violations"][0]["step"] == 2
    assert by_id["arity"]["ok"] is False and "line 1" in by_id["arity"]["field"]
    assert by_id["missing"]["field"] == "plan"
    assert by_id["scene"]["valid"] and by_id["scene"]["goal_reached"]
    assert by_id["neither"]["error"] == "InputFileError"
    assert "not JSON" in by_id["line 7"]["message"]
    assert "plan" in r.stderr  # the progress bar's unit
    assert "Traceback" not in r.stderr
