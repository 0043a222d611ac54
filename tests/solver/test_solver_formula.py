"""solve over goal formulas: optimal over the formula (not over one naming of its
objects), the bound admissible against breadth-first search, the plan verified."""

from __future__ import annotations

import random
from collections.abc import Callable, Hashable, Iterable
from typing import TypeVar

import pytest

from verigraph.actions.report import validate_plan
from verigraph.graph.formula import Formula, parse_formula
from verigraph.graph.formula_eval import facts_of, holds
from verigraph.graph.goal import Goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.solver import solve
from verigraph.solver.budget import SearchBudget
from verigraph.solver.encoding import RELATIONS, SearchProblem
from verigraph.solver.formula_bound import formula_bound
from verigraph.solver.search import _facts_at

pytestmark = pytest.mark.fast
T = TypeVar("T")
NO_CUP_ON_A_PLATE = "(forall (?c - cup) (not (exists (?p - plate) (ontop ?c ?p))))"
A_LID_IN_EACH_POT = "(forall (?p - pot) (exists (?l - lid) (inside ?l ?p)))"
BOTH = f"(and {NO_CUP_ON_A_PLATE} {A_LID_IN_EACH_POT})"


def kitchen(cups: int) -> SceneGraph:
    """`cups` cups on plates (two to a plate), two one-lid pots, lid_2 in pot_1, lid_1 on
    the counter: naming lid_1 for pot_1 and lid_2 for pot_2 costs one move more than the
    goal "a lid in each pot" needs."""
    plates = (cups + 1) // 2
    nodes = [("counter", "counter", {}), ("pot_1", "pot", {"capacity": 1}),
             ("pot_2", "pot", {"capacity": 1}), ("lid_1", "lid", {}), ("lid_2", "lid", {})]
    nodes += [(f"plate_{i}", "plate", {}) for i in range(1, plates + 1)]
    nodes += [(f"cup_{i}", "cup", {}) for i in range(1, cups + 1)]
    edges = [("pot_1", "on", "counter"), ("pot_2", "on", "counter"), ("lid_2", "in", "pot_1"),
             ("lid_1", "on", "counter")]
    edges += [(f"plate_{i}", "on", "counter") for i in range(1, plates + 1)]
    edges += [(f"cup_{i}", "on", f"plate_{(i + 1) // 2}") for i in range(1, cups + 1)]
    return SceneGraph.model_validate({
        "nodes": [{"id": i, "label": label, "attrs": attrs} for i, label, attrs in nodes],
        "edges": [{"source": s, "relation": r, "target": t} for s, r, t in edges]})


def named_one_by_one(cups: int) -> Goal:
    """The same wish with every object named: lid_1 in pot_1, lid_2 in pot_2, each cup on
    the counter."""
    graph = kitchen(cups)
    edges = [{"source": "lid_1", "relation": "in", "target": "pot_1"},
             {"source": "lid_2", "relation": "in", "target": "pot_2"}]
    edges += [{"source": f"cup_{i}", "relation": "on", "target": "counter"}
              for i in range(1, cups + 1)]
    return Goal(graph=SceneGraph.model_validate({"nodes": graph.model_dump()["nodes"],
                                                 "edges": edges}), partial=True)


def test_the_formula_is_solved_in_fewer_moves_than_naming_objects_one_by_one() -> None:
    scene = kitchen(9)
    named = solve(scene, named_one_by_one(9))
    assert named.optimal and len(named.plan) == 11
    result = solve(scene, Goal(formula=BOTH))
    assert result.reachable and result.optimal and len(result.plan) == 10
    assert "move(lid_1, in, pot_2)" in [a.text() for a in result.plan]  # the lid swap
    report = validate_plan(WorldState.from_graph(scene), result.plan, Goal(formula=BOTH))
    assert report["valid"] and report["goal_diff"]["satisfied"]


def test_anytime_says_optimal_only_when_the_bound_proves_it() -> None:
    result = solve(kitchen(5), Goal(formula=BOTH), anytime=True)
    assert result.reachable and len(result.plan) == 6 and result.optimal
    assert result.lower_bound == 6
    stopped = solve(kitchen(9), Goal(formula=BOTH), max_expansions=3)
    assert stopped.reachable is None and not stopped.optimal
    assert stopped.lower_bound is not None and stopped.lower_bound <= 10


def test_a_formula_and_a_goal_graph_must_both_hold() -> None:
    scene = kitchen(3)
    goal = Goal(formula=A_LID_IN_EACH_POT, graph=SceneGraph.model_validate({
        "nodes": [{"id": "cup_1", "label": "cup"}, {"id": "counter", "label": "counter"}],
        "edges": [{"source": "cup_1", "relation": "on", "target": "counter"}]}), partial=True)
    result = solve(scene, goal)
    assert result.optimal and sorted(a.text() for a in result.plan) == [
        "move(cup_1, on, counter)", "move(lid_1, in, pot_2)"]


