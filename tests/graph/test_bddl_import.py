"""A BEHAVIOR-1K problem (BDDL text) as a scene and formula goal: names through the
`behavior` dictionary, rooms and furniture, the roles an activity gives, refusals that
name the predicate and the activity. No `bddl` package is needed for a problem's text."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from bddl_problems import DISHES, FILLED

from verigraph.graph.bddl_problem import UnsupportedActivityError, import_problem
from verigraph.graph.formula import parse_formula
from verigraph.graph.formula_eval import facts_of, holds
from verigraph.graph.state import WorldState

pytestmark = pytest.mark.fast

ROOT = Path(__file__).parents[2]


def test_objects_rooms_furniture_and_states() -> None:
    imported = import_problem(DISHES)
    assert imported.activity == "putting_dishes_away"
    nodes = {n["id"]: n for n in imported.scene["nodes"]}
    # the agent and the `_*` cabinet are left out; the fridge reads by its common name
    assert set(nodes) == {"plate_1", "plate_2", "countertop_1", "cabinet_1", "fridge_1",
                          "floor_1", "kitchen"}
    assert nodes["fridge_1"] == {"id": "fridge_1", "label": "fridge", "state": {"open": True}}
    assert nodes["kitchen"]["label"] == "kitchen"
    edges = {(e["source"], e["relation"], e["target"]) for e in imported.scene["edges"]}
    assert ("cabinet_1", "inroom", "kitchen") in edges
    assert ("plate_1", "on", "countertop_1") in edges
    assert not [e for e in edges if e[0] == "cabinet_1" and e[1] != "inroom"]
    assert imported.scene["dictionary"] == "behavior"
    assert imported.predicate_class == "household"
    graph = imported.scene_graph()  # well formed
    assert len(graph.nodes) == 7


def test_the_goal_is_the_same_formula_over_ids_and_kinds() -> None:
    imported = import_problem(DISHES)
    assert imported.goal == {"formula": imported.formula}
    assert imported.formula == ("(and (forall (?plate - plate) (inside ?plate cabinet_1)) "
                                "(not (open fridge_1)))")
    state = WorldState.from_graph(imported.scene_graph())
    formula = parse_formula(imported.formula)
    assert not holds(formula, facts_of(state))
    for plate in ("plate_1", "plate_2"):
        state.set_support(plate, "in", "cabinet_1")
    state.set_state("fridge_1", "open", False)
    assert holds(formula, facts_of(state))


def test_an_unsupported_predicate_is_refused_naming_it_and_the_activity() -> None:
    with pytest.raises(UnsupportedActivityError) as err:
        import_problem(FILLED, activity="putting_dishes_away")
    assert err.value.predicate == "filled"
    assert err.value.activity == "putting_dishes_away"
    assert "'filled'" in err.value.message and "putting_dishes_away" in err.value.message
    goal_only = DISHES.replace("(not (open ?electric_refrigerator.n.01_1))",
                               "(covered ?plate.n.04_1 ?dust.n.01_1)")
    with pytest.raises(UnsupportedActivityError) as err:
        import_problem(goal_only)
    assert err.value.predicate == "covered" and "(goal)" in err.value.message


@pytest.mark.parametrize("text, why", [
    ("(define (problem x) (:objects a - b) (:init)", "never closed"),
    ("(define (problem x) (:objects a - b) (:init))", "no (:goal"),
    ("(problem x)", "does not start with (define"),
    ("(define (problem x)) )", "closes nothing"),
    ("(" * 100, "deeper than"),
])
def test_text_that_is_no_bddl_problem_is_refused(text: str, why: str) -> None:
    with pytest.raises(UnsupportedActivityError) as err:
        import_problem(text)
    assert why in err.value.message
    assert err.value.predicate is None


def test_roles_the_activity_gives_and_furniture_the_goal_moves() -> None:
    text = """(define (problem tidy-0) (:domain omnigibson)
      (:objects book.n.02_1 - book.n.02 swivel_chair.n.01_1 - swivel_chair.n.01
                desk.n.01_1 - desk.n.01 floor.n.01_1 - floor.n.01 bowl.n.01_1 - bowl.n.01)
      (:init (ontop book.n.02_1 desk.n.01_1) (ontop bowl.n.01_1 desk.n.01_1)
             (inroom desk.n.01_1 private_office) (inroom swivel_chair.n.01_1 private_office)
             (inroom floor.n.01_1 private_office))
      (:goal (and (ontop ?book.n.02_1 ?bowl.n.01_1) (nextto ?swivel_chair.n.01_1 ?desk.n.01_1))))"""
    imported = import_problem(text)
    nodes = {n["id"]: n for n in imported.scene["nodes"]}
    # the goal puts a book on a bowl: the bowl is a surface here, carrying any of the
    # activity's movable objects (BEHAVIOR has no capacities)
    assert nodes["bowl_1"]["attrs"]["surface"] is True
    assert nodes["bowl_1"]["attrs"]["capacity"] == 3
    # the chair the goal moves stands movable on its room's floor
    assert nodes["swivel_chair_1"]["attrs"]["movable"] is True
    edges = {(e["source"], e["relation"], e["target"]) for e in imported.scene["edges"]}
    assert ("swivel_chair_1", "on", "floor_1") in edges
    assert ("desk_1", "inroom", "private_office") in edges
    imported.scene_graph()


def test_thermal_states_and_several_goal_formulas() -> None:
    text = """(define (problem cook-0) (:domain omnigibson)
      (:objects bacon.n.01_1 - bacon.n.01 stove.n.01_1 - stove.n.01
                floor.n.01_1 - floor.n.01)
      (:init (ontop bacon.n.01_1 floor.n.01_1) (not (cooked bacon.n.01_1))
             (inroom stove.n.01_1 kitchen) (inroom floor.n.01_1 kitchen))
      (:goal (cooked ?bacon.n.01_1) (not (toggled_on ?stove.n.01_1))))"""
    imported = import_problem(text)
    assert imported.predicate_class == "thermal"
    assert imported.formula == "(and (cooked bacon_1) (not (toggled_on stove_1)))"
    node = next(n for n in imported.scene["nodes"] if n["id"] == "bacon_1")
    assert node["state"] == {"cooked": False}
    imported.scene_graph()


def test_cli_writes_scene_and_goal_or_exits_2_writing_nothing(tmp_path: Path) -> None:
    good, bad = tmp_path / "dishes.bddl", tmp_path / "filled.bddl"
    good.write_text(DISHES)
    bad.write_text(FILLED)
    run = [sys.executable, "-m", "verigraph", "bddl", "import"]
    out = subprocess.run([*run, str(good), "-o", str(tmp_path / "ok"), "--json"],
                         capture_output=True, text=True, cwd=ROOT, timeout=120, check=False)
    assert out.returncode == 0, out.stderr
    summary = json.loads(out.stdout)
    assert summary["objects"] == 6 and summary["rooms"] == 1
    scene = json.loads((tmp_path / "ok" / "scene.json").read_text())
    goal = json.loads((tmp_path / "ok" / "goal.json").read_text())
    assert scene["dictionary"] == "behavior" and goal["formula"].startswith("(and (forall")
    out = subprocess.run([*run, str(bad), "-o", str(tmp_path / "no")], capture_output=True,
                         text=True, cwd=ROOT, timeout=120, check=False)
    assert out.returncode == 2
    assert "activity filled needs the predicate 'filled'" in out.stderr
    assert not (tmp_path / "no").exists()
