"""The environment takes a formula goal: a task whose set_goal gives `formula` is played
to the end, the prompt shows the formula (or, for an instruction task, hides it), and an
answer that leaves the formula false is told every counterexample."""

from __future__ import annotations

import pytest

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")

from verigraph.env import VeriGraphEnv  # noqa: E402
from verigraph.env.rollout import make_policy  # noqa: E402
from verigraph.graph.goal import Goal  # noqa: E402
from verigraph.tasks.task import Task  # noqa: E402

pytestmark = pytest.mark.fast
NO_CUP_ON_A_PLATE = "(forall (?c - cup) (not (exists (?p - plate) (ontop ?c ?p))))"


def task(show: bool = True) -> Task:
    nodes = [("table", "table"), ("plate_1", "plate"), ("plate_2", "plate"), ("cup_1", "cup"),
             ("cup_2", "cup")]
    edges = [("plate_1", "on", "table"), ("plate_2", "on", "table"), ("cup_1", "on", "plate_1"),
             ("cup_2", "on", "plate_2")]
    graph = {"nodes": [{"id": i, "label": label} for i, label in nodes],
             "edges": [{"source": s, "relation": r, "target": t} for s, r, t in edges],
             "dictionary": "tableware"}
    return Task.create(task_id="language/0", load={"graph": graph},
                       set_goal={"formula": NO_CUP_ON_A_PLATE,
                                 "instruction": "Take every cup off the plates."},
                       family="kitchen", group="language", kind="formula", optimal_length=2,
                       show_goal_graph=show)


def test_a_formula_task_is_played_to_the_goal() -> None:
    t = task()
    assert t.goal == Goal(formula=NO_CUP_ON_A_PLATE, instruction="Take every cup off the "
                                                                  "plates.")
    env = VeriGraphEnv(tasks=[t], k=3)
    obs, info = env.reset(options={"task": 0})
    assert NO_CUP_ON_A_PLATE in obs and info["goal_distance"] == 2
    obs, reward, terminated, _, info = env.step("move(cup_1, on, table)")
    assert not terminated and info["goal_distance"] == 1
    obs, reward, terminated, _, info = env.step("done")
    assert not terminated
    assert "(not (exists (?p - plate) (ontop cup_2 ?p))) fails: cup_2 is on plate_2" in obs
    answer = make_policy("oracle")(env, obs, info)
    obs, reward, terminated, _, info = env.step(answer)
    assert terminated and info["goal_satisfied"] is True and reward == 1.0
    env.close()


def test_an_instruction_task_hides_its_formula() -> None:
    env = VeriGraphEnv(tasks=[task(show=False)])
    obs, _ = env.reset(options={"task": 0})
    assert "Take every cup off the plates." in obs and "forall" not in obs
    assert env.privileged_goal is not None and env.privileged_goal.formula == NO_CUP_ON_A_PLATE
    env.close()
