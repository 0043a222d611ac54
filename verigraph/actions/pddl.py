"""A plan report (`verigraph.reporting`'s plain form, any engine) as a `ValidationReport`.

The engines return plain dicts; this module is the one place a dict becomes the pydantic
model the MCP tools return, at their boundary. `validate_pddl_dict` (either PDDL engine,
chosen as in `verigraph.pddl.validate`) is re-exported here, so
`verigraph.actions.pddl.validate_pddl_dict` keeps working (docs/validator.md).

A scene-graph report is the model's own form. A PDDL report converts too: the blocks
world keeps its scene (blocks, table, hand) as `final_graph`; a STRIPS report has no
scene, so `final_graph` is empty and the final atoms stay in the dict form. The
explanations the model has no field for go into text it has: each unsatisfied
precondition with the step that last made it false into the violation's message (with
every achiever, as `reporting.achiever_text` writes them), led by a plain summary
(`in short: ...`) when the message is long; the achievers of each unmet goal, the plan's
total cost and, with all_errors, from which state later steps were checked, into
`goal_diff.detail`. The goal literals that do not hold (`goal_diff.missing_atoms`) are
the model's `goal_diff.missing_edges`, its one list of unmet goal parts.
"""

from __future__ import annotations

from typing import Any

from verigraph.actions.report import ValidationReport
from verigraph.errors import VeriGraphError
from verigraph.pddl.blocksworld.validate import validate_blocks_dict
from verigraph.pddl.text import plain_summary
from verigraph.pddl.validate import validate_pddl_dict
from verigraph.reporting import AFTER_FAILURE, achiever_text

__all__ = ["as_validation_report", "validate_pddl_dict", "validate_pddl_plan"]

MAX_DETAIL_GOALS = 10
# A PDDL failure whose message is longer than this gets a plain summary before it.
PLAIN_FROM_CHARS = 160


def _explained(items: list[dict[str, Any]]) -> str:
    """Why each unmet goal literal is false; one alone is not named again (the text's
    `missing:` list has just named it): `why: 5 counterexamples: for ?p = alice: ...`."""
    parts = []
    for u in items[:MAX_DETAIL_GOALS]:
        text = f"why: {u['explanation']}" if len(items) == 1 else \
            f"{u['literal']}: {u['explanation']}"
        achievers = achiever_text(u)
        if achievers:
            text += f", {achievers}"
        parts.append(text)
    return "; ".join(parts)


def as_validation_report(data: dict[str, Any]) -> ValidationReport:
    """The report dict (any engine) as a ValidationReport."""
    if "engine" not in data:  # a scene-graph report: the model's own form
        return ValidationReport.model_validate(data)
    strips = data["engine"] == "strips"
    steps = []
    for s in data["steps"]:
        step = {k: v for k, v in s.items() if k not in ("edit", "violation")}
        if s.get("edit") and not strips:
            step["edit"] = s["edit"]
        steps.append(step)
    texts = {s["step"]: s["text"] for s in data["steps"] if not s["ok"]}
    violations = []
    by_step = {}
    for v in data["violations"]:
        unsatisfied = v.get("unsatisfied") or []
        v = {k: x for k, x in v.items() if k != "unsatisfied"}
        if not strips and unsatisfied:
            v["message"] += " (needs " + _explained(unsatisfied) + ")"
        elif unsatisfied:
            achievers = "; ".join(f"{u['literal']} {achiever_text(u)}"
                                  for u in unsatisfied[:MAX_DETAIL_GOALS] if u.get("achievers"))
            if achievers:
                v["message"] += f" ({achievers})"
        if unsatisfied and len(v["message"]) > PLAIN_FROM_CHARS:
            v["message"] = (f"in short: {plain_summary(texts.get(v['step'], 'it'), unsatisfied)}."
                            " In full: " + v["message"])
        violations.append(v)
        by_step[v["step"]] = v
    for s in steps:
        if not s["ok"]:
            s["violation"] = by_step[s["step"]]
    # the model's goal diff is a graph's: the unmet goal literals go where its missing
    # goal edges go (a blocks-world atom is one of its edges, `(on c a)`)
    diff = {"satisfied": data["goal_diff"]["satisfied"],
            "missing_edges": data["goal_diff"]["missing_atoms"]}
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
    return as_validation_report({"engine": "blocksworld",
                                 **validate_blocks_dict(domain_text, problem_text, plan_text)})