def test_an_unreachable_formula_is_said_unreachable() -> None:
    # the plate carries two (capacity 2) and three are demanded on it (`ontop` is the
    # direct support)
    goal = Goal(formula="(and (ontop lid_1 plate_1) (ontop lid_2 plate_1) "
                        "(ontop cup_1 plate_1))")
    result = solve(kitchen(1), goal)
    assert result.reachable is False and result.status == "unreachable"
    # while `inside` reads down the placements: the cup in pot_1 carries the lid, which
    # is in pot_1 too, though pot_1 holds one (capacity 1)
    result = solve(kitchen(1), Goal(formula="(and (inside lid_1 pot_1) (inside cup_1 pot_1))"))
    assert result.optimal and [a.text() for a in result.plan][-1] == "move(lid_1, in, cup_1)"


def fewest_steps(start: T, successors: Callable[[T], Iterable[T]], key: Callable[[T], Hashable],
                 reached: Callable[[T], bool], limit: int) -> int | None:
    """Breadth first, layer by layer: the fewest steps from `start` to a state `reached`
    accepts (None beyond `limit`); `reached` sees every state visited."""
    seen = {key(start)}
    layer = [start]
    for steps in range(limit + 1):
        if [s for s in layer if reached(s)]:  # every state of the layer is looked at
            return steps
        fresh = []
        for state in layer:
            for after in successors(state):
                if key(after) not in seen:
                    seen.add(key(after))
                    fresh.append(after)
        layer = fresh
    return None


FORMULAS = [
    NO_CUP_ON_A_PLATE,
    A_LID_IN_EACH_POT,
    BOTH,
    "(forall (?c - cup) (exists (?p - plate) (ontop ?c ?p)))",
    "(or (inside lid_1 pot_2) (not (exists (?c - cup) (ontop ?c plate_1))))",
    "(imply (inside lid_2 pot_1) (ontop cup_1 lid_1))",
    "(forn (1) (?c - cup) (ontop ?c counter))",
    "(forpairs (?l - lid) (?p - pot) (inside ?l ?p))",
    "(not (forall (?l - lid) (ontop ?l counter)))",
    "(and (ontop pot_1 plate_1) (not (ontop cup_2 plate_1)))",
    "(exists (?c - cup) (and (inside ?c pot_2) (inside lid_1 ?c)))",
]


@pytest.mark.parametrize("text", FORMULAS)
def test_the_bound_never_exceeds_the_true_distance(text: str) -> None:
    formula = parse_formula(text)
    rng = random.Random(text)
    state = WorldState.from_graph(kitchen(2))
    problem = SearchProblem(state)
    facts_at = _facts_at(problem, state)
    budget = SearchBudget()
    starts = [problem.start]
    for _ in range(6):  # random walks from the scene give other start states
        codes = problem.start
        for _ in range(rng.randrange(1, 4)):
            codes = rng.choice([n for n, _ in problem.successors(codes, budget)])
        starts.append(codes)
    distances = []
    for codes in starts:
        problem.start = codes
        distance = fewest_steps(codes, lambda c: (n for n, _ in problem.successors(c, budget)),
                                lambda c: c, lambda c: holds(formula, facts_at(c)), limit=5)
        bound = formula_bound(formula, facts_at(codes))
        if distance is None:
            continue
        distances.append(distance)
        assert bound <= distance, (codes, bound, distance)
        trial = state.copy()
        for k, i in enumerate(problem.movable):
            trial.set_support(problem.ids[i], RELATIONS[codes[k] & 1],
                              problem.ids[codes[k] >> 1])
        result = solve(trial, Goal(formula=text))
        assert result.optimal and len(result.plan) == distance, (text, codes)
        assert (bound == 0) is (distance == 0)
        assert facts_of(trial).edges == facts_at(codes).edges
    assert any(d > 0 for d in distances), distances  # the bound met real searches


def household() -> SceneGraph:
    """A kitchen: a closed fridge, a stove that is off, a sink, the milk, a pot and a lid
    on the counter."""
    nodes = [("kitchen", "kitchen", {}), ("counter", "counter", {}),
             ("fridge", "fridge", {"open": False}), ("stove", "stove", {}), ("sink", "sink", {}),
             ("milk", "milk", {}), ("pot", "pot", {}), ("lid", "lid", {})]
    edges = [("counter", "inroom", "kitchen"), ("fridge", "inroom", "kitchen"),
             ("stove", "inroom", "kitchen"), ("sink", "inroom", "kitchen"),
             ("milk", "on", "counter"), ("pot", "on", "counter"), ("lid", "on", "counter")]
    return SceneGraph.model_validate({
        "nodes": [{"id": i, "label": label, **({"state": st} if st else {})}
                  for i, label, st in nodes],
        "edges": [{"source": s, "relation": r, "target": t} for s, r, t in edges],
        "dictionary": "household"})


