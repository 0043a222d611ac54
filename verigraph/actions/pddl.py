"""The PDDL report as a `ValidationReport`, the model the library and the MCP tools return.

The PDDL engines live in `verigraph.pddl` (below `actions`) and return plain dicts; this
module is the one place a dict becomes the pydantic model. `validate_pddl_dict` (either
engine, chosen as in `verigraph.pddl.validate`) is re-exported here, so
`verigraph.actions.pddl.validate_pddl_dict` keeps working (docs/validator.md).

Both engines' dicts convert: the blocks world keeps its scene (blocks, table, hand) as
`final_graph`; a STRIPS report has no scene, so `final_graph` is empty and the final
atoms stay in the dict form. The explanations the model has no field for are folded into
text it has: each unsatisfied precondition with the step that last made it false goes
into the violation's message (with every achiever, as `text.achiever_text` writes them
for the CLI), and the achievers of each unmet goal, the plan's total cost and, with
all_errors, from which state later steps were checked, into `goal_diff.detail`.
"""

from __future__ import annotations

from typing import Any

from verigraph.actions.report import ValidationReport
from verigraph.errors import VeriGraphError
from verigraph.pddl.blocksworld.validate import validate_blocks_dict
from verigraph.pddl.text import AFTER_FAILURE, achiever_text
from verigraph.pddl.validate import validate_pddl_dict

__all__ = ["as_validation_report", "validate_pddl_dict", "validate_pddl_plan"]

MAX_DETAIL_GOALS = 10


def _explained(items: list[dict[str, Any]]) -> str:
    parts = []
    for u in items[:MAX_DETAIL_GOALS]:
        text = f"{u['literal']}: {u['explanation']}"
        achievers = achiever_text(u)
        if achievers:
            text += f", {achievers}"
        parts.append(text)
    return "; ".join(parts)


def as_validation_report(data: dict[str, Any]) -> ValidationReport:
    """The report dict (either engine) as a ValidationReport."""
    steps = []
    for s in data["steps"]:
        step = {k: v for k, v in s.items() if k != "edit"}
        if s.get("edit") and data.get("engine") != "strips":
            step["edit"] = s["edit"]
        steps.append(step)
    violations = []
    by_step = {}
    for v in data["violations"]:
        unsatisfied = v.get("unsatisfied") or []
        v = {k: x for k, x in v.items() if k != "unsatisfied"}
        if data.get("engine") != "strips" and unsatisfied:
            v["message"] += " (needs " + _explained(unsatisfied) + ")"
        elif unsatisfied:
            achievers = "; ".join(f"{u['literal']} {achiever_text(u)}"
                                  for u in unsatisfied[:MAX_DETAIL_GOALS] if u.get("achievers"))
            if achievers:
                v["message"] += f" ({achievers})"
        violations.append(v)
        by_step[v["step"]] = v
    for s in steps:
        if not s["ok"]:
            s["violation"] = by_step[s["step"]]
    diff = dict(data["goal_diff"])
    notes = []
    if data.get("unmet_goals"):
        notes.append(_explained(data["unmet_goals"]))
    if data.get("after_failure") and data["violations"]:
        notes.append(f"all errors: {AFTER_FAILURE}")
    if "total_cost" in data:
        notes.append(f"total cost {data['total_cost']}")
    if notes:
        diff["detail"] = "; ".join(notes)
    body = {"valid": data["valid"], "plan_valid": data["plan_valid"],
            "goal_reached": data["goal_reached"], "steps": steps, "violations": violations,
            "not_checked": data["not_checked"], "done": False, "goal_diff": diff,
            "final_graph": data.get("final_graph") or {"nodes": [], "edges": []}}
    try:
        return ValidationReport.model_validate(body)
    except ValueError as exc:  # a name the scene model cannot hold (longer than 128)
        raise VeriGraphError("the report cannot be given as a scene-graph report: "
                             f"{str(exc).splitlines()[0][:120]}", field="problem", value=None,
                             fix="use object names of at most 128 characters, or the JSON "
                                 "report (verigraph validate --json)") from None


def validate_pddl_plan(domain_text: str, problem_text: str, plan_text: str
                       ) -> ValidationReport:
    """The blocks-world engine alone, its report as a `ValidationReport`.

    Raises UnsupportedDomainError for domains outside the blocks-world family,
    PddlSyntaxError for unreadable PDDL and PlanParseError (naming the line) for plan
    lines that are no action or have the wrong number of arguments.
    """
    return ValidationReport.model_validate(
        validate_blocks_dict(domain_text, problem_text, plan_text))
