"""VeriGraph as a training and evaluation environment for LLM planners (docs/env.md).

>>> import gymnasium as gym
>>> import verigraph.env
>>> env = gym.make("verigraph/blocks-v0")
>>> obs, info = env.reset(seed=0)
>>> "## Goal" in obs, info["step"]
(True, 0)
>>> env.close()

Needs the `env` extra (`pip install 'verigraph-mcp[env]'`): gymnasium, and openenv
for the OpenEnv adapter (verigraph.env.openenv_adapter).
"""

from verigraph.extras import require

require("env", "gymnasium")

from verigraph.env.core import VeriGraphEnv, state_hash  # noqa: E402
from verigraph.env.dataset import (  # noqa: E402
    build_tasks,
    check_disjoint,
    read_jsonl,
    select,
    split_tasks,
    write_jsonl,
)
from verigraph.env.procedural import ProceduralEnv, register_procedural_envs  # noqa: E402
from verigraph.env.registration import ENV_IDS, register_envs  # noqa: E402
from verigraph.env.rubric import Rubric, StepOutcome, score  # noqa: E402
from verigraph.tasks.task import FAMILIES, Task  # noqa: E402

register_envs()
register_procedural_envs()

__all__ = ["ENV_IDS", "FAMILIES", "ProceduralEnv", "Rubric", "StepOutcome", "Task", "VeriGraphEnv",
           "build_tasks", "check_disjoint", "read_jsonl", "register_envs",
           "register_procedural_envs", "score",
           "select", "split_tasks", "state_hash", "write_jsonl"]
