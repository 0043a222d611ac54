"""PDDL's own readings of a report: a failing step in plain words, and PlanBench's answer.

Both read the JSON-ready report dict (`verigraph.reporting`, whose `report_text` is the
one text of any report), so every name the report can hold prints as in `--json`.

PlanBench task 3 ("plan verification") scores a verifier's answer by three fields, as
its `response_evaluation.parse_output` extracts them: `valid`; for an inexecutable plan
`unmet_precondition` = {`action`, `predicate`}; for a plan that misses its goal
`unmet_goal`. `planbench_verdict` gives exactly those fields (atoms written as PlanBench
writes them, `on_a_b`; the action as `(stack a b)`) and the answer in PlanBench's words.
"""

from __future__ import annotations

from typing import Any

# A precondition the text shows as it is written only when it is this short; a longer
# one (an ADL `imply` over quantifiers) is named by what failed in it.
SHORT_LITERAL = 60
PLAIN_PARTS = 3


def plain_summary(action: str, unsatisfied: list[dict[str, Any]]) -> str:
    """One plain line for a failing step, before the raw PDDL: `(stop f3) cannot run
    here: for ?q = bob: none of (served bob), (not (origin bob f3)) holds; ...`. Each
    unsatisfied precondition is said by what failed in it (the innermost part of its
    explanation, after any `... holds but`), a short one with its literal."""
    parts = []
    for u in unsatisfied[:PLAIN_PARTS]:
        why = str(u.get("explanation") or "is false")
        core = why.rsplit(" holds but ", 1)[-1]
        literal = str(u.get("literal", ""))
        parts.append(f"{literal} {core}" if len(literal) <= SHORT_LITERAL and
                     not core.startswith(literal) else core)
    more = len(unsatisfied) - PLAIN_PARTS
    tail = f"; and {more} more" if more > 0 else ""
    count = f"{len(unsatisfied)} precondition(s) fail" if unsatisfied else "a precondition fails"
    return f"{action} cannot run here, {count}: " + "; ".join(parts) + tail


def planbench_atom(literal: str) -> str:
    """`(on a b)` -> `on_a_b`, PlanBench's form of a ground atom."""
    return "_".join(literal.replace("(not ", "").strip("()").split())


def planbench_verdict(data: dict[str, Any]) -> dict[str, Any]:
    """PlanBench task 3's answer for this report: its fields and its wording."""
    if data["valid"]:
        return {"valid": True, "message": "The above plan is valid."}
    if data["violations"]:
        v = data["violations"][0]
        action = "(" + " ".join((v["action"]["action"], *v["action"]["args"])) + ")"
        literals = [u["literal"] for u in v.get("unsatisfied", [])]
        many = len(literals) > 1
        message = ("The above plan is invalid. The following action at step "
                   f"{v['step']} has {'unmet preconditions' if many else 'an unmet precondition'}"
                   f":\n{action}\n")
        if literals:
            message += ("The unmet preconditions are:\n" if many else
                        "The unmet precondition is:\n") + "\n".join(literals)
        else:
            message += f"It cannot be executed: {v['message']}"
        return {"valid": False, "unmet_precondition": {
            "action": action, "predicate": [planbench_atom(x) for x in literals]},
            "message": message}
    missing = data["goal_diff"]["missing_atoms"]
    many = len(missing) > 1
    return {"valid": False, "unmet_goal": [planbench_atom(x) for x in missing],
            "message": "The above plan is invalid. "
                       + ("These are the unmet goal conditions:\n" if many else
                          "This is the unmet goal condition:\n") + "\n".join(missing)}
