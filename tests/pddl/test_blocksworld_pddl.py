"""PDDL blocks world in: domain spellings, plan formats, the hand model's feedback, CLI."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from blocksworld_corpus import DATA
from verigraph.actions.blocksworld import validate_pddl_plan
from verigraph.pddl.blocksworld import UnsupportedDomainError, recognise_domain

pytestmark = pytest.mark.fast

PROBLEM = (DATA / "planbench_instance.pddl").read_text()  # d on c, a on b; goal c on a
PLANBENCH = (DATA / "planbench_domain.pddl").read_text()


@pytest.mark.parametrize("name,family,ops", [
    ("planbench", "4op", {"pick-up", "put-down", "stack", "unstack"}),
    ("ipc2000", "4op", {"pick-up", "put-down", "stack", "unstack"}),
    ("typed", "4op", {"pickup", "putdown", "stack", "unstack"}),
    ("three_op", "3op", {"move-b-to-b", "move-b-to-t", "move-t-to-b"}),
])
def test_each_domain_spelling_is_recognised(name, family, ops):
    domain = recognise_domain((DATA / f"{name}_domain.pddl").read_text())
    assert domain.family == family and set(domain.operators) == ops


@pytest.mark.parametrize("edit,fragment", [
    (lambda d: d.replace("(not (arm-empty))))", "(not (arm-empty)) (on ?ob ?ob)))", 1),
     "pick-up"),
    (lambda d: d.replace("(holding ?x)", "(holding ?x) (painted ?x)", 1), "predicate"),
    (lambda d: d.replace("(:requirements :strips)", "(:requirements :strips :fluents)"),
     "fluents"),
    (lambda d: d.replace("(:action put-down", "(:action put-down-twice", 1)
     .replace(":parameters  (?ob)\n  :precondition (holding ?ob)",
              ":parameters  (?ob)\n  :precondition (or (holding ?ob) (clear ?ob))", 1), "or"),
])
def test_anything_outside_the_family_is_unsupported(edit, fragment):
    with pytest.raises(UnsupportedDomainError, match="unsupported domain") as err:
        recognise_domain(edit(PLANBENCH))
    assert fragment in str(err.value)


def test_the_documented_library_paths_give_the_engines_reports():
    """docs/validator.md names `verigraph.actions.pddl.validate_pddl_dict` and
    `verigraph.actions.blocksworld.validate_pddl_plan`: they are the `pddl` package's
    engine and its report as the model."""
    from verigraph.actions import pddl as boundary
    from verigraph.pddl import validate_pddl_dict

    plan = "(unstack d c)\n(put-down d)\n(pick-up c)"
    data = boundary.validate_pddl_dict(PLANBENCH, PROBLEM, plan)
    assert data == validate_pddl_dict(PLANBENCH, PROBLEM, plan) and data["engine"] == "blocksworld"
    report = validate_pddl_plan(PLANBENCH, PROBLEM, plan)
    assert report.plan_valid and not report.goal_reached
    assert report.model_dump()["steps"] == boundary.as_validation_report(data).model_dump()["steps"]


def test_planbench_sentences_and_sexpr_lines_give_the_same_report():
    text = (DATA / "planbench_plan.txt").read_text()
    sexpr = (DATA / "planbench_plan.pddl").read_text()
    a, b = validate_pddl_plan(PLANBENCH, PROBLEM, text), validate_pddl_plan(PLANBENCH, PROBLEM,
                                                                           sexpr)
    assert a.valid and a.model_dump() == b.model_dump()
    val_style = "; VAL output\n0.000: (unstack d c) [1]\n1: (put-down d)\n(PICK-UP C)\n(stack c a)"
    assert validate_pddl_plan(PLANBENCH, PROBLEM, val_style).valid


@pytest.mark.parametrize("plan,step,constraint", [
    ("(pick-up a)", 1, "wrong_source"),                   # a is on b
    ("(unstack d a)", 1, "wrong_source"),                 # d is on c
    ("(pick-up b)", 1, "object_not_clear"),               # a is on b
    ("(unstack d c)\n(unstack a b)", 2, "hand_full"),
    ("(put-down a)", 1, "not_held"),
    ("(unstack d c)\n(stack d b)", 2, "target_full"),     # a is on b
    ("(unstack d c)\n(stack d d)", 2, "same_object"),
])
def test_hand_model_violations_have_their_own_ids(plan, step, constraint):
    report = validate_pddl_plan(PLANBENCH, PROBLEM, plan)
    v = report.violations[0]
    assert (v.step, v.constraint) == (step, constraint) and v.suggestion


def test_a_block_still_held_is_not_a_violation_the_goal_decides():
    report = validate_pddl_plan(PLANBENCH, PROBLEM, "(unstack d c)\n(put-down d)\n(pick-up c)")
    assert report.plan_valid and not report.goal_reached
    assert report.goal_diff is not None and report.goal_diff.missing_edges == ["(on c a)"]
    held = [e for e in report.final_graph.edges if e.relation == "in"]
    assert [(e.source, e.target) for e in held] == [("c", "hand")]


def test_empty_plan_is_valid_input():
    report = validate_pddl_plan(PLANBENCH, PROBLEM, "")
    assert report.plan_valid and report.goal_reached is False and report.steps == []


def test_inconsistent_initial_state_is_refused():
    broken = PROBLEM.replace("(clear d)\n", "")
    with pytest.raises(UnsupportedDomainError, match="clear d"):
        validate_pddl_plan(PLANBENCH, broken, "")


def verigraph(*args, cwd):
    return subprocess.run([sys.executable, "-m", "verigraph", *args], capture_output=True,
                          text=True, cwd=cwd, timeout=120)


def test_cli_pddl_text_json_and_bad_input(tmp_path):
    base = ["validate", "--domain", "planbench_domain.pddl", "--problem",
            "planbench_instance.pddl"]
    r = verigraph(*base, "--plan", "planbench_plan.txt", cwd=DATA)
    assert r.returncode == 0 and "VALID: 4 step(s) checked" in r.stdout
    (tmp_path / "bad.txt").write_text("(unstack d c)\n(stack d b)\n")
    r = verigraph(*base, "--plan", str(tmp_path / "bad.txt"), "--json", cwd=DATA)
    assert r.returncode == 1
    assert json.loads(r.stdout)["violations"][0]["constraint"] == "target_full"
    (tmp_path / "arity.txt").write_text("(unstack d c)\n(unstack b)\n")
    r = verigraph(*base, "--plan", str(tmp_path / "arity.txt"), cwd=DATA)
    assert r.returncode == 1 and "Traceback" not in r.stderr  # a failing step, not bad input
    assert "2 FAIL  (unstack b): [malformed_action] line 2: unstack takes 2 argument(s)" \
        in r.stdout
    # a domain outside the blocks-world family goes to the STRIPS engine, which judges it
    (tmp_path / "d.pddl").write_text(PLANBENCH.replace("(holding ?x)", "(holding ?x) (wet ?x)"))
    r = verigraph("validate", "--domain", str(tmp_path / "d.pddl"), "--problem",
                  "planbench_instance.pddl", "--plan", "planbench_plan.pddl", "--json", cwd=DATA)
    assert r.returncode == 0 and json.loads(r.stdout)["engine"] == "strips"
    # and what neither engine supports is refused with the requirement named
    (tmp_path / "d.pddl").write_text(PLANBENCH.replace("(:requirements :strips)",
                                                       "(:requirements :strips :fluents)"))
    r = verigraph("validate", "--domain", str(tmp_path / "d.pddl"), "--problem",
                  "planbench_instance.pddl", "--plan", "planbench_plan.pddl", cwd=DATA)
    assert r.returncode == 2 and "unsupported requirement :fluents" in r.stderr
    assert "Traceback" not in r.stderr


def test_three_op_self_move_is_refused_when_the_domain_allows_it():
    three = (DATA / "three_op_domain.pddl").read_text()
    problem = PROBLEM.replace("(arm-empty)\n", "")
    strict = validate_pddl_plan(three, problem, "(move-b-to-t d c)\n(move-t-to-b d d)")
    assert strict.violations[0].constraint == "same_object" and strict.violations[0].step == 2
    loose = three.replace("(on-table ?bm) (not (= ?bm ?bt)))", "(on-table ?bm))")
    with pytest.raises(UnsupportedDomainError, match="onto itself"):
        validate_pddl_plan(loose, problem, "(move-b-to-t d c)\n(move-t-to-b d d)")


def test_cli_html_is_for_scene_plans_only():
    # (--all-errors applies to PDDL plans too: tests/cli/test_cli_core.py)
    r = verigraph("validate", "--domain", "planbench_domain.pddl", "--problem",
                  "planbench_instance.pddl", "--plan", "planbench_plan.txt", "--html", "x.html",
                  cwd=DATA)
    assert r.returncode == 2 and "scene plans only" in r.stderr


def test_the_ascii_line_pattern_reads_every_ascii_line_as_the_unicode_one():
    """The fast run reads ASCII plans with the name class written as byte ranges; on
    every ASCII character, in every position of a line, it agrees with the Unicode one."""
    from verigraph.pddl.blocksworld.plans import _PLAIN_ASCII_LINE, _PLAIN_LINE

    for code in range(128):
        c = chr(code)
        for line in (f"(pick-up a{c}b)", f"({c}stack a b)", f"(stack a b{c})", f"(x {c} y)",
                     f"(move a b c{c})", f"(x y)\n({c})\n(z w)", f"(x y){c}"):
            assert _PLAIN_ASCII_LINE.findall(line) == _PLAIN_LINE.findall(line), repr(line)


def test_the_native_engine_explains_as_the_strips_engine_does():
    """One engine judges a blocks-world plan and explains its own failure: the native
    report's `unsatisfied` and `unmet_goals` are those the STRIPS engine gives for the same
    plan, on domains with renamed names and a reordered parameter list."""
    import random
    import re

    from blocksworld_corpus import generate
    from verigraph.pddl import validate_pddl_dict

    names = ["pick-up", "put-down", "stack", "unstack", "on", "on-table", "clear", "holding",
             "arm-empty"]
    pool = ["at", "over", "start", "end", "all", "goal", "either", "define", "and-2", "p",
            "p-1", "move", "x"]

    def rename(text: str, renaming: dict[str, str]) -> str:
        return re.sub(r"[^\s()]+", lambda m: renaming.get(m.group(0).lower(), m.group(0)),
                      text)

    rng = random.Random(11)
    explained = {"unsatisfied": 0, "unmet_goals": 0}
    swapped = PLANBENCH.replace(":parameters  (?ob ?underob)\n  :precondition (and (clear "
                                "?underob) (holding ?ob))", ":parameters  (?underob ?ob)\n"
                                "  :precondition (and (clear ?underob) (holding ?ob))", 1)
    assert swapped != PLANBENCH
    for _spelling, problem, plan, _kind in generate(28, seed=4):
        if _spelling != "planbench":
            continue
        plan = [f"(stack {a.split()[2][:-1]} {a.split()[1]})" if a.startswith("(stack")
                else a for a in plan]
        renaming = dict(zip(names, rng.sample(pool, len(names)), strict=False))
        domain, problem = rename(swapped, renaming), rename(problem, renaming)
        text = "\n".join(rename(a, renaming) for a in plan)
        native = validate_pddl_dict(domain, problem, text)
        strips = validate_pddl_dict(domain, problem, text, engine="strips")
        assert native["engine"] == "blocksworld" and native["valid"] == strips["valid"]
        if native["violations"]:
            got, want = native["violations"][0], strips["violations"][0]
            assert got["step"] == want["step"]
            assert got["unsatisfied"] == want["unsatisfied"]
            explained["unsatisfied"] += bool(got["unsatisfied"])
        elif not native["valid"]:
            assert native["unmet_goals"] == strips["unmet_goals"]
            explained["unmet_goals"] += 1
    assert explained["unsatisfied"] >= 5 and explained["unmet_goals"] >= 1, explained
