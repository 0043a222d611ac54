"""BEHAVIOR-style goals the solver reaches: `nextto` beside a placement (an object next
to another stands where that one stands; next to furniture, on its room's floor), a
thermal state with no source to make it said unreachable before any search, a goal
whose bound is flat for A* found by the greedy first phase of the anytime search, and
`inside` read where the object is (a pizza on a plate in the fridge)."""

from __future__ import annotations

import pytest
from bddl_problems import KINDLING, STEWED, VODKA

from verigraph.actions.execution import run_actions
from verigraph.actions.model import MoveAction
from verigraph.actions.report import validate_plan
from verigraph.actions.validator import validate_action
from verigraph.graph.bddl_problem import import_problem
from verigraph.graph.formula import parse_formula
from verigraph.graph.formula_eval import facts_of, holds
from verigraph.graph.goal import Goal
from verigraph.graph.state import WorldState
from verigraph.solver import solve

pytestmark = pytest.mark.fast


def solved(text: str) -> tuple[WorldState, Goal, list[str]]:
    """Import, solve (optimal), validate against the formula and run on a copy."""
    imported = import_problem(text)
    state = WorldState.from_graph(imported.scene_graph())
    goal = Goal(formula=imported.formula)
    result = solve(state, goal, time_limit=10)
    assert result.reachable and result.optimal, result.reason
    report = validate_plan(state.copy(), result.plan or "done", goal)
    assert report["valid"] and report["goal_diff"]["satisfied"]
    after = state.copy()
    run = run_actions(after, result.plan)
    assert not run.violations
    assert holds(parse_formula(imported.formula), facts_of(after))
    return state, goal, [a.text() for a in result.plan]


def test_next_to_a_bottle_in_the_cabinet_is_in_the_cabinet() -> None:
    _, _, plan = solved(VODKA)
    assert plan[0] == "open(cabinet_1)" and len(plan) == 3
    assert plan[2] in ("move(bottle_of_vodka_2, nextto, bottle_of_vodka_1)",
                       "move(bottle_of_vodka_1, nextto, bottle_of_vodka_2)")


def test_next_to_the_fireplace_is_on_the_floor_of_its_room() -> None:
    state, goal, plan = solved(KINDLING)
    assert sorted(plan) == ["move(firewood_1, nextto, wood_fireplace_1)",
                            "move(firewood_2, nextto, wood_fireplace_1)"]
    facts = facts_of(state)
    assert not holds(parse_formula("(ontop firewood_1 floor_2)"), facts)
    run_actions(state, [MoveAction(object="firewood_1", relation="nextto",
                                   target="wood_fireplace_1")])
    facts = facts_of(state)
    assert holds(parse_formula("(ontop firewood_1 floor_2)"), facts)  # the living room's
    assert not holds(parse_formula("(ontop firewood_1 floor_1)"), facts)  # the garden's
    assert not holds(parse_formula("(inside firewood_1 floor_2)"), facts)
    assert holds(parse_formula("(inroom firewood_1 living_room)"), facts)


def test_next_to_an_object_in_a_closed_cabinet_is_refused_until_it_is_opened() -> None:
    state = WorldState.from_graph(import_problem(VODKA).scene_graph())
    state.set_state("cabinet_1", "open", True)
    assert not run_actions(state, [MoveAction(object="bottle_of_vodka_1", relation="in",
                                              target="cabinet_1")]).violations
    state.set_state("cabinet_1", "open", False)
    beside = MoveAction(object="bottle_of_vodka_2", relation="nextto",
                        target="bottle_of_vodka_1")
    violation = validate_action(state, beside)
    assert violation is not None and violation.constraint == "container_closed"
    assert "cabinet_1" in violation.message and violation.blocking == ["cabinet_1"]
    state.set_state("cabinet_1", "open", True)
    assert validate_action(state, beside) is None


def test_a_state_no_source_can_make_is_unreachable_without_search() -> None:
    imported = import_problem(STEWED)
    result = solve(imported.scene_graph(), Goal(formula=imported.formula))
    assert result.reachable is False and result.expanded == 0
    assert result.reason is not None
    assert "(cooked pear_1)" in result.reason and "no heat source" in result.reason


