"""Plan parsing: text and JSON, errors with line and column, linear time."""

import time

import pytest

from verigraph.actions import AlignAction, MoveAction, parse_plan
from verigraph.actions.model import DoneAction
from verigraph.actions.parser import parse_text_plan
from verigraph.errors import PlanParseError

pytestmark = pytest.mark.fast


def test_text_plan_with_comments_shorthand_and_done():
    plan = parse_plan("""# clear the book first
move(cup, on, table)
move(book, shelf)   # shorthand for on
move(spoon, in, cup)
align(small_triangle_1, 1, square, 3)
done
""")
    assert plan == [MoveAction(object="cup", relation="on", target="table"),
                    MoveAction(object="book", relation="on", target="shelf"),
                    MoveAction(object="spoon", relation="in", target="cup"),
                    AlignAction(object="small_triangle_1", side=1, target="square",
                                target_side=3),
                    DoneAction()]


def test_numbered_llm_style_lines_are_accepted():
    assert parse_plan("1. move(cup, table)\n2) done")[0].target == "table"


def test_json_plans():
    assert parse_plan('[{"action": "move", "object": "cup", "target": "table"}, '
                      '{"action": "done"}]')[0].relation == "on"
    assert parse_plan({"actions": ["move(cup, table)"]})[0].object == "cup"


@pytest.mark.parametrize("text,line,column,fragment", [
    ("move(cup, on, table)\nmove(cup on table)", 2, 6, "2 or 3 arguments"),
    ("shove(cup, table)", 1, 1, "unknown action"),
    ("move(cup, , table)", 1, 11, "empty argument"),
    ("align(square, one, parallelogram, 2)", 1, 15, "not a whole number"),
    ("move cup to table", 1, 1, "not an action"),
    ("done\nmove(cup, table)", 2, 1, "after done"),
    ("  move(cup, on, ta ble)", 1, 17, "not a valid"),
])
def test_parse_errors_name_line_column_and_expected_form(text, line, column, fragment):
    with pytest.raises(PlanParseError) as err:
        parse_plan(text)
    e = err.value
    assert (e.line, e.column) == (line, column)
    assert fragment in e.message and e.expected


def test_empty_plan_is_an_error():
    with pytest.raises(PlanParseError, match="empty"):
        parse_plan("# nothing to do\n\n")


def test_bad_json_plan_names_the_action_and_field():
    with pytest.raises(PlanParseError) as err:
        parse_plan('[{"action": "move", "object": "cup"}]')
    assert "target" in err.value.message and err.value.line == 1
    with pytest.raises(PlanParseError, match="invalid JSON"):
        parse_plan('[{"action": ')


def test_parsing_is_linear_in_plan_length():
    def timed(n):
        text = "move(cup, on, table)\n" * n
        start = time.perf_counter()
        assert len(parse_plan(text)) == n
        return time.perf_counter() - start

    small, large = timed(10_000), timed(100_000)
    # Linear would be 10x; allow generous noise but catch quadratic behaviour (100x).
    assert large < small * 30


def test_every_bad_line_is_reported_and_the_location_once():
    plan = "move(cup, desk)\nmove(book shelf\nfoo(bar)\nmove(cup, table)\nmove(,x)\n"
    with pytest.raises(PlanParseError) as err:
        parse_text_plan(plan)
    e = err.value
    assert (e.line, e.column) == (2, 1)
    assert [(m.line, m.message) for m in e.more] == [
        (3, "unknown action 'foo'"), (5, "empty argument")]
    text = str(e)
    assert text.startswith("plan line 2, column 1: not an action; also line 3, column 1: ")
    assert text.count("line 2") == 1 and "line 5, column" in text