@pytest.mark.parametrize(("text", "plan"), [
    ("(and (inside milk fridge) (not (open fridge)))",
     ["open(fridge)", "move(milk, in, fridge)", "close(fridge)"]),
    ("(exists (?s - stove) (and (toggled_on ?s) (ontop pot ?s)))",
     ["move(pot, on, stove)", "toggle_on(stove)"]),
    ("(nextto pot sink)", ["move(pot, nextto, sink)"]),
    ("(inroom milk kitchen)", []),
])
def test_household_formulas_are_solved_over_the_action_table(text: str, plan: list[str]
                                                             ) -> None:
    result = solve(household(), Goal(formula=text))
    assert result.reachable and result.optimal
    assert sorted(a.text() for a in result.plan) == sorted(plan)
    if text.startswith("(and"):
        assert [a.text() for a in result.plan] == plan  # opened before, closed after
    report = validate_plan(WorldState.from_graph(household()), result.plan or "done",
                           Goal(formula=text))
    assert report["valid"] and report["goal_diff"]["satisfied"]


@pytest.mark.parametrize("text", [
    "(and (inside milk fridge) (not (open fridge)))",
    "(or (toggled_on stove) (open fridge))",
    "(not (exists (?x - pot) (ontop ?x counter)))",
    "(imply (not (open fridge)) (inside pot fridge))",
    "(forall (?x - milk) (nextto ?x sink))",
    "(and (inside milk fridge) (inside lid fridge))",
    "(and (nextto pot sink) (nextto lid milk))",
    "(and (inside milk fridge) (nextto lid milk))",
])
def test_the_bound_is_admissible_over_the_action_table(text: str) -> None:
    from verigraph.solver.table_search import TableProblem, neighbours

    formula = parse_formula(text)
    goal = Goal(formula=text)
    start = WorldState.from_graph(household())
    problem = TableProblem(start, goal)
    budget = SearchBudget(max_expansions=10**6, time_limit_s=30)

    def reached(world: WorldState) -> bool:  # the bound is 0 exactly where the formula holds
        truth = holds(formula, facts_of(world))
        assert (formula_bound(formula, facts_of(world)) == 0) is truth
        return truth

    distance = fewest_steps(start, lambda w: (after for _, after in
                                              neighbours(problem, w, budget)),
                            problem.key, reached, limit=3)
    assert distance is not None, text
    assert 0 < formula_bound(formula, facts_of(start)) <= distance


def test_the_bound_counts_the_opening_of_a_closed_container() -> None:
    facts = facts_of(WorldState.from_graph(household()))
    assert formula_bound(parse_formula("(inside milk fridge)"), facts) == 2  # open, move
    assert formula_bound(parse_formula("(and (inside milk fridge) (inside lid fridge))"),
                         facts) == 3  # one opening serves both
    assert formula_bound(parse_formula("(and (inside milk fridge) (not (open fridge)))"),
                         facts) == 3  # open, move, close again


def nested_kitchen(seed: int) -> SceneGraph:
    """A kitchen with a fridge (open or closed), a counter and four movables placed at
    random on the counter, in the fridge, on the plate or in the bowl (no cycle): the
    `inside` of a formula reads through such nesting (milk on the plate in the fridge
    is in the fridge)."""
    rng = random.Random(seed)
    nodes = [("kitchen", "kitchen", {}), ("counter", "counter", {}),
             ("fridge", "fridge", {"open": rng.random() < 0.5}), ("plate", "plate", {}),
             ("bowl", "bowl", {}), ("milk", "milk", {}), ("cheese", "cheese", {})]
    edges = [("counter", "inroom", "kitchen"), ("fridge", "inroom", "kitchen")]
    placed: dict[str, str] = {}  # object -> what it rests on or in
    for obj in rng.sample(["plate", "bowl", "milk", "cheese"], 4):
        places = [("on", "counter"), ("in", "fridge")]
        places += [(r, t) for r, t in (("on", "plate"), ("in", "bowl"))
                   if t in placed and t != obj
                   and sum(p == t for p in placed.values()) < 2]
        relation, target = rng.choice(places)
        placed[obj] = target
        edges.append((obj, relation, target))
    return SceneGraph.model_validate({
        "nodes": [{"id": i, "label": label, **({"state": st} if st else {})}
                  for i, label, st in nodes],
        "edges": [{"source": s, "relation": r, "target": t} for s, r, t in edges],
        "dictionary": "household"})


