"""The plan report: one plain-data form every engine returns, and its one text renderer.

Every engine that checks a plan (the scene-graph validator `actions.execution.check_plan`,
the native blocks world `pddl.blocksworld`, the general STRIPS engine `pddl.simulate`)
returns the same JSON-ready dict, the one `verigraph validate --json` and `--batch`
print; the MCP tools turn it into their `ValidationReport` model at the boundary
(`actions.pddl.as_validation_report`), and nothing else builds a model from it. Plain
data keeps the hot loop of a long plan free of model objects and lets a PDDL check load
no pydantic at all (docs/validator.md, Start-up).

The form (keys whose value would be None are left out):

* `valid`, `plan_valid`, `goal_reached` (absent: no goal given), `not_checked` (actions
  after the first failure), `done` (the plan ended with the end token);
* `steps`: `{step, ok, action, text, edit | violation}`; `action` is the action as data
  (`{"action": "move", "object": ..., ...}` or `{"action": op, "args": [...]}`), `text`
  the step as written; `edit` is `{removed, added, states?}` (scene edges as
  `{source, relation, target}`, PDDL atoms as literal strings); a `violation` is
  `{ok, step, action, constraint, message, blocking, suggestion}` and, from a PDDL
  engine, `unsatisfied` (each literal with its explanation and achievers);
* `violations`: every step's violation, in order;
* `goal_diff`: a scene's `{satisfied, missing_edges, extra_edges, missing_nodes,
  extra_nodes, predicate?, detail?, missing_states?, formula_detail?}` (edges as
  sentences, `cup on desk`), or a PDDL problem's `{satisfied, missing_atoms}` (the goal
  literals that do not hold, `(on c a)`);
* `final_graph` (a scene, or the blocks world's), `label_readings` (how the labels the
  caller wrote were read);
* PDDL only: `engine`, `unmet_goals` (explained like `unsatisfied`), `total_cost`,
  `after_failure`, `final_state` (STRIPS: the final atoms).

`report_text` is the one way a report becomes text (the command line, the MCP tool's
text, the demo): the verdict, one line per step (its edit, or the failure with its fix
and, from a PDDL engine, every unsatisfied precondition explained), what was not
checked, the unmet goals. `max_steps` caps the accepted steps shown (a long plan's
others are counted) and `max_failures` the failures, so a tool text stays bounded.
This module imports nothing of the package: every layer may use it.
"""

from __future__ import annotations

import re
from typing import Any

# How an object's states read (`fridge: closed -> open`; a goal's `fridge closed`).
STATE_WORDS = {"open": ("closed", "open"), "toggled_on": ("off", "on"),
               "cooked": ("raw", "cooked"), "hot": ("not hot", "hot"),
               "frozen": ("not frozen", "frozen")}
MAX_LISTED = 10  # items joined into one sentence before "and N more"
MAX_TEXT_UNMET = 10  # explained literals shown per failing step or unmet goal list
AFTER_FAILURE = ("later steps are checked from the state before each failing step (the "
                 "failing step is skipped)")
_MORE = re.compile(r"\.\.\. and (\d+) more")
PlanReport = dict[str, Any]  # the one report form (module docstring)


def listed_count(lines: list[str]) -> int:
    """The items a kept list stands for (its last item may say "... and N more")."""
    m = _MORE.fullmatch(lines[-1]) if lines else None
    return len(lines) - 1 + int(m.group(1)) if m else len(lines)


def shortened(lines: list[str], limit: int = MAX_LISTED) -> list[str]:
    """The first `limit` items of a kept list, then "... and N more" for the rest."""
    total = listed_count(lines)
    shown = [line for line in lines[:limit] if not _MORE.fullmatch(line)]
    return shown + ([f"... and {total - len(shown)} more"] if total > len(shown) else [])


def goal_text(diff: dict[str, Any]) -> str:
    """`goal reached`, or `goal not reached: missing: ... | extra: ...`: a goal diff in
    one line (`graph.goal.GraphDiff.summary` is this, on its model)."""
    detail = diff.get("detail")
    formula = diff.get("formula_detail") or []
    if diff["satisfied"]:  # a reached goal's detail is a note (a PDDL plan's total cost)
        head = f"goal reached ({detail})" if detail else "goal reached"
        return f"{head}; " + "; ".join(shortened(formula)) if formula else head
    parts = []
    for key, name, sep in (("missing_atoms", "missing: ", "; "),
                           ("missing_edges", "missing: ", "; "),
                           ("missing_states", "states not reached: ", "; "),
                           ("extra_edges", "extra: ", "; "),
                           ("missing_nodes", "missing objects: ", ", "),
                           ("extra_nodes", "extra objects: ", ", ")):
        if diff.get(key):
            parts.append(name + sep.join(diff[key]))
    if detail:
        parts.append(detail)
    if formula:
        n = listed_count(formula)
        parts.append(f"formula fails ({n} counterexample{'s' if n != 1 else ''}): "
                     + "; ".join(shortened(formula)))
    return "goal not reached: " + " | ".join(parts)


def state_change_text(obj: str, key: str, before: bool, after: bool) -> str:
    """`fridge: closed -> open`."""
    words = STATE_WORDS[key]
    return f"{obj}: {words[before]} -> {words[after]}"


