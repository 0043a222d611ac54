"""`--goal` takes a formula: as a file (a formula as the whole text, a `(:goal ...)`
section, or JSON `{"formula": ...}`) or as the text itself."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from verigraph.cli import main

pytestmark = pytest.mark.fast

EXAMPLES = Path(__file__).parents[2] / "examples" / "scenes"
SCENE = str(EXAMPLES / "cup_on_book.json")
GOAL_FILE = str(EXAMPLES / "cup_on_book_goal.bddl")


def test_solve_with_a_formula_file(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["solve", "--scene", SCENE, "--goal", GOAL_FILE, "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["optimal"] is True
    assert [(a["object"], a["target"]) for a in result["plan"]] == [("cup", "desk"),
                                                                   ("book", "shelf")]


def test_formula_as_text_and_as_json(tmp_path: Path, capsys: pytest.CaptureFixture[str]
                                     ) -> None:
    assert main(["solve", "--scene", SCENE, "--goal", "(not (ontop cup book))"]) == 0
    assert capsys.readouterr().out.splitlines()[:2] == ["# length 1, optimal",
                                                        "move(cup, on, desk)"]
    goal = tmp_path / "goal.json"
    goal.write_text(json.dumps({"formula": "(ontop book shelf)"}))
    assert main(["solve", "--scene", SCENE, "--goal", str(goal)]) == 0
    assert "# length 2, optimal" in capsys.readouterr().out


def test_validate_reports_every_counterexample(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    plan = tmp_path / "plan.txt"
    plan.write_text("move(cup, on, desk)\n")
    assert main(["validate", "--scene", SCENE, "--plan", str(plan), "--goal", GOAL_FILE]) == 1
    out = capsys.readouterr().out
    assert "formula fails (1 counterexample): (ontop book shelf) fails: book is not on shelf " \
           "(book is on desk)" in out
    plan.write_text("move(cup, on, desk)\nmove(book, on, shelf)\n")
    assert main(["validate", "--scene", SCENE, "--plan", str(plan), "--goal", GOAL_FILE]) == 0


def test_a_bad_formula_file_exits_2_naming_the_position(tmp_path: Path,
                                                        capsys: pytest.CaptureFixture[str]
                                                        ) -> None:
    goal = tmp_path / "goal.bddl"
    goal.write_text("(and (ontop cup desk)\n     (forall (?b - book) (ontop ?b shelf))")
    assert main(["solve", "--scene", SCENE, "--goal", str(goal)]) == 2
    err = capsys.readouterr().err
    assert "character 65: the formula ends with 1 parenthesis(es) open" in err
    assert "fix: close it with )" in err
    assert main(["export-pddl", "--scene", SCENE, "--goal", GOAL_FILE, "--domain-out",
                 str(tmp_path / "d.pddl"), "--problem-out", str(tmp_path / "p.pddl")]) == 2
    assert "formula" in capsys.readouterr().err


def test_a_formula_naming_what_the_scene_lacks_exits_2(capsys: pytest.CaptureFixture[str]
                                                       ) -> None:
    assert main(["solve", "--scene", SCENE, "--goal", "(ontop cupp desk)"]) == 2
    err = capsys.readouterr().err
    assert "object 'cupp' (did you mean cup?)" in err and "fix:" in err


def test_the_household_request_as_a_formula_is_solved_optimally(
        capsys: pytest.CaptureFixture[str]) -> None:
    """The milk in the fridge, the fridge closed, the pot on a burner that is on, no cup
    on any plate: checked, and solved in the fewest actions."""
    scene = str(EXAMPLES / "kitchen_household.json")
    goal = str(EXAMPLES / "kitchen_household_goal.bddl")
    assert main(["solve", "--scene", scene, "--goal", goal, "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["optimal"] is True and len(result["plan"]) == 6
    plan = [a["action"] + "(" + ", ".join(str(a[k]) for k in ("object", "relation", "target")
                                          if k in a) + ")" for a in result["plan"]]
    assert plan.index("open(fridge)") < plan.index("move(milk, in, fridge)") \
        < plan.index("close(fridge)")
    assert "move(cup, on, plate)" not in plan and "toggle_on(stove)" in plan
