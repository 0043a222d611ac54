"""PDDL export cross-checked against unified-planning's plan validator."""

import random

import pytest
import unified_planning as up  # noqa: E402
from unified_planning.io import PDDLReader  # noqa: E402
from unified_planning.shortcuts import (  # noqa: E402
    OneshotPlanner,
    PlanValidator,
    get_environment,
)

from scenes import random_blocks
from verigraph.actions import MoveAction, validate_plan
from verigraph.errors import GoalError
from verigraph.graph import Goal, WorldState
from verigraph.reporting import report_text
from verigraph.solver import solve
from verigraph.solver.pddl import (
    PddlNames,
    action_from_pddl,
    domain_pddl,
    ground_plan,
    problem_pddl,
)

get_environment().credits_stream = None


def up_verdict(tmp_path, state, goal, actions) -> bool:
    (tmp_path / "d.pddl").write_text(domain_pddl())
    (tmp_path / "p.pddl").write_text(problem_pddl(state, goal))
    problem = PDDLReader().parse_problem(str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"))
    instances = [up.plans.ActionInstance(problem.action(name),
                                         [problem.object(p) for p in params])
                 for name, params in ground_plan(state, actions)]
    plan = up.plans.SequentialPlan(instances)
    with PlanValidator(problem_kind=problem.kind, plan_kind=plan.kind) as validator:
        result = validator.validate(problem, plan)
    return result.status.name == "VALID"


def random_plan(rng, ids, length):
    return [MoveAction(object=rng.choice(ids), relation="on",
                       target=rng.choice(ids + ["table"])) for _ in range(length)]


def test_validator_and_unified_planning_agree_on_generated_blocks_plans(tmp_path):
    rng = random.Random(7)
    verdicts = {True: 0, False: 0}
    for case in range(60):
        n = rng.randint(2, 5)
        start, goal = random_blocks(n, case), Goal(graph=random_blocks(n, case + 1000))
        state = WorldState.from_graph(start)
        ids = [f"b{i}" for i in range(n)]
        if case % 3 == 0:
            actions = solve(start, goal).plan  # valid plans
        else:
            actions = random_plan(rng, ids, rng.randint(1, 6))  # mostly invalid
        if not actions:
            continue
        ours = validate_plan(start, actions, goal)["valid"]
        theirs = up_verdict(tmp_path, state, goal, actions)
        assert ours == theirs, (case, [a.text() for a in actions],
                                report_text(validate_plan(start, actions, goal)))
        verdicts[ours] += 1
    assert verdicts[True] >= 10 and verdicts[False] >= 10


def test_tableware_capacities_and_containers_agree(tmp_path):
    from scenes import random_tableware

    rng = random.Random(3)
    verdicts = []
    for case in range(30):
        start = random_tableware(4, case)
        goal = Goal(graph=random_tableware(4, case + 500, labels_seed=case))
        state = WorldState.from_graph(start)
        ids = [n.id for n in start.nodes]
        actions = [MoveAction(object=rng.choice(ids), relation=rng.choice(["on", "in"]),
                              target=rng.choice(ids)) for _ in range(3)]
        if case % 3 == 0:
            actions = solve(start, goal).plan or actions
        ours = validate_plan(start, actions, goal)["valid"]
        assert ours == up_verdict(tmp_path, state, goal, actions), [a.text() for a in actions]
        verdicts.append(ours)
    assert True in verdicts and False in verdicts


def test_predicate_goals_cannot_be_exported():
    with pytest.raises(GoalError, match="graph"):
        problem_pddl(WorldState.from_graph(random_blocks(3, 0)), Goal(predicate="single_stack"))


def test_pyperplan_plans_for_the_export_pass_our_validator(tmp_path):
    """The other direction: a classical planner solves the exported problem with A*
    (admissible hmax), and our validator accepts its plan, which is as short as ours."""
    for seed in range(3):
        start, goal = random_blocks(4, seed), Goal(graph=random_blocks(4, seed + 40))
        state = WorldState.from_graph(start)
        (tmp_path / "d.pddl").write_text(domain_pddl())
        (tmp_path / "p.pddl").write_text(problem_pddl(state, goal))
        problem = PDDLReader().parse_problem(str(tmp_path / "d.pddl"),
                                             str(tmp_path / "p.pddl"))
        with OneshotPlanner(name="pyperplan",
                            params={"search": "astar", "heuristic": "hmax"}) as planner:
            result = planner.solve(problem)
        names = PddlNames(list(state.objects))
        plan = [action_from_pddl(a.action.name, [str(p) for p in a.actual_parameters], names)
                for a in result.plan.actions]
        report = validate_plan(start, plan or "done", goal)
        assert report["valid"], report_text(report)
        assert len(plan) == len(solve(start, goal).plan)
