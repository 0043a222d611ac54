"""validate_action, execute_actions (Algorithm 1 step and tau), check_goal, validate_plan."""

from __future__ import annotations

from typing import Any

import pytest

from verigraph.errors import VeriGraphError
from verigraph.tools import EpisodeStateError, ToolArgumentError, Toolbox

pytestmark = pytest.mark.fast


@pytest.fixture()
def box() -> Toolbox:
    return Toolbox()


def episode(box: Toolbox, scene_id: str = "cup_on_book", **extra: Any) -> str:
    return str(box.call("load_scene", {"scene_id": scene_id, **extra}).episode_id)


def state(box: Toolbox, eid: str) -> Any:
    return box.call("get_state", {"episode_id": eid})


def test_validate_action_reports_the_violation_and_changes_nothing(box: Toolbox) -> None:
    eid = episode(box)
    before = state(box, eid)
    check = box.call("validate_action", {"episode_id": eid, "action": "move(book, on, shelf)"})
    assert not check.ok and check.violation.constraint == "object_not_clear"
    assert check.violation.blocking == ["cup"]
    assert "move(cup, on, desk)" in check.violation.suggestion
    assert state(box, eid) == before


def test_validate_action_predicts_the_edit_and_goal(box: Toolbox) -> None:
    eid = episode(box)
    box.call("execute_actions", {"episode_id": eid, "actions": ["move(cup, desk)"]})
    check = box.call("validate_action", {"episode_id": eid, "action": {
        "action": "move", "object": "book", "relation": "on", "target": "shelf"}})
    assert check.ok and check.goal_satisfied_after is True
    assert [e.sentence() for e in check.would_change.removed] == ["book on desk"]
    assert [e.sentence() for e in check.would_change.added] == ["book on shelf"]
    assert state(box, eid).graph.sentences() == ["book on desk", "cup on desk"]


def test_validate_action_takes_exactly_one_action(box: Toolbox) -> None:
    eid = episode(box)
    with pytest.raises(ToolArgumentError) as err:
        box.call("validate_action", {"episode_id": eid, "action": "move(cup, desk)\ndone"})
    assert err.value.field == "action" and "validate_plan" in (err.value.fix or "")


def test_execute_keeps_the_valid_prefix_and_counts_tau(box: Toolbox) -> None:
    eid = episode(box)
    out = box.call("execute_actions", {"episode_id": eid, "actions": [
        "move(cup, on, desk)", "move(desk, on, shelf)", "move(book, on, shelf)"]})
    assert out.executed == ["move(cup, on, desk)"]
    assert out.not_executed == ["move(desk, on, shelf)", "move(book, on, shelf)"]
    assert out.violation.constraint == "not_movable" and out.violation.step == 2
    assert out.tau == 1 and not out.threshold_reached and out.goal_satisfied is False
    assert out.graph.sentences() == ["book on desk", "cup on desk"]
    out = box.call("execute_actions", {"episode_id": eid, "actions": ["move(book, shelf)"]})
    assert out.ok and out.tau == 0 and out.goal_satisfied is True
    assert out.violation is None and out.edits[0].added[0].sentence() == "book on shelf"
    assert state(box, eid).executed == ["move(cup, on, desk)", "move(book, on, shelf)"]


def test_threshold_stops_the_episode(box: Toolbox) -> None:
    eid = episode(box, t=2)
    for expected_tau in (1, 2):
        out = box.call("execute_actions", {"episode_id": eid, "actions": ["move(book, shelf)"]})
        assert out.tau == expected_tau
    assert out.threshold_reached and "end_episode" in out.summary()
    with pytest.raises(EpisodeStateError) as err:
        box.call("execute_actions", {"episode_id": eid, "actions": ["move(cup, desk)"]})
    assert "end_episode" in (err.value.fix or "")


def test_more_than_k_actions_is_refused_without_changes(box: Toolbox) -> None:
    eid = episode(box, k=1)
    before = state(box, eid)
    with pytest.raises(ToolArgumentError) as err:
        box.call("execute_actions", {"episode_id": eid,
                                     "actions": ["move(cup, desk)", "move(book, shelf)"]})
    assert "k=1" in str(err.value) and err.value.field == "actions"
    assert state(box, eid) == before
    out = box.call("execute_actions", {"episode_id": eid, "actions": ["move(cup, desk)", "done"]})
    assert out.done and out.ok  # done does not count towards k


