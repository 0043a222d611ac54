"""The agent: Algorithm 1 (iterative planning with verifier feedback) and planner backends.

>>> from verigraph.agent import EpisodeSpec, InProcessTools, LoopConfig, make_planner
>>> from verigraph.agent import run_episode
>>> trace = run_episode(InProcessTools(), make_planner("oracle"),
...                     EpisodeSpec(load={"scene_id": "cup_on_book"}), LoopConfig(k=1))
>>> trace.success, trace.actions_executed, len(trace.iterations)
(True, 2, 2)
"""

from verigraph.agent.environment import InProcessTools, McpTools, ToolCallError, ToolEnvironment
from verigraph.agent.factory import PLANNER_NAMES, PlannerOptions, make_planner
from verigraph.agent.loop import EpisodeSpec, LoopConfig, run_episode, split_proposal
from verigraph.agent.models import (
    EpisodeTrace,
    Feedback,
    IterationRecord,
    PlannerReply,
    PlannerRequest,
)
from verigraph.agent.planner import Planner

__all__ = [
    "PLANNER_NAMES", "EpisodeSpec", "EpisodeTrace", "Feedback", "InProcessTools",
    "IterationRecord", "LoopConfig", "McpTools", "Planner", "PlannerOptions", "PlannerReply",
    "PlannerRequest", "ToolCallError", "ToolEnvironment", "make_planner", "run_episode",
    "split_proposal",
]
