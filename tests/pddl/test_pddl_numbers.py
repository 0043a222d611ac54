"""Numbers in PDDL: action costs counted from the initial `(= (total-cost) N)` as VAL
counts them, totals printed in a fixed format, and numbers that are no finite decimal
(`1e999`, `nan`, `inf`) refused by name on every surface (library, `verigraph validate`
text and `--json`, `--batch`, `verigraph val`, the MCP tool), never a traceback."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from mcp import Client
from mcp_helpers import in_process_client, structured, text  # noqa: F401 - the client fixture
from roads import ROADS

from verigraph.actions.pddl import as_validation_report
from verigraph.cli import main as verigraph_main
from verigraph.cli import val
from verigraph.pddl import (
    PddlInputError,
    validate_pddl_dict,
)
from verigraph.reporting import report_text

pytestmark = pytest.mark.fast

TRIP = """(define (problem trip) (:domain roads) (:objects x y z - place)
  (:init (at x) (road x y) (road y z)
         (= (road-length x y) {xy}) (= (road-length y z) 5) {start})
  (:goal (at z)) (:metric minimize (total-cost)))
"""
PLAN = "(drive x y)\n(drive y z)\n"
BLOCKS = (Path(__file__).parents[1] / "data" / "blocksworld")


def trip(xy: str = "3", start: str = "(= (total-cost) 10)") -> str:
    return TRIP.format(xy=xy, start=start)


# -- the initial total-cost ---------------------------------------------------------------

def test_the_initial_total_cost_is_counted_as_val_counts_it(capsys, tmp_path):
    """VAL's `Final value` is total-cost at the end: its initial value plus the plan's
    increases (10 + 3 + 5 = 18), in the JSON report, its text, the MCP text and `val`."""
    report = validate_pddl_dict(ROADS, trip(), PLAN)
    assert report["valid"] and report["total_cost"] == 18
    assert "plan cost 18 " in report_text(report)
    assert "total cost 18" in (as_validation_report(report).goal_diff.detail or "")
    assert validate_pddl_dict(ROADS, trip(start=""), PLAN)["total_cost"] == 8
    stepwise = validate_pddl_dict(ROADS, trip(), PLAN, all_errors=True)
    assert stepwise["total_cost"] == 18
    failing = validate_pddl_dict(ROADS, trip(), "(drive x y)\n(drive x y)\n")
    assert failing["total_cost"] == 13  # the start and the one applied step
    for name, body in (("d.pddl", ROADS), ("p.pddl", trip()), ("plan", PLAN)):
        (tmp_path / name).write_text(body)
    assert val.run([str(tmp_path / n) for n in ("d.pddl", "p.pddl", "plan")]) == 0
    assert "Plan valid\nFinal value: 18 \n" in capsys.readouterr().out


def test_a_blocks_world_with_costs_counts_them_on_either_engine():
    """The native blocks-world engine reports the total cost the STRIPS engine reports."""
    domain = (BLOCKS / "planbench_domain.pddl").read_text()
    costed = domain.replace("(:predicates", "(:functions (total-cost))\n(:predicates")
    costed = costed.replace(":effect\n", ":effect\n").replace(
        ":effect (and", ":effect (and (increase (total-cost) 2)")
    costed = costed.replace("(:requirements :strips", "(:requirements :strips :action-costs")
    assert costed.count("(increase (total-cost) 2)") == 4, costed
    problem = (BLOCKS / "planbench_instance.pddl").read_text()
    problem = problem.replace("(:init", "(:init (= (total-cost) 7)")
    plan = (BLOCKS / "planbench_plan.pddl").read_text()
    native = validate_pddl_dict(costed, problem, plan)
    strips = validate_pddl_dict(costed, problem, plan, engine="strips")
    assert native["engine"] == "blocksworld" and strips["engine"] == "strips"
    assert native["valid"] and native["total_cost"] == strips["total_cost"] == 7 + 2 * 4


# -- numbers that are no finite decimal -------------------------------------------------------

BAD_NUMBERS = ["1e999", "nan", "inf", "-inf", "Infinity", "1_000", "NaN"]


@pytest.mark.parametrize("number", BAD_NUMBERS)
@pytest.mark.parametrize("where", ["value", "start"])
def test_a_number_that_is_no_finite_decimal_is_refused_by_name(number: str, where: str):
    problem = trip(xy=number) if where == "value" else trip(start=f"(= (total-cost) {number})")
    with pytest.raises(PddlInputError) as caught:
        validate_pddl_dict(ROADS, problem, PLAN)
    error = caught.value
    assert error.field == "problem" and error.value == number.lower()
    assert f"'{number.lower()}'" in error.message and error.fix


@pytest.mark.parametrize("number", ["1e999", "nan", "-1", "1_0"])
def test_a_domain_cost_that_is_no_finite_non_negative_decimal_is_refused(number: str):
    domain = ROADS.replace("(increase (total-cost) (road-length ?a ?b))",
                           f"(increase (total-cost) {number})")
    with pytest.raises(PddlInputError, match=f"'{number}'") as caught:
        validate_pddl_dict(domain, trip(), PLAN)
    assert caught.value.field == "domain"


def test_a_negative_cost_value_is_refused_as_a_negative_cost_in_the_domain_is():
    with pytest.raises(PddlInputError, match="'-3'") as caught:
        validate_pddl_dict(ROADS, trip(xy="-3"), PLAN)
    assert "negative" in caught.value.message or ">= 0" in caught.value.fix


def test_a_blocks_world_problem_with_a_bad_number_is_refused_too():
    domain = (BLOCKS / "planbench_domain.pddl").read_text()
    problem = (BLOCKS / "planbench_instance.pddl").read_text()
    with pytest.raises(PddlInputError, match="'nan'"):
        validate_pddl_dict(domain, problem.replace("(:init", "(:init (= (total-cost) nan)"),
                           "")


def _files(tmp_path: Path, problem: str) -> list[str]:
    for name, body in (("d.pddl", ROADS), ("p.pddl", problem), ("plan", PLAN)):
        (tmp_path / name).write_text(body)
    return ["--domain", str(tmp_path / "d.pddl"), "--problem", str(tmp_path / "p.pddl"),
            "--plan", str(tmp_path / "plan")]


@pytest.mark.parametrize("number", ["1e999", "nan"])
def test_the_command_line_refuses_a_bad_number_without_a_traceback(capsys, tmp_path,
                                                                   number: str):
    args = _files(tmp_path, trip(xy=number))
    assert verigraph_main(["validate", *args]) == 2
    out, err = capsys.readouterr()
    assert out == "" and f"'{number}'" in err and "Traceback" not in err
    assert verigraph_main(["validate", *args, "--json"]) == 2
    out, err = capsys.readouterr()
    data = json.loads(out)
    assert data["error"] == "PddlInputError" and data["value"] == number
    (tmp_path / "items.jsonl").write_text(json.dumps(
        {"id": "n", "domain": "d.pddl", "problem": "p.pddl", "plan": "plan"}) + "\n")
    assert verigraph_main(["validate", "--batch", str(tmp_path / "items.jsonl"),
                           "--no-progress"]) == 1
    line = json.loads(capsys.readouterr().out)
    assert line["error"] == "PddlInputError" and f"'{number}'" in line["message"]
    assert val.run([str(tmp_path / n) for n in ("d.pddl", "p.pddl", "plan")]) == 255
    out, err = capsys.readouterr()
    assert f"'{number}'" in err and "Traceback" not in err


@pytest.mark.anyio
async def test_mcp_refuses_a_bad_number_naming_it(client: Client) -> None:
    pddl = {"domain": ROADS, "problem": trip(xy="1e999")}
    refused = await client.call_tool("validate_plan", {"plan": PLAN, "pddl": pddl})
    assert refused.is_error and "'1e999'" in text(refused) and "pddl.problem" in text(refused)
    fine = await client.call_tool("validate_plan", {"plan": PLAN, "pddl": {
        "domain": ROADS, "problem": trip()}})
    assert "plan cost 18 " in text(fine) and structured(fine)["valid"]


# -- how totals are written -----------------------------------------------------------------

@pytest.mark.parametrize(("xy", "total", "shown"), [
    ("3", 18, "18"), ("2.5", 17.5, "17.5"), ("1e300", 1e300, "1e+300"),
    ("1e308", 1e308, "1e+308"), ("0.1", 15.1, "15.1"),
])
def test_a_total_is_an_integer_when_integral_and_small_else_a_float(xy: str, total: float,
                                                                    shown: str):
    report = validate_pddl_dict(ROADS, trip(xy=xy), PLAN)
    assert report["total_cost"] == total
    assert isinstance(report["total_cost"], int) is (shown == "18")
    assert f"plan cost {shown} " in report_text(report)
    assert len(json.dumps(report["total_cost"])) < 25


def test_a_total_beyond_the_largest_double_is_refused_not_printed():
    problem = trip(xy="1.7e308", start="(= (total-cost) 1.7e308)")
    with pytest.raises(PddlInputError, match="total cost") as caught:
        validate_pddl_dict(ROADS, problem, PLAN)
    assert caught.value.fix
