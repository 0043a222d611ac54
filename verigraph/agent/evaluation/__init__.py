"""The planning evaluation behind `verigraph bench plan` (the paper's Table 2).

The public entry point is `engine.run_jobs(jobs, tasks, options)`; jobs come from
`spec.jobs_for`, tasks from `verigraph.tasks.build_groups`, tables from `tables`.
"""

from verigraph.agent.evaluation.spec import EpisodeJob, Setting

__all__ = ["EpisodeJob", "Setting"]
