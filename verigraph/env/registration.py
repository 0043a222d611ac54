"""Gymnasium ids, one per task family: `gymnasium.make("verigraph/blocks-v0")`.

`verigraph/blocks-v0` holds the stacking, language and reference-image block tasks,
`verigraph/kitchen-v0` the kitchen rearrangements, `verigraph/tangram-v0` the tangram
figures, `verigraph/household-v0` the household tasks (doors, switches, food and
dishes; docs/env.md). Keyword arguments of `make` reach `VeriGraphEnv` (split, k,
threshold, rubric, tools, ...). Registering twice is harmless, so importing
`verigraph.env` from several places is fine; `gymnasium.make("verigraph.env:verigraph/
blocks-v0")` imports it on the way.
"""

from __future__ import annotations

import gymnasium as gym

from verigraph.tasks.task import FAMILIES

ENTRY_POINT = "verigraph.env.core:VeriGraphEnv"
ENV_IDS: dict[str, str] = {f"verigraph/{family}-v0": family for family in FAMILIES}


def register_envs() -> list[str]:
    """Register every id (idempotent); returns the ids."""
    for env_id, family in ENV_IDS.items():
        if env_id not in gym.registry:
            gym.register(id=env_id, entry_point=ENTRY_POINT, kwargs={"family": family},
                         nondeterministic=False, disable_env_checker=False)
    return list(ENV_IDS)