def edit_text(edit: dict[str, Any]) -> str:
    """`-cup on book, +cup on desk, fridge: closed -> open` (PDDL: `-(clear b), +(holding a)`)."""
    def one(e: Any) -> str:
        if isinstance(e, str):
            return e
        if e["relation"] == "touches":
            return (f"{e['source']}[{e.get('source_side')}] touches "
                    f"{e['target']}[{e.get('target_side')}]")
        return f"{e['source']} {e['relation']} {e['target']}"
    parts = [f"-{one(e)}" for e in edit.get("removed", ())]
    parts += [f"+{one(e)}" for e in edit.get("added", ())]
    parts += [state_change_text(s["object"], s["key"], s["before"], s["after"])
              for s in edit.get("states") or ()]
    return ", ".join(parts)


def violation_text(v: dict[str, Any], with_step: bool = True) -> str:
    """`step 2: [object_not_clear] ... Suggestion: ...` (`actions.feedback.Violation.text`)."""
    where = f"step {v['step']}: " if v.get("step") is not None and with_step else ""
    return f"{where}[{v['constraint']}] {v['message']}. Suggestion: {v['suggestion']}"


def achiever_text(item: dict[str, Any]) -> str:
    """The achievers of an unsatisfied literal or unmet goal, as every surface shows them
    (CLI text, `--batch` readers, the MCP tool): each with its grounding applicable now,
    or its closest grounding and what that still needs, in the engine's order."""
    parts = []
    for a in item.get("achievers") or []:
        if a.get("applicable_now"):
            parts.append(f"{a['applicable_now']} (applicable now)")
        elif a.get("closest"):
            parts.append(f"{a['closest']} (needs {' and '.join(a['needs'][:3])})")
        else:
            parts.append(a["action"])
    return "achieved by " + ", ".join(parts) if parts else ""


def explained_text(item: dict[str, Any]) -> str:
    """`(clear b): never true; achieved by (unstack a b) (applicable now)`."""
    achievers = achiever_text(item)
    return f"{item['literal']}: {item['explanation']}" + (f"; {achievers}" if achievers else "")


def cost_text(data: dict[str, Any]) -> str:
    """The plan's total cost as the verdict says it (PDDL with action costs), else ''."""
    if "total_cost" not in data:
        return ""
    if data["plan_valid"]:
        return (f"plan cost {data['total_cost']} (the sum of its actions' costs, the "
                "domain's total-cost)")
    return f"cost of the applied steps {data['total_cost']}"


def verdict_text(data: dict[str, Any]) -> str:
    """`INVALID: 3 step(s) checked, 1 violation(s); goal not reached: missing: ...`."""
    head = (f"{'VALID' if data['valid'] else 'INVALID'}: {len(data['steps'])} step(s) "
            "checked")
    if data["violations"]:
        head += f", {len(data['violations'])} violation(s)"
    diff = data.get("goal_diff")
    if diff is not None:
        detail = diff.get("detail") or ""
        if diff["satisfied"] and detail.startswith("total cost "):  # the model's form
            head += ("; goal reached; plan cost " + detail.removeprefix("total cost ")
                     + " (the sum of its actions' costs, the domain's total-cost)")
        else:
            head += f"; {goal_text(diff)}"
    cost = cost_text(data)
    return head + (f"; {cost}" if cost else "") + " (a check only, nothing was executed)"


def report_text(data: dict[str, Any], *, max_steps: int | None = None,
                max_failures: int | None = None) -> str:
    """The report as text: the verdict, then one line per step (accepted steps after
    `max_steps` and failures after `max_failures` are only counted; None: all shown),
    what was not checked, the unmet goals explained, how labels were read."""
    lines = [verdict_text(data)]
    hidden_ok = hidden_failed = failures = 0
    pad = " " * 10
    for s in data["steps"]:
        if s["ok"]:
            if max_steps is not None and s["step"] > max_steps:
                hidden_ok += 1
                continue
            edit = edit_text(s["edit"]) if s.get("edit") else ""
            lines.append(f"{s['step']:>3} ok    {s['text']}" + (f"   {edit}" if edit else ""))
            continue
        failures += 1
        if max_failures is not None and failures > max_failures:
            hidden_failed += 1
            continue
        v = s["violation"]
        lines.append(f"{s['step']:>3} FAIL  {s['text']}: {violation_text(v, False)}")
        lines += [f"{pad}unsatisfied {explained_text(u)}"
                  for u in (v.get("unsatisfied") or [])[:MAX_TEXT_UNMET]]
    if hidden_ok:
        lines.append(f"... and {hidden_ok} more accepted step(s) after step {max_steps}")
    if hidden_failed:
        lines.append(f"... and {hidden_failed} more failed step(s) (see structured content)")
    if data["not_checked"]:
        lines.append(f"... {data['not_checked']} later action(s) not checked: it stopped at "
                     "the first violation (all_errors=true, or --all-errors, checks them)")
    elif data.get("after_failure") and data["violations"]:
        lines.append(f"(all errors: {AFTER_FAILURE})")
    lines += [f"{pad}unmet goal {explained_text(u)}"
              for u in (data.get("unmet_goals") or [])[:MAX_TEXT_UNMET]]
    if data.get("label_readings"):
        lines.append(readings_line(data["label_readings"]))
    return "\n".join(lines)


def readings_line(readings: list[str]) -> str:
    """`labels read: box read as block (synonym, blocks dictionary)`: every label the
    client wrote that was taken as another name (never silent); empty when none."""
    return "labels read: " + "; ".join(readings) if readings else ""
