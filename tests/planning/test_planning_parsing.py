"""Reading model answers: every accepted form, and feedback for every malformed one."""

from __future__ import annotations

import pytest

from verigraph.actions import DoneAction, MoveAction
from verigraph.graph.builtin_scenes import cup_on_book
from verigraph.planning.parsing import ParseFailure, parse_answer, parse_tool_input
from verigraph.planning.schema import action_schema, format_instruction

pytestmark = pytest.mark.fast

CUP = MoveAction(object="cup", relation="on", target="desk")


@pytest.mark.parametrize("text", [
    '{"actions": [{"action": "move", "object": "cup", "relation": "on", "target": "desk"}, '
    '{"action": "done"}]}',
    '[{"action": "move", "object": "cup", "relation": "on", "target": "desk"}, '
    '{"action": "done"}]',
    'Here you go:\n```json\n{"actions": [{"action": "move", "object": "cup", "relation": '
    '"on", "target": "desk"}, {"action": "done"}]}\n```',
    "move(cup, on, desk)\ndone",
    "1. move(cup, desk)\n2. done",
    '{"actions": ["move(cup, on, desk)", "done"]}',
])
def test_accepted_forms(text: str) -> None:
    assert parse_answer(text) == [CUP, DoneAction()]


def test_single_action_object() -> None:
    assert parse_answer('{"action": "done"}') == [DoneAction()]


@pytest.mark.parametrize(("text", "needle"), [
    ("", "empty"),
    ('{"actions": [{"action": "move", "object": "cup"', "not valid JSON"),
    ('{"actions": [{"action": "move", "object": "cup", "relation": "on"}]}',
     "actions[0].target: Field required"),
    ('{"actions": [{"action": "fly", "object": "cup"}]}', "actions[0]"),
    ('{"actions": "move(cup, desk)"}', "'actions' must be a list"),
    ('{"plan": []}', "expected an object with an 'actions' list"),
    ("I think we should move the cup first.", "could not read the answer"),
])
def test_malformed_answers_explain_what_to_fix(text: str, needle: str) -> None:
    with pytest.raises(ParseFailure) as info:
        parse_answer(text)
    assert needle in str(info.value)


def test_truncated_answers_say_so() -> None:
    with pytest.raises(ParseFailure, match="cut off by the token limit"):
        parse_answer('{"actions": [{"action": "move", "obj', truncated=True)
    # a truncated answer that still parses completely is accepted
    assert parse_answer('{"action": "done"}', truncated=True) == [DoneAction()]


def test_tool_input() -> None:
    data = {"actions": [{"action": "move", "object": "cup", "relation": "on",
                         "target": "desk"}]}
    assert parse_tool_input(data) == [CUP]
    with pytest.raises(ParseFailure):
        parse_tool_input({"actions": [{"action": "move"}]})


def test_schema_is_strict_subset_and_enumerates_scene_ids() -> None:
    schema = action_schema(cup_on_book())
    assert schema["required"] == ["actions"] and schema["additionalProperties"] is False
    variants = schema["properties"]["actions"]["items"]["anyOf"]
    move = variants[0]
    assert move["properties"]["object"]["enum"] == ["book", "cup", "desk", "shelf"]
    assert set(move["required"]) == set(move["properties"])
    assert [v["properties"]["action"]["enum"] for v in variants] == [["move"], ["done"]]
    text = repr(schema)
    for banned in ("const", "maxItems", "minimum", "maxLength"):
        assert banned not in text
    free = action_schema(cup_on_book(), constrain_ids=False)
    assert "enum" not in free["properties"]["actions"]["items"]["anyOf"][0]["properties"][
        "object"]
    assert "at most 3 actions" in format_instruction(3)
