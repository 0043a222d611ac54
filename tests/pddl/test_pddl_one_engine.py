"""One engine judges each blocks-world plan: the plans the native engine hands to the
STRIPS engine (an invalid plan checked with `all_errors`, a plan with a line the native
reader cannot read) get the report the STRIPS engine gives for the plan written in its
own form, field for field, though the native engine's applied steps are replayed, not
judged again, and the plan is read once."""

from __future__ import annotations

import random
from collections import Counter

import pytest

from blocksworld_corpus import domain_text as spelling_domain
from blocksworld_corpus import generate
from verigraph.errors import PlanParseError
from verigraph.pddl import validate_pddl_dict
from verigraph.pddl.blocksworld.domain import cached_domain
from verigraph.pddl.blocksworld.plans import PLANBENCH_COLOURS, parse_blocks_plan
from verigraph.pddl.blocksworld.problem import read_blocks_problem
from verigraph.pddl.plans import parse_strips_plan
from verigraph.pddl.simulate import (
    cached_strips_domain,
    validate_strips_dict,
    validate_strips_steps,
)

pytestmark = pytest.mark.fast

COLOUR = {letter: colour for colour, letter in PLANBENCH_COLOURS.items()}
PLANBENCH = spelling_domain("planbench")
# the stack action with its parameters reordered (the block below first): the native
# engine's steps reach the STRIPS engine in the domain's order
SWAPPED = PLANBENCH.replace(":parameters  (?ob ?underob)\n  :precondition (and (clear "
                            "?underob) (holding ?ob))", ":parameters  (?underob ?ob)\n"
                            "  :precondition (and (clear ?underob) (holding ?ob))", 1)
GARBAGE = ["(no plan possible)", "(1) (stack {x} {y})", "hello world", "(unstack {x})",
           "(fly {x} {y})", "(pick-up {x} {y})", "(", "stack", "put the {x} block away"]


def english(line: str) -> str:
    """A 4-op PlanBench line as its sentence (the colours for the letters)."""
    op, *args = line[1:-1].split()
    blocks = [f"the {COLOUR[a]} block" for a in args]
    return {"unstack": f"unstack {blocks[0]} from on top of {blocks[-1]}",
            "stack": f"stack {blocks[0]} on top of {blocks[-1]}",
            "pick-up": f"pick up {blocks[0]}", "put-down": f"put down {blocks[0]}"}[op]


def plans(rng: random.Random, plan: list[str], blocks: list[str]) -> dict[str, list[str]]:
    """The plan and its corruptions: swapped and removed steps, garbage lines, noise."""
    x, y = rng.choice(blocks), rng.choice(blocks)
    out = {"plain": list(plan), "garbage": list(plan), "two_garbage": list(plan)}
    out["garbage"].insert(rng.randrange(len(plan) + 1), rng.choice(GARBAGE).format(x=x, y=y))
    for _ in range(2):
        out["two_garbage"].insert(rng.randrange(len(out["two_garbage"]) + 1),
                                  rng.choice(GARBAGE).format(x=y, y=x))
    if len(plan) > 2:
        i = rng.randrange(len(plan) - 1)
        out["swapped"] = plan[:i] + [plan[i + 1], plan[i]] + plan[i + 2:]
        out["removed"] = plan[:i] + plan[i + 1:]
    noisy: list[str] = []
    for line in plan:
        r = rng.random()
        noisy.append(line.upper() if r < .2 else f"{len(noisy)}: {line} [1]" if r < .4
                     else line)
        noisy += ["; a comment"] if rng.random() < .1 else [""] if rng.random() < .1 else []
    out["noisy"] = noisy
    out["noisy_removed"] = noisy[:-2] + noisy[-1:]
    return out


