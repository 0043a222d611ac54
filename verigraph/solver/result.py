"""What a solve returns, and the reasons a goal can never hold (found without search)."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, Field

from verigraph.actions.model import AnyAction
from verigraph.graph.dictionary import PLACEMENT_RELATIONS, ROOM_RELATION
from verigraph.graph.goal import Goal
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import check_well_formed


class SolveResult(BaseModel):
    """A plan, or why there is none; with the budget used and the lower bound proved."""

    reachable: bool | None = Field(description="None when the search budget ran out first")
    status: Literal["solved", "unreachable", "budget_exhausted"] = "solved"
    plan: list[AnyAction] = Field(default_factory=list)
    reason: str | None = Field(default=None, description="why the goal cannot be reached, "
                                                         "or why refinement stopped")
    expanded: int = Field(default=0, description="search nodes expanded")
    optimal: bool = Field(default=False, description="the plan has the fewest possible moves")
    lower_bound: int | None = Field(default=None, description="no plan is shorter than this")
    elapsed_s: float = Field(default=0.0, description="wall-clock seconds spent")
    first_plan_s: float | None = Field(default=None, description="anytime: seconds until the "
                                                                 "first plan was in hand")
    memory_mb: float = Field(default=0.0, description="peak memory growth, MiB")

    def summary(self) -> str:
        if self.status == "budget_exhausted":
            return f"no plan: {self.reason}"
        if not self.reachable:
            return f"no plan: {self.reason}"
        if self.optimal:
            return f"length {len(self.plan)}, optimal"
        return f"length {len(self.plan)}, optimal is at least {self.lower_bound}"

    def text(self) -> str:
        if self.reachable:
            lines = [f"# {self.summary()}", *(a.text() for a in self.plan), "done"]
            return "\n".join(lines)
        return f"# {self.summary()}"


def static_reason(state: WorldState, goal: Goal) -> str | None:
    """Reasons a goal can never hold, found without search."""
    if goal.formula is not None:
        reason = process_reason(state, goal.formula)
        if reason:
            return reason
    if goal.graph is None:
        return None
    g = goal.graph
    missing = [n for n in g.node_ids() if n not in state.objects]
    if missing:
        return f"the goal names objects that are not in the scene: {', '.join(missing)}"
    if not goal.partial:
        extra = [o for o in state.objects if g.node(o) is None]
        if extra:
            return f"the goal lacks objects the scene has (moves cannot remove them): " \
                   f"{', '.join(extra)}"
    problems = check_well_formed(g, state.dictionary, partial=True)
    if problems:
        return f"the goal itself breaks a rule: {problems[0].message}"
    for e in g.edges:
        if state.objects[e.source].props.movable:
            continue
        if e.relation == ROOM_RELATION:
            holds = state.rooms.get(e.source) == e.target
        elif e.relation in PLACEMENT_RELATIONS:
            holds = state.support.get(e.source) == (e.relation, e.target)
        else:
            continue
        if not holds:
            return f"{e.source} is fixed, so '{e.sentence()}' can never be made true"
    if not goal.partial:
        for o in state.objects.values():
            if not o.props.movable and o.id in state.support and not any(
                    e.source == o.id for e in g.edges):
                return f"{o.id} is fixed on {state.support[o.id][1]}; the goal removes that edge"
    return None


def process_reason(state: WorldState, formula: str) -> str | None:
    """A thermal state the formula needs (`(cooked x)` under `and` and `forall` alone, x
    an id or each object of the kind) that does not hold yet, where the scene has no
    source for it at all: no action can ever make it true (cook and heat need a heat
    source, freeze a cold source)."""
    from verigraph.actions.processes import PROCESSES, SOURCE_WORDS
    from verigraph.graph.formula import Atom, Junction, Quantified, parse_formula
    from verigraph.graph.formula_eval import facts_of

    makes = {key: (name, source) for name, (key, value, _, source, needed) in PROCESSES.items()
             if value and needed}
    have = {source for source in SOURCE_WORDS
            if any(getattr(o.props, source) for o in state.objects.values())}
    facts = None
    stack: list[tuple[object, dict[str, str]]] = [(parse_formula(formula), {})]
    while stack:
        node, env = stack.pop()
        if isinstance(node, Junction) and node.op == "and":
            stack.extend((part, env) for part in node.parts)
        elif isinstance(node, Quantified) and node.op == "forall":
            facts = facts or facts_of(state)
            stack.extend((node.body, {**env, node.param.name: o})
                         for o in facts.objects_of(node.param.kind))
        elif isinstance(node, Atom) and node.relation in makes:
            obj = env.get(node.terms[0], node.terms[0])
            name, source = makes[node.relation]
            if source not in have and obj in state.objects \
                    and not state.state_value(obj, node.relation):
                word = SOURCE_WORDS[source]
                return (f"the goal needs ({node.relation} {obj}), which only {name} makes, "
                        f"on or in a {word} that is on, and the scene has no {word}")
    return None
