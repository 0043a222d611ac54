"""One entry point for PDDL plans: the native blocks world when the domain is one, else STRIPS.

`validate_pddl_dict` tries the blocks-world recogniser first (any names: recognition is
by structure) because its hand model is several times faster; a domain or problem it
refuses (another domain, or a blocks-world problem whose initial state no scene can
hold) goes to the general STRIPS simulator, which judges it by PDDL's own semantics.
An invalid blocks-world plan is then also explained by the STRIPS simulator, so both
engines report the same fields: the unsatisfied preconditions with the step that last
made each false, and the actions that would achieve an unmet goal. The report says
which engine judged it (`engine`).
"""

from __future__ import annotations

from typing import Any

from verigraph.actions.blocksworld.domain import UnsupportedDomainError
from verigraph.actions.blocksworld.plans import parse_blocks_plan
from verigraph.actions.blocksworld.problem import read_problem
from verigraph.actions.blocksworld.validate import cached_domain, validate_blocks_dict
from verigraph.actions.pddl.simulate import validate_strips_dict
from verigraph.errors import VeriGraphError

ENGINES = ("auto", "blocksworld", "strips")


def validate_pddl_dict(domain_text: str, problem_text: str, plan_text: str, *,
                       engine: str = "auto") -> dict[str, Any]:
    """The JSON-ready report for any supported PDDL domain (see the module docstring)."""
    if engine not in ENGINES:
        raise VeriGraphError(f"unknown engine '{engine}'", field="engine", value=engine,
                             fix=f"use one of {', '.join(ENGINES)}")
    if engine != "strips":
        try:
            data = validate_blocks_dict(domain_text, problem_text, plan_text)
        except UnsupportedDomainError:
            if engine == "blocksworld":
                raise
        else:
            data = {"engine": "blocksworld", **data}
            if not data["valid"]:
                _explain(data, domain_text, problem_text, plan_text)
            return data
    return validate_strips_dict(domain_text, problem_text, plan_text)


def _explain(data: dict[str, Any], domain_text: str, problem_text: str, plan_text: str) -> None:
    """Add the STRIPS explanation (unsatisfied literals, achievers) to a blocks report."""
    try:
        domain = cached_domain(domain_text)
        declared = set(read_problem(problem_text, domain).blocks)
        canonical = "\n".join(s.text for s in parse_blocks_plan(plan_text, domain, declared))
        strips = validate_strips_dict(domain_text, problem_text, canonical)
    except VeriGraphError:
        return
    if data["violations"] and strips["violations"] \
            and strips["violations"][0]["step"] == data["violations"][0]["step"]:
        data["violations"][0]["unsatisfied"] = strips["violations"][0]["unsatisfied"]
    if not data["violations"] and not strips["violations"]:
        data["unmet_goals"] = strips["unmet_goals"]
