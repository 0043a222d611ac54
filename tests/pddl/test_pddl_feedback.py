"""STRIPS and renamed blocks worlds: feedback in the domain's names, explanations, bad input,
PlanBench's verification answer, the CLI and the MCP tool."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from mcp import Client
from mcp_helpers import in_process_client, structured, text  # noqa: F401 - the client fixture

from pddl_corpus import PDDL_DATA
from verigraph.errors import PlanParseError
from verigraph.pddl import (
    PddlInputError,
    UnsupportedRequirementError,
    planbench_verdict,
    validate_pddl_dict,
)
from verigraph.pddl.syntax import MAX_DEPTH, PddlSyntaxError
from verigraph.reporting import report_text

MYSTERY = (PDDL_DATA / "mystery_domain.pddl").read_text()
MYSTERY_PROBLEM = (PDDL_DATA / "mystery_instance.pddl").read_text()  # b craves c; goal c craves b
LOGISTICS = (PDDL_DATA / "logistics_typed_domain.pddl").read_text()
LOG_PROBLEM = """(define (problem two) (:domain logistics-typed)
(:objects c0 - city l0 - location ap - airport t0 - truck a0 - airplane p0 - package)
(:init (in-city l0 c0) (in-city ap c0) (in-city hub c0) (at t0 l0) (at p0 l0) (at a0 ap))
(:goal (and (at p0 ap))))"""


def test_mystery_blocksworld_is_native_with_feedback_in_its_own_names():
    bad = validate_pddl_dict(MYSTERY, MYSTERY_PROBLEM, "(attack a)\n(overcome a d)\n(attack b)")
    assert bad["engine"] == "blocksworld"
    v = bad["violations"][0]
    assert (v["step"], v["constraint"]) == (3, "wrong_source")  # b craves c: b is not planet
    assert "(planet b)" in v["message"] and v["suggestion"] == "(feast b c)"
    assert [(u["literal"], u["explanation"]) for u in v["unsatisfied"]] == \
        [("(planet b)", "never true")]
    full = validate_pddl_dict(MYSTERY, MYSTERY_PROBLEM, "(attack a)\n(attack d)")
    v = full["violations"][0]
    assert v["constraint"] == "hand_full" and "(pain a)" in v["message"]
    assert "(succumb a)" in v["suggestion"]
    (u,) = v["unsatisfied"]
    assert u["literal"] == "(harmony)" and u["last_changed"] == {"step": 1, "action": "(attack a)"}
    good = validate_pddl_dict(MYSTERY, MYSTERY_PROBLEM,
                              "feast object b from object c\nsuccumb object b\n"
                              "attack object c\novercome object c from object b")
    assert good["valid"] and good["engine"] == "blocksworld"


def test_strips_names_the_precondition_the_step_that_broke_it_and_an_achiever():
    plan = "(drive-truck t0 l0 ap c0)\n(load-truck p0 t0 l0)"
    report = validate_pddl_dict(LOGISTICS, LOG_PROBLEM, plan)
    assert report["engine"] == "strips" and not report["valid"]
    v = report["violations"][0]
    assert v["step"] == 2 and v["constraint"] == "precondition_unsatisfied"
    (u,) = v["unsatisfied"]
    assert u["literal"] == "(at t0 l0)"
    assert u["last_changed"] == {"step": 1, "action": "(drive-truck t0 l0 ap c0)"}
    assert any(a["applicable_now"] == "(drive-truck t0 ap l0 c0)" for a in u["achievers"])
    assert "drive-truck t0 ap l0 c0" in v["suggestion"]


def test_never_true_and_negative_and_equality_preconditions_are_explained():
    r = validate_pddl_dict(LOGISTICS, LOG_PROBLEM, "(load-airplane p0 a0 ap)")
    u = r["violations"][0]["unsatisfied"][0]
    assert u["explanation"] == "never true; instead (at p0 l0) holds (true since the start)"
    assert u["instead"] == [{"literal": "(at p0 l0)", "since": "true since the start"}]
    r = validate_pddl_dict(LOGISTICS, LOG_PROBLEM, "(drive-truck t0 l0 l0 c0)")
    (u,) = r["violations"][0]["unsatisfied"]
    assert u["literal"] == "(not (= l0 l0))" and "same object" in u["explanation"]
    broken = LOG_PROBLEM.replace("(at t0 l0)", "(at t0 l0) (broken t0)")
    r = validate_pddl_dict(LOGISTICS, broken, "(load-truck p0 t0 l0)")
    (u,) = r["violations"][0]["unsatisfied"]
    assert u["literal"] == "(not (broken t0))" and u["explanation"].startswith("true in the init")


def test_unmet_goal_lists_the_actions_that_achieve_it():
    plan = "(load-truck p0 t0 l0)\n(drive-truck t0 l0 ap c0)"
    r = validate_pddl_dict(LOGISTICS, LOG_PROBLEM, plan)
    assert r["plan_valid"] and not r["goal_reached"]
    (g,) = r["unmet_goals"]
    assert g["literal"] == "(at p0 ap)" and g["explanation"].startswith("never true")
    assert g["achievers"][0]["applicable_now"] == "(unload-truck p0 t0 ap)"
    assert "(unload-airplane p0 ?airplane ap)" in [a["action"] for a in g["achievers"]]
    text = report_text(r)
    assert "unload-truck p0 t0 ap" in text
    assert text.startswith("INVALID: 2 step(s) checked; goal not reached: missing: (at p0 ap)")
    assert "unmet goal (at p0 ap): never true" in text
    assert planbench_verdict(r) == {"valid": False, "unmet_goal": ["at_p0_ap"], "message":
                                    "The above plan is invalid. This is the unmet goal "
                                    "condition:\n(at p0 ap)"}


def test_planbench_verdict_for_an_inexecutable_step():
    r = validate_pddl_dict(MYSTERY, MYSTERY_PROBLEM, "(attack b)")
    pb = planbench_verdict(r)
    assert pb["unmet_precondition"] == {"action": "(attack b)", "predicate": ["planet_b"]}
    assert "step 1 has an unmet precondition" in pb["message"]


def test_type_errors_and_unknown_objects_fail_their_step():
    r = validate_pddl_dict(LOGISTICS, LOG_PROBLEM, "(load-truck p0 a0 l0)")
    assert r["violations"][0]["constraint"] == "wrong_type"
    assert "a0 is a airplane" in r["violations"][0]["message"]
    r = validate_pddl_dict(LOGISTICS, LOG_PROBLEM, "(load-truck p9 t0 l0)")
    assert r["violations"][0]["constraint"] == "unknown_object"


@pytest.mark.parametrize("edit,error,fragment", [
    (lambda d: d.replace(":negative-preconditions", ":durative-actions"),
     UnsupportedRequirementError, ":durative-actions"),
    (lambda d: d.replace("(not (broken ?truck)))\n    :effect (and (not (at ?pkg ?loc))",
                         "(> (fuel ?truck) 1))\n    :effect (and (not "
                         "(at ?pkg ?loc))", 1), UnsupportedRequirementError,
     ":numeric-fluents"),
    (lambda d: d.replace("(in ?pkg ?truck)))", "(in ?pkg ?truck) (wet ?pkg)))", 1),
     PddlInputError, "wet"),
    (lambda d: d.replace("(:constants hub - airport)", "(:constants hub - seaport)"),
     PddlInputError, "seaport"),
    (lambda d: d.replace("(at ?truck ?loc) (at ?pkg ?loc)", "(at ?truck ?place) (at ?pkg ?loc)",
                         1), PddlInputError, "?place"),
])
def test_bad_domains_are_refused_naming_what(edit, error, fragment):
    with pytest.raises(error) as err:
        validate_pddl_dict(edit(LOGISTICS), LOG_PROBLEM, "")
    assert fragment in str(err.value)


def test_bad_problems_and_plans_are_refused_naming_what():
    with pytest.raises(PddlInputError, match="ap is a airport, but argument 1 of at"):
        validate_pddl_dict(LOGISTICS, LOG_PROBLEM.replace("(at t0 l0)", "(at ap l0)"), "")
    with pytest.raises(PddlInputError, match="'zz'"):
        validate_pddl_dict(LOGISTICS, LOG_PROBLEM.replace("(at t0 l0)", "(at t0 zz)"), "")
    r = validate_pddl_dict(LOGISTICS, LOG_PROBLEM, "(load-truck p0 t0 l0)\n(fly a0)")
    v = r["violations"][0]  # a plan line that is no action is a failing step
    assert (r["valid"], v["step"], v["constraint"]) == (False, 2, "malformed_action")
    assert "line 2" in v["message"] and "fly" in v["message"] and "fly-airplane" in v["suggestion"]
    r = validate_pddl_dict(LOGISTICS, LOG_PROBLEM, "(load-truck p0 t0)")
    v = r["violations"][0]
    assert (v["step"], v["constraint"]) == (1, "malformed_action")
    assert v["suggestion"] == "write (load-truck ?pkg ?truck ?loc)"


def test_deep_nesting_and_non_ascii_names_are_refused_with_the_line():
    deep = LOG_PROBLEM.replace("(:goal (and (at p0 ap))))",
                               "(:goal\n" + "(and " * 100_000 + ")" * 100_000 + "))")
    with pytest.raises(PddlSyntaxError, match=f"more than {MAX_DEPTH} deep on line 5"):
        validate_pddl_dict(LOGISTICS, deep, "")
    with pytest.raises(PddlSyntaxError, match="line 2 is not ASCII"):
        validate_pddl_dict(LOGISTICS, LOG_PROBLEM.replace("p0 - package", "блок - package"), "")
    ok_comment = LOG_PROBLEM + "\n; 積み木 in a comment is fine"
    assert validate_pddl_dict(LOGISTICS, ok_comment, "")["plan_valid"]
    with pytest.raises(PlanParseError, match="ASCII"):
        validate_pddl_dict(MYSTERY, MYSTERY_PROBLEM, "(attack 積み木)")


def test_huge_object_lists_are_refused_within_the_budget():
    many = " ".join(f"o{i}" for i in range(100_001))
    problem = LOG_PROBLEM.replace("p0 - package)", f"p0 - package {many} - package)")
    with pytest.raises(PddlInputError, match="objects"):
        validate_pddl_dict(LOGISTICS, problem, "")


def run(*args, cwd):
    return subprocess.run([sys.executable, "-m", "verigraph", "validate", *args],
                          capture_output=True, text=True, cwd=cwd, timeout=120)


def test_cli_one_rule_for_non_ascii_and_depth_in_every_mode(tmp_path):
    (tmp_path / "d.pddl").write_text(MYSTERY)
    (tmp_path / "p.pddl").write_text(MYSTERY_PROBLEM.replace("(:objects a b c d )",
                                                             "(:objects a b c d 積み木)"))
    (tmp_path / "plan.txt").write_text("(attack a)\n")
    base = ["--domain", "d.pddl", "--problem", "p.pddl", "--plan", "plan.txt"]
    text, as_json = run(*base, cwd=tmp_path), run(*base, "--json", cwd=tmp_path)
    (tmp_path / "b.jsonl").write_text(json.dumps({"id": 1, "domain": "d.pddl",
                                                  "problem": "p.pddl", "plan": "plan.txt"}))
    batch = run("--batch", "b.jsonl", "--no-progress", cwd=tmp_path)
    assert text.returncode == as_json.returncode == 2 and batch.returncode == 1
    assert "not ASCII" in text.stderr and "Traceback" not in text.stderr + as_json.stderr
    assert json.loads(as_json.stdout)["error"] == "PddlSyntaxError"
    line = json.loads(batch.stdout)
    assert line["ok"] is False and "not ASCII" in line["message"]
    (tmp_path / "p.pddl").write_text("(define (problem x)\n" + "(" * 100_000 + ")" * 100_000)
    deep = run(*base, cwd=tmp_path)
    assert deep.returncode == 2 and "line 2" in deep.stderr and "Traceback" not in deep.stderr


def test_cli_strips_text_json_and_planbench(tmp_path):
    (tmp_path / "d.pddl").write_text(LOGISTICS)
    (tmp_path / "p.pddl").write_text(LOG_PROBLEM)
    (tmp_path / "ok.txt").write_text("(load-truck p0 t0 l0)\n(drive-truck t0 l0 ap c0)\n"
                                     "(unload-truck p0 t0 ap)\n")
    (tmp_path / "bad.txt").write_text("(drive-truck t0 l0 ap c0)\n(load-truck p0 t0 l0)\n")
    base = ["--domain", "d.pddl", "--problem", "p.pddl", "--plan"]
    ok = run(*base, "ok.txt", cwd=tmp_path)
    assert ok.returncode == 0 and "VALID: 3 step(s) checked" in ok.stdout
    bad = run(*base, "bad.txt", "--json", "--planbench", cwd=tmp_path)
    assert bad.returncode == 1
    data = json.loads(bad.stdout)
    assert data["planbench"]["unmet_precondition"]["predicate"] == ["at_t0_l0"]
    pb = run(*base, "bad.txt", "--planbench", cwd=tmp_path)
    assert pb.stdout.startswith("The above plan is invalid. The following action at step 2")


@pytest.mark.anyio
async def test_mcp_validate_plan_takes_pddl_text(client: Client) -> None:
    pddl = {"domain": MYSTERY, "problem": MYSTERY_PROBLEM}
    ok = await client.call_tool("validate_plan", {
        "plan": "(feast b c)\n(succumb b)\n(attack c)\n(overcome c b)", "pddl": pddl})
    assert structured(ok)["valid"] is True
    bad = await client.call_tool("validate_plan", {"plan": "(attack b)", "pddl": pddl})
    assert structured(bad)["violations"][0]["constraint"] == "wrong_source"
    assert "(feast b c)" in text(bad) and "(planet b)" in text(bad)
    deep = {"domain": MYSTERY, "problem": "(define (problem x)\n" + "(" * 5000 + ")" * 5000}
    refused = await client.call_tool("validate_plan", {"plan": "(attack b)", "pddl": deep})
    assert refused.is_error and "deep on line 2" in text(refused)
    both = await client.call_tool("validate_plan", {"plan": "(attack b)", "pddl": pddl,
                                                    "scene_id": "cup_on_book"})
    assert both.is_error and "pddl" in text(both)
    extra = await client.call_tool("validate_plan", {"plan": "(attack b)",
                                                     "pddl": {**pddl, "goal": "(on a b)"}})
    assert extra.is_error and "exactly 'domain' and 'problem'" in text(extra)


def test_the_plain_plan_fast_path_gives_the_line_by_line_report():
    from blocksworld_corpus import DATA, reference_plan

    below = {"a": "b", "b": None, "c": None, "d": "c"}  # the shipped instance
    goal = {"a": None, "b": None, "c": "a", "d": None}
    plan = reference_plan(below, goal)
    domain = (DATA / "planbench_domain.pddl").read_text()
    problem = (DATA / "planbench_instance.pddl").read_text()
    plain = "\n".join(plan)
    fast = validate_pddl_dict(domain, problem, plain)
    slow = validate_pddl_dict(domain, problem, "; a comment takes the line-by-line path\n"
                              + "\n".join(f"  {a}  " for a in plan))
    assert [s["text"] for s in fast["steps"]] == [s["text"] for s in slow["steps"]] == plan
    assert json.dumps([s["edit"] for s in fast["steps"]]) == json.dumps(
        [s["edit"] for s in slow["steps"]])
    assert fast["valid"] and slow["valid"]


@pytest.mark.anyio
async def test_mcp_all_errors_checks_every_pddl_step(client: Client) -> None:
    """all_errors reaches the PDDL engine over MCP as on the CLI: both failing steps are
    reported (the first skipped, as VAL continues), and the text says so."""
    pddl = {"domain": MYSTERY, "problem": MYSTERY_PROBLEM}
    plan = "(attack b)\n(attack b)\n(feast b c)"
    first = structured(await client.call_tool("validate_plan", {"plan": plan, "pddl": pddl}))
    assert len(first["violations"]) == 1 and first["not_checked"] == 2
    out = await client.call_tool("validate_plan", {"plan": plan, "pddl": pddl,
                                                   "all_errors": True})
    every = structured(out)
    assert [v["step"] for v in every["violations"]] == [1, 2]
    assert every["not_checked"] == 0 and "not checked" not in text(out)
