"""Validate a blocks-world PDDL plan natively: domain + problem + plan text -> report.

The report has the shape of `ValidationReport` (valid, plan_valid, goal_reached, steps,
violations, not_checked, done, goal_diff, final_graph) and is built as plain dicts, so
batch runs and `--json` never pay for pydantic; `validate_pddl_plan` wraps it in the
model for library users. Step numbers are 1-based indices of actions in the plan.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

from verigraph.actions.blocksworld.domain import BlocksDomain, recognise_domain
from verigraph.actions.blocksworld.hand import HandModel
from verigraph.actions.blocksworld.plans import parse_blocks_plan
from verigraph.actions.blocksworld.problem import native_state, read_problem
from verigraph.actions.report import ValidationReport
from verigraph.graph.bulk import collector_paused


@lru_cache(maxsize=64)
def cached_domain(text: str) -> BlocksDomain:
    """Domains repeat across a batch: recognise each text once."""
    return recognise_domain(text)


def _edge(e: tuple[str, str, str]) -> dict[str, str]:
    return {"source": e[0], "relation": e[1], "target": e[2]}


def validate_blocks_dict(domain_text: str, problem_text: str, plan_text: str
                         ) -> dict[str, Any]:
    """The JSON-ready report (what `verigraph validate --json` prints for PDDL input).

    Long plans make hundreds of thousands of small acyclic dicts: the cyclic garbage
    collector is paused meanwhile (see `collector_paused`).
    """
    with collector_paused(plan_text.count("\n") + 1):
        return _report(domain_text, problem_text, plan_text)


def _report(domain_text: str, problem_text: str, plan_text: str) -> dict[str, Any]:
    domain = cached_domain(domain_text)
    problem = read_problem(problem_text, domain)
    steps = parse_blocks_plan(plan_text, domain, set(problem.blocks))
    model = HandModel(native_state(problem), problem, domain)
    ops = {op.role: op for op in domain.operators.values()}
    out_steps: list[dict[str, Any]] = []
    violations: list[dict[str, Any]] = []
    for index, step in enumerate(steps, start=1):
        op = ops[step.role]
        action = {"action": op.name, "args": list(step.args)}
        failure = model.check(step, op.self_move_forbidden)
        if failure is None:
            (x, r0, t0), (_, r1, t1) = model.apply(step)
            out_steps.append({"step": index, "ok": True, "action": action, "text": step.text,
                              "edit": {"removed": [{"source": x, "relation": r0, "target": t0}],
                                       "added": [{"source": x, "relation": r1, "target": t1}]}})
            continue
        constraint, message, blocking, suggestion = failure
        violation = {"ok": False, "step": index, "action": action, "constraint": constraint,
                     "message": message, "blocking": blocking, "suggestion": suggestion}
        violations.append(violation)
        out_steps.append({"step": index, "ok": False, "action": action, "text": step.text,
                          "violation": violation})
        break
    names = {role: name for name, role in domain.predicates.items()}
    missing = ["(" + " ".join((names[role], *args)) + ")" for role, args in problem.goal
               if not model.holds(role, args)]
    plan_valid = not violations
    state = model.state
    return {
        "valid": plan_valid and not missing, "plan_valid": plan_valid,
        "goal_reached": not missing, "steps": out_steps, "violations": violations,
        "not_checked": len(steps) - len(out_steps), "done": False,
        "goal_diff": {"satisfied": not missing, "missing_nodes": [], "extra_nodes": [],
                      "missing_edges": missing, "extra_edges": []},
        "final_graph": {
            "nodes": [{"id": o.id, "label": o.label, "attrs": {}} for o in state.objects.values()],
            "edges": [_edge((o, r, t)) for o, (r, t) in state.support.items()],
            "dictionary": "blocksworld"},
    }


def validate_pddl_plan(domain_text: str, problem_text: str, plan_text: str
                       ) -> ValidationReport:
    """Library form: the same report as a `ValidationReport`.

    Raises UnsupportedDomainError for domains outside the blocks-world family,
    PddlSyntaxError for unreadable PDDL and PlanParseError (naming the line) for plan
    lines that are no action or have the wrong number of arguments.
    """
    return ValidationReport.model_validate(
        validate_blocks_dict(domain_text, problem_text, plan_text))
