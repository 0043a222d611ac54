"""Perception's outputs on a fixed set of images, to show that a speed-up changed nothing.

`dump FILE` writes, for 20 seeded scenes per family rendered at 640x480 (clean, plus a
fixed selection of the robustness suite's degradations on the first six, plus family
auto-detection on the first three tabletop scenes), the graph, warnings, uncertain
items, confidences, detected objects and the family chosen; `check FILE` recomputes
them and lists every image whose output differs (exit 1 if any). Run `dump` before a
change and `check` after it:

    PYTHONPATH=$PWD python benchmarks/perception_fingerprint.py dump /tmp/before.json
    PYTHONPATH=$PWD python benchmarks/perception_fingerprint.py check /tmp/before.json
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from typing import Any

import numpy as np

from verigraph.perception.pipeline import perceive_image
from verigraph.perception.result import PerceptionResult
from verigraph.perception.robustness import SUITE
from verigraph.sim2d.degrade import degrade
from verigraph.sim2d.generator import generate_scene

FAMILIES = ("blocks", "kitchen", "tableware", "tangram")
FIRST_SEED = 30_000
DEGRADED_SCENES = 6  # the first scenes of each family also get degraded copies
AUTO_SCENES = 3  # ... and are perceived without a dictionary (tabletop families)


def fingerprint(result: PerceptionResult) -> dict[str, Any]:
    """Everything a caller sees of a result except its timing."""
    return json.loads(result.model_dump_json(exclude={"seconds"}))


def outputs(n: int) -> tuple[dict[str, Any], dict[str, list[float]]]:
    """Fingerprints per image key, and clean-render times per family."""
    out: dict[str, Any] = {}
    times: dict[str, list[float]] = {}
    for family in FAMILIES:
        for i in range(n):
            scene = generate_scene(family, FIRST_SEED + i)
            image = np.asarray(scene.world.render(640, 480))
            start = time.perf_counter()
            out[f"{family}/{i}/clean"] = fingerprint(perceive_image(image, dictionary=family))
            times.setdefault(family, []).append(time.perf_counter() - start)
            if i < DEGRADED_SCENES:
                for name, levels in SUITE.items():
                    for level, spec in levels.items():
                        if (i + len(name) + len(level)) % 3 == 0:  # a spread, not all
                            spoilt = degrade(image, spec, seed=scene.seed)
                            out[f"{family}/{i}/{name}/{level}"] = fingerprint(
                                perceive_image(spoilt, dictionary=family))
            if i < AUTO_SCENES and family != "tangram":
                out[f"{family}/{i}/auto"] = fingerprint(perceive_image(image))
    return out, times


def _known(before: Any, now: Any) -> Any:
    """`now` restricted to the fields `before` has: a field added since is no change."""
    if isinstance(before, dict) and isinstance(now, dict):
        return {k: now[k] for k in before if k in now}
    return now


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mode", choices=("dump", "check"))
    parser.add_argument("file")
    parser.add_argument("--n", type=int, default=20, help="scenes per family (default 20)")
    args = parser.parse_args(argv)
    found, times = outputs(args.n)
    for family, seconds in times.items():
        print(f"{family}: median {1000 * statistics.median(seconds):.1f} ms (clean)",
              file=sys.stderr)
    if args.mode == "dump":
        with open(args.file, "w", encoding="utf-8") as f:
            json.dump(found, f, sort_keys=True)
        print(f"{len(found)} images written to {args.file}")
        return 0
    with open(args.file, encoding="utf-8") as f:
        before = json.load(f)
    differ = sorted(k for k in before.keys() | found.keys()
                    if _known(before.get(k), found.get(k)) != before.get(k))
    print(f"{len(before)} images before, {len(found)} now; {len(differ)} differ"
          + (f": {', '.join(differ[:20])}" if differ else ""))
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
