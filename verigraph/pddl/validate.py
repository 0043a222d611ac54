"""One entry point for PDDL plans: the native blocks world when the domain is one, else STRIPS.

Every domain is first read by the STRIPS reader (cached per text), which refuses by name
anything it cannot read or judge (a misspelt keyword, an unsupported requirement, an
undeclared name), whichever engine then judges the plan, so no engine can skip a part of
a domain silently. `validate_pddl_dict` then tries the blocks-world recogniser (any
names: recognition is by structure) because its hand model is several times faster; a
domain or problem it refuses (another domain, or a blocks-world problem whose initial
state no scene can hold) goes to the general STRIPS simulator, which judges it by PDDL's
own semantics. One engine judges each step, once (but the failing step at which the
blocks engine hands an `all_errors` check over, below, which both read): where the
blocks engine refuses a step or misses the goal it explains that itself, in the STRIPS
engine's form (the unsatisfied preconditions with the step that last made each false,
the actions that would achieve an unmet goal), from the history of the steps it applied
(`simulate.explain_steps`, which grounds and applies them as the STRIPS step-by-step run
does), so both engines report the same fields.

Two kinds of blocks-world plan get the STRIPS engine's report (its steps' edits are
atoms, its constraint ids and messages its own), because only that engine judges what
they need: a plan with a line that is no action of the domain (the STRIPS engine makes
such a line a failing step), and an invalid plan checked with `all_errors=True` (the
STRIPS engine goes on after a failure, skipping the failing step). Their lines are read
once, by the blocks world's reader (PlanBench sentences and colours included), which
hands each line it cannot read to the STRIPS reader (`_strips_steps`). A plan with such
a line is judged by the STRIPS engine alone; the blocks engine reads a whole plan before
it judges a step, except that its fast run meets an unknown operator or a wrong number of
arguments in a plain `(op args)` line only when it gets there. An invalid plan checked
with `all_errors` is judged by the blocks engine up to its first failing step, and the
STRIPS engine takes over there (`simulate.validate_strips_steps`): it replays the steps
the blocks engine applied, as `explain_steps` does, which gives its history and its form
of their report steps, and judges from the failing step on. A valid plan, or one that
only misses the goal, is the blocks engine's with or without `all_errors`. The report
says which engine judged it (`engine`: "strips" for both kinds above).
"""

from __future__ import annotations

import re
from functools import lru_cache
from operator import attrgetter
from typing import Any

from verigraph.errors import PlanParseError, VeriGraphError
from verigraph.graph.bulk import collector_paused
from verigraph.pddl.blocksworld.domain import (
    BlocksDomain,
    UnsupportedDomainError,
    cached_domain,
)
from verigraph.pddl.plans import Step, read_step
from verigraph.pddl.reader import PROBLEM_SECTIONS, SUPPORTED_REQUIREMENTS
from verigraph.pddl.simulate import (
    cached_strips_domain,
    cached_strips_problem,
    explain_steps,
    total_value,
    validate_strips_dict,
    validate_strips_steps,
)
from verigraph.pddl.syntax import COMMENT, ascii_names

ENGINES = ("auto", "blocksworld", "strips")
_SECTION = re.compile(r"\(\s*(:[^\s()]+)")
_REQUIREMENTS = re.compile(r"\(\s*:requirements\b([^()]*)\)")
_STRAY = re.compile(r"\)\s*[^\s()]+\s*\(")  # a bare word between two lists
_VALUE = re.compile(r"\(\s*=")  # `(= (total-cost) 0)`: its number is checked


def _check_problem(problem_text: str, domain_text: str) -> None:
    """What the blocks-world reader would pass over (an unknown section, a requirement
    that is no supported keyword, a stray word between sections) is refused by the STRIPS
    reader, by name. A few regex scans; the full read runs only when one finds something."""
    text = COMMENT.sub("", problem_text) if ";" in problem_text else problem_text
    text = text.lower()
    suspicious = any(k not in PROBLEM_SECTIONS for k in _SECTION.findall(text)) \
        or _STRAY.search(text) is not None or _VALUE.search(text) is not None
    if not suspicious and ":requirements" in text:
        found = _REQUIREMENTS.findall(text)
        suspicious = not found or any(r not in SUPPORTED_REQUIREMENTS
                                      for items in found for r in items.split())
    if suspicious:
        cached_strips_problem(domain_text, problem_text)


