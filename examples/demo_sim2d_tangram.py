"""Repair a perturbed tangram figure in the simulator with one verified align.

Run: python examples/demo_sim2d_tangram.py [SEED] [OUT_DIR]
Writes start.png, repaired.png and target.png (side indices drawn) and prints the plan.
"""

from __future__ import annotations

import sys
from pathlib import Path

import cv2

from verigraph.actions import AlignAction
from verigraph.actions.execution import execute_in_world
from verigraph.graph import WorldState, check_goal
from verigraph.sim2d import generate_scene


def main(seed: int = 3, out: Path = Path("out/tangram")) -> int:
    scene = generate_scene("tangram", seed)
    assert scene.goal.graph is not None and scene.goal_world is not None
    out.mkdir(parents=True, exist_ok=True)
    cv2.imwrite(str(out / "start.png"), scene.world.render(640, 480, labels=True))
    cv2.imwrite(str(out / "target.png"), scene.goal_world.render(640, 480, labels=True))
    # The perturbation lost exactly one contact; the loose piece is the one without any.
    lost = next(iter(scene.goal.graph.edge_keys() - scene.graph.edge_keys()))
    a, _, b, side_a, side_b = lost
    touching = {k[0] for k in scene.graph.edge_keys()} | {k[2] for k in scene.graph.edge_keys()}
    if a in touching:
        a, b, side_a, side_b = b, a, side_b, side_a
    action = AlignAction(object=a, side=side_a or 0, target=b, target_side=side_b or 0)
    print(f"lost contact: {a}[{side_a}] touches {b}[{side_b}]; plan: {action.text()}")
    state = WorldState.from_graph(scene.graph)
    _, _, violation, _, state = execute_in_world(state, [action], scene.world)
    cv2.imwrite(str(out / "repaired.png"), scene.world.render(640, 480, labels=True))
    verdict = check_goal(state, scene.goal)
    print(violation.text() if violation else verdict.summary(), f"(images in {out})")
    return 0 if violation is None and verdict.satisfied else 1


if __name__ == "__main__":
    args = sys.argv[1:]
    sys.exit(main(int(args[0]) if args else 3, Path(args[1]) if len(args) > 1 else
                  Path("out/tangram")))
