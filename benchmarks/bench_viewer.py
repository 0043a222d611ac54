"""Viewer cost: the per-step view of a 20-step episode with and without simulator pictures.

A simulated episode's view replays the executed actions on a rebuilt copy of the world
as loaded and renders each step (see `verigraph.viewer.frames`); the peer is the same
trace in a graph-only episode (drawings only), measured in the same run. Also the memory
an episode keeps for it (the world as loaded, JSON) next to what keeping a PNG per step
would cost. Run: python benchmarks/bench_viewer.py [--quick]
"""

from __future__ import annotations

import json
import random
import sys
import tracemalloc
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from common import median_time, write_table  # noqa: E402

from verigraph.sim2d.generator import valid_moves  # noqa: E402
from verigraph.sim2d.render import encode_png  # noqa: E402
from verigraph.sim2d.room import room_violation  # noqa: E402
from verigraph.tools import Toolbox  # noqa: E402
from verigraph.viewer import ViewInput, view  # noqa: E402
from verigraph.viewer.frames import FRAME_WIDTH  # noqa: E402

STEPS = 20


def simulated_episode(box: Toolbox, family: str, seed: int) -> tuple[str, list[str]]:
    """A sim2d episode with STEPS executed moves (random, valid, with room)."""
    eid: str = box.call("load_scene", {"generator": {"family": family, "seed": seed},  # type: ignore[union-attr]
                                       "executor": "sim2d", "t": 100}).episode_id
    rng = random.Random(seed)
    executed: list[str] = []
    while len(executed) < STEPS:
        with box.context.store.use(eid) as episode:
            state = episode.require_state().copy()
        options = [a for a in valid_moves(state) if room_violation(state, a) is None] \
            or valid_moves(state)  # the simulator may refuse one: then try again
        out = box.call("execute_actions", {"episode_id": eid,
                                           "actions": [rng.choice(options).text()]})
        executed += out.executed  # type: ignore[union-attr]
    return eid, executed


def graph_episode(box: Toolbox, eid: str, executed: list[str]) -> str:
    """The same trace in a graph-only episode (the peer: drawings, no simulator)."""
    with box.context.store.use(eid) as episode:
        graph = episode.initial_graph
    assert graph is not None
    other: str = box.call("load_scene", {"graph": graph.model_dump(mode="json"),  # type: ignore[union-attr]
                                         "executor": "graph", "k": 50}).episode_id
    out = box.call("execute_actions", {"episode_id": other, "actions": executed})
    assert out.ok, out  # type: ignore[union-attr]
    return other


def peak_kib(box: Toolbox, eid: str) -> float:
    tracemalloc.start()
    view(box.context, ViewInput(episode_id=eid))
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return peak / 1024


def main(quick: bool) -> None:
    runs = 3 if quick else 7
    rows: list[list[str]] = []
    kept_notes: list[str] = []
    for family in ("blocks", "kitchen"):
        box = Toolbox()
        sim, executed = simulated_episode(box, family, 1)
        plain = graph_episode(box, sim, executed)
        results = {}
        for name, eid in (("graph only", plain), ("sim2d", sim)):
            seconds, _ = median_time(lambda e=eid, b=box: view(b.context, ViewInput(episode_id=e)),
                                     runs)
            size = len(view(box.context, ViewInput(episode_id=eid)).model_dump_json())
            results[name] = seconds
            rows.append([f"{family}, {name}", f"{seconds * 1000:.0f}",
                         f"{seconds / results['graph only']:.2f}", f"{size / 1024:.0f}",
                         f"{peak_kib(box, eid):.0f}"])
        with box.context.store.use(sim) as episode:
            kept = len(json.dumps(episode.initial_world))
            frame = len(encode_png(episode.world.render(width=FRAME_WIDTH)))  # type: ignore[union-attr]
        kept_notes.append(f"{family} {kept / 1024:.1f} KiB (vs {STEPS * frame / 1024:.0f} KiB "
                          f"for {STEPS} PNG frames)")
    write_table("viewer", f"viewer: per-step view of a {STEPS}-step episode", [
        "episode", "view median ms", "ratio to graph only", "answer KiB (JSON)",
        "peak KiB (tracemalloc)"], rows,
        notes=f"The view of a {STEPS}-step episode executed in the simulator (random valid "
              "moves on a generated scene, seed 1) next to the same trace in a graph-only "
              "episode (drawings only), measured in the same run. The simulator's pictures "
              f"are replayed from the world as loaded and rendered {FRAME_WIDTH} px wide. "
              "Peak memory is what Python and numpy allocate during one view (tracemalloc; "
              "pymunk's C allocations are not counted: one rebuilt world). What an episode "
              "keeps for this, the world as loaded in JSON: " + "; ".join(kept_notes) + ".")


if __name__ == "__main__":
    main("--quick" in sys.argv)
