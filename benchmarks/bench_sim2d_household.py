"""Does the household simulator do what the verifier predicts? Random valid actions.

N random valid actions of the action table (moves on, in, under and next to things,
open, close, toggle_on, toggle_off) on random household scenes (a kitchen and a dining
room: counter, stove, sink, fridge, cabinet, table; food and dishes; random door and
switch states), seeds from 20000, apart from the tests. An action the household room
check refuses is counted and not run; every other one must be carried out and end in
the predicted graph, placements, rooms and states alike
(`verigraph.sim2d.household_scenes.household_agreement`).

Run: verigraph bench sim2d_household [--actions 1000]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from common import write_table  # noqa: E402

from verigraph.sim2d.household_scenes import household_agreement  # noqa: E402

FIRST_SEED = 20_000


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--actions", type=int, default=1000)
    args = parser.parse_args(argv)
    start = time.perf_counter()
    executed, refused, failures = household_agreement(args.actions, FIRST_SEED)
    seconds = time.perf_counter() - start
    row = ["household", str(args.actions), str(executed), str(refused), str(len(failures)),
           f"{seconds:.1f}"]
    print(" | ".join(row), file=sys.stderr)
    notes = ("Random valid actions of the action table on random household scenes (seeds "
             "from 20000, 15 draws per scene). refused: the household room check "
             "predicted `no_room` (the action is not run). failures: an action the room "
             "check passed that the simulator refused, or one that ended in a graph "
             "(placements, rooms, states) other than the prediction. Target: 0 failures.")
    if failures:
        notes += "\n\nFailures:\n" + "\n".join(f"- {f}" for f in failures[:20])
    write_table("sim2d_household", "household sim2d vs the verifier's predictions",
                ["scenes", "actions", "executed", "refused", "failures", "seconds"], [row],
                notes)
    return 0


if __name__ == "__main__":
    sys.exit(main())
