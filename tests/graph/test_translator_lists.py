"""The rule-based translator keeps every object a request names: comma lists stay whole,
"with the knife on it" names the board, "lying on" is "on", and a place that cannot hold
every object asked for is said (`unplaced`, with why), never left out silently."""

from __future__ import annotations

import pytest

from llm_trials import THIRD_SET, with_attachments
from verigraph.graph.model import SceneGraph
from verigraph.graph.translator import TranslationError, read_instruction, translate

pytestmark = pytest.mark.fast


def kitchen() -> SceneGraph:
    return SceneGraph.model_validate(
        with_attachments(THIRD_SET / "t10_dinner", "@json:./start.json"))


def test_a_comma_list_on_a_place_keeps_its_first_object() -> None:
    reading = read_instruction("put the pot, the frying pan and the kettle on the stove",
                               kitchen())
    assert [e.sentence() for e in reading.edges] == ["pan on stove", "pot on stove"]
    assert [edge for edge, _ in reading.unplaced] == ["kettle on stove"]
    why = reading.unplaced[0][1]
    assert why.startswith("stove holds 2") and "(pot, pan, kettle)" in why
    assert not reading.not_understood


def test_with_it_names_the_object_before_and_lying_on_is_on() -> None:
    reading = read_instruction("the cutting board on the counter with the knife on it, and "
                               "the spoon lying on the shelf", kitchen())
    assert [e.sentence() for e in reading.edges] == [
        "cutting_board on counter", "knife on cutting_board", "spoon on shelf"]
    assert not reading.not_understood and not reading.unplaced


def test_translate_refuses_what_cannot_be_placed_and_says_why() -> None:
    with pytest.raises(TranslationError, match=r"cannot place 'kettle on stove': stove holds 2"):
        translate("the pot, the pan and the kettle on the stove", kitchen())
