"""A goal formula's `inside` read where the object is, as BEHAVIOR reads Inside: a pizza
on a plate in the fridge, a book on a book in the bookcase. Activities that ask for
`ontop` and `inside` of one object at once are solved, optimally, and their plans
validate with the goal reached."""

from __future__ import annotations

import pytest

from verigraph.actions.execution import run_actions
from verigraph.actions.report import validate_plan
from verigraph.graph.bddl_problem import import_problem
from verigraph.graph.formula import parse_formula
from verigraph.graph.formula_eval import facts_of, holds
from verigraph.graph.goal import Goal
from verigraph.graph.state import WorldState
from verigraph.solver import solve

pytestmark = pytest.mark.fast

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


def solved(text: str) -> list[str]:
    """Import, solve (optimal), validate against the formula and run on a copy."""
    imported = import_problem(text)
    state = WorldState.from_graph(imported.scene_graph())
    goal = Goal(formula=imported.formula)
    result = solve(state, goal, time_limit=10)
    assert result.reachable and result.optimal, result.reason
    report = validate_plan(state.copy(), result.plan or "done", goal)
    assert report["valid"] and report["goal_diff"]["satisfied"]
    after = state.copy()
    assert not run_actions(after, result.plan).violations
    assert holds(parse_formula(imported.formula), facts_of(after))
    return [a.text() for a in result.plan]


def test_a_pizza_on_a_plate_in_the_fridge_is_in_the_fridge() -> None:
    # the plate goes in, so the pizza comes off first and back on after; closed at last
    plan = solved(PIZZA)
    assert len(plan) == 5 and plan[0] != "move(plate_1, in, fridge_1)", plan
    assert plan[-2:] == ["move(pizza_1, on, plate_1)", "close(fridge_1)"], plan
    assert {"open(fridge_1)", "move(plate_1, in, fridge_1)"} <= set(plan[:3]), plan
    assert plan.index("open(fridge_1)") < plan.index("move(plate_1, in, fridge_1)")


def test_books_stacked_on_books_in_the_bookcase_are_in_the_bookcase() -> None:
    plan = solved(BOOKS)
    assert len(plan) == 4 and all(step.startswith("move(") for step in plan)
