"""The agent: Algorithm 1 (iterative planning with verifier feedback) driving a planner.

The loop (`loop.run_episode`) asks a planner (verigraph.planning) for actions and sends
them to the tools: over MCP (`environment.McpTools`, what `verigraph agent` uses) or in
process (verigraph.planning.tool_calls). `evaluation` is the benchmark behind
`verigraph bench plan`. The agent uses the environment (verigraph.env) and the server,
never the other way round.

>>> from verigraph.agent import LoopConfig, run_episode
>>> from verigraph.planning import InProcessTools, make_planner
>>> from verigraph.tasks import EpisodeSpec
>>> trace = run_episode(InProcessTools(), make_planner("oracle"),
...                     EpisodeSpec(load={"scene_id": "cup_on_book"}), LoopConfig(k=1))
>>> trace.success, trace.actions_executed, len(trace.iterations)
(True, 2, 2)
"""

from verigraph.agent.environment import McpTools
from verigraph.agent.loop import LoopConfig, run_episode

__all__ = ["LoopConfig", "McpTools", "run_episode"]
