"""Validate a blocks-world PDDL plan natively: domain + problem + plan text -> report.

The report is the plan report every engine returns (`verigraph.reporting`: valid,
plan_valid, goal_reached, steps, violations, not_checked, done, goal_diff, final_graph),
built as plain dicts, so batch runs and `--json` never pay for pydantic;
`verigraph.actions.pddl.validate_pddl_plan` wraps it in the tools' model. Step numbers
are 1-based indices of actions in the plan.
An accepted step's arrays (`args`, `edit.removed`, `edit.added`) are tuples: immutable,
cheaper to build, and the same JSON; the edge a block leaves, with the tuple around it,
is the one the step that put it there added.
"""

from __future__ import annotations

import gc
from typing import Any

from verigraph.graph.bulk import LARGE_GRAPH_ITEMS, collector_paused, promote_young_objects
from verigraph.pddl.blocksworld.domain import BlocksDomain, cached_domain
from verigraph.pddl.blocksworld.hand import HandModel
from verigraph.pddl.blocksworld.plans import parse_blocks_plan, plain_actions
from verigraph.pddl.blocksworld.problem import BlocksProblem, native_state, read_blocks_problem


def _edge(e: tuple[str, str, str]) -> dict[str, str]:
    return {"source": e[0], "relation": e[1], "target": e[2]}


def validate_blocks_dict(domain_text: str, problem_text: str, plan_text: str
                         ) -> dict[str, Any]:
    """The JSON-ready report (what `verigraph validate --json` prints for PDDL input).

    Long plans make hundreds of thousands of small acyclic dicts: the cyclic garbage
    collector is paused meanwhile (see `collector_paused`).
    """
    lines = plan_text.count("\n") + 1
    with collector_paused(lines):
        report = _report(domain_text, problem_text, plan_text)
        if lines >= LARGE_GRAPH_ITEMS and gc.get_freeze_count() == 0:
            promote_young_objects()
    return report




Run = tuple[HandModel, list[dict[str, Any]], list[dict[str, Any]], int]


def _report(domain_text: str, problem_text: str, plan_text: str) -> dict[str, Any]:
    domain = cached_domain(domain_text)
    problem = read_blocks_problem(problem_text, domain)
    model, out_steps, violations, n_steps = (_plain_run(domain, problem, plan_text)
                                             or _stepwise_run(domain, problem, plan_text))
    state = model.state
    names = {role: name for name, role in domain.predicates.items()}
    missing = ["(" + " ".join((names[role], *args)) + ")" for role, args in problem.goal
               if not model.holds(role, args)]
    plan_valid = not violations
    return {
        "valid": plan_valid and not missing, "plan_valid": plan_valid,
        "goal_reached": not missing, "steps": out_steps, "violations": violations,
        "not_checked": n_steps - len(out_steps), "done": False,
        "goal_diff": {"satisfied": not missing, "missing_atoms": missing},
        "final_graph": {
            "nodes": [{"id": o, "label": label, "attrs": {}} for o, label in state.objects.items()],
            "edges": [_edge((o, r, t)) for o, (r, t) in state.support.items()],
            "dictionary": "blocksworld"},
    }


