"""Planners and the text protocol they share with the agent and the environment.

A planner proposes the next actions from a prompt or a state (`planner.Planner`): the
offline planners (`oracle`, `rule_based`, `greedy`, `noisy`) and the LLM backends
(`openai_backend`, `anthropic_backend`, `local`), built by name with
`factory.make_planner`. Around them is what the agent's loop (verigraph.agent) and the
environment (verigraph.env) both speak: the request and reply models (`models`), the
prompt (`prompting`), the answer parser and `split_proposal` (`parsing`), the goal
distance and the feedback a planner is shown (`progress`), and where tool calls go
(`tool_calls`: the `ToolEnvironment` protocol and the in-process tool layer).
"""

from verigraph.planning.factory import PLANNER_NAMES, PlannerOptions, make_planner
from verigraph.planning.models import (
    EpisodeTrace,
    Feedback,
    IterationRecord,
    PlannerReply,
    PlannerRequest,
)
from verigraph.planning.parsing import split_proposal
from verigraph.planning.planner import Planner
from verigraph.planning.tool_calls import InProcessTools, ToolCallError, ToolEnvironment

__all__ = [
    "PLANNER_NAMES", "EpisodeTrace", "Feedback", "InProcessTools", "IterationRecord",
    "Planner", "PlannerOptions", "PlannerReply", "PlannerRequest", "ToolCallError",
    "ToolEnvironment", "make_planner", "split_proposal",
]
