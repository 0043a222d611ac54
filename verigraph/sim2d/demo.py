"""`verigraph demo`: the verifier catches a planning mistake, the simulator shows why.

1. A built-in scene and its goal are loaded into the simulator.
2. A plan with a typical mistake goes through the validator: the mistake is caught
   before anything moves and the feedback says how to fix it.
3. For contrast, the mistaken first action is executed without the verifier in a copy
   of the world: physics shows the consequence (the cup on the book falls over).
4. The corrected plan runs through `execute_in_world` (validate, act, observe, compare)
   one action at a time, writing a PNG per step, then a side-by-side of start and goal.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np

from verigraph.actions.execution import execute_in_world
from verigraph.actions.model import AnyAction
from verigraph.actions.parser import parse_plan
from verigraph.actions.report import validate_plan
from verigraph.graph.builtin_scenes import BUILTIN_GOALS, BUILTIN_SCENES
from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.reporting import report_text
from verigraph.sim2d import world_for_graph
from verigraph.sim2d.render import side_by_side
from verigraph.sim2d.tabletop import TabletopWorld


@dataclass(frozen=True, slots=True)
class DemoTask:
    """A scene, its goal, a plan with a mistake and the corrected plan."""

    scene: str
    goal: Goal
    mistaken: str
    corrected: str


def _kitchen_goal() -> Goal:
    graph = BUILTIN_SCENES["kitchen_pan"]()
    edges = [Edge(source="pot", relation="on", target="counter"),
             Edge(source="pan", relation="on", target="stove"),
             Edge(source="spoon", relation="in", target="pan"),
             Edge(source="lid", relation="on", target="counter")]
    return Goal(graph=graph.model_copy(update={"edges": edges}),
                instruction="Put the pan on the stove with the spoon in it; the pot goes "
                            "on the counter.")


TASKS = {
    "cup_on_book": DemoTask(
        "cup_on_book", BUILTIN_GOALS["cup_on_book"](),
        mistaken="move(book, on, shelf)\nmove(cup, on, desk)",
        corrected="move(cup, on, desk)\nmove(book, on, shelf)"),
    "kitchen_pan": DemoTask(
        "kitchen_pan", _kitchen_goal(),
        mistaken="move(pot, on, counter)\nmove(pan, on, stove)\nmove(spoon, in, pan)",
        corrected="move(spoon, on, counter)\nmove(pot, on, counter)\nmove(pan, on, stove)\n"
                  "move(spoon, in, pan)"),
}


def _say(text: str = "") -> None:
    print(text, flush=True)


def _sentences(graph: SceneGraph) -> str:
    return "; ".join(graph.sentences()) or "(no relations)"


def _save(out: Path, name: str, image: np.ndarray) -> Path:
    path = out / name
    cv2.imwrite(str(path), image)
    return path


def play_demo(scene: str, out: Path, width: int | None = None, height: int | None = None
        ) -> bool:
    """Run the demo; True when the goal holds in the simulator at the end."""
    task = TASKS[scene]
    assert task.goal.graph is not None
    out.mkdir(parents=True, exist_ok=True)
    graph = BUILTIN_SCENES[task.scene]()
    world = world_for_graph(graph)
    state = WorldState.from_graph(graph)
    _say(f"VeriGraph demo: '{task.scene}' ({graph.dictionary} dictionary) in the 2-D "
         "simulator")
    _say(f"  scene: {_sentences(world.observe())}")
    _say(f"  goal:  {_sentences(task.goal.graph)}   ({task.goal.instruction})")
    start_image = world.render(width, height, labels=True)
    _say(f"  start image: {_save(out, 'step_0_start.png', start_image)}")

    _say("\n1. A plan with a mistake goes through the verifier first:")
    for line in task.mistaken.splitlines():
        _say(f"     {line}")
    report = validate_plan(state, task.mistaken, task.goal)
    for line in report_text(report).splitlines():
        _say(f"   {line}")
    assert report["violations"], "the demo's mistaken plan must be caught"
    first = report["violations"][0]
    _say(f"   -> caught at step {first['step']} [{first['constraint']}]; nothing was executed.")

    _say("\n2. What the mistake would do without the verifier (unverified, in a copy):")
    what_if = world.copy()
    bad = parse_plan(task.mistaken)[(first["step"] or 1) - 1]
    assert not isinstance(bad, str)
    observed = what_if.perform_unverified(bad)  # type: ignore[arg-type]
    fallen = what_if.tipped() if isinstance(what_if, TabletopWorld) else []
    _say(f"     {bad.text()} -> {_sentences(observed)}")
    if fallen:
        _say(f"     fell over: {', '.join(fallen)} (a graph edge cannot show that; the "
             "image does)")
    mess = what_if.render(width, height, labels=True)
    _say(f"     image: {_save(out, 'unverified_mistake.png', mess)}")

    _say("\n3. The corrected plan, checked:")
    for line in task.corrected.splitlines():
        _say(f"     {line}")
    fixed = validate_plan(state, task.corrected, task.goal)
    _say(f"   -> {'valid' if fixed['plan_valid'] else 'INVALID'}, goal "
         f"{'reached' if fixed.get('goal_reached') else 'missed'} (symbolically)")

    _say("\n4. Executing it in the simulator (validate, act, observe, compare per step):")
    actions: list[AnyAction] = parse_plan(task.corrected)
    failures = 0
    for step, action in enumerate(actions, start=1):
        executed, _, violation, _, state = execute_in_world(state, [action], world,
                                                            first_step=step)
        image = _save(out, f"step_{step}.png", world.render(width, height, labels=True))
        if violation is not None:
            failures += 1
            _say(f"   step {step}: {action.text()}  FAILED [{violation.constraint}] "
                 f"{violation.message}")
            break
        _say(f"   step {step}: {action.text()}  ok, observed = predicted: "
             f"{_sentences(world.observe())}  ({image})")
    diff = check_goal(state, task.goal)
    goal_image = world_for_graph(task.goal.graph).render(width, height, labels=True)
    pair = side_by_side([start_image, goal_image], ["start", "goal"])
    _say(f"\n   start vs goal: {_save(out, 'start_vs_goal.png', pair)}")
    ok = diff.satisfied and failures == 0 and not executed_mismatch(world, task.goal)
    _say(f"\nVerdict: {'SUCCESS' if ok else 'FAILURE'}: {diff.summary()} in the simulator "
         f"after {len(actions)} action(s); the mistake was caught before execution.")
    return ok


def executed_mismatch(world: object, goal: Goal) -> bool:
    """The world's own observation disagrees with the goal (belt and braces)."""
    observe = getattr(world, "observe", None)
    if goal.graph is None or observe is None:
        return False
    observed: SceneGraph = observe()
    return observed.edge_keys() != goal.graph.edge_keys()
