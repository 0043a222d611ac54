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
    # A malformed plan line is a verdict (invalid at that step), as VAL and PlanBench count it.
    assert by_id["arity"]["valid"] is False
    assert [v["step"] for v in by_id["arity"]["violations"]] == [1]
    assert "argument" in by_id["arity"]["violations"][0]["message"]
    assert by_id["missing"]["field"] == "plan"
    assert by_id["scene"]["valid"] and by_id["scene"]["goal_reached"]
    assert by_id["neither"]["error"] == "InputFileError"
    assert "not JSON" in by_id["line 7"]["message"]
    assert "plan" in r.stderr  # the progress bar's unit
    assert "Traceback" not in r.stderr


def test_malformed_plan_lines_are_verdicts_in_a_batch_as_in_a_single_check(tmp_path):
    """Wrong arity, `(no plan possible)` and numbered lines fail at their step, the same
    report in --batch as from `validate --json`; an unreadable plan stays an error."""
    for name in ("planbench_domain.pddl", "planbench_instance.pddl"):
        shutil.copy(DATA / name, tmp_path / name)
    # (plan, failing step, a word of the reason); the constraint ids are the engine's.
    plans = {"arity": ("(unstack d c)\n(put-down d c)\n", 2, "argument"),
             "none": ("(no plan possible)\n", 1, "no"),
             "numbered": ("(1) (unstack d c)\n", 1, "(1)")}
    pddl = {"domain": "planbench_domain.pddl", "problem": "planbench_instance.pddl"}
    items = []
    for name, (text, _, _) in plans.items():
        (tmp_path / f"{name}.txt").write_text(text)
        items.append({"id": name, **pddl, "plan": f"{name}.txt"})
    (tmp_path / "latin1.txt").write_bytes("(unstack d c) ; caf\xe9\n".encode("latin-1"))
    items.append({"id": "latin1", **pddl, "plan": "latin1.txt"})
    (tmp_path / "b.jsonl").write_text("\n".join(json.dumps(i) for i in items) + "\n")
    r = subprocess.run([sys.executable, "-m", "verigraph", "validate", "--batch",
                        str(tmp_path / "b.jsonl"), "--no-progress", "--planbench"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 1 and "Traceback" not in r.stderr
    by_id = {o["id"]: o for o in map(json.loads, r.stdout.splitlines())}
    for name, (_, step, word) in plans.items():
        report = by_id.pop(name)
        assert report["valid"] is False and report["planbench"]["valid"] is False, name
        assert [v["step"] for v in report["violations"]] == [step], name
        assert word in report["violations"][0]["message"], name
        single = subprocess.run([sys.executable, "-m", "verigraph", "validate", "--json",
                                 "--planbench", "--plan", f"{name}.txt", "--domain",
                                 pddl["domain"], "--problem", pddl["problem"]],
                                capture_output=True, text=True, timeout=120, cwd=tmp_path)
        assert single.returncode == 1, single.stderr
        assert json.loads(single.stdout) == {k: v for k, v in report.items() if k != "id"}
    assert by_id["latin1"]["ok"] is False and by_id["latin1"]["field"] == "plan"
