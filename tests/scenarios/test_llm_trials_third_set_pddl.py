"""The deliveries task of the third set: the user asked whether a cheaper plan exists,
and solve now takes the PDDL (Fast Downward from the `pddl` extra), cost-optimal where
its search proves it and saying so, satisficing otherwise."""

from __future__ import annotations

import re

import pytest
from mcp import Client
from mcp_helpers import structured, text

from llm_trials import THIRD_SET, refused, transcript, with_attachments
from optional import require
from verigraph.server import build_server
from verigraph.tools import Toolbox

require("up_fast_downward", "pip install 'verigraph-mcp[pddl]'")
pytestmark = pytest.mark.anyio


def pddl_of(task: str) -> dict[str, str]:
    folder = THIRD_SET / task
    return {"domain": (folder / "domain.pddl").read_text(),
            "problem": (folder / "problem.pddl").read_text()}


async def test_solve_on_the_transport_pddl_gives_the_cheapest_plan_and_says_so() -> None:
    pddl = pddl_of("t03_deliveries")
    async with Client(build_server(Toolbox())) as client:
        solved = await client.call_tool("solve", {"pddl": pddl, "time_limit": 60})
        said = text(solved)
        assert said.startswith("plan of 13 action(s), verified, plan cost 146, cost-optimal "
                               "(Fast Downward seq-opt-lmcut proved that no plan costs "
                               "less): "), said
        assert structured(solved)["cost"] == 146 and structured(solved)["optimal"] is True
        plan = "\n".join(structured(solved)["plan"])
        again = text(await client.call_tool("validate_plan", {"plan": plan, "pddl": pddl}))
        assert again.startswith("VALID: 13 step(s) checked; goal reached; plan cost 146")
        scheduler = (THIRD_SET / "t03_deliveries" / "plan.txt").read_text()
        theirs = text(await client.call_tool("validate_plan", {"plan": scheduler, "pddl": pddl}))
        cost = re.search(r"plan cost (\d+)", theirs)
        assert cost is not None and int(cost.group(1)) > 146


async def test_the_recorded_solve_call_is_answered_now() -> None:
    """The model's third call, refused then ("pddl: unknown argument"), runs as sent."""
    folder = THIRD_SET / "t03_deliveries"
    entry = transcript(folder)[2]
    assert entry["tool"] == "solve" and refused(entry)
    async with Client(build_server(Toolbox())) as client:
        result = await client.call_tool("solve", with_attachments(folder, entry["args"]))
    assert not result.is_error and structured(result)["verified"] is True, text(result)


async def test_solve_on_the_elevator_adl_says_satisficing_when_not_proven() -> None:
    async with Client(build_server(Toolbox())) as client:
        solved = await client.call_tool("solve", {"pddl": pddl_of("t02_elevator"),
                                                  "time_limit": 5})
    said = text(solved)
    assert structured(solved)["verified"] is True, said
    if not structured(solved)["optimal"]:
        assert "satisficing (Fast Downward lama-first; not proven optimal)" in said
        assert "Fast Downward seq-opt-lmcut: " in said
    else:  # the domain has no action costs: optimal in actions, and said so
        assert structured(solved)["cost"] is None
        assert "optimal (Fast Downward seq-opt-lmcut proved that no plan has fewer " \
               "actions)" in said, said


async def test_a_failing_adl_step_names_an_action_that_applies_instead() -> None:
    """The elevator plan's step 10 fails an ADL condition no single action is known to
    make true: the fix names a step that applies in that state (it said only "choose an
    action whose preconditions hold"), checked by running it there."""
    folder = THIRD_SET / "t02_elevator"
    entry = transcript(folder)[0]
    async with Client(build_server(Toolbox())) as client:
        said = text(await client.call_tool("validate_plan", with_attachments(folder,
                                                                             entry["args"])))
        assert "choose an action whose preconditions hold" not in said
        fix = re.search(r" 10 FAIL .*applies in this state", said)
        assert fix is not None, said
        instead = re.search(r"or choose another action: (\([^)]*\)) applies", fix.group(0))
        assert instead is not None, fix.group(0)
        steps = (folder / "plan.txt").read_text().splitlines()[:9] + [instead.group(1)]
        replaced = structured(await client.call_tool(
            "validate_plan", {"plan": "\n".join(steps), "pddl": pddl_of("t02_elevator")}))
        assert replaced["plan_valid"] is True


GRIPPER = """(define (domain gripper) (:requirements :strips)
 (:predicates (at ?b ?r) (robot ?r) (free) (holding ?b))
 (:action pick :parameters (?b ?r) :precondition (and (at ?b ?r) (robot ?r) (free))
  :effect (and (holding ?b) (not (at ?b ?r)) (not (free))))
 (:action drop :parameters (?b ?r) :precondition (and (holding ?b) (robot ?r))
  :effect (and (at ?b ?r) (free) (not (holding ?b))))
 (:action go :parameters (?from ?to) :precondition (robot ?from)
  :effect (and (robot ?to) (not (robot ?from)))))"""
TWO_BALLS = """(define (problem two) (:domain gripper) (:objects a b left right)
 (:init (at a left) (at b left) (robot left) (free))
 (:goal (and (at a right) (at b right))))"""


async def test_solve_on_a_pddl_without_costs_says_optimal_in_actions() -> None:
    """No action costs: the proof is about the number of actions, and the text says only
    that (not a cost it does not have)."""
    async with Client(build_server(Toolbox())) as client:
        solved = await client.call_tool("solve", {"pddl": {"domain": GRIPPER,
                                                           "problem": TWO_BALLS}})
    said = text(solved)
    assert said.startswith("plan of 7 action(s), verified, optimal (Fast Downward "
                           "seq-opt-lmcut proved that no plan has fewer actions): "), said
    assert "cost" not in said.splitlines()[0] and structured(solved)["cost"] is None
