"""The job engine: run a list of jobs serially or on Ray, resumably, with a progress bar.

`dispatch.run_on_workers` runs any `workers.Worker` a `workers.WorkerFactory` builds,
in this process or as Ray actors (`ray_runner`), with per-backend request limits
(`limiter`) and `bench plan`'s progress bar (`progress_bar`). It knows no episodes: the
benchmark's episodes (verigraph.agent.evaluation) and the environment's rollouts
(verigraph.env.rollout) are two kinds of job it runs.
"""
