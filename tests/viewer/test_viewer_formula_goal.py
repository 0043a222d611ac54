"""The viewer page's goal box takes a formula as it takes a predicate's name."""

from __future__ import annotations

import pytest

from verigraph.graph.goal import Goal
from verigraph.viewer.inputs import plan_input

pytestmark = pytest.mark.fast


def test_a_formula_in_the_goal_box_is_a_formula_goal() -> None:
    formula = "(forall (?b - book) (ontop ?b shelf))"
    params = plan_input("cup_on_book", "move(cup, on, desk)\nmove(book, on, shelf)", formula)
    assert params.goal == Goal(formula=formula)
    assert plan_input("cup_on_book", "done", "single_stack").goal == Goal(
        predicate="single_stack")