def _plain_run(domain: BlocksDomain, problem: BlocksProblem, plan_text: str) -> Run | None:
    """The fast path: a 4-op plan of plain `(op args)` lines in which every step applies.

    It reads the lines with one regex and applies each step with one fused test per
    precondition, building the report as it goes; anything else (another line form, an
    unknown operator or arity, a failing step) returns None and the plan is run again by
    `_stepwise_run`, which gives the same report and every message. A failing plan thus
    costs at most one extra pass up to its failure.
    """
    if problem.hand is None or not plan_text.isascii():
        return None
    matches = plain_actions(plan_text.lower(), domain)
    if matches is None:
        return None
    model = HandModel(native_state(problem), problem, domain)
    state = model.state
    support, carried, declared = state.support, state.carried, model.declared
    table, hand = model.table, problem.hand
    on_table, in_hand = ("on", table), ("in", hand)
    roles = {name: op.role for name, op in domain.operators.items()}
    held = carried[hand]
    placed: dict[str, tuple[dict[str, str]]] = {}
    out_steps: list[dict[str, Any]] = []
    append = out_steps.append
    for index, (line, name, x, y, extra) in enumerate(matches, start=1):
        role = roles.get(name)
        if extra or x not in declared:
            return None
        sx = support[x]
        if role == "pick-up":
            if y or sx != on_table or carried[x] or held:
                return None
            new = in_hand
            args: tuple[str, ...] = (x,)
        elif role == "put-down":
            if y or sx != in_hand:
                return None
            new = on_table
            args = (x,)
        elif role == "stack":
            if sx != in_hand or y not in declared or x == y or carried[y] \
                    or support[y][0] == "in":
                return None
            new = ("on", y)
            args = (x, y)
        elif role == "unstack":
            if sx[1] != y or sx[0] != "on" or y not in declared or carried[x] or held:
                return None
            new = in_hand
            args = (x, y)
        else:
            return None
        r0, t0 = sx
        del carried[t0][x]
        support[x] = new
        carried[new[1]][x] = new[0]
        # the edge a block leaves is the one an earlier step added: share it (and the
        # tuple around it)
        removed = placed.get(x) or ({"source": x, "relation": r0, "target": t0},)
        added = placed[x] = ({"source": x, "relation": new[0], "target": new[1]},)
        append({"step": index, "ok": True, "action": {"action": name, "args": args},
                "text": line, "edit": {"removed": removed, "added": added}})
    return model, out_steps, [], len(matches)


def _stepwise_run(domain: BlocksDomain, problem: BlocksProblem, plan_text: str) -> Run:
    """Every plan form and every failure: parse all lines, then check step by step."""
    steps = parse_blocks_plan(plan_text, domain, set(problem.blocks))
    model = HandModel(native_state(problem), problem, domain)
    ops = {op.role: op for op in domain.operators.values()}
    out_steps: list[dict[str, Any]] = []
    violations: list[dict[str, Any]] = []
    append = out_steps.append
    state = model.state
    support, carried, declared = state.support, state.carried, model.declared
    table, hand = model.table, model.hand
    on_table, in_hand = ("on", table), ("in", hand or "")
    last_edge: dict[str, dict[str, str]] = {}
    names = {role: op.name for role, op in ops.items()}
    four = hand is not None
    hand_id = hand or ""
    for index, step in enumerate(steps, start=1):
        role, args, text, _ = step
        x = args[0]
        # The hand operators' happy path, fused (one test per precondition); a step that
        # fails it, and every 3-operator step, goes through the hand model.
        new: tuple[str, str] | None = None
        if four and x in declared:
            sx = support[x]
            if role == "pick-up":
                if sx == on_table and not carried[x] and not carried[hand_id]:
                    new = in_hand
            elif role == "put-down":
                if sx == in_hand:
                    new = on_table
            elif role == "stack":
                y = args[1]
                if sx == in_hand and y in declared and x != y and not carried[y] \
                        and support[y][0] != "in":
                    new = ("on", y)
            elif sx[1] == args[1] and sx[0] == "on" and args[1] in declared \
                    and not carried[x] and not carried[hand_id]:
                new = in_hand
        if new is not None:
            r0, t0 = sx
            del carried[t0][x]
            support[x] = new
            carried[new[1]][x] = new[0]
            # the edge a block leaves is the one an earlier step added: share the dict
            removed = last_edge.get(x) or {"source": x, "relation": r0, "target": t0}
            added = last_edge[x] = {"source": x, "relation": new[0], "target": new[1]}
            append({"step": index, "ok": True, "action": {"action": names[role], "args": args},
                    "text": text, "edit": {"removed": (removed,), "added": (added,)}})
            continue
        op = ops[role]
        failure = model.check(step, op.self_move_forbidden)
        if failure is None:
            (x, r0, t0), (_, r1, t1) = model.apply(step)
            last_edge.pop(x, None)
            append({"step": index, "ok": True, "action": {"action": op.name, "args": args},
                    "text": text,
                    "edit": {"removed": ({"source": x, "relation": r0, "target": t0},),
                             "added": ({"source": x, "relation": r1, "target": t1},)}})
            continue
        action = {"action": op.name, "args": list(args)}
        constraint, message, blocking, suggestion = failure
        violation = {"ok": False, "step": index, "action": action, "constraint": constraint,
                     "message": message, "blocking": blocking, "suggestion": suggestion}
        violations.append(violation)
        append({"step": index, "ok": False, "action": action, "text": step.text,
                "violation": violation})
        break
    return model, out_steps, violations, len(steps)

