"""Random blocks-world problems (IPC-2000 style: random start and goal towers) in two forms:
PDDL 4-op text for classical planners and validators, and scene graph + goal for VeriGraph.
"""

from __future__ import annotations

import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent.parent / "tests"))

from blocksworld_corpus import DATA, problem_text, random_state  # noqa: E402
from verigraph.graph import Edge, Goal, Node, SceneGraph  # noqa: E402

DOMAIN_FILE = DATA / "planbench_domain.pddl"


def names(n: int) -> list[str]:
    return [f"b{i}" for i in range(n)]


def scene(below: dict[str, str | None]) -> SceneGraph:
    nodes = [Node(id="table", label="table")] + [Node(id=b, label="block") for b in below]
    edges = [Edge(source=b, relation="on", target=v or "table") for b, v in below.items()]
    return SceneGraph(nodes=nodes, edges=edges, dictionary="blocks")


def problem(n: int, seed: int) -> tuple[str, SceneGraph, Goal, dict[str, str | None],
                                        dict[str, str | None]]:
    """(PDDL problem text, start scene, goal, start towers, goal towers)."""
    rng = random.Random(seed)
    blocks = names(n)
    start, goal = random_state(blocks, rng), random_state(blocks, rng)
    text = problem_text(f"bw-{n}-{seed}", start, goal, "planbench")
    return text, scene(start), Goal(graph=scene(goal)), start, goal
