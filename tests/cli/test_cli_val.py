"""`verigraph val` / `verigraph-val`: VAL's Validate interface, lines and exit statuses.

The expected lines are VAL 4's own strings (applications/Validate/src/main.cpp,
libraries/VAL/src/{Validator,Plan,State,RepairAdvice,Proposition}.cpp of
KCL-Planning/VAL), written out here so that a change of wording fails a test.
"""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from roads import ROADS

from verigraph.cli import val

pytestmark = pytest.mark.fast

ROOT = Path(__file__).parents[2]
BW = ROOT / "tests" / "data" / "blocksworld"
DOMAIN, PROBLEM = str(BW / "planbench_domain.pddl"), str(BW / "planbench_instance.pddl")
GOOD = str(BW / "planbench_plan.pddl")  # 4 steps, reaches (on c a)


@pytest.fixture
def plans(tmp_path: Path) -> dict[str, str]:
    texts = {"bad": "(unstack d c)\n(put-down d)\n(pick-up a)\n",   # a is under nothing, on b
             "short": "(unstack d c)\n(put-down d)\n",              # executes, misses the goal
             "two": "(unstack d c)\n(pick-up b)\n"}  # b is under a, the hand holds d
    out = {}
    for name, text in texts.items():
        (tmp_path / f"{name}.txt").write_text(text)
        out[name] = str(tmp_path / f"{name}.txt")
    return out


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    code = val.run(list(args))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_a_valid_plan_in_vals_words(capsys):
    code, out, err = run(capsys, DOMAIN, PROBLEM, GOOD)
    assert code == 0 and err == ""
    assert out == (f"Checking plan: {GOOD}\n"
                   "Plan executed successfully - checking goal\n"
                   "Plan valid\n"
                   "Final value: 4 \n"
                   "\n"
                   "Successful plans:\n"
                   "Value: 4\n"
                   f" {GOOD} 4 \n"
                   "\n")


def test_failed_and_unsatisfied_plans_and_the_exit_status_counts_them(capsys, plans):
    code, out, _ = run(capsys, DOMAIN, PROBLEM, plans["bad"], GOOD, plans["short"])
    assert code == 2  # VAL's errorCount: the plans that are not valid
    bad, good, short = out.split("Checking plan: ")[1:]
    assert bad == f"{plans['bad']}\n\nPlan failed to execute\n"
    assert "Plan valid\nFinal value: 4 \n" in good
    assert short.startswith(f"{plans['short']}\nPlan executed successfully - checking goal\n"
                            "Goal not satisfied\nPlan invalid\n")
    assert out.endswith(f"\n\nFailed plans:\n {plans['bad']} {plans['short']} \n")


def test_verbose_gives_the_trace_and_vals_repair_advice(capsys, plans):
    code, out, _ = run(capsys, "-v", DOMAIN, PROBLEM, plans["bad"])
    assert code == 1
    assert "Plan to validate:\n\nPlan size: 3\n1:\n(unstack d c)\n \n" in out
    assert "Plan Validation details\n-----------------------\n" in out
    assert "\nChecking next happening (time 1)\nDeleting (on d c)\n" in out
    assert "Adding (holding d)\n" in out
    assert ("\nChecking next happening (time 3)\n"
            "Plan failed because of unsatisfied precondition in:\n(pick-up a)\n"
            "\nPlan failed to execute\n") in out
    advice = out.split("\nPlan Repair Advice:\n\n")[1]
    assert advice.startswith("(pick-up a) has an unsatisfied precondition at time 3\n"
                             "(Set (on-table a) to true)\n")
    # VeriGraph's why and fix follow VAL's lines, indented.
    assert "    (on-table a): never true" in advice and "    fix: " in advice


def test_several_unmet_preconditions_and_an_unmet_goal_are_vals_conjunctions(capsys, plans):
    _, out, _ = run(capsys, "-v", DOMAIN, PROBLEM, plans["two"])
    assert ("(pick-up b) has an unsatisfied precondition at time 2\n(Follow each of:\n"
            "    (Set (clear b) to true)\n    and (Set (arm-empty) to true)\n)\n") in out
    _, out, _ = run(capsys, "-v", DOMAIN, PROBLEM, plans["short"])
    assert "\nPlan Repair Advice:\n\nThe goal is not satisfied\n(Set (on c a) to true)\n" in out
    _, out, _ = run(capsys, "-v", "-a", DOMAIN, PROBLEM, plans["short"])
    assert "Plan Repair Advice" not in out and "Goal not satisfied" in out


def test_silent_modes(capsys, plans):
    code, out, _ = run(capsys, "-s", DOMAIN, PROBLEM, GOOD, plans["bad"])
    assert code == 1
    assert out == f"\nPlan failed to execute\n\n\nFailed plans:\n {plans['bad']} \n"
    code, out, _ = run(capsys, "-S", DOMAIN, PROBLEM, GOOD, plans["bad"], plans["short"])
    assert (code, out) == (2, "4 \nfailed\nfailed\n")
    code, out, _ = run(capsys, "-t", "0.001", "-s", DOMAIN, PROBLEM, GOOD)
    assert (code, out) == (0, "")


