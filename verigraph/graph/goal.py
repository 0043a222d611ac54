"""Goals and the goal check: a graph to match (fully or partially), a named predicate, or
a formula in BDDL's syntax (verigraph.graph.formula; evaluated by formula_eval).

`diff` reports missing/extra nodes and edges, and the states a goal node asks for that do
not hold (`{"id": "fridge", "label": "fridge", "state": {"open": false}}`: the fridge
must be closed; a goal node without a state asks for none, in a partial goal or an
exact one). Tangram contacts are compared up to each
piece's rotational symmetry (square: 4, parallelogram: 2), so a square turned by 90
degrees still matches.
"""

from __future__ import annotations

import itertools
import operator
import re
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from verigraph.errors import GoalError
from verigraph.graph.dictionary import KIND_KEYS, STATE_WORDS, ObjectProperties
from verigraph.graph.formula import (
    FORMULA_EXAMPLE,
    MAX_FORMULA_CHARS,
    STATE_KEYS,
    Atom,
    Formula,
    Imply,
    Junction,
    Not,
    Pairs,
    Quantified,
    parse_formula,
    show,
)
from verigraph.graph.formula_eval import evaluate, facts_of
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import GraphProblem, resolve_properties
from verigraph.reporting import goal_text, listed_count

PREDICATES = ("single_stack",)
EdgeKey = tuple[str, str, str, int | None, int | None]


_LEADING_COMMENTS = re.compile(r"(?:\s*;[^\n]*)*\s*")


def looks_like_formula(text: str) -> bool:
    """Goal text starting with `(` (after any `;` comment lines) is a formula; edges
    text never does."""
    skipped = _LEADING_COMMENTS.match(text)
    return text[skipped.end() if skipped else 0:].startswith("(")


class Goal(BaseModel):
    """What the planner must reach: a goal graph, a predicate, a formula, or several
    (all must hold)."""

    model_config = ConfigDict(extra="forbid")

    graph: SceneGraph | None = Field(default=None, description="goal scene graph")
    partial: bool = Field(default=False, description="only the listed edges must hold")
    predicate: Literal["single_stack"] | None = Field(
        default=None, description="single_stack: every movable object in one tower")
    formula: str | None = Field(default=None, max_length=MAX_FORMULA_CHARS)  # BDDL
    instruction: str | None = Field(default=None, description="the instruction it came from")

    @field_validator("formula")
    @classmethod
    def _parses(cls, value: str | None) -> str | None:
        if value is not None:
            try:
                parse_formula(value)
            except GoalError as exc:
                raise ValueError(f"{exc.message} (fix: {exc.fix})") from None
        return value

    def formula_text(self) -> str | None:
        """The formula on one line, as parsed (comments and spacing dropped)."""
        return None if self.formula is None else show(parse_formula(self.formula))

    @model_validator(mode="after")
    def _needs_something(self) -> Goal:
        if self.graph is None and self.predicate is None and self.formula is None:
            raise ValueError("a goal needs a 'graph', a 'predicate' or a 'formula'")
        return self

    @classmethod
    def parse(cls, data: object) -> Goal:
        """Accept a Goal object, a bare scene graph (an exact goal), a predicate's name or
        a formula's text (text starting with `(`)."""
        if isinstance(data, Goal):
            return data
        if isinstance(data, SceneGraph):
            return cls(graph=data)
        if isinstance(data, dict) and "nodes" in data and "graph" not in data:
            partial = bool(data.get("partial", False))
            graph = {k: v for k, v in data.items() if k != "partial"}
            return cls(graph=SceneGraph.model_validate(graph), partial=partial)
        if isinstance(data, str):
            if looks_like_formula(data):
                parse_formula(data)  # its GoalError names the position and the fix
                return cls(formula=data)
            if data in PREDICATES:
                return cls(predicate=data)  # type: ignore[arg-type]
            raise GoalError(f"unknown goal predicate '{data}'", field="goal", value=data,
                            fix=f"use one of {', '.join(PREDICATES)}, a goal graph or a "
                                f"formula such as {FORMULA_EXAMPLE}")
        return cls.model_validate(data)


