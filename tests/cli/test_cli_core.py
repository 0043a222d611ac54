"""The installed `verigraph` command, run as a subprocess: exit codes and JSON."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).parents[2] / "examples" / "scenes"
VERIGRAPH = str(Path(sys.executable).parent / "verigraph")


def run(*args, cwd=EXAMPLES):
    return subprocess.run([VERIGRAPH, *args], capture_output=True, text=True, cwd=cwd,
                          timeout=120)


def test_bad_plan_exits_1_with_the_failing_step_explained():
    r = run("validate", "--scene", "cup_on_book.json", "--plan", "cup_on_book_bad.txt",
            "--goal", "cup_on_book_goal.json")
    assert r.returncode == 1
    assert "FAIL  move(book, on, shelf)" in r.stdout and "object_not_clear" in r.stdout
    assert "Suggestion: move cup somewhere else first" in r.stdout


def test_fixed_plan_exits_0_and_reaches_the_goal():
    r = run("validate", "--scene", "cup_on_book.json", "--plan", "cup_on_book_fixed.txt",
            "--goal", "cup_on_book_goal.json")
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.startswith("VALID: 2 step(s) checked; goal reached")


def test_json_report():
    r = run("validate", "--scene", "cup_on_book.json", "--plan", "cup_on_book_bad.txt",
            "--json", "--all-errors")
    assert r.returncode == 1
    report = json.loads(r.stdout)
    assert report["valid"] is False
    assert [s["ok"] for s in report["steps"]] == [False, True]
    assert report["steps"][0]["violation"]["blocking"] == ["cup"]
    assert report["steps"][1]["edit"]["added"] == [
        {"source": "cup", "relation": "on", "target": "desk"}]


def test_goal_missed_exits_1():
    r = run("validate", "--scene", "three_blocks.yaml", "--plan", "cup_on_book_fixed.txt",
            "--goal", "single_stack_goal.json")
    assert r.returncode == 1 and "unknown_object" in r.stdout


@pytest.mark.parametrize("scene_text,plan_text,fragment", [
    ("{not json", "done", "invalid JSON"),
    ('{"nodes": [{"id": "a", "label": "cup"}, {"id": "a", "label": "cup"}], "edges": []}',
     "done", "duplicate"),
    ('{"nodes": [{"id": "a", "label": "book"}, {"id": "b", "label": "book"}], "edges": '
     '[{"source": "a", "relation": "on", "target": "b"}, {"source": "b", "relation": "on", '
     '"target": "a"}]}', "done", "cycle"),
    ('{"nodes": [{"id": "a", "label": "teapot"}], "edges": []}', "done", "not in the"),
    ('{"nodes": [], "edges": []}', "move(a b)", "line 1"),
    ('{"nodes": [], "edges": []}', '[{"action": "move", "object": "a"}]', "line 1"),
    ('{"nodes": [], "edges": []}', "move(a)", "line 1"),
])
def test_bad_input_exits_2_without_traceback(tmp_path, scene_text, plan_text, fragment):
    (tmp_path / "s.json").write_text(scene_text)
    (tmp_path / "p.txt").write_text(plan_text)
    r = run("validate", "--scene", "s.json", "--plan", "p.txt", cwd=tmp_path)
    assert r.returncode == 2, r.stdout + r.stderr
    assert fragment in r.stderr and "Traceback" not in r.stderr


@pytest.mark.parametrize("plan_text", ["", "# only a comment\n", "[]"])
def test_an_empty_plan_is_valid_input_and_the_goal_decides(tmp_path, plan_text):
    (tmp_path / "p.txt").write_text(plan_text)
    r = run("validate", "--scene", str(EXAMPLES / "cup_on_book.json"), "--plan", "p.txt",
            "--goal", str(EXAMPLES / "cup_on_book_goal.json"), "--json", cwd=tmp_path)
    assert r.returncode == 1, r.stderr
    report = json.loads(r.stdout)
    assert report["steps"] == [] and report["plan_valid"] and report["goal_reached"] is False
    r = run("validate", "--scene", str(EXAMPLES / "cup_on_book.json"), "--plan", "p.txt",
            cwd=tmp_path)
    assert r.returncode == 0 and "VALID: 0 step(s) checked" in r.stdout


def test_huge_plan_is_handled(tmp_path):
    lines = ["move(cup, on, desk)", "move(cup, on, book)"] * 50_000
    (tmp_path / "p.txt").write_text("\n".join(lines))
    r = run("validate", "--scene", str(EXAMPLES / "cup_on_book.json"), "--plan", "p.txt",
            "--json", cwd=tmp_path)
    # The first action is fine, the second puts the cup back: also fine. All 100,000 pass.
    assert r.returncode == 0, r.stderr
    assert len(json.loads(r.stdout)["steps"]) == 100_000


def test_solve_and_export(tmp_path):
    r = run("solve", "--scene", "cup_on_book.json", "--goal", "cup_on_book_goal.json", "--json")
    assert r.returncode == 0
    plan = json.loads(r.stdout)["plan"]
    assert [a["object"] for a in plan] == ["cup", "book"]
    r = run("export-pddl", "--scene", "cup_on_book.json", "--goal", "cup_on_book_goal.json",
            "--domain-out", str(tmp_path / "d.pddl"), "--problem-out", str(tmp_path / "p.pddl"))
    assert r.returncode == 0 and "(:action move-on-to-on" in (tmp_path / "d.pddl").read_text()
    r = run("export-pddl", "--scene", "three_blocks.yaml", "--goal", "single_stack",
            "--domain-out", str(tmp_path / "d.pddl"), "--problem-out", str(tmp_path / "p.pddl"))
    assert r.returncode == 2 and "predicate" in r.stderr


def test_unreachable_goal_exits_1(tmp_path):
    goal = {"nodes": [{"id": "desk", "label": "desk"}, {"id": "shelf", "label": "shelf"}],
            "edges": [{"source": "desk", "relation": "on", "target": "shelf"}],
            "partial": True}
    (tmp_path / "g.json").write_text(json.dumps(goal))
    r = run("solve", "--scene", str(EXAMPLES / "cup_on_book.json"), "--goal", "g.json",
            cwd=tmp_path)
    assert r.returncode == 1 and "fixed" in r.stdout


def test_bench_lists_benchmarks_for_an_unknown_name():
    r = run("bench", "no_such_benchmark")
    assert r.returncode == 2 and "validate" in r.stderr


def test_all_errors_on_a_pddl_plan_lists_every_failing_step(tmp_path):
    data = Path(__file__).parents[1] / "data" / "blocksworld"
    (tmp_path / "plan.txt").write_text("(pick-up a)\n(unstack d c)\n(stack d a)\n(pick-up zz)\n")
    args = ("validate", "--domain", str(data / "planbench_domain.pddl"), "--problem",
            str(data / "planbench_instance.pddl"), "--plan", "plan.txt", "--json")
    first = json.loads(run(*args, cwd=tmp_path).stdout)
    assert [v["step"] for v in first["violations"]] == [1] and first["not_checked"] == 3
    r = run(*args, "--all-errors", cwd=tmp_path)
    assert r.returncode == 1, r.stderr
    report = json.loads(r.stdout)
    assert [v["step"] for v in report["violations"]] == [1, 4]
    assert [s["ok"] for s in report["steps"]] == [False, True, True, False]
