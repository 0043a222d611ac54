"""The command line's CPU budget (verigraph.budget.command_line_budget): every check of
`verigraph validate` (a plan, each `--batch` item) and each plan of `verigraph val` may
use at most `--cpu-seconds` (or $VERIGRAPH_CPU_SECONDS, default 60) of CPU; beyond it
the check ends with a structured error naming the budget, also in code that never
reaches a checkpoint, and the next item or plan is still checked."""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import pytest

from verigraph.budget import (
    CPU_SECONDS_ENV,
    DEFAULT_CLI_CPU_S,
    BudgetExceeded,
    CallBudget,
    command_line_budget,
    run_within,
)
from verigraph.cli import main as verigraph_main
from verigraph.cli import val
from verigraph.errors import VeriGraphError

pytestmark = pytest.mark.fast

N = 1000  # a forall over N * N bindings: about 0.1 s of CPU a step
DOMAIN = """(define (domain big) (:requirements :typing :adl)
 (:types obj) (:predicates (p ?x - obj) (q ?x - obj) (done))
 (:action every :parameters () :precondition (forall (?x ?y - obj) (or (p ?x) (q ?y)))
   :effect (done)))"""
PROBLEM = (f"(define (problem b) (:domain big) (:objects {' '.join(f'o{i}' for i in range(N))}"
           f" - obj) (:init {' '.join(f'(p o{i})' for i in range(N))}) (:goal (done)))")


def spin_cpu(seconds: float) -> int:
    """Pure Python for `seconds` of this thread's CPU, never calling checkpoint()."""
    end = time.thread_time() + seconds
    n = 0
    while time.thread_time() < end:
        n += 1
    return n


def test_a_cpu_budget_stops_a_loop_without_checkpoints_and_spares_a_sleeping_one():
    budget = CallBudget(wall_s=math.inf, memory_mib=math.inf, cpu_s=0.2)
    started = time.process_time()
    with pytest.raises(BudgetExceeded) as caught:
        run_within(budget, "validate", lambda: spin_cpu(10))
    assert time.process_time() - started < 2
    assert "used more than its 0.2 s of CPU" in caught.value.message
    assert "--cpu-seconds" in (caught.value.fix or "")
    assert run_within(budget, "validate", lambda: time.sleep(0.4) or 7) == 7  # wall, no CPU


def test_the_budget_comes_from_the_flag_else_the_environment_else_the_default(monkeypatch):
    monkeypatch.delenv(CPU_SECONDS_ENV, raising=False)
    assert DEFAULT_CLI_CPU_S == 60
    default = command_line_budget(None)
    assert default is not None and default.cpu_s == DEFAULT_CLI_CPU_S
    assert default.wall_s == math.inf and default.memory_mib == math.inf
    monkeypatch.setenv(CPU_SECONDS_ENV, "2.5")
    assert command_line_budget(None).cpu_s == 2.5  # type: ignore[union-attr]
    assert command_line_budget(4).cpu_s == 4  # type: ignore[union-attr]
    assert command_line_budget(0) is None  # 0: no limit
    for bad in ("abc", "-1", "nan", "inf"):
        monkeypatch.setenv(CPU_SECONDS_ENV, bad)
        with pytest.raises(VeriGraphError) as caught:
            command_line_budget(None)
        assert caught.value.field == CPU_SECONDS_ENV and caught.value.fix


def _files(tmp_path: Path, steps: int) -> list[str]:
    (tmp_path / "d.pddl").write_text(DOMAIN)
    (tmp_path / "p.pddl").write_text(PROBLEM)
    (tmp_path / "plan").write_text("(every)\n" * steps)
    return [str(tmp_path / n) for n in ("d.pddl", "p.pddl", "plan")]


def test_validate_stops_a_check_over_its_cpu_budget(capsys, tmp_path, monkeypatch):
    monkeypatch.delenv(CPU_SECONDS_ENV, raising=False)
    d, p, plan = _files(tmp_path, 200)  # some 20 s of CPU unchecked
    args = ["validate", "--domain", d, "--problem", p, "--plan", plan, "--cpu-seconds", "0.3"]
    started = time.process_time()
    assert verigraph_main(args) == 2
    assert time.process_time() - started < 5
    out, err = capsys.readouterr()
    assert "used more than its 0.3 s of CPU" in err and "Traceback" not in err
    assert verigraph_main([*args, "--json"]) == 2
    data = json.loads(capsys.readouterr().out)
    assert data["error"] == "BudgetExceeded" and "--cpu-seconds" in data["fix"]
    short = tmp_path / "short"
    short.write_text("(every)\n")
    assert verigraph_main([*args[:-3], str(short), "--cpu-seconds", "30"]) == 0


def test_a_batch_item_over_the_budget_is_an_error_line_and_the_batch_goes_on(
        capsys, tmp_path, monkeypatch):
    _files(tmp_path, 200)
    (tmp_path / "one").write_text("(every)\n")
    items = [{"id": "long", "domain": "d.pddl", "problem": "p.pddl", "plan": "plan"},
             {"id": "short", "domain": "d.pddl", "problem": "p.pddl", "plan": "one"}]
    (tmp_path / "items.jsonl").write_text("".join(json.dumps(i) + "\n" for i in items))
    monkeypatch.setenv(CPU_SECONDS_ENV, "0.3")
    assert verigraph_main(["validate", "--batch", str(tmp_path / "items.jsonl"),
                           "--no-progress"]) == 1
    long, short = (json.loads(line) for line in capsys.readouterr().out.splitlines())
    assert long["id"] == "long" and long["error"] == "BudgetExceeded"
    assert short["id"] == "short" and short["valid"] is True


def test_val_counts_a_plan_over_the_budget_as_the_validator_failing(capsys, tmp_path,
                                                                   monkeypatch):
    d, p, plan = _files(tmp_path, 200)
    (tmp_path / "one").write_text("(every)\n")
    monkeypatch.setenv(CPU_SECONDS_ENV, "0.3")
    assert val.run([d, p, plan, str(tmp_path / "one")]) == 1
    out = capsys.readouterr().out
    assert "Error occurred in validation attempt:" in out and "0.3 s of CPU" in out
    assert "Plan valid" in out and f"Queries (validator failed):\n {plan} " in out


def test_a_commands_cpu_seconds_hold_for_that_command_only(capsys, tmp_path, monkeypatch):
    """`--cpu-seconds 30` given to one in-process `verigraph validate` does not become the
    budget of the next check: `verigraph-val` after it keeps $VERIGRAPH_CPU_SECONDS."""
    d, p, plan = _files(tmp_path, 200)
    (tmp_path / "one").write_text("(every)\n")
    assert verigraph_main(["validate", "--domain", d, "--problem", p, "--plan",
                           str(tmp_path / "one"), "--cpu-seconds", "30"]) == 0
    monkeypatch.setenv(CPU_SECONDS_ENV, "0.3")
    started = time.process_time()
    assert val.run([d, p, plan]) == 1
    assert time.process_time() - started < 5
    assert "0.3 s of CPU" in capsys.readouterr().out