def test_unparseable_actions_change_nothing(box: Toolbox) -> None:
    eid = episode(box)
    before = state(box, eid)
    with pytest.raises(ToolArgumentError) as err:
        box.call("execute_actions", {"episode_id": eid,
                                     "actions": ["move(cup, desk)", "move(book shelf"]})
    assert err.value.field == "actions[1]" and "move(book shelf" in str(err.value)
    assert state(box, eid) == before


def test_a_text_item_may_hold_several_lines(box: Toolbox) -> None:
    eid = episode(box)
    out = box.call("execute_actions", {"episode_id": eid, "actions": [
        "# clear the book first\nmove(cup, desk)\nmove(book, shelf)\ndone"]})
    assert out.ok and out.done and len(out.executed) == 2


def test_check_goal_episode_goal_and_ad_hoc_goal(box: Toolbox) -> None:
    eid = episode(box)
    check = box.call("check_goal", {"episode_id": eid})
    assert not check.satisfied and "book on shelf" in check.diff.missing_edges
    check = box.call("check_goal", {"episode_id": eid, "goal": {"graph": {
        "nodes": [{"id": "cup", "label": "cup"}, {"id": "book", "label": "book"}],
        "edges": [{"source": "cup", "relation": "on", "target": "book"}]}, "partial": True}})
    assert check.satisfied
    assert state(box, eid).goal.graph.sentences() == ["book on shelf", "cup on desk"]


def test_check_goal_without_any_goal(box: Toolbox) -> None:
    eid = episode(box, "kitchen_pan")
    with pytest.raises(ToolArgumentError) as err:
        box.call("check_goal", {"episode_id": eid})
    assert err.value.field == "goal" and "set_goal" in (err.value.fix or "")


@pytest.mark.parametrize("plan", [
    "move(cup, desk)\nmove(book, shelf)\ndone",
    ["move(cup, desk)", {"action": "move", "object": "book", "target": "shelf"}, "done"],
])
def test_validate_plan_text_or_list(box: Toolbox, plan: Any) -> None:
    report = box.call("validate_plan", {"scene_id": "cup_on_book", "plan": plan})
    assert report.valid and report.goal_reached and report.done
    assert [s.text for s in report.steps] == ["move(cup, on, desk)", "move(book, on, shelf)"]


def test_validate_plan_all_errors_and_goal(box: Toolbox) -> None:
    report = box.call("validate_plan", {"scene_id": "cup_on_book", "all_errors": True,
                                        "plan": "move(book, shelf)\nmove(desk, shelf)"})
    assert [v.constraint for v in report.violations] == ["object_not_clear", "not_movable"]
    assert report.goal_reached is False and not report.valid


def test_validate_plan_from_an_episode_changes_nothing(box: Toolbox) -> None:
    eid = episode(box)
    box.call("execute_actions", {"episode_id": eid, "actions": ["move(cup, desk)"]})
    before = state(box, eid)
    report = box.call("validate_plan", {"episode_id": eid, "plan": "move(book, shelf)"})
    assert report.valid and report.goal_reached
    assert state(box, eid) == before


def test_validate_plan_from_a_graph_with_a_predicate(box: Toolbox) -> None:
    graph = {"nodes": [{"id": "table", "label": "table"}, {"id": "a", "label": "block"},
                       {"id": "b", "label": "block"}],
             "edges": [{"source": "a", "relation": "on", "target": "table"},
                       {"source": "b", "relation": "on", "target": "table"}],
             "dictionary": "blocks"}
    report = box.call("validate_plan", {"graph": graph, "plan": ["move(a, b)"],
                                        "goal": {"predicate": "single_stack"}})
    assert report.valid and report.final_graph.sentences() == ["a on b", "b on table"]


@pytest.mark.parametrize("args, field", [
    ({"plan": "move(cup, desk)"}, None),
    ({"scene_id": "cup_on_book", "plan": "fly(cup)"}, "plan"),
    ({"scene_id": "cup_on_book", "plan": []}, "plan"),
    ({"scene_id": "cup_on_book", "plan": ["move(cup, desk)", "jump"]}, "plan[1]"),
])
def test_validate_plan_bad_input(box: Toolbox, args: dict[str, Any], field: str | None) -> None:
    with pytest.raises(VeriGraphError) as err:
        box.call("validate_plan", args)
    if field:
        assert err.value.field == field
    else:
        assert "exactly one initial scene" in str(err.value)