class GraphDiff(BaseModel):
    """How the current graph differs from the goal; `satisfied` when nothing is missing."""

    satisfied: bool
    missing_nodes: list[str] = Field(default_factory=list)
    extra_nodes: list[str] = Field(default_factory=list)
    missing_edges: list[str] = Field(default_factory=list, description="goal edges not holding")
    extra_edges: list[str] = Field(default_factory=list,
                                   description="current edges the goal does not have")
    predicate: str | None = None
    detail: str | None = None
    # Written only when the goal lists states, so an edge goal's diff dumps as before.
    missing_states: list[str] = Field(
        default_factory=list, exclude_if=operator.not_,
        description="goal states not holding, e.g. `fridge closed`, `stove on`")
    # A goal formula's findings: when the goal is not reached, every counterexample of
    # the formula (its failing part with the objects, and why; empty when the formula
    # holds); when it is reached, the witnesses of each exists. The first 1,000 are kept,
    # the last item then saying "... and N more". Written only when there are some.
    formula_detail: list[str] = Field(default_factory=list,
                                      exclude_if=operator.not_)

    def formula_count(self) -> int:
        """How many counterexamples (or witnesses) `formula_detail` stands for."""
        return listed_count(self.formula_detail)

    def summary(self) -> str:
        """The diff in one line (`reporting.goal_text`, the one renderer's goal part)."""
        return goal_text(self.model_dump(exclude_none=True))


def check_formula(state: WorldState, formula: str) -> GraphDiff:
    """The goal formula evaluated on the state, as a GraphDiff."""
    result = evaluate(parse_formula(formula), facts_of(state))
    return GraphDiff(satisfied=result.satisfied, formula_detail=result.kept())


def _sentence(key: EdgeKey) -> str:
    return Edge(source=key[0], relation=key[1], target=key[2], source_side=key[3],
                target_side=key[4]).sentence()


def _symmetric_variants(keys: set[EdgeKey], symmetry: dict[str, tuple[int, int]]
                        ) -> list[set[EdgeKey]]:
    """Every relabelling of contact sides under the pieces' rotational symmetries."""
    pieces = sorted(symmetry)
    if not pieces:
        return [keys]
    variants = []
    for shifts in itertools.product(*[range(symmetry[p][0]) for p in pieces]):
        shift = dict(zip(pieces, shifts, strict=True))
        out = set()
        for s, rel, t, ss, ts in keys:
            if rel == "touches":
                if s in shift:
                    ss = _rotate(ss, shift[s], *symmetry[s])
                if t in shift:
                    ts = _rotate(ts, shift[t], *symmetry[t])
                out.add(Edge(source=s, relation=rel, target=t, source_side=ss,
                             target_side=ts).key())
            else:
                out.add((s, rel, t, ss, ts))
        variants.append(out)
    return variants