def test_unusable_input_exits_255_with_vals_line_and_the_reason(capsys, tmp_path):
    code, out, err = run(capsys, str(tmp_path / "nope.pddl"), PROBLEM, GOOD)
    assert (code, out) == (255, "") and err.startswith("Bad domain file!\nerror: ")
    code, out, err = run(capsys, DOMAIN, str(tmp_path / "nope.pddl"), GOOD)
    assert (code, out) == (255, "") and err.startswith("Bad problem file!\nerror: ")
    (tmp_path / "d.pddl").write_text("(define (domain x) (:requirements :durative-actions))")
    code, out, err = run(capsys, str(tmp_path / "d.pddl"), PROBLEM, GOOD)
    assert code == 255 and err.startswith("Problem in domain definition!\nerror: ")
    assert ":durative-actions" in err
    (tmp_path / "p.pddl").write_text("(define (problem p) (:domain blocksworld-4ops)")
    code, out, err = run(capsys, DOMAIN, str(tmp_path / "p.pddl"), GOOD)
    assert code == 255 and err.startswith("Type problem in problem specification!\nerror: ")
    # The domain and problem are read before any plan: a bad problem prints no plan line,
    # even when the first plan cannot be read.
    code, out, err = run(capsys, DOMAIN, str(tmp_path / "p.pddl"), str(tmp_path / "no.txt"))
    assert (code, out) == (255, "") and err.startswith("Type problem in problem")
    code, out, err = run(capsys, "-x", DOMAIN, PROBLEM, GOOD)
    assert (code, err) == (255, "Unrecognised command line switch: -x\n")
    code, out, err = run(capsys, "-c", DOMAIN, PROBLEM, GOOD)
    assert code == 255 and "not supported" in err
    code, out, err = run(capsys, "-t")
    assert code == 255 and "-t needs" in err


def test_a_domain_alone_is_checked_and_no_arguments_print_the_usage(capsys):
    assert run(capsys, DOMAIN) == (0, "", "")
    code, out, _ = run(capsys)
    assert code == 0 and "Usage: verigraph-val [options] domainFile problemFile" in out
    assert run(capsys, "-h")[1] == out


def test_a_plan_that_cannot_be_read_or_parsed_is_counted_and_says_why(capsys, tmp_path):
    missing = str(tmp_path / "none.txt")
    (tmp_path / "garbled.txt").write_text("(pick-up\n")
    code, out, _ = run(capsys, DOMAIN, PROBLEM, missing, str(tmp_path / "garbled.txt"))
    assert code == 2  # VAL exits 0 here; a script must not read a missing plan as valid
    assert f"Checking plan: {missing}\nBad plan file!\n    why: " in out
    garbled = out.split("garbled.txt\n", 1)[1]
    assert garbled.startswith(("Bad plan description!\n    why: ", "\nPlan failed to execute"))
    assert "Traceback" not in out


def test_the_command_and_the_console_script(tmp_path, plans):
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]
    assert scripts["verigraph-val"] == "verigraph.cli.val:main"
    for command in ([sys.executable, "-m", "verigraph", "val"],
                    [sys.executable, "-m", "verigraph.cli.val"]):
        r = subprocess.run([*command, "-v", DOMAIN, PROBLEM, GOOD, plans["bad"]],
                           capture_output=True, text=True, timeout=120)
        assert r.returncode == 1, r.stderr
        assert "Plan valid\nFinal value: 4 \n" in r.stdout
        assert "Plan Repair Advice:" in r.stdout and r.stderr == ""


TRIP = """(define (problem trip) (:domain roads) (:objects x y z - place)
  (:init (at x) (road x y) (road y z) (road x z)
         (= (road-length x y) 3) (= (road-length y z) 4.5) (= (road-length x z) 10)
         (= (total-cost) 0))
  (:goal (at z)){metric})
"""


@pytest.mark.parametrize("metric", [True, False])
def test_final_value_is_the_total_cost_under_a_metric_else_the_length(capsys, tmp_path,
                                                                       metric):
    (tmp_path / "d.pddl").write_text(ROADS)
    (tmp_path / "p.pddl").write_text(
        TRIP.format(metric=" (:metric minimize (total-cost))" if metric else ""))
    (tmp_path / "via_y.txt").write_text("(drive x y)\n(drive y z)\n")
    (tmp_path / "direct.txt").write_text("(drive x z)\n")
    files = [str(tmp_path / n) for n in ("d.pddl", "p.pddl", "direct.txt", "via_y.txt")]
    code, out, _ = run(capsys, *files)
    assert code == 0
    direct, via_y = files[2], files[3]
    if metric:  # VAL: the metric's value, plans listed from the best (lowest) value
        assert "Final value: 10 \n" in out and "Final value: 7.5 \n" in out
        assert out.endswith(f"Successful plans:\nValue: 7.5\n {via_y} 7.5 \n"
                            f"Value: 10\n {direct} 10 \n\n")
    else:  # VAL without a metric: the plan's length, listed from the highest
        assert "Final value: 1 \n" in out and "Final value: 2 \n" in out
        assert out.endswith(f"Successful plans:\nValue: 2\n {via_y} 2 \n"
                            f"Value: 1\n {direct} 1 \n\n")


def test_a_step_val_crashes_on_is_a_failed_step_with_the_reason(capsys, tmp_path):
    """VAL segfaults on a step of the wrong arity; here it fails at its step and says why."""
    (tmp_path / "arity.txt").write_text("(unstack d c)\n(put-down d c)\n")
    (tmp_path / "none.txt").write_text("(no plan possible)\n")
    files = [DOMAIN, PROBLEM, str(tmp_path / "arity.txt"), str(tmp_path / "none.txt")]
    code, out, err = run(capsys, *files)
    assert (code, err) == (2, "")
    assert out.count("\nPlan failed to execute\n") == 2
    code, out, _ = run(capsys, "-v", *files[:3])
    assert code == 1
    advice = out.split("\nPlan Repair Advice:\n\n")[1]
    assert advice.startswith("(put-down d c) cannot be executed at time 2: line 2: ")
    assert "argument" in advice and "\n    fix: " in advice  # the engine's reason and fix