def _add_total_cost(data: dict[str, Any], domain_text: str, problem_text: str) -> None:
    """A blocks-world report's `total_cost`, as the STRIPS engine gives it: the initial
    `(= (total-cost) N)` plus the cost of every applied step (a blocks world's costs are
    numbers: its only function is total-cost)."""
    domain = cached_strips_domain(domain_text)
    has_costs = any(s.cost for s in domain.schemas.values()) or bool(domain.functions)
    if not has_costs and "total-cost" not in problem_text.lower():
        return
    problem = cached_strips_problem(domain_text, problem_text)
    if not has_costs and problem.initial_cost is None:
        return
    total = problem.initial_cost or 0.0
    for step in data["steps"]:
        if step["ok"]:
            schema = domain.schemas[step["action"]["action"]]
            total += sum(c for c in schema.cost if isinstance(c, float))
    data["total_cost"] = total_value(total)


def validate_pddl_dict(domain_text: str, problem_text: str, plan_text: str, *,
                       engine: str = "auto", all_errors: bool = False) -> dict[str, Any]:
    """The JSON-ready report for any supported PDDL domain (see the module docstring)."""
    if engine not in ENGINES:
        raise VeriGraphError(f"unknown engine '{engine}'", field="engine", value=engine,
                             fix=f"use one of {', '.join(ENGINES)}")
    cached_strips_domain(domain_text)  # refuses what no engine may skip (module docstring)
    if engine == "auto" and not _blocks_world(domain_text):
        engine = "strips"  # the blocks engine (and the scene-graph stack) is not loaded
    if engine != "strips":
        data = _judge_blocks(domain_text, problem_text, plan_text, engine, all_errors)
        if data is not None:
            return data
    return validate_strips_dict(domain_text, problem_text, plan_text, all_errors=all_errors)


def _judge_blocks(domain_text: str, problem_text: str, plan_text: str, engine: str,
                  all_errors: bool) -> dict[str, Any] | None:
    """The report when the blocks world takes the domain and problem, its failure
    explained in the STRIPS engine's form; None when it takes neither (the STRIPS
    simulator then judges the plan as written; with engine="blocksworld" the refusal is
    raised instead).

    A plan with a line the blocks world cannot read is judged by the STRIPS simulator,
    which makes that line a failing step; an invalid plan checked with `all_errors` is
    handed to it at its first failing step (`_strips_judges`; module docstring). A name
    that is not ASCII is bad input in every engine, so that refusal (`ascii_names`, the
    first thing either engine's plan reader does) is raised as it is.
    """
    from verigraph.pddl.blocksworld.validate import validate_blocks_dict

    _check_problem(problem_text, domain_text)
    try:
        data = validate_blocks_dict(domain_text, problem_text, plan_text)
    except UnsupportedDomainError:
        if engine == "blocksworld":
            raise
        return None
    except PlanParseError:
        if not plan_text.isascii():
            ascii_names(plan_text)
        return _strips_judges(domain_text, problem_text, plan_text, all_errors, 0)
    except VeriGraphError:  # PDDL the recogniser does not take (either types, ...)
        if engine == "blocksworld":
            raise
        return None
    data = {"engine": "blocksworld", **data}
    _add_total_cost(data, domain_text, problem_text)
    if not data["valid"]:
        if all_errors and data["violations"]:
            return _strips_judges(domain_text, problem_text, plan_text, True,
                                  data["violations"][0]["step"] - 1)
        _explain(data, domain_text, problem_text)
    return data