def _rotate(side: int | None, k: int, order: int, n_sides: int) -> int | None:
    if side is None:
        return None
    return (side + k * (n_sides // order)) % n_sides


def diff(current: WorldState, goal_graph: SceneGraph, *, partial: bool = False) -> GraphDiff:
    """Missing and extra nodes and edges between the current state and a goal graph."""
    cur_nodes = set(current.objects)
    cur_keys = set(map(Edge.key, current.edges()))
    goal_nodes = set(goal_graph.node_ids())
    goal_keys = goal_graph.edge_keys()
    symmetry = {o.id: (o.props.symmetry, o.props.sides or 1) for o in current.objects.values()
                if o.props.symmetry > 1 and o.props.sides}
    best: tuple[int, set[EdgeKey], set[EdgeKey]] | None = None
    for variant in _symmetric_variants(cur_keys, symmetry):
        missing = goal_keys - variant
        extra = set() if partial else variant - goal_keys
        score = len(missing) + len(extra)
        if best is None or score < best[0]:
            best = (score, missing, extra)
        if score == 0:
            break
    assert best is not None
    _, missing_keys, extra_keys = best
    missing_nodes = sorted(goal_nodes - cur_nodes)
    extra_nodes = [] if partial else sorted(cur_nodes - goal_nodes)
    missing_states = [f"{n.id} {STATE_WORDS[key][wanted]}" for n in goal_graph.nodes
                      if n.state and n.id in current.objects
                      for key, wanted in n.state.items()
                      if current.state_value(n.id, key) != wanted]
    return GraphDiff(
        satisfied=not (missing_keys or extra_keys or missing_nodes or extra_nodes
                       or missing_states),
        missing_nodes=missing_nodes, extra_nodes=extra_nodes,
        missing_edges=sorted(_sentence(k) for k in missing_keys),
        extra_edges=sorted(_sentence(k) for k in extra_keys), missing_states=missing_states)


def towers(state: WorldState) -> list[list[str]]:
    """Stacks of movable objects standing on fixed objects, bottom first (linear chains)."""
    result = []
    for base in state.objects.values():
        if base.props.movable:
            continue
        for obj in state.carried[base.id]:
            tower = [obj]
            while len(state.carried[tower[-1]]) == 1:
                tower.append(next(iter(state.carried[tower[-1]])))
            result.append(tower)
    return result


def single_stack(state: WorldState) -> GraphDiff:
    """All movable objects form one tower on a fixed object."""
    movable = [o.id for o in state.objects.values() if o.props.movable]
    all_towers = towers(state)
    tallest = max(all_towers, key=len, default=[])
    ok = len(all_towers) == 1 and len(tallest) == len(movable)
    outside = sorted(set(movable) - set(tallest))
    detail = None if ok else (f"{len(all_towers)} stacks; not in the tallest stack "
                              f"({' on '.join(reversed(tallest)) or 'none'}): {', '.join(outside)}")
    return GraphDiff(satisfied=ok, predicate="single_stack", detail=detail)


def check_goal(state: WorldState, goal: Goal) -> GraphDiff:
    """Goal check used by execution, the validator and the server."""
    result: GraphDiff | None = None
    if goal.graph is not None:
        result = diff(state, goal.graph, partial=goal.partial)
    if goal.predicate == "single_stack":
        pred = single_stack(state)
        if result is None:
            result = pred
        else:
            result = result.model_copy(update={
                "satisfied": result.satisfied and pred.satisfied, "predicate": "single_stack",
                "detail": pred.detail})
    if goal.formula is not None:
        holds = check_formula(state, goal.formula)
        if result is None:
            return holds
        satisfied = result.satisfied and holds.satisfied
        # witnesses only for a goal reached, counterexamples only for a formula that fails
        detail = holds.formula_detail if satisfied or not holds.satisfied else []
        result = result.model_copy(update={"satisfied": satisfied, "formula_detail": detail})
    assert result is not None
    return result



def _kind_text(props: ObjectProperties) -> str:
    kinds = [k for k in ("surface", "container") if getattr(props, k)]
    text = " ".join(["movable" if props.movable else "fixed", *kinds])
    if kinds:
        text += f", capacity {'unlimited' if props.capacity is None else props.capacity}"
    return text


def goal_kind_problems(graph: SceneGraph, state: WorldState) -> list[GraphProblem]:
    """Goal nodes that give a scene object another kind (role or capacity) than it has.

    A goal says where the scene's objects should be, not what they are: every action
    is checked with the scene's properties, so a goal that needs `cup in plate` because
    its plate node says `container: true` could never be reached. Compared: the role and
    capacity keys a goal node's attrs give, and all of them when its label names another
    kind than the scene's node (a goal node with neither is the scene's object as it is).
    """
    problems: list[GraphProblem] = []
    resolved = resolve_properties(graph, state.dictionary, [])
    for i, node in enumerate(graph.nodes):
        scene = state.objects.get(node.id)
        mine = resolved.get(node.id)
        if scene is None or mine is None:
            continue
        label, wanted = mine
        relabelled = label != scene.label
        changed = [k for k in KIND_KEYS if (relabelled or k in node.attrs)
                   and getattr(wanted, k) != getattr(scene.props, k)]
        if not changed:
            continue
        how = ", ".join(f"{k}: {_json_word(getattr(wanted, k))}" for k in changed)
        fixes = [f"write label {scene.label}"] if relabelled else []
        dropped = [f"attrs.{k}" for k in changed if k in node.attrs]
        if dropped:
            fixes.append(f"drop {', '.join(dropped)}")
        problems.append(GraphProblem(
            rule="goal_changes_kind", node=node.id, field=f"nodes[{i}]",
            message=f"goal node '{node.id}' makes it {_kind_text(wanted)} ({how}), but in "
                    f"the scene {node.id} ({scene.label}) is {_kind_text(scene.props)}: a "
                    "goal says where objects go, not what they are, and actions are checked "
                    "with the scene's properties, so this goal could never be reached",
            fix=f"{' and '.join(fixes)} in the goal; to change what {node.id} is, load the "
                "scene with it (node attrs or your dictionary)"))
    return problems


def _json_word(value: object) -> str:
    return "null" if value is None else str(value).lower()


Placement = tuple[str, str, str]


def wanted_placements(goal: Goal) -> frozenset[Placement]:
    """The (object, relation, place) edges a goal asks for: a goal graph's edges, and a
    formula's positive atoms of two object ids (`(inside tube_e tube_rack)`; an atom with
    a variable, under a `not` or in an `imply`'s condition asks for no one placement).
    Fixes use them to keep goal edges that hold and to suggest moves toward the goal.

    Also in the set, in the same shape: the states a goal asks for, `(fridge, open,
    "false")` (a goal node's state, a formula's `(open fridge)` or `(not (open fridge))`),
    a formula's placements it forbids, `(cup_1, "not on", plate_a)` (for every object of
    a kind, by kind: `("?cup", "not on", "?plate")`), and each tangram
    contact with its sides, `(square[1], touches, medium_triangle[1])`, so a fix neither
    undoes a wanted state or contact nor proposes against it."""
    wanted: set[Placement] = set()
    if goal.graph is not None:
        for e in goal.graph.edges:
            wanted.add((e.source, e.relation, e.target))
            if e.relation == "touches":
                wanted.add((f"{e.source}[{e.source_side or 0}]", "touches",
                            f"{e.target}[{e.target_side or 0}]"))
        wanted.update((n.id, key, str(value).lower()) for n in goal.graph.nodes
                      for key, value in n.state.items())
    if goal.formula is not None:
        # `every`: the variables a `forall` (or a negated `exists`) binds, with their kinds
        stack: list[tuple[Formula, bool, dict[str, str]]] = [
            (parse_formula(goal.formula), True, {})]
        while stack:
            node, positive, every = stack.pop()
            if isinstance(node, Atom):
                if any(t.startswith("?") for t in node.terms):
                    # "no cup on any plate": a place forbidden to every object of a kind,
                    # written by kind, `("?cup", "not on", "?plate")`
                    if not positive and len(node.terms) == 2 and all(
                            not t.startswith("?") or t in every for t in node.terms):
                        source, target = (f"?{every[t]}" if t in every else t
                                          for t in node.terms)
                        wanted.add((source, "not " + node.relation, target))
                    continue
                if len(node.terms) == 2:  # `(not (on cup plate))`: (cup, "not on", plate)
                    wanted.add((node.terms[0], ("" if positive else "not ") + node.relation,
                                node.terms[1]))
                elif len(node.terms) == 1 and node.relation in STATE_KEYS:
                    wanted.add((node.terms[0], node.relation, str(positive).lower()))
            elif isinstance(node, Not):
                stack.append((node.body, not positive, every))
            elif isinstance(node, Junction):
                stack.extend((part, positive, every) for part in node.parts)
            elif isinstance(node, Quantified):
                name = node.param.name
                inner = {k: v for k, v in every.items() if k != name}
                if (node.op == "forall") == positive:  # every object of the kind
                    inner[name] = node.param.kind
                stack.append((node.body, positive, inner))
            elif isinstance(node, Pairs):
                stack.append((node.body, positive, every))
            elif isinstance(node, Imply):
                stack.append((node.then, positive, every))
    return frozenset(wanted)
