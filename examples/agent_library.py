"""Algorithm 1 from Python: a noisy planner against `verigraph serve`, over real MCP stdio.

Run: python examples/agent_library.py [--noise 0.5] [--seed 3]
Swap the planner for `make_planner("openai", PlannerOptions(base_url=..., model=...))`
to plan with a real model; nothing else changes.
"""

from __future__ import annotations

import argparse
import sys

from verigraph.agent import LoopConfig, McpTools, run_episode
from verigraph.agent.console import print_iteration, verdict_line
from verigraph.planning import PlannerOptions, make_planner
from verigraph.tasks import EpisodeSpec


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--noise", type=float, default=0.5)
    parser.add_argument("--seed", type=int, default=3)
    args = parser.parse_args()
    planner = make_planner("noisy", PlannerOptions(noise=args.noise, seed=args.seed))
    env = McpTools.stdio()  # spawns `verigraph serve` and speaks MCP to it
    try:
        trace = run_episode(env, planner, EpisodeSpec(load={"scene_id": "three_blocks"}),
                            LoopConfig(k=1, threshold=5),
                            on_iteration=lambda r: print_iteration(r, sys.stdout))
    finally:
        env.close()
    print(verdict_line(trace))
    return 0 if trace.success else 1


if __name__ == "__main__":
    sys.exit(main())
