"""Goal formulas wherever a goal is accepted: set_goal (formula, or edges text starting
with '('), check_goal, validate_plan and solve (text or {formula}), in process and over
MCP; a goal not reached names every counterexample, an exists its witnesses."""

from __future__ import annotations

from typing import Any

import pytest
from mcp import Client
from mcp_helpers import in_process_client, structured, text  # noqa: F401 - the fixture

from verigraph.errors import VeriGraphError
from verigraph.tools import Toolbox
from verigraph.tools.registry import TOOLS

pytestmark = pytest.mark.fast
NO_CUP_ON_A_PLATE = "(forall (?c - cup) (not (exists (?p - plate) (ontop ?c ?p))))"
A_LID_IN_EACH_POT = "(forall (?p - pot) (exists (?l - lid) (inside ?l ?p)))"
BOTH = f"(and {NO_CUP_ON_A_PLATE} {A_LID_IN_EACH_POT})"


def kitchen() -> dict[str, Any]:
    """Three cups on two plates, two one-lid pots, lid_2 in pot_1, lid_1 on the counter."""
    nodes = [("counter", "counter", {}), ("pot_1", "pot", {"capacity": 1}),
             ("pot_2", "pot", {"capacity": 1}), ("lid_1", "lid", {}), ("lid_2", "lid", {}),
             ("plate_1", "plate", {}), ("plate_2", "plate", {}), ("cup_1", "cup", {}),
             ("cup_2", "cup", {}), ("cup_3", "cup", {})]
    edges = [("pot_1", "on", "counter"), ("pot_2", "on", "counter"), ("lid_2", "in", "pot_1"),
             ("lid_1", "on", "counter"), ("plate_1", "on", "counter"),
             ("plate_2", "on", "counter"), ("cup_1", "on", "plate_1"),
             ("cup_2", "on", "plate_1"), ("cup_3", "on", "plate_2")]
    return {"nodes": [{"id": i, "label": label, "attrs": attrs} for i, label, attrs in nodes],
            "edges": [{"source": s, "relation": r, "target": t} for s, r, t in edges]}


def said(box: Toolbox, tool: str, arguments: dict[str, Any]) -> str:
    return TOOLS[tool].summary(box.call(tool, arguments))


def test_set_goal_takes_a_formula_and_names_every_counterexample() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"graph": kitchen()}).episode_id
    out = box.call("set_goal", {"episode_id": eid, "formula": BOTH})
    assert out.goal is not None and out.goal.formula == BOTH and out.goal_satisfied is False
    assert out.goal_diff is not None and out.goal_diff.formula_count() == 4
    summary = TOOLS["set_goal"].summary(out)
    assert summary.startswith("goal set; goal not reached: formula fails (4 counterexamples): ")
    for cup, plate in (("cup_1", "plate_1"), ("cup_2", "plate_1"), ("cup_3", "plate_2")):
        assert (f"(not (exists (?p - plate) (ontop {cup} ?p))) fails: {cup} is on "
                f"{plate}") in summary
    assert ("(exists (?l - lid) (inside ?l pot_2)) fails: missing: no lid as ?l makes "
            "(inside ?l pot_2) hold; of the 2 lid(s): lid_1 is not in pot_2 (lid_1 is on "
            "counter); lid_2 is not in pot_2 (lid_2 is in pot_1)") in summary
    assert f"goal: formula {BOTH}" in summary
    # edges text starting with '(' is the same formula
    again = box.call("set_goal", {"episode_id": eid, "edges": BOTH})
    assert again.goal == out.goal


def test_a_bad_formula_changes_nothing_and_says_where_and_how() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"graph": kitchen()}).episode_id
    box.call("set_goal", {"episode_id": eid, "formula": A_LID_IN_EACH_POT})
    for args, field, words in [
        ({"formula": "(forall (?c - cup) (ontop ?c plate_1)"}, "formula",
         "character 38: the formula ends with 1 parenthesis(es) open"),
        ({"edges": "(ontop cup_9 plate_1)"}, "edges", "object 'cup_9' (did you mean cup_3?)"),
        ({"formula": "(forall (?c - cupz) (ontop ?c plate_1))"}, "formula", "kind 'cupz'"),
    ]:
        with pytest.raises(VeriGraphError) as refused:
            box.call("set_goal", {"episode_id": eid, **args})
        assert refused.value.field == field and words in refused.value.message, \
            refused.value.message
        assert refused.value.fix
    kept = box.call("get_state", {"episode_id": eid})
    assert kept.goal is not None and kept.goal.formula == A_LID_IN_EACH_POT


