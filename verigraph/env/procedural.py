"""Procedural environments: a family and a level, fresh tasks every episode.

`gymnasium.make("verigraph/blocks-procedural-v0", level=3)` (also kitchen and tangram)
is a `VeriGraphEnv` whose tasks come from the family's seeded generator
(verigraph.tasks.procedural) instead of the stored suites, which stay the fixed test
sets. Without `size`, every `reset(seed=s)` draws a task index from the seeded generator
and builds that task (a stream as long as training wants; the same seed gives the same
task); with `size=N` the pool is the level's first N tasks, built once, which
`verigraph rollouts`-style jobs address by id. `set_level(L)` (or `set_config`) moves
the knob between episodes for a curriculum. `split` keeps the content-hash cut of the
stored suites: a train stream never yields a task whose hash falls in the test range.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym

from verigraph.env.core import VeriGraphEnv
from verigraph.env.dataset import DEFAULT_TEST_FRACTION, Split, split_of, split_tasks
from verigraph.errors import VeriGraphError
from verigraph.tasks.procedural import (
    GENERATORS,
    LevelConfig,
    generate_task,
    generate_tasks,
    generator_for,
)
from verigraph.tasks.task import Task

ENTRY_POINT = "verigraph.env.procedural:ProceduralEnv"
MAX_INDEX = 2**31
MAX_SKIPS = 64  # indexes tried for one of the wanted split (a fifth lands in test)


def procedural_id(family: str) -> str:
    return f"verigraph/{family}-procedural-v0"


class ProceduralEnv(VeriGraphEnv):
    """A `VeriGraphEnv` over a family's generated tasks at one level (module docstring)."""

    def __init__(self, family: str = "blocks", *, level: int = 1, seed: int = 0,
                 size: int | None = None, config: LevelConfig | None = None,
                 split: Split = "train", test_fraction: float = DEFAULT_TEST_FRACTION,
                 **kwargs: Any) -> None:
        if "tasks" in kwargs or "per_group" in kwargs:
            raise VeriGraphError("a procedural environment draws its own tasks",
                                 field="tasks", fix="use verigraph/FAMILY-v0 for task "
                                 "files and stored suites")
        self.generator = generator_for(family)
        self.level = level
        self.level_config = config or self.generator.config(level)
        self.generator_seed = seed
        self.size = size
        self.split = split
        self.test_fraction = test_fraction
        super().__init__(family, tasks=self._pool(), split=split,
                         test_fraction=test_fraction, **kwargs)
        self.family = family

    def _pool(self) -> list[Task]:
        if self.size is not None:
            pool = split_tasks(generate_tasks(self.generator.family, self.level, self.size,
                                              self.generator_seed, self.level_config),
                               self.split, self.test_fraction)
            if not pool:
                raise VeriGraphError("no task of this size lands in the split",
                                     field="size", value=self.size, fix="raise size")
            return pool
        return [self._draw(0)]

    def _draw(self, index: int) -> Task:
        for offset in range(MAX_SKIPS):
            task = generate_task(self.generator.family, self.level,
                                 (index + offset) % MAX_INDEX, self.generator_seed,
                                 self.level_config)
            if split_of(task.content_hash, self.test_fraction) == self.split:
                return task
        raise VeriGraphError(f"no {self.split} task in {MAX_SKIPS} draws", field="split",
                             value=self.split, fix="use a test_fraction below 1")

    def set_level(self, level: int, config: LevelConfig | None = None) -> None:
        """The knob for the next episodes (a curriculum moves it between episodes)."""
        self.level_config = config or self.generator.config(level)
        self.level = level
        self.tasks = self._pool()
        self._by_id = {t.task_id: t for t in self.tasks}

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None
              ) -> tuple[str, dict[str, Any]]:
        if self.size is not None or (isinstance(options, dict) and "task" in options):
            return super().reset(seed=seed, options=options)
        gym.Env.reset(self, seed=seed)  # seeds np_random; the draw below reads it
        task = self._draw(int(self.np_random.integers(MAX_INDEX)))
        self.tasks, self._by_id = [task], {task.task_id: task}
        return super().reset(options={**(options or {}), "task": task.task_id})

    def _info(self, **kwargs: Any) -> dict[str, Any]:
        return {**super()._info(**kwargs), "level": self.level}


def make_env(**env_kwargs: Any) -> VeriGraphEnv:
    """A `ProceduralEnv` when the arguments name a `level`, else a `VeriGraphEnv`."""
    if "level" in env_kwargs:
        return ProceduralEnv(**env_kwargs)
    return VeriGraphEnv(**env_kwargs)


def register_procedural_envs() -> list[str]:
    """Register `verigraph/FAMILY-procedural-v0` for every generator (idempotent)."""
    ids = []
    for family in GENERATORS:
        env_id = procedural_id(family)
        if env_id not in gym.registry:
            gym.register(id=env_id, entry_point=ENTRY_POINT,
                         kwargs={"family": family, "level": 1},
                         nondeterministic=False, disable_env_checker=False)
        ids.append(env_id)
    return ids
