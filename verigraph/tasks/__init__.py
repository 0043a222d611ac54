"""The tasks the benchmark and the environment draw episodes from.

A task is a scene with a goal, what a prompt or a score reads of it, and the hashes that
identify it (`task.Task`; its start as a `task.EpisodeSpec`). The suites are versioned and
seeded (`task.SUITE_VERSION`, `groups.build_groups`): stacking, reversal and multi-tower
rearrangement (`suite_blocks`), kitchen tables (`suite_kitchen`), tangram figures
(`suite_tangram`) and language instructions (`language`). The benchmark
(verigraph.agent.evaluation) runs them as episodes; the environment (verigraph.env.dataset)
serves and stores the same `Task` objects.
"""

from verigraph.tasks.groups import GroupTasks, build_groups
from verigraph.tasks.task import (
    FAMILIES,
    GROUPS,
    SUITE_VERSION,
    EpisodeSpec,
    Family,
    GroupName,
    Task,
)

__all__ = ["FAMILIES", "GROUPS", "SUITE_VERSION", "EpisodeSpec", "Family", "GroupName",
           "GroupTasks", "Task", "build_groups"]
