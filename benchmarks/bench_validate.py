"""Validate a 10,000-action plan on a 1,000-object scene; report actions per second.

Target (issue 2): at least 100,000 actions/s in-process. Run: python benchmarks/bench_validate.py
"""

from __future__ import annotations

import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from common import median_time, write_table  # noqa: E402

from verigraph.actions import MoveAction, parse_plan, validate_plan  # noqa: E402
from verigraph.actions.validator import run_until_violation  # noqa: E402
from verigraph.graph import Edge, Goal, Node, SceneGraph, WorldState  # noqa: E402
from verigraph.solver import solve  # noqa: E402

N_OBJECTS, N_ACTIONS = 1000, 10_000


def big_scene(seed: int = 0) -> SceneGraph:
    rng = random.Random(seed)
    ids = [f"b{i}" for i in range(N_OBJECTS - 1)]
    edges, tops = [], []
    for b in ids:
        if tops and rng.random() < 0.5:
            t = tops.pop(rng.randrange(len(tops)))
            edges.append(Edge(source=b, relation="on", target=t))
        else:
            edges.append(Edge(source=b, relation="on", target="table"))
        tops.append(b)
    nodes = [Node(id="table", label="table")] + [Node(id=b, label="block") for b in ids]
    return SceneGraph(nodes=nodes, edges=edges, dictionary="blocks")


def valid_random_walk(scene: SceneGraph, n: int, seed: int = 1) -> list[MoveAction]:
    """n valid moves: a clear block onto another clear block or the table."""
    rng = random.Random(seed)
    state = WorldState.from_graph(scene)
    clear = [o for o in state.objects if o != "table" and state.is_clear(o)]
    plan = []
    for _ in range(n):
        obj = rng.choice(clear)
        options = [c for c in clear if c != obj]
        below = state.support[obj][1]
        target = "table" if below != "table" and rng.random() < 0.3 else rng.choice(options)
        plan.append(MoveAction(object=obj, relation="on", target=target))
        state.set_support(obj, "on", target)
        if target != "table":
            clear.remove(target)
        if below != "table":
            clear.append(below)
    return plan


def main() -> None:
    scene = big_scene()
    plan = valid_random_walk(scene, N_ACTIONS)
    text = "\n".join(a.text() for a in plan)
    state = WorldState.from_graph(scene)

    def core() -> None:
        executed, _, violation, _ = run_until_violation(state.copy(), plan, record_edits=False)
        assert violation is None and len(executed) == N_ACTIONS

    def report() -> None:
        r = validate_plan(state, plan)
        assert r.valid

    def parse() -> None:
        assert len(parse_plan(text)) == N_ACTIONS

    def index() -> None:
        WorldState.from_graph(scene)

    rows = []
    def core_with_edits() -> None:
        executed, edits, violation, _ = run_until_violation(state.copy(), plan)
        assert violation is None and len(edits) == N_ACTIONS

    for name, fn in [("validate + apply (execute_until_violation core)", core),
                     ("same, recording each step's graph edit", core_with_edits),
                     ("validate_plan with per-step report", report),
                     ("parse 10,000-line text plan", parse)]:
        med, _ = median_time(fn)
        rows.append([name, f"{med * 1000:.1f}", f"{N_ACTIONS / med:,.0f}"])
    med, _ = median_time(index)
    rows.append(["load + check + index the 1,000-object scene", f"{med * 1000:.1f}", "-"])

    solve_times = []
    sys.path.insert(0, str(Path(__file__).parent.parent / "tests"))
    from scenes import random_blocks

    for seed in range(10):
        start, goal = random_blocks(12, seed), Goal(graph=random_blocks(12, seed + 100))
        med, _ = median_time(lambda s=start, g=goal: solve(s, g), runs=3)
        solve_times.append(med)
    solve_times.sort()
    rows.append(["solve: 12 blocks to a random goal (median of 10 scenes)",
                 f"{solve_times[len(solve_times) // 2] * 1000:.1f}", "-"])
    rows.append(["solve: worst of those 10 scenes", f"{solve_times[-1] * 1000:.1f}", "-"])
    write_table("validate", "Validator throughput", ["what", "median ms", "actions/s"], rows,
                notes=f"{N_ACTIONS:,} valid moves on a {N_OBJECTS:,}-object blocks scene; "
                      "median of 7 runs after a warm-up. Target: >= 100,000 actions/s.")


if __name__ == "__main__":
    main()