def cases():
    """(label, domain, problem, plan text) over the generated PlanBench-style problems."""
    rng = random.Random(3)
    for spelling, problem, plan, kind in generate(36, seed=9):
        if spelling == "typed":
            plan = [a.replace("pick-up", "pickup").replace("put-down", "putdown") for a in plan]
        domain = spelling_domain(spelling)
        blocks = sorted(read_blocks_problem(problem, cached_domain(domain)).blocks)
        variants = plans(rng, plan, blocks)
        if spelling == "planbench":
            sentences = [english(a) if rng.random() < .6 else a for a in plan]
            variants |= {f"english_{k}": v for k, v in plans(rng, sentences, blocks).items()}
        for name, lines in variants.items():
            yield f"{spelling}/{kind}/{name}", domain, problem, "\n".join(lines)
        if spelling == "planbench":  # the reordered stack, its steps and corruptions
            swapped = [f"(stack {a.split()[2][:-1]} {a.split()[1]})" if a.startswith("(stack")
                       else a for a in plan]
            for name, lines in plans(rng, swapped, blocks).items():
                yield f"swapped/{kind}/{name}", SWAPPED, problem, "\n".join(lines)


def strips_form(domain: str, problem: str, plan: str) -> str:
    """The plan as the STRIPS engine reads it: each line the native reader reads written
    `(op args)` in the domain's parameter order, the others as they are."""
    blocks = cached_domain(domain)
    declared = set(read_blocks_problem(problem, blocks).blocks)
    out = []
    for line in plan.splitlines():
        try:
            steps = parse_blocks_plan(line, blocks, declared)
        except PlanParseError:
            out.append(line)
            continue
        out.append(steps[0].text if steps else line)
    return "\n".join(out)


def unreadable(domain: str, problem: str, plan: str) -> bool:
    blocks = cached_domain(domain)
    try:
        parse_blocks_plan(plan, blocks, set(read_blocks_problem(problem, blocks).blocks))
    except PlanParseError:
        return True
    return False


def test_handed_over_plans_get_the_strips_engines_report_field_for_field():
    seen: Counter[str] = Counter()
    for label, domain, problem, plan in cases():
        for all_errors in (False, True):
            got = validate_pddl_dict(domain, problem, plan, all_errors=all_errors)
            want = validate_pddl_dict(domain, problem, strips_form(domain, problem, plan),
                                      engine="strips", all_errors=all_errors)
            where = f"{label} all_errors={all_errors}"
            if unreadable(domain, problem, plan):
                kind = "unreadable line" + (", all_errors" if all_errors else "")
            elif all_errors and want["violations"]:
                kind = "failing step, all_errors"
            else:  # the native engine judges: same verdict, its own report form
                assert got["engine"] == "blocksworld", where
                assert (got["valid"], [v["step"] for v in got["violations"]][:1]) == (
                    want["valid"], [v["step"] for v in want["violations"]][:1]), where
                seen["native"] += 1
                continue
            assert set(got) == set(want), where
            for field in want:
                if field != "engine":
                    assert got[field] == want[field], f"{where}: {field}"
            failures = [v["step"] for v in want["violations"]]
            seen[kind] += 1
            seen["after a failure"] += kind.endswith("all_errors") and len(failures) > 1
            seen["steps replayed"] += kind.startswith("failing") and failures[0] > 1
    assert len(seen) == 6 and min(seen.values()) >= 20, seen  # every kind, many times


def test_steps_the_strips_engine_would_not_apply_are_judged_again():
    """`applied` steps that do not apply in the STRIPS engine (the engines disagree) make
    it judge the whole plan: the report is the one the plan's text gives."""
    problem = ("(define (problem p) (:domain d) (:objects a b) (:init (arm-empty) (clear a) "
               "(on a b) (on-table b)) (:goal (and (on b a))))")
    plan = "(pick-up a)\n(put-down a)\n(unstack a b)\n(pick-up b)"
    steps = parse_strips_plan(plan, cached_strips_domain(PLANBENCH))
    want = validate_strips_dict(PLANBENCH, problem, plan, all_errors=True)
    assert [v["step"] for v in want["violations"]] == [1, 2, 4]
    for applied in (0, 1, 3):
        got = validate_strips_steps(PLANBENCH, problem, steps, all_errors=True,
                                    applied=applied)
        assert got == want, applied
    # steps that do apply are replayed: the same report, from the first failing one on
    plan = "(unstack a b)\n(put-down a)\n(pick-up b)\n(stack b b)\n(stack b a)"
    steps = parse_strips_plan(plan, cached_strips_domain(PLANBENCH))
    want = validate_strips_dict(PLANBENCH, problem, plan, all_errors=True)
    assert [v["step"] for v in want["violations"]] == [4]
    assert validate_strips_steps(PLANBENCH, problem, steps, all_errors=True,
                                 applied=3) == want