def test_check_goal_and_validate_plan_take_formula_text_or_json() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"graph": kitchen()}).episode_id
    reached = said(box, "check_goal", {"episode_id": eid,
                                       "goal": {"formula": "(exists (?l - lid) (inside ?l "
                                                           "pot_1))"}})
    assert reached == "goal reached; (exists (?l - lid) (inside ?l pot_1)) holds with ?l = lid_2"
    missed = said(box, "check_goal", {"episode_id": eid, "goal": A_LID_IN_EACH_POT})
    assert missed.startswith("goal not reached: formula fails (1 counterexample): (exists "
                             "(?l - lid) (inside ?l pot_2)) fails: missing: no lid")
    plan = "move(cup_1, on, counter)\nmove(cup_2, on, counter)\nmove(lid_1, in, pot_2)"
    report = said(box, "validate_plan", {"graph": kitchen(), "goal": BOTH, "plan": plan})
    assert report.startswith("INVALID: 3 step(s) checked; goal not reached: formula fails "
                             "(1 counterexample): (not (exists (?p - plate) (ontop cup_3 ?p))) "
                             "fails: cup_3 is on plate_2")
    done = said(box, "validate_plan", {"graph": kitchen(), "goal": {"formula": BOTH},
                                       "plan": plan + "\nmove(cup_3, on, counter)"})
    assert done.startswith("VALID: 4 step(s) checked; goal reached")
    with pytest.raises(VeriGraphError) as refused:
        box.call("check_goal", {"episode_id": eid, "goal": "(ontop cup_1"})
    assert refused.value.field == "goal" and "parenthesis(es) open" in refused.value.message


def test_solve_is_optimal_over_the_formula_not_over_one_naming() -> None:
    box = Toolbox()
    named = ("lid_1 in pot_1; lid_2 in pot_2; cup_1 on counter; cup_2 on counter; "
             "cup_3 on counter")
    one_by_one = said(box, "solve", {"graph": kitchen(), "goal": named})
    assert one_by_one.startswith("plan of 5 action(s), verified, optimal")
    formula = said(box, "solve", {"graph": kitchen(), "goal": BOTH})
    assert formula.startswith("plan of 4 action(s), verified, optimal (no plan has fewer "
                              "moves)")
    assert "move(lid_1, in, pot_2)" in formula
    eid = box.call("load_scene", {"graph": kitchen()}).episode_id
    box.call("set_goal", {"episode_id": eid, "formula": BOTH})
    out = box.call("solve", {"episode_id": eid})
    assert out.optimal and out.verified and out.length == 4
    # a budget that stops the search says so, and never calls the plan optimal
    stopped = box.call("solve", {"graph": kitchen(), "goal": BOTH, "max_expansions": 1})
    assert not stopped.optimal


@pytest.mark.anyio
async def test_formula_goals_over_mcp(client: Client) -> None:
    eid = structured(await client.call_tool("load_scene", {"graph": kitchen(), "k": 4})
                     )["episode_id"]
    goal = await client.call_tool("set_goal", {"episode_id": eid, "formula": BOTH})
    data = structured(goal)
    assert data["goal"]["formula"] == BOTH
    assert len(data["goal_diff"]["formula_detail"]) == 4
    assert "formula fails (4 counterexamples)" in text(goal)
    solved = await client.call_tool("solve", {"episode_id": eid})
    assert structured(solved)["optimal"] is True and structured(solved)["length"] == 4
    executed = await client.call_tool("execute_actions", {
        "episode_id": eid, "actions": structured(solved)["plan"]})
    assert structured(executed)["goal_satisfied"] is True
    checked = await client.call_tool("check_goal", {"episode_id": eid})
    assert text(checked).startswith("goal reached; (exists (?l - lid) (inside ?l pot_1)) "
                                    "holds with ?l = lid_2")
    bad = await client.call_tool("set_goal", {"episode_id": eid, "formula": "(onn a b)"})
    assert bad.is_error and "character 2" in text(bad) and "ontop" in text(bad)


def party() -> dict[str, Any]:
    """After the party: plates to stack on the tray, cups on plates, spoons in cups."""
    nodes = [("table", "table", {}), ("shelf", "shelf", {}), ("tray", "tray", {}),
             ("plate_a", "plate", {"width": 10}), ("plate_b", "plate", {"width": 18}),
             ("plate_c", "plate", {"width": 14}), ("cup_1", "cup", {}), ("cup_2", "cup", {}),
             ("cup_3", "cup", {}), ("spoon_1", "spoon", {}), ("spoon_2", "spoon", {}),
             ("bowl", "bowl", {})]
    edges = [("tray", "on", "table"), ("plate_b", "on", "tray"), ("cup_2", "on", "plate_b"),
             ("plate_a", "on", "shelf"), ("cup_1", "on", "plate_a"), ("spoon_1", "in", "cup_1"),
             ("plate_c", "on", "table"), ("bowl", "on", "plate_c"), ("cup_3", "on", "table"),
             ("spoon_2", "in", "cup_3")]
    return {"nodes": [{"id": i, "label": label, "attrs": attrs} for i, label, attrs in nodes],
            "edges": [{"source": s, "relation": r, "target": t} for s, r, t in edges],
            "dictionary": "tableware"}


