"""sim2d speed: execute and settle one move, render a frame, generate scenes.

Targets (issue 4): one move executed and settled in under 50 ms (median), a 640x480
frame rendered in under 5 ms. Run: python benchmarks/bench_sim2d.py [--quick]
"""

from __future__ import annotations

import random
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from common import median_time, write_table  # noqa: E402

from verigraph.actions import AlignAction  # noqa: E402
from verigraph.graph.state import WorldState  # noqa: E402
from verigraph.sim2d import Degradation, degrade, generate_scene, world_for_graph  # noqa: E402
from verigraph.sim2d.generator import valid_moves  # noqa: E402
from verigraph.sim2d.room import room_violation  # noqa: E402
from verigraph.sim2d.tangram_geometry import piece_model  # noqa: E402

TABLETOP = ("blocks", "kitchen", "tableware")


def ms(seconds: float) -> str:
    return f"{seconds * 1000:.2f}"


def move_times(family: str, scenes: int, moves: int) -> list[float]:
    """Wall time of world.perform (lift, place, settle, verify) for random roomy moves."""
    times = []
    for seed in range(scenes):
        scene = generate_scene(family, seed)
        state = WorldState.from_graph(scene.graph)
        rng = random.Random(seed)
        for _ in range(moves):
            options = [a for a in valid_moves(state) if room_violation(state, a) is None]
            if not options:
                break
            action = rng.choice(options)
            start = time.perf_counter()
            refused = scene.world.perform(action)
            times.append(time.perf_counter() - start)
            if refused is None:
                state = WorldState.from_graph(scene.world.observe())
    return times


def align_times(scenes: int) -> list[float]:
    times = []
    rng = random.Random(0)
    for seed in range(scenes):
        world = generate_scene("tangram", seed).world
        ids = [n.id for n in world.nodes]
        for _ in range(20):
            p, q = rng.sample(ids, 2)
            action = AlignAction(object=p, side=rng.randrange(len(piece_model(p))), target=q,
                                 target_side=rng.randrange(len(piece_model(q))))
            start = time.perf_counter()
            world.perform(action)
            world.observe()
            times.append(time.perf_counter() - start)
    return times


def main() -> None:
    quick = "--quick" in sys.argv
    scenes, moves, gen = (4, 5, 10) if quick else (20, 10, 40)
    rows: list[list[str]] = []
    every: list[float] = []
    for family in TABLETOP:
        t = move_times(family, scenes, moves)
        every += t
        t.sort()
        rows.append([f"move + settle + read back ({family})", ms(statistics.median(t)),
                     ms(t[int(0.9 * (len(t) - 1))]), ms(t[-1]), str(len(t))])
    every.sort()
    rows.append(["move + settle + read back (all tabletop)", ms(statistics.median(every)),
                 ms(every[int(0.9 * (len(every) - 1))]), ms(every[-1]), str(len(every))])
    a = sorted(align_times(scenes // 2 or 1))
    rows.append(["tangram align + contacts", ms(statistics.median(a)),
                 ms(a[int(0.9 * (len(a) - 1))]), ms(a[-1]), str(len(a))])
    kitchen = generate_scene("kitchen", 3, n_objects=7).world
    tangram = generate_scene("tangram", 3).world
    for label, world in (("kitchen, 7 objects", kitchen), ("tangram, 7 pieces", tangram)):
        median, runs = median_time(lambda w=world: w.render(640, 480), runs=50)
        rows.append([f"render 640x480 ({label})", ms(median), ms(sorted(runs)[44]),
                     ms(max(runs)), "50"])
    h, w = kitchen.render().shape[:2]
    median, runs = median_time(lambda: kitchen.render(), runs=50)
    rows.append([f"render default frame (kitchen, {w}x{h})", ms(median), ms(sorted(runs)[44]),
                 ms(max(runs)), "50"])
    frame = kitchen.render(640, 480)
    spec = Degradation(noise=6, blur=1.0, lighting=0.4, jpeg=60)
    median, runs = median_time(lambda: degrade(frame, spec, seed=1), runs=20)
    rows.append(["degrade 640x480 (noise, blur, lighting, JPEG)", ms(median),
                 ms(sorted(runs)[17]), ms(max(runs)), "20"])
    graph = generate_scene("tableware", 1, n_objects=7).graph
    median, runs = median_time(lambda: world_for_graph(graph), runs=10)
    rows.append(["world_for_graph (tableware, 7 objects)", ms(median), "-", ms(max(runs)),
                 "10"])
    rates = []
    for family in (*TABLETOP, "tangram"):
        start = time.perf_counter()
        for seed in range(gen):
            generate_scene(family, 1000 + seed)
        rates.append(f"{family} {gen / (time.perf_counter() - start):.0f}/s")
    write_table(
        "sim2d", "sim2d: moves, frames, scenes", ["what", "median ms", "p90 ms", "max ms", "n"],
        rows,
        notes=("Moves: `SimWorld.perform` on random valid moves that pass the room check, "
               "over generated scenes (lift, placement search, put down, settle, read the "
               "graph back, compare). Targets: move < 50 ms, render < 5 ms (median).\n\n"
               "Scenes generated per second (layout, physics check and a goal reached by "
               f"2-4 simulated moves): {', '.join(rates)}."))


if __name__ == "__main__":
    main()