@lru_cache(maxsize=64)
def _blocks_world(domain_text: str) -> bool:
    """Whether the domain is a blocks world up to renaming, answered once per text (a
    batch of another domain asks for every item; a refusal is not cached below). A
    domain whose predicates or actions cannot be the family's (one binary predicate, at
    most three unary and one nullary, three or four actions) is not read again."""
    domain = cached_strips_domain(domain_text)
    arities = [len(signature) for signature in domain.predicates.values()]
    if len(domain.schemas) not in (3, 4) or max(arities, default=0) > 2 \
            or arities.count(2) != 1 or arities.count(1) > 3 or arities.count(0) > 1:
        return False
    try:
        cached_domain(domain_text)
    except VeriGraphError:  # another domain, or PDDL the recogniser does not take
        return False
    return True


def _strips_judges(domain_text: str, problem_text: str, plan_text: str, all_errors: bool,
                   applied: int) -> dict[str, Any]:
    """The STRIPS engine's report of a blocks-world plan that engine judges: its steps
    read once (`_strips_steps`), the first `applied` replayed, not judged again
    (`validate_strips_steps`)."""
    with collector_paused(plan_text.count("\n") + 1):  # a long plan's steps: acyclic
        steps = _strips_steps(domain_text, problem_text, plan_text)
        return validate_strips_steps(domain_text, problem_text, steps, all_errors=all_errors,
                                     applied=applied)


def _strips_steps(domain_text: str, problem_text: str, plan_text: str) -> list[Step]:
    """The plan's steps for the STRIPS engine, read in one pass: each line the blocks
    world reads as the action it reads there (a PlanBench sentence, a colour for a name, a
    reordered parameter list), each other line as the STRIPS reader reads it (a line that
    is no action a failing step, with that reader's message and fix). The steps are those
    the STRIPS reader gives for the plan with the first kind of line written `(op args)`."""
    from verigraph.pddl.blocksworld.plans import parse_blocks_plan
    from verigraph.pddl.blocksworld.problem import read_blocks_problem

    blocks = cached_domain(domain_text)
    declared = set(read_blocks_problem(problem_text, blocks).blocks)
    domain = cached_strips_domain(domain_text)
    others: list[Step] = []

    def unreadable(number: int, raw: str) -> None:
        step = read_step(raw, number, domain)
        if step is not None:
            others.append(step)

    steps = [_strips_step(s.text, s.line)
             for s in parse_blocks_plan(plan_text, blocks, declared, unreadable=unreadable)]
    return sorted([*steps, *others], key=attrgetter("line")) if others else steps


def _strips_step(text: str, line: int) -> Step:
    """A step the blocks world read, `(op args)` with the domain's parameter order, as the
    STRIPS reader reads that text."""
    name, *args = text[1:-1].split(" ")
    return Step(name, tuple(args), line)


def _explain(data: dict[str, Any], domain_text: str, problem_text: str) -> None:
    """The blocks engine's own failure or unmet goal explained in the STRIPS engine's
    form (`unsatisfied` on the violation, `unmet_goals`), with the history of the steps
    it applied (`simulate.explain_steps`)."""
    blocks = cached_domain(domain_text)
    try:
        domain = cached_strips_domain(domain_text)
        problem = cached_strips_problem(domain_text, problem_text)
        applied = (_written(blocks, s) for s in data["steps"] if s["ok"])
        failing = _written(blocks, data["violations"][0])[1:] if data["violations"] else None
        unsatisfied, unmet = explain_steps(domain, problem, applied, failing)
    except VeriGraphError:
        return
    if unmet is not None:
        data["unmet_goals"] = unmet
    elif unsatisfied is not None:
        data["violations"][0]["unsatisfied"] = unsatisfied


def _written(blocks: BlocksDomain, step: dict[str, Any]) -> tuple[int, str, tuple[str, ...]]:
    """A blocks report's step as the STRIPS engine reads it: its number, the action and
    its arguments in the domain's parameter order (the report has the template's)."""
    name, args = step["action"]["action"], step["action"]["args"]
    order = blocks.operators[name].order
    return step["step"], name, tuple(args[order[i]] for i in range(len(args)))