def test_the_party_request_is_said_as_asked_and_solved_optimally() -> None:
    """"No cup may stay on any plate, no spoon in any cup, the plates stacked on the tray
    largest first": a model could only approximate this by naming a place for every cup
    and spoon; as a formula it is the request itself."""
    request = """(and (forall (?c - cup) (not (exists (?p - plate) (ontop ?c ?p))))
                      (forall (?s - spoon) (not (exists (?c - cup) (inside ?s ?c))))
                      (ontop plate_b tray) (ontop plate_c plate_b) (ontop plate_a plate_c))"""
    box = Toolbox()
    eid = box.call("load_scene", {"graph": party(), "k": 7}).episode_id
    goal = box.call("set_goal", {"episode_id": eid, "formula": request})
    assert goal.goal_diff is not None and goal.goal_diff.formula_count() == 6
    text = TOOLS["set_goal"].summary(goal)
    for failing in ("cup_1 is on plate_a", "cup_2 is on plate_b", "spoon_1 is in cup_1",
                    "spoon_2 is in cup_3", "plate_c is not on plate_b (plate_c is on table)",
                    "plate_a is not on plate_c (plate_a is on shelf)"):
        assert failing in text, failing
    solved = box.call("solve", {"episode_id": eid})
    assert solved.optimal and solved.verified and solved.length == 7
    assert solved.expanded < 100  # the bound sees the bowl that must leave plate_c
    run = box.call("execute_actions", {"episode_id": eid, "actions": solved.plan})
    assert run.goal_satisfied is True


def test_a_commented_formula_is_shown_on_one_line_as_read() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"graph": kitchen()}).episode_id
    written = """; after dinner
    (and (forall (?c - cup) (not (exists (?p - plate) (ontop ?c ?p))))  ; cups off plates
         (forall (?p - pot) (exists (?l - lid) (inside ?l ?p))))        ; a lid per pot"""
    out = box.call("set_goal", {"episode_id": eid, "edges": written})
    assert out.goal is not None and out.goal.formula == written.strip()
    assert f"goal: formula {BOTH}" in TOOLS["set_goal"].summary(out)
    state = TOOLS["get_state"].summary(box.call("get_state", {"episode_id": eid}))
    assert f"goal: formula {BOTH}" in state


def test_load_scene_takes_a_formula_goal_and_checks_its_names() -> None:
    box = Toolbox()
    out = box.call("load_scene", {"graph": kitchen(), "goal": {"formula": BOTH}})
    state = box.call("get_state", {"episode_id": out.episode_id})
    assert state.goal is not None and state.goal.formula == BOTH
    assert state.goal_diff is not None and state.goal_diff.formula_count() == 4
    with pytest.raises(VeriGraphError) as refused:
        box.call("load_scene", {"graph": kitchen(),
                                "goal": {"formula": "(forall (?b - bowll) (on ?b counter))"}})
    assert refused.value.field == "goal.formula" and "kind 'bowll'" in refused.value.message


# (formula, meanings the text states): a formula's own reading of `inside` and
# `nextto` (beyond the edge) is said where the formula uses the word, and only there.
MEANINGS = [(A_LID_IN_EACH_POT, ["inside"]), (NO_CUP_ON_A_PLATE, []),
            ("(and (inside lid_1 pot_1) (nextto cup_1 cup_2))", ["inside", "nextto"])]


@pytest.mark.parametrize(("formula", "stated"), MEANINGS)
def test_what_a_formula_means_by_inside_and_nextto_is_said(formula: str,
                                                            stated: list[str]) -> None:
    from verigraph.graph.formula_eval import FORMULA_MEANINGS
    from verigraph.graph.goal import Goal
    from verigraph.prompts.filling import goal_section

    box = Toolbox()
    eid = box.call("load_scene", {"graph": kitchen()}).episode_id
    summary = said(box, "set_goal", {"episode_id": eid, "formula": formula})
    prompt = goal_section(Goal(formula=formula))
    for word, meaning in FORMULA_MEANINGS.items():
        assert (meaning in summary) is (word in stated), summary
        assert (meaning in prompt) is (word in stated), prompt

