"""A closed pipe (`verigraph ... | head -1`) ends a command quietly with its own status.

Each command writes more than a pipe holds (64 KiB), so it must block on the pipe; the
test reads one line and closes its end, as `head -1` does, and the command's next write
meets the closed pipe. What must come out: the verdict's exit status and nothing on
stderr (no BrokenPipeError traceback, no "Exception ignored" at exit).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.fast

VERIGRAPH = str(Path(sys.executable).parent / "verigraph")
DOMAIN = """(define (domain bw) (:requirements :strips)
  (:predicates (on ?x ?y) (ontable ?x) (clear ?x) (handempty) (holding ?x))
  (:action pick-up :parameters (?x)
    :precondition (and (clear ?x) (ontable ?x) (handempty))
    :effect (and (not (ontable ?x)) (not (clear ?x)) (not (handempty)) (holding ?x)))
  (:action put-down :parameters (?x)
    :precondition (holding ?x)
    :effect (and (not (holding ?x)) (clear ?x) (handempty) (ontable ?x)))
  (:action stack :parameters (?x ?y)
    :precondition (and (holding ?x) (clear ?y))
    :effect (and (not (holding ?x)) (not (clear ?y)) (clear ?x) (handempty) (on ?x ?y)))
  (:action unstack :parameters (?x ?y)
    :precondition (and (on ?x ?y) (clear ?x) (handempty))
    :effect (and (holding ?x) (clear ?y) (not (clear ?x)) (not (handempty))
                 (not (on ?x ?y)))))
"""
PROBLEM = """(define (problem p) (:domain bw) (:objects a b)
  (:init (ontable a) (ontable b) (clear a) (clear b) (handempty))
  (:goal (and {goal})))
"""


def first_line_then_close(args: list[str], cwd: Path, size: int | None = None,
                          merged: bool = False) -> tuple[bytes, int, str]:
    """Run `args`, read one line of its output (or `size` bytes: `head -c`), close the
    pipe; (what was read, exit status, stderr). `merged`: stderr into the same pipe
    (`2>&1 | head -1`)."""
    proc = subprocess.Popen(args, cwd=cwd, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT if merged else subprocess.PIPE)
    assert proc.stdout is not None
    line = proc.stdout.readline() if size is None else proc.stdout.read(size)
    proc.stdout.close()
    err = "" if proc.stderr is None else proc.stderr.read().decode()
    return line, proc.wait(timeout=120), err


def long_pddl_files(tmp_path: Path, goal: str) -> list[str]:
    """A 4,000-step valid plan (about 200 KB of report) on a two-block problem."""
    (tmp_path / "d.pddl").write_text(DOMAIN)
    (tmp_path / "p.pddl").write_text(PROBLEM.format(goal=goal))
    (tmp_path / "plan.txt").write_text("(pick-up a)\n(put-down a)\n" * 2000)
    return ["--domain", "d.pddl", "--problem", "p.pddl", "--plan", "plan.txt"]


@pytest.mark.parametrize(("goal", "status"), [("(ontable a)", 0), ("(on a b)", 1)])
def test_validate_into_a_closed_pipe_exits_with_the_verdict(tmp_path, goal, status):
    args = long_pddl_files(tmp_path, goal)
    line, code, err = first_line_then_close([VERIGRAPH, "validate", *args], tmp_path)
    assert line.startswith(b"VALID: 4000" if status == 0 else b"INVALID: 4000")
    assert code == status, err
    assert err == ""


def test_json_and_batch_into_a_closed_pipe(tmp_path):
    args = long_pddl_files(tmp_path, "(ontable a)")
    # The JSON report is one long line: read its first 4 KiB, as `head -c 4096` does.
    start, code, err = first_line_then_close([VERIGRAPH, "validate", *args, "--json"],
                                             tmp_path, size=4096)
    assert start.startswith(b"{") and (code, err) == (0, "")
    # A batch of items that cannot be read: a long run of error lines, exit 1.
    items = [json.dumps({"id": k, "domain": "d.pddl", "problem": "p.pddl",
                         "plan": f"missing-{k}.txt"}) for k in range(1500)]
    (tmp_path / "b.jsonl").write_text("\n".join(items) + "\n")
    line, code, err = first_line_then_close(
        [VERIGRAPH, "validate", "--batch", "b.jsonl", "--no-progress"], tmp_path)
    assert json.loads(line)["id"] == 0
    assert (code, err) == (1, "")


def test_the_val_interface_into_a_closed_pipe(tmp_path):
    long_pddl_files(tmp_path, "(ontable a)")
    line, code, err = first_line_then_close(
        [sys.executable, "-m", "verigraph", "val", "-v", "d.pddl", "p.pddl", "plan.txt"],
        tmp_path)
    assert line == b"Checking plan: plan.txt\n"
    assert (code, err) == (0, "")


def test_a_batch_with_its_progress_bar_into_one_closed_pipe(tmp_path):
    """`2>&1 | head -1`: the progress bar (stderr) meets the closed pipe too, at the
    latest when it closes after the last item; the batch still ends with its verdict."""
    long_pddl_files(tmp_path, "(ontable a)")
    (tmp_path / "short.txt").write_text("(pick-up a)\n(put-down a)\n")
    item = {"domain": "d.pddl", "problem": "p.pddl", "plan": "short.txt"}
    (tmp_path / "b.jsonl").write_text(
        "\n".join(json.dumps({"id": k, **item}) for k in range(2000)) + "\n")
    _, code, _ = first_line_then_close([VERIGRAPH, "validate", "--batch", "b.jsonl"],
                                       tmp_path, merged=True)
    assert code == 0