def test_the_guide_counts_each_pair_and_each_part_still_missing() -> None:
    from verigraph.graph.model import SceneGraph
    from verigraph.solver.formula_bound import formula_bound

    nodes = [("table", "table"), ("plate_1", "plate"), ("plate_2", "plate"),
             ("plate_3", "plate"), ("cup_1", "cup"), ("cup_2", "cup"), ("cup_3", "cup")]
    edges = [(n, "on", "table") for n, label in nodes if label != "table"]
    state = WorldState.from_graph(SceneGraph.model_validate({
        "nodes": [{"id": i, "label": label} for i, label in nodes],
        "edges": [{"source": s, "relation": r, "target": t} for s, r, t in edges],
        "dictionary": "household"}))
    pairs = parse_formula("(forpairs (?c - cup) (?p - plate) (ontop ?c ?p))")
    two = parse_formula("(forn (2) (?c - cup) (exists (?p - plate) (ontop ?c ?p)))")
    facts = facts_of(state)
    # the bound only knows some action is needed; the guide counts a move per pair
    assert formula_bound(pairs, facts) == 1
    assert formula_bound(pairs, facts, additive=True) == 3
    assert formula_bound(two, facts, additive=True) == 2
    run_actions(state, [MoveAction(object="cup_1", relation="on", target="plate_2")])
    facts = facts_of(state)
    assert formula_bound(pairs, facts, additive=True) == 2
    assert formula_bound(two, facts, additive=True) == 1


def test_thermal_actions_the_goal_does_not_read_are_not_searched() -> None:
    from verigraph.solver.table_search import TableProblem

    imported = import_problem(VODKA)
    state = WorldState.from_graph(imported.scene_graph())
    rows = {row.name for row in TableProblem(state, Goal(formula=imported.formula)).rows}
    assert {"move", "open", "close", "toggle_on", "toggle_off"} <= rows
    assert not rows & {"cook", "heat", "cool", "freeze", "thaw"}
    cooked = TableProblem(state, Goal(formula="(cooked bottle_of_vodka_1)"))
    assert "cook" in {row.name for row in cooked.rows}
    assert "freeze" not in {row.name for row in cooked.rows}


def test_helpful_actions_change_what_the_requirements_name() -> None:
    from verigraph.actions.schemas import SCHEMAS
    from verigraph.solver.table_search import TableProblem, _changes

    imported = import_problem(VODKA)
    state = WorldState.from_graph(imported.scene_graph())
    problem = TableProblem(state, Goal(formula=imported.formula), additive=True)
    helpful = problem.helpful(state)
    assert {("place", "bottle_of_vodka_1"), ("place", "bottle_of_vodka_2"),
            ("open", "cabinet_1")} <= helpful
    assert ("place", "floor_1") not in helpful
    assert _changes(SCHEMAS["open"], ("cabinet_1",)) == ("open", "cabinet_1")
    assert _changes(SCHEMAS["close"], ("cabinet_1",)) == ("close", "cabinet_1")
    assert _changes(SCHEMAS["move"], ("bottle_of_vodka_1", "in", "cabinet_1")) == \
        ("place", "bottle_of_vodka_1")


