"""Planning benchmark: the paper's Table 2 and the t/k ablations, written to results/plan.md.

Run: `verigraph bench plan [--episodes 50] [--ground-truth-graphs] [--simulate]`
(or `python benchmarks/bench_plan.py ...`); `--help` lists every option. The episodes
run in-process against the tool layer (the same functions the MCP server wraps), not
through a server per episode; `verigraph agent` exercises the real MCP transport.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from common import RESULTS, machine  # noqa: E402

from verigraph.agent.evaluation.bench import run  # noqa: E402
from verigraph.errors import VeriGraphError  # noqa: E402


def main(argv: list[str]) -> int:
    out = None if "--out" in argv else RESULTS / "plan.md"
    try:
        report = run(argv)
    except VeriGraphError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    text = f"# Planning benchmark (verigraph bench plan)\n\nMachine: {machine()}\n\n{report}"
    print(text)
    if out is not None:
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(text)
        print(f"written to {out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
