"""Readable forms of a PDDL report: the per-step text, and PlanBench's verification answer.

Both read the JSON-ready report dict directly (no pydantic model), so every name the
report can hold prints the same in text mode as in `--json` and `--batch`.

PlanBench task 3 ("plan verification") scores a verifier's answer by three fields, as
its `response_evaluation.parse_output` extracts them: `valid`; for an inexecutable plan
`unmet_precondition` = {`action`, `predicate`}; for a plan that misses its goal
`unmet_goal`. `planbench_verdict` gives exactly those fields (atoms written as PlanBench
writes them, `on_a_b`; the action as `(stack a b)`) and the answer in PlanBench's words.
"""

from __future__ import annotations

from typing import Any

MAX_TEXT_UNMET = 10


def _edit_text(edit: dict[str, Any]) -> str:
    def one(e: Any) -> str:
        if isinstance(e, str):
            return e
        return f"{e['source']} {e['relation']} {e['target']}"
    return ", ".join([f"-{one(e)}" for e in edit.get("removed", [])]
                     + [f"+{one(e)}" for e in edit.get("added", [])])


def achiever_text(item: dict[str, Any]) -> str:
    """The achievers of an unsatisfied literal or unmet goal, as every surface shows them
    (CLI text, `--batch` readers, the MCP tool): each with its grounding applicable now,
    or its closest grounding and what that still needs, in the engine's order."""
    achievers = item.get("achievers") or []
    parts = []
    for a in achievers:
        if a.get("applicable_now"):
            parts.append(f"{a['applicable_now']} (applicable now)")
        elif a.get("closest"):
            parts.append(f"{a['closest']} (needs {' and '.join(a['needs'][:3])})")
        else:
            parts.append(a["action"])
    return "achieved by " + ", ".join(parts) if parts else ""


def _achiever_text(item: dict[str, Any]) -> str:
    text = achiever_text(item)
    return f"; {text}" if text else ""


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


AFTER_FAILURE = ("later steps are checked from the state before each failing step (the "
                 "failing step is skipped)")


def report_text(data: dict[str, Any]) -> str:
    """One line per step; the failing step explained in full; the goal; the verdict."""
    lines = []
    for s in data["steps"]:
        if s["ok"]:
            edit = _edit_text(s.get("edit") or {})
            lines.append(f"{s['step']:>4} ok    {s['text']}" + (f"   {edit}" if edit else ""))
            continue
        v = s["violation"]
        lines.append(f"{s['step']:>4} FAIL  {s['text']}   [{v['constraint']}] {v['message']}")
        lines.append(f"{'':>10}fix: {v['suggestion']}")
        for u in v.get("unsatisfied", [])[:MAX_TEXT_UNMET]:
            lines.append(f"{'':>10}unsatisfied {u['literal']}: {u['explanation']}"
                         + _achiever_text(u))
    if data["not_checked"]:
        lines.append(f"      ... {data['not_checked']} later action(s) not checked: it "
                     "stopped at the first failing step")
    elif data.get("after_failure") and data["violations"]:
        lines.append(f"      (all errors: {AFTER_FAILURE})")
    diff = data.get("goal_diff")
    if diff is not None:
        if diff["satisfied"]:
            lines.append("goal reached")
        else:
            lines.append("goal not reached: missing: " + "; ".join(diff["missing_edges"]))
            for u in data.get("unmet_goals", [])[:MAX_TEXT_UNMET]:
                lines.append(f"{'':>10}{u['literal']}: {u['explanation']}" + _achiever_text(u))
    reason = []
    if not data["plan_valid"]:
        reason.append(f"{len(data['violations'])} violation(s)")
    if data.get("goal_reached") is False:
        reason.append("goal not reached")
    if "total_cost" in data:
        reason.append(f"total cost {data['total_cost']} (the applied steps' action costs)")
    lines.append(f"{'VALID' if data['valid'] else 'INVALID'}: {len(data['steps'])} step(s) "
                 "checked" + (f", {', '.join(reason)}" if reason else ""))
    return "\n".join(lines)


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
    missing = data["goal_diff"]["missing_edges"]
    many = len(missing) > 1
    return {"valid": False, "unmet_goal": [planbench_atom(x) for x in missing],
            "message": "The above plan is invalid. "
                       + ("These are the unmet goal conditions:\n" if many else
                          "This is the unmet goal condition:\n") + "\n".join(missing)}
