"""The tasks the benchmark and the environment draw episodes from.

A task is a scene with a goal and what a prompt or a score reads of it (`groups.Task`,
its start as an `groups.EpisodeSpec`). The suites are versioned and seeded
(`groups.SUITE_VERSION`, `groups.build_groups`): stacking, reversal and multi-tower
rearrangement (`suite_blocks`), kitchen tables (`suite_kitchen`), tangram figures
(`suite_tangram`) and language instructions (`language`). The benchmark
(verigraph.agent.evaluation) runs them as episodes; the environment (verigraph.env.dataset)
stores them as hashed task records.
"""

from verigraph.tasks.groups import (
    GROUPS,
    SUITE_VERSION,
    EpisodeSpec,
    GroupName,
    GroupTasks,
    Task,
    build_groups,
)

__all__ = ["GROUPS", "SUITE_VERSION", "EpisodeSpec", "GroupName", "GroupTasks", "Task",
           "build_groups"]
