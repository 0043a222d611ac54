"""Planning benchmark: the paper's Table 2 and the t/k ablations.

A thin wrapper: the benchmark is part of the package (`verigraph bench plan`, parsed in
`verigraph/cli/bench.py`, run by `verigraph.agent.evaluation`), so an installed package
runs it without this folder. `python benchmarks/bench_plan.py ARGS` is the same as
`verigraph bench plan ARGS`; add `--update-results` to write results/plan.md.
"""

from __future__ import annotations

import sys

from verigraph.cli import main

if __name__ == "__main__":
    sys.exit(main(["bench", "plan", *sys.argv[1:]]))