# Folder, book and backpack pairwise next to each other, the backpack on the bed
# (BEHAVIOR's organizing_school_stuff, smaller); chairs each next to the table and to
# another chair (setting_up_garden_furniture, smaller: a chair's own name among the
# others, as there).
SCHOOL = """(define (problem organizing_school_stuff-0)
    (:domain omnigibson)
    (:objects
        folder.n.02_1 - folder.n.02
        book.n.02_1 - book.n.02
        backpack.n.01_1 - backpack.n.01
        bed.n.01_1 - bed.n.01
        floor.n.01_1 - floor.n.01
    )
    (:init
        (ontop folder.n.02_1 floor.n.01_1)
        (ontop book.n.02_1 floor.n.01_1)
        (ontop backpack.n.01_1 floor.n.01_1)
        (inroom floor.n.01_1 bedroom)
        (inroom bed.n.01_1 bedroom)
    )
    (:goal
        (and
            (nextto ?folder.n.02_1 ?book.n.02_1)
            (nextto ?folder.n.02_1 ?backpack.n.01_1)
            (nextto ?book.n.02_1 ?backpack.n.01_1)
            (ontop ?backpack.n.01_1 ?bed.n.01_1)
        )
    )
)"""
GARDEN = """(define (problem setting_up_garden_furniture-0)
    (:domain omnigibson)
    (:objects
        lawn_chair.n.01_1 lawn_chair.n.01_2 - lawn_chair.n.01
        coffee_table.n.01_1 - coffee_table.n.01
        floor.n.01_1 - floor.n.01
        driveway.n.01_1 - driveway.n.01
    )
    (:init
        (ontop lawn_chair.n.01_1 driveway.n.01_1)
        (ontop lawn_chair.n.01_2 driveway.n.01_1)
        (inroom floor.n.01_1 garden)
        (inroom driveway.n.01_1 garden)
        (inroom coffee_table.n.01_1 garden)
    )
    (:goal
        (forall (?lawn_chair.n.01 - lawn_chair.n.01)
            (and (ontop ?lawn_chair.n.01 ?floor.n.01_1)
                 (nextto ?lawn_chair.n.01 ?coffee_table.n.01_1)
                 (or (nextto ?lawn_chair.n.01 ?lawn_chair.n.01_1)
                     (nextto ?lawn_chair.n.01 ?lawn_chair.n.01_2))))
    )
)"""


def test_objects_asked_pairwise_next_to_each_other_stand_around_one() -> None:
    from verigraph.graph.model import SceneGraph
    from verigraph.solver.budget import SearchBudget
    from verigraph.solver.satisfiable import unsatisfiable_reason

    state = WorldState.from_graph(SceneGraph.model_validate({
        "nodes": [{"id": i, "label": i} for i in ("kitchen", "desk", "folder", "book",
                                                    "bag")],
        "edges": [*({"source": o, "relation": "on", "target": "desk"}
                    for o in ("folder", "book", "bag")),
                  {"source": "desk", "relation": "inroom", "target": "kitchen"}],
        "dictionary": "behavior"}))

    def possible(text: str) -> bool:
        return unsatisfiable_reason(state, parse_formula(text), SearchBudget()) is None

    triangle = "(and (nextto folder book) (nextto folder bag) (nextto book bag))"
    assert possible(triangle)  # two placed beside the third
    assert possible("(and (nextto folder book) (ontop folder desk))")
    assert not possible("(and (ontop folder desk) (inside folder bag))")
    # on a plate and inside the fridge at once: the plate in the fridge
    pizza = WorldState.from_graph(import_problem(PIZZA).scene_graph())
    both = parse_formula("(and (ontop pizza_1 plate_1) (inside pizza_1 fridge_1))")
    assert unsatisfiable_reason(pizza, both, SearchBudget()) is None
    _, _, plan = solved(SCHOOL)
    assert len(plan) == 3 and plan[0] == "move(backpack_1, on, bed_1)"
    assert sorted(plan[1:]) == ["move(book_1, nextto, backpack_1)",
                                "move(folder_1, nextto, backpack_1)"]
    _, _, plan = solved(GARDEN)  # each chair beside the table, so beside each other
    assert sorted(plan) == ["move(lawn_chair_1, nextto, coffee_table_1)",
                            "move(lawn_chair_2, nextto, coffee_table_1)"]


# `inside` read where the object is, as BEHAVIOR reads Inside: a pizza on a plate in
# the fridge, a book on a book in the bookcase (`ontop` and `inside` of one object).
# cleaning_up_plates_and_food cut to one pizza on its plate, no bowls or sink
PIZZA = """(define (problem cleaning_up_plates_and_food-0)
    (:domain omnigibson)
    (:objects
        plate.n.04_1 - plate.n.04
        floor.n.01_1 - floor.n.01
        pizza.n.01_1 - pizza.n.01
        breakfast_table.n.01_1 - breakfast_table.n.01
        electric_refrigerator.n.01_1 - electric_refrigerator.n.01
        agent.n.01_1 - agent.n.01
    )
    (:init
        (ontop plate.n.04_1 breakfast_table.n.01_1)
        (ontop pizza.n.01_1 plate.n.04_1)
        (ontop agent.n.01_1 floor.n.01_1)
        (inroom breakfast_table.n.01_1 kitchen)
        (inroom floor.n.01_1 kitchen)
        (inroom electric_refrigerator.n.01_1 kitchen)
    )
    (:goal
        (and
            (forpairs (?pizza.n.01 - pizza.n.01) (?plate.n.04 - plate.n.04)
                (ontop ?pizza.n.01 ?plate.n.04))
            (exists (?electric_refrigerator.n.01 - electric_refrigerator.n.01)
                (forall (?pizza.n.01 - pizza.n.01)
                    (inside ?pizza.n.01 ?electric_refrigerator.n.01)))
            (forall (?electric_refrigerator.n.01 - electric_refrigerator.n.01)
                (not (open ?electric_refrigerator.n.01)))
        )
    )
)"""

