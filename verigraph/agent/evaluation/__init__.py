"""The planning evaluation behind `verigraph bench plan` (the paper's Table 2)."""

from verigraph.agent.evaluation.runner import EpisodeResult, GroupStats, Setting, run_setting
from verigraph.agent.evaluation.tasks import GROUPS, GroupTasks, Task, build_groups

__all__ = ["GROUPS", "EpisodeResult", "GroupStats", "GroupTasks", "Setting", "Task",
           "build_groups", "run_setting"]