def random_formula(rng: random.Random, depth: int = 2, var: str | None = None) -> str:
    """A formula over the nested kitchen: `inside`/`ontop` atoms (the plate bound by a
    quantifier where one is open), `open`, joined by and/or/not/exists/forall."""
    choice = rng.random() if depth > 0 else 0.0
    if choice < 0.45:
        if rng.random() < 0.1:
            return "(open fridge)"
        relation, targets = rng.choice([("inside", ["fridge", "bowl"]),
                                         ("inside", ["fridge", "bowl"]),
                                         ("ontop", ["plate", "counter", *([var] if var else [])])])
        target = rng.choice(targets)
        source = rng.choice([o for o in ("plate", "bowl", "milk", "cheese", var)
                             if o and o != target and not (o == var and target == "plate")])
        return f"({relation} {source} {target})"
    if choice < 0.55:
        return f"(not {random_formula(rng, depth - 1, var)})"
    if choice < 0.85:
        op = rng.choice(["and", "and", "or"])
        parts = " ".join(random_formula(rng, depth - 1, var) for _ in range(rng.randint(2, 3)))
        return f"({op} {parts})"
    op = rng.choice(["exists", "forall"])
    return f"({op} (?p{depth} - plate) {random_formula(rng, depth - 1, f'?p{depth}')})"


NESTED = [  # read through nesting: on a plate and in the fridge at once, and the like
    "(and (ontop milk plate) (inside milk fridge))",
    "(and (inside cheese bowl) (inside cheese fridge) (not (open fridge)))",
    "(and (ontop milk plate) (not (inside milk fridge)))",
    "(forall (?p - plate) (and (inside ?p fridge) (exists (?x - milk) (ontop ?x ?p))))",
]


@pytest.mark.parametrize("seed", range(16))
def test_the_bound_never_exceeds_the_true_cost_over_nested_placements(seed: int) -> None:
    """Random formulas on random nested kitchens: from the start and from states a random
    walk reaches, the bound is at most the fewest actions (breadth first over the action
    table), 0 exactly where the formula holds, and `solve` finds a plan of that length
    and proves it optimal."""
    from verigraph.solver.table_search import TableProblem, neighbours

    rng = random.Random(seed)
    scene = nested_kitchen(seed)
    texts = [NESTED[seed % len(NESTED)], *(random_formula(rng) for _ in range(3))]
    budget = SearchBudget(max_expansions=10**6, time_limit_s=60)
    measured = 0
    for text in texts:
        formula = parse_formula(text)
        goal = Goal(formula=text)
        start = WorldState.from_graph(scene)
        problem = TableProblem(start, goal)
        for _ in range(rng.randrange(0, 4)):  # a random walk gives another start
            start = rng.choice([after for _, after in neighbours(problem, start, budget)])

        def reached(world: WorldState, formula: Formula = formula, text: str = text) -> bool:
            truth = holds(formula, facts_of(world))
            assert (formula_bound(formula, facts_of(world)) == 0) is truth, text
            return truth

        distance = fewest_steps(start, lambda w, p=problem: (
            after for _, after in neighbours(p, w, budget)), problem.key, reached, limit=4)
        if distance is None:
            continue
        bound = formula_bound(formula, facts_of(start))
        assert bound <= distance, (text, bound, distance)
        result = solve(start, goal, time_limit=30)
        assert result.reachable and result.optimal, (text, result.reason)
        assert len(result.plan) == distance, (text, [a.text() for a in result.plan])
        measured += distance > 0
    assert measured, "no formula met a real search"


# (plan, kept): a detour is dropped, a needed action kept; `cup` goes into the fridge.
DETOURS = [
    (["open(fridge)", "move(cup, on, table)", "move(cup, in, fridge)"],
     ["open(fridge)", "move(cup, in, fridge)"]),
    (["toggle_on(stove)", "open(fridge)", "move(cup, in, fridge)", "toggle_off(stove)"],
     ["open(fridge)", "move(cup, in, fridge)"]),
    (["open(fridge)", "move(cup, in, fridge)"], ["open(fridge)", "move(cup, in, fridge)"]),
]


@pytest.mark.parametrize(("plan", "kept"), DETOURS)
def test_a_plan_keeps_none_of_its_detours(plan: list[str], kept: list[str]) -> None:
    from verigraph.actions.parser import parse_plan
    from verigraph.actions.schemas import schema_of
    from verigraph.graph.builtin_scenes import kitchen_household
    from verigraph.solver.table_search import without_detours

    state = WorldState.from_graph(kitchen_household())
    goal = Goal(formula="(inside cup fridge)")
    steps = []
    for action in parse_plan("\n".join(plan)):
        row = schema_of(action)
        assert row is not None
        steps.append((row, row.args(action)))
    shortened = without_detours(state, goal, steps, SearchBudget(time_limit_s=5))
    assert [a.text() for a in shortened] == kept
