"""Scene-graph generation quality (the paper's Table 1) and speed of built-in perception.

Renders N generated scenes per family (blocks, kitchen, tableware, tangram) at 640x480,
spoils them at each degradation level, perceives them, and scores node F1, edge F1 and
exact graph accuracy against the simulator's ground truth; the paper's GPT-4V numbers
stand beside ours. Also scores the goal states of the tabletop families laid out afresh
(the structurally similar scenes that reference-image goals show).

Targets (issue 5): exact >= 0.99 clean for every family, >= 0.95 under moderate
degradation, median < 20 ms per 640x480 image with the default labeller.

Run: verigraph bench sgg [--n 100] [--families blocks,kitchen] [--levels clean,noise]
Seeds start at 10000, apart from the seeds the detectors were developed on.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from common import write_table  # noqa: E402

from verigraph.perception import perceive_image  # noqa: E402
from verigraph.perception.metrics import GraphScore, score_graph, summarise  # noqa: E402
from verigraph.sim2d import world_for_graph  # noqa: E402
from verigraph.sim2d.degrade import Degradation, degrade  # noqa: E402
from verigraph.sim2d.generator import generate_scene  # noqa: E402

FAMILIES = ("blocks", "kitchen", "tableware", "tangram")
LEVELS: dict[str, tuple[Degradation, str]] = {
    "clean": (Degradation(), "the render as drawn"),
    "noise": (Degradation(noise=8.0), "Gaussian pixel noise, sigma 8 (0-255)"),
    "blur": (Degradation(blur=1.0), "Gaussian blur, sigma 1 px"),
    "jpeg": (Degradation(jpeg=50), "JPEG quality 50"),
    "lighting": (Degradation(lighting=0.4), "uneven lighting 0.4: gain 0.7-1.3 with a "
                                            "gradient"),
}
LAYOUT = "goal layout"
HIRES = (1280, 960)
HIRES_LEVELS = ("blur", "jpeg")  # where 640x480 is too small for the thinnest parts
PAPER = {"blocks": "1.00 / 1.00 / 1.00", "kitchen": "0.98 / 0.87 / 0.65",
         "tableware": "0.99 / 0.95 / 0.89", "tangram": "-"}
FIRST_SEED = 10_000


def run(families: list[str], levels: list[str], n: int, layouts: bool, hires_n: int
        ) -> tuple[list[list[str]], list[float], dict[str, list[float]]]:
    rows: list[list[str]] = []
    times: list[float] = []
    by_level: dict[str, list[float]] = {}
    for family in families:
        scenes = [generate_scene(family, FIRST_SEED + i) for i in range(n)]
        renders = [s.world.render(640, 480) for s in scenes]
        cases: list[tuple[str, str, list]] = []
        for level in levels:
            spec = LEVELS[level][0]
            cases.append((level, "640x480", [(degrade(img, spec, seed=s.seed), s.graph)
                                             for img, s in zip(renders, scenes, strict=True)]))
        if layouts and family != "tangram":
            goals = [(world_for_graph(g, seed=s.seed + 1).render(640, 480), g)
                     for s in scenes if (g := s.goal.graph) is not None]
            cases.append((LAYOUT, "640x480", goals))
        if hires_n and family in ("kitchen", "tableware"):
            for level in (lv for lv in HIRES_LEVELS if lv in levels):
                spec = LEVELS[level][0]
                cases.append((level, f"{HIRES[0]}x{HIRES[1]}", [
                    (degrade(s.world.render(*HIRES), spec, seed=s.seed), s.graph)
                    for s in scenes[:hires_n]]))
        for level, size, items in cases:
            scores: list[GraphScore] = []
            for image, truth in items:
                start = time.perf_counter()
                result = perceive_image(image, dictionary=family)
                elapsed = time.perf_counter() - start
                if size == "640x480":
                    times.append(elapsed)
                    by_level.setdefault(level, []).append(elapsed)
                scores.append(score_graph(result.graph, truth, family))
            summary = summarise(scores)
            rows.append([family, level, size, str(summary.images), f"{summary.node_f1:.3f}",
                         f"{summary.edge_f1:.3f}", f"{summary.exact:.3f}",
                         PAPER[family] if level == "clean" else ""])
            print(" | ".join(rows[-1]), file=sys.stderr)
    return rows, times, by_level


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=100, help="scenes per family (default 100)")
    parser.add_argument("--families", default=",".join(FAMILIES))
    parser.add_argument("--levels", default=",".join(LEVELS))
    parser.add_argument("--no-layouts", action="store_true",
                        help="skip the goal layouts (structurally similar scenes)")
    parser.add_argument("--hires-n", type=int, default=50,
                        help="kitchen/tableware scenes also scored at 1280x960 under blur "
                             "and JPEG (default 50, 0 = none)")
    args = parser.parse_args(argv)
    families = [f for f in args.families.split(",") if f]
    levels = [lv for lv in args.levels.split(",") if lv]
    unknown = [x for x in families if x not in FAMILIES] + [x for x in levels if x not in LEVELS]
    if unknown:
        parser.error(f"unknown family or level: {', '.join(unknown)}")
    rows, times, by_level = run(families, levels, args.n, not args.no_layouts,
                                min(args.hires_n, args.n))
    ms = sorted(t * 1000 for t in times)
    timing = ", ".join(f"{lv} {statistics.median(v) * 1000:.1f}" for lv, v in by_level.items())
    notes = "\n".join([
        f"{args.n} generated scenes per family (seeds {FIRST_SEED}-{FIRST_SEED + args.n - 1}),"
        " rendered at 640x480 by sim2d; default (colour/shape) labeller, no weights.",
        "Levels: " + "; ".join(f"**{lv}** = {LEVELS[lv][1]}" for lv in levels)
        + (f"; **{LAYOUT}** = the scene's goal graph laid out afresh by "
           "`world_for_graph` (what a reference-image goal shows), clean." if not
           args.no_layouts else ""),
        f"Rows at {HIRES[0]}x{HIRES[1]}: the same scenes rendered larger (first "
        f"{min(args.hires_n, args.n)}), to separate resolution from method: at 640x480 a "
        "kitchen or tableware render has 3-5 px per world unit, so a cup wall or a spoon "
        "is thinner than the 3 px outline around it, and blur or JPEG erase it.",
        "Metrics per image, averaged: node F1 (label and colour), edge F1 (after matching "
        "look-alike ids; tangram sides up to piece symmetry), exact = the whole graph "
        "equals the truth. GPT-4V column: the paper's Table 1 (node F1 / edge F1 / "
        "exact), on its own images; not the same scenes.",
        f"Perception time per 640x480 image: median {statistics.median(ms):.1f} ms, p90 "
        f"{ms[int(0.9 * (len(ms) - 1))]:.1f} ms, max {ms[-1]:.1f} ms over {len(ms)} "
        f"images (median by level, ms: {timing}).",
        "Targets: exact >= 0.99 clean, >= 0.95 under moderate degradation, median < 20 ms.",
    ])
    write_table("sgg", "Scene-graph generation: built-in perception vs ground truth",
                ["family", "level", "size", "images", "node F1", "edge F1", "exact",
                 "GPT-4V (paper)"], rows, notes)
    return 0


if __name__ == "__main__":
    sys.exit(main())