# sorting_books_on_shelf, problem0 of bddl 3.6.0
BOOKS = """(define (problem sorting_books_on_shelf-0)
    (:domain omnigibson)

    (:objects
        textbook.n.01_1 textbook.n.01_2 - textbook.n.01
        comic_book.n.01_1 comic_book.n.01_2 comic_book.n.01_3 - comic_book.n.01
        notebook.n.01_1 notebook.n.01_2 - notebook.n.01
        coffee_table.n.01_1 - coffee_table.n.01
        bookcase.n.01_1 - bookcase.n.01
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01
    )

    (:init
        (inside notebook.n.01_1 bookcase.n.01_1)
        (inside comic_book.n.01_1 bookcase.n.01_1)
        (ontop notebook.n.01_2 comic_book.n.01_1)
        (ontop comic_book.n.01_2 notebook.n.01_1)
        (inside textbook.n.01_1 bookcase.n.01_1)
        (inside comic_book.n.01_3 bookcase.n.01_1)
        (ontop textbook.n.01_2 comic_book.n.01_3)
        (inroom coffee_table.n.01_1 living_room)
        (inroom bookcase.n.01_1 living_room)
        (inroom floor.n.01_1 living_room)
        (ontop agent.n.01_1 floor.n.01_1)
    )

    (:goal
        (and
            (forall
                (?comic_book.n.01 - comic_book.n.01)
                (inside ?comic_book.n.01 ?bookcase.n.01_1)
            )
            (forn
                (2)
                (?comic_book.n.01 - comic_book.n.01)
                (or
                    (ontop ?comic_book.n.01 ?comic_book.n.01_1)
                    (ontop ?comic_book.n.01 ?comic_book.n.01_2)
                    (ontop ?comic_book.n.01 ?comic_book.n.01_3)
                )
            )
            (forall
                (?notebook.n.01 - notebook.n.01)
                (inside ?notebook.n.01 ?bookcase.n.01_1)
            )
            (exists
                (?notebook.n.01 - notebook.n.01)
                (or
                    (ontop ?notebook.n.01 ?notebook.n.01_1)
                    (ontop ?notebook.n.01 ?notebook.n.01_2)
                )
            )
            (forall
                (?textbook.n.01 - textbook.n.01)
                (inside ?textbook.n.01 ?bookcase.n.01_1)
            )
            (exists
                (?textbook.n.01 - textbook.n.01)
                (or
                    (ontop ?textbook.n.01 ?textbook.n.01_1)
                    (ontop ?textbook.n.01 ?textbook.n.01_2)
                )
            )
        )
    )
)"""


def test_a_pizza_on_a_plate_in_the_fridge_is_in_the_fridge() -> None:
    # the plate goes in, so the pizza comes off first and back on after; closed at last
    _, _, plan = solved(PIZZA)
    assert len(plan) == 5 and plan[0] != "move(plate_1, in, fridge_1)", plan
    assert plan[-2:] == ["move(pizza_1, on, plate_1)", "close(fridge_1)"], plan
    assert {"open(fridge_1)", "move(plate_1, in, fridge_1)"} <= set(plan[:3]), plan
    assert plan.index("open(fridge_1)") < plan.index("move(plate_1, in, fridge_1)")


def test_books_stacked_on_books_in_the_bookcase_are_in_the_bookcase() -> None:
    _, _, plan = solved(BOOKS)
    assert len(plan) == 4 and all(step.startswith("move(") for step in plan)
